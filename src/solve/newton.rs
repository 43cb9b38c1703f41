//! The one Newton solver of the crate: options, status, result, stop
//! reasons; Armijo backtracking on a scaled merit function; convergence
//! against an estimated rounding floor.
//!
//! Merit: `phi(x) = |f(x)|^2 / 2` of the *scaled* residual (each caller
//! scales its residual to be dimensionless and of order one for an order-one
//! error; shooting: strain errors, see [`crate::shooting::residual_scales`]).
//! The step solves `J dx = -f`; it is a descent direction of `phi`
//! (`grad phi . dx = -|f|^2 < 0`) whenever `J` is the Jacobian, which is
//! checked (`f^T J dx < 0`); if not, the steepest-descent direction `-J^T f`
//! is taken. Backtracking: `x + t dx` is accepted when
//! `phi <= phi0 + 1e-4 t grad phi . dx` (Armijo), else `t` is halved (a
//! quadratic-interpolation step stalled where a TCA's coil contact makes the
//! residual only C1). A trial where `f` fails (e.g. an IVP that cannot
//! be integrated) counts as an infinite merit.
//!
//! Convergence: `max |f_i| <= max(tol, floor)`, where `floor` is the
//! caller's estimate of the rounding floor of the residual at `x` (the
//! residual cannot be computed more accurately than that). A `tol` below
//! the floor converges to the floor with [`Status::ConvergedAtFloor`]. A
//! line search that fails within `FLOOR_MARGIN` times the floor is also
//! convergence at the floor (rounding noise, not a wrong Jacobian).

use nalgebra::{DMatrix, DVector};

use super::cancel;
use crate::error::{Error, Result, StopReason};

/// How a Newton solve ended successfully.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// `max |f| <= tol`.
    Converged,
    /// `tol` lies below the estimated rounding floor; `max |f|` reached the floor.
    ConvergedAtFloor,
}

/// A nonlinear system `f(x) = 0` for [`newton`].
pub trait System {
    /// `f(x)`.
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>>;
    /// `f(x)` and the Jacobian `df/dx` at `x`. Default: forward differences
    /// (step `sqrt(eps) max(1, |x_j|)`; one-sided the other way where `f` fails).
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let r = self.residual(x)?;
        let (n, m) = (x.len(), r.len());
        let mut jac = DMatrix::zeros(m, n);
        let mut xp = x.to_vec();
        for j in 0..n {
            let h = f64::EPSILON.sqrt() * x[j].abs().max(1.0);
            xp[j] = x[j] + h;
            let h = xp[j] - x[j];
            let col: Vec<f64> = match self.residual(&xp) {
                Ok(rp) => rp.iter().zip(&r).map(|(a, b)| (a - b) / h).collect(),
                Err(_) => {
                    xp[j] = x[j] - h;
                    let rm = self.residual(&xp)?;
                    r.iter().zip(&rm).map(|(a, b)| (a - b) / h).collect()
                }
            };
            for i in 0..m {
                jac[(i, j)] = col[i];
            }
            xp[j] = x[j];
        }
        Ok((r, jac))
    }
    /// Estimated rounding floor of `max |f|` at `x` with residual `r`
    /// (default 0: no floor known).
    fn floor(&self, _x: &[f64], _r: &[f64]) -> f64 {
        0.0
    }
    /// Function evaluations so far (IVPs for shooting, failed ones included).
    fn evaluations(&self) -> usize;
    /// Switch to a more accurate Jacobian, if the system has one; `true` if
    /// it did (then a failed line search is retried with it).
    fn refine(&mut self) -> bool {
        false
    }
}

/// Options of [`newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonOptions {
    /// Tolerance on `max |f_i|`.
    pub tol: f64,
    /// Iteration limit.
    pub max_iter: usize,
    /// Smallest line-search step before giving up.
    pub min_step: f64,
}

/// Outcome of [`newton`].
#[derive(Debug, Clone)]
pub struct NewtonResult {
    /// Solution.
    pub x: Vec<f64>,
    /// Residual at `x`.
    pub residual: Vec<f64>,
    /// `max |residual|`.
    pub norm: f64,
    /// Estimated rounding floor of the residual at `x`.
    pub floor: f64,
    /// How it converged.
    pub status: Status,
    /// Newton iterations performed.
    pub iterations: usize,
    /// Evaluations (IVPs), counted by the system.
    pub evaluations: usize,
    /// The last Jacobian computed (`None` if `x0` already converged).
    pub jacobian: Option<DMatrix<f64>>,
}

/// Multiple of the floor within which a stalled line search counts as convergence.
const FLOOR_MARGIN: f64 = 100.0;

fn inf_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn merit(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|x| x * x).sum::<f64>()
}

/// Newton's method on `sys` from `x0` (see the module docs). Errors:
/// [`Error::NotConverged`] with the best residual reached, the iterations,
/// the evaluations and a [`StopReason`]; [`Error::Interrupted`] if the
/// cancel check (see [`crate::solve::cancel`]) fires. An error of the first
/// evaluation is returned as it is (e.g. an invalid input).
pub fn newton<S: System>(
    sys: &mut S,
    x0: &[f64],
    opts: &NewtonOptions,
    solver: &'static str,
) -> Result<NewtonResult> {
    newton_from(sys, x0, opts, solver, None)
}

/// [`newton`] with an initial Jacobian `jac0` (e.g. that of a neighbouring
/// solution, for warm starts).
///
/// Jacobian reuse: a Jacobian is kept for the next iteration while it
/// contracts the residual, and a step taken with a kept (not freshly
/// computed) Jacobian must at least halve `max |f|` at full length; otherwise
/// the Jacobian is recomputed at the current point and the iteration redone
/// with the full line search. A kept Jacobian that reduces `max |f|` by less
/// than four times, or before the last allowed iteration, is recomputed for
/// the next step. A kept Jacobian costs no tangent IVP, so warm
/// starts and the last iterations of a cold solve cost one plain IVP each.
pub fn newton_from<S: System>(
    sys: &mut S,
    x0: &[f64],
    opts: &NewtonOptions,
    solver: &'static str,
    jac0: Option<&DMatrix<f64>>,
) -> Result<NewtonResult> {
    let mut x = x0.to_vec();
    let mut r = sys.residual(&x)?;
    let mut iterations = 0;
    let mut best = inf_norm(&r);
    let mut jacobian: Option<DMatrix<f64>> = jac0
        .filter(|j| j.nrows() == r.len() && j.ncols() == x.len() && j.iter().all(|v| v.is_finite()))
        .cloned();
    let mut fresh = false;
    let fail =
        |sys: &S, iterations, best: f64, reason: StopReason, detail: String| Error::NotConverged {
            solver,
            iterations,
            evaluations: sys.evaluations(),
            residual: best,
            stop: reason,
            reason: detail,
        };
    loop {
        let res = inf_norm(&r);
        if !res.is_finite() {
            return Err(fail(
                sys,
                iterations,
                best,
                StopReason::NonFinite,
                "non-finite residual".into(),
            ));
        }
        best = best.min(res);
        let floor = sys.floor(&x, &r);
        if res <= opts.tol.max(floor) {
            let status = if res <= opts.tol {
                Status::Converged
            } else {
                Status::ConvergedAtFloor
            };
            let evaluations = sys.evaluations();
            return Ok(NewtonResult {
                x,
                residual: r,
                norm: res,
                floor,
                status,
                iterations,
                evaluations,
                jacobian,
            });
        }
        if iterations >= opts.max_iter {
            return Err(fail(
                sys,
                iterations,
                best,
                StopReason::IterationLimit,
                "iteration limit reached".into(),
            ));
        }
        cancel::check()?;
        iterations += 1;
        let jac = match jacobian.take() {
            Some(j) => j,
            None => {
                fresh = true;
                // keep the plain residual (the Jacobian's is equal to rounding)
                sys.residual_and_jacobian(&x)?.1
            }
        };
        let rv = DVector::from_column_slice(&r);
        let (m, n) = jac.shape();
        let dx = if m == n {
            jac.clone().lu().solve(&(-&rv))
        } else {
            jac.clone().svd(true, true).solve(&(-&rv), 1e-14).ok()
        };
        let grad = jac.tr_mul(&rv); // grad phi = J^T f
        let mut dx = match dx {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ if !fresh => {
                // a kept Jacobian gone singular: recompute it
                iterations -= 1;
                continue;
            }
            _ => {
                return Err(fail(
                    sys,
                    iterations,
                    best,
                    StopReason::SingularJacobian,
                    "singular Jacobian".into(),
                ));
            }
        };
        let mut slope = grad.dot(&dx);
        if !(slope < 0.0) {
            if !fresh {
                iterations -= 1;
                continue;
            }
            // not a descent direction (inaccurate Jacobian): steepest descent,
            // scaled to the Gauss-Newton step length
            let g2 = grad.norm_squared();
            if !(g2 > 0.0) {
                return Err(fail(
                    sys,
                    iterations,
                    best,
                    StopReason::SingularJacobian,
                    "zero gradient of the merit".into(),
                ));
            }
            let jg = &jac * &grad;
            dx = -&grad * (g2 / jg.norm_squared().max(f64::MIN_POSITIVE));
            slope = grad.dot(&dx);
        }
        jacobian = Some(jac);
        let phi0 = merit(&r);
        let mut t = 1.0;
        if !fresh {
            // a kept Jacobian: full step only, and it must halve max |f|
            let xt: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
            match sys.residual(&xt) {
                Ok(rt) if inf_norm(&rt) <= 0.5 * res => {
                    // slow (linear) contraction, or the last iteration next:
                    // a fresh Jacobian for the next step
                    if inf_norm(&rt) > 0.25 * res || iterations + 1 >= opts.max_iter {
                        jacobian = None;
                    }
                    x = xt;
                    r = rt;
                }
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                _ => {
                    jacobian = None;
                    iterations -= 1;
                }
            }
            continue;
        }
        fresh = false;
        loop {
            let xt: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + t * b).collect();
            let phi = match sys.residual(&xt) {
                Ok(rt) => {
                    let phi = merit(&rt);
                    if phi.is_finite() && (phi <= phi0 + 1e-4 * t * slope) {
                        x = xt;
                        r = rt;
                        break;
                    }
                    phi
                }
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(_) => f64::INFINITY,
            };
            // plain halving: the residual is only C1 where a TCA's coils
            // touch, and a quadratic model there shrinks the step too far
            let _ = phi;
            t *= 0.5;
            if t < opts.min_step {
                if sys.refine() {
                    jacobian = None;
                    iterations -= 1;
                    break;
                }
                let floor = sys.floor(&x, &r);
                if res <= FLOOR_MARGIN * floor {
                    let evaluations = sys.evaluations();
                    return Ok(NewtonResult {
                        x,
                        residual: r,
                        norm: res,
                        floor,
                        status: Status::ConvergedAtFloor,
                        iterations,
                        evaluations,
                        jacobian,
                    });
                }
                return Err(fail(
                    sys,
                    iterations,
                    best,
                    StopReason::LineSearch,
                    "line search failed to reduce the residual".into(),
                ));
            }
        }
        if t < 1.0 {
            // a damped step: the Jacobian is recomputed at the new point
            jacobian = None;
        }
    }
}

/// A [`System`] from a closure, with the forward-difference Jacobian; counts
/// its evaluations.
pub struct FnSystem<F: FnMut(&[f64]) -> Result<Vec<f64>>> {
    f: F,
    evaluations: usize,
}

impl<F: FnMut(&[f64]) -> Result<Vec<f64>>> FnSystem<F> {
    /// Wrap `f`.
    pub fn new(f: F) -> Self {
        FnSystem { f, evaluations: 0 }
    }
}

impl<F: FnMut(&[f64]) -> Result<Vec<f64>>> System for FnSystem<F> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        self.evaluations += 1;
        (self.f)(x)
    }
    fn evaluations(&self) -> usize {
        self.evaluations
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's function as a system: f = (10 (y - x^2), 1 - x), root (1, 1).
    #[test]
    fn solves_rosenbrock_from_afar_and_reports_failures() {
        let mut sys = FnSystem::new(|x: &[f64]| Ok(vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]]));
        let o = NewtonOptions {
            tol: 1e-12,
            max_iter: 50,
            min_step: 1e-10,
        };
        let r = newton(&mut sys, &[-1.2, 1.0], &o, "test").unwrap();
        assert!((r.x[0] - 1.0).abs() < 1e-10 && (r.x[1] - 1.0).abs() < 1e-10);
        assert_eq!(r.status, Status::Converged);
        // x^2 + 1 = 0 has no real root: the merit's minimum is at 0 with f = 1
        let mut sys = FnSystem::new(|x: &[f64]| Ok(vec![x[0] * x[0] + 1.0]));
        match newton(&mut sys, &[0.7], &o, "test") {
            Err(Error::NotConverged {
                residual,
                evaluations,
                stop,
                ..
            }) => {
                assert!((residual - 1.0).abs() < 1e-6, "best residual {residual}");
                assert!(evaluations > 2);
                assert!(matches!(
                    stop,
                    StopReason::LineSearch
                        | StopReason::SingularJacobian
                        | StopReason::IterationLimit
                ));
            }
            other => panic!("expected NotConverged, got {other:?}"),
        }
    }

    /// A residual with rounding noise of 1e-9: tol 1e-12 converges to the
    /// floor (reported), instead of failing.
    #[test]
    fn tol_below_the_floor_converges_to_the_floor() {
        struct Noisy(usize);
        impl System for Noisy {
            fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
                self.0 += 1;
                let noise = 1e-9 * ((self.0 as f64 * 12.9898).sin() * 43758.5453).fract();
                Ok(vec![x[0] - 2.0 + noise])
            }
            fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
                Ok((self.residual(x)?, DMatrix::from_element(1, 1, 1.0)))
            }
            fn floor(&self, _x: &[f64], _r: &[f64]) -> f64 {
                1e-9
            }
            fn evaluations(&self) -> usize {
                self.0
            }
        }
        let o = NewtonOptions {
            tol: 1e-12,
            max_iter: 20,
            min_step: 1e-6,
        };
        let r = newton(&mut Noisy(0), &[10.0], &o, "test").unwrap();
        assert_eq!(r.status, Status::ConvergedAtFloor);
        assert!((r.x[0] - 2.0).abs() <= 2e-9);
        assert_eq!(r.floor, 1e-9);
    }
}
