//! The steps of a Newton run ([`super::newton`]): the direction with its
//! descent check, the chord step with a kept Jacobian, Armijo backtracking,
//! and the slow-contraction count that refines the Jacobian; and a run of
//! chord steps with a kept Jacobian that hands over to Newton
//! ([`chord_then_newton`], the coarse pre-solve's).

use nalgebra::{DMatrix, DVector};

use super::{
    inf_norm, merit, newton_from, NewtonOptions, NewtonResult, Run, Status, Step, System,
    SLOW_CONTRACTION, SLOW_STEPS_BEFORE_REFINE, WATCHDOG_COOLDOWN, WATCHDOG_MIN_STEP,
};
use crate::error::{Error, Result, StopReason};

impl<S: System> Run<'_, S> {
    /// The Newton direction for `jac` (steepest descent scaled to the
    /// Gauss-Newton length where it is not a descent direction), its slope
    /// `grad phi . dx`; `None`: singular or not descending with a kept Jacobian.
    pub(super) fn direction(&self, jac: &DMatrix<f64>) -> Result<Option<(DVector<f64>, f64)>> {
        let rv = DVector::from_column_slice(&self.r);
        let (m, n) = jac.shape();
        let dx = if m == n {
            jac.clone().lu().solve(&(-&rv))
        } else {
            jac.clone().svd(true, true).solve(&(-&rv), 1e-14).ok()
        };
        let grad = jac.tr_mul(&rv); // grad phi = J^T f
        let dx = match dx {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ if !self.fresh => return Ok(None),
            _ => return Err(self.fail(StopReason::SingularJacobian, "singular Jacobian")),
        };
        let slope = grad.dot(&dx);
        if slope < 0.0 {
            return Ok(Some((dx, slope)));
        }
        if !self.fresh {
            return Ok(None);
        }
        // not a descent direction (inaccurate Jacobian): steepest descent,
        // scaled to the Gauss-Newton step length
        let g2 = grad.norm_squared();
        if !(g2 > 0.0) {
            return Err(self.fail(StopReason::SingularJacobian, "zero gradient of the merit"));
        }
        let jg = jac * &grad;
        let dx = -&grad * (g2 / jg.norm_squared().max(f64::MIN_POSITIVE));
        let slope = grad.dot(&dx);
        Ok(Some((dx, slope)))
    }

    /// Count a full step's contraction; refine the Jacobian after
    /// [`SLOW_STEPS_BEFORE_REFINE`] slow ones in a row.
    fn note_full_step(&mut self, before: f64, after: f64) {
        if after > SLOW_CONTRACTION * before {
            self.slow += 1;
            if self.slow >= SLOW_STEPS_BEFORE_REFINE && self.sys.refine(&self.x) {
                self.jacobian = None;
                self.slow = 0;
            }
        } else {
            self.slow = 0;
        }
    }

    /// A chord step with a kept Jacobian: full length only, and it must
    /// halve `max |f|`.
    pub(super) fn chord_step(&mut self, dx: &DVector<f64>, res: f64) -> Result<Step> {
        let xt: Vec<f64> = self.x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
        match self.sys.residual(&xt) {
            Ok(rt) if inf_norm(&rt) <= 0.5 * res => {
                let after = inf_norm(&rt);
                // slow (linear) contraction, or the last iteration next:
                // a fresh Jacobian for the next step
                if after > 0.25 * res || self.iterations + 1 >= self.opts.max_iter {
                    self.jacobian = None;
                }
                self.x = xt;
                self.r = rt;
                self.note_full_step(res, after);
                Ok(Step::Moved)
            }
            Err(Error::Interrupted) => Err(Error::Interrupted),
            _ => {
                self.jacobian = None;
                Ok(Step::Redo)
            }
        }
    }

    /// Armijo backtracking (plain halving) along `dx` from the current point.
    /// `Ok(None)`: converged at the floor after a failed search.
    pub(super) fn line_search(
        &mut self,
        dx: &DVector<f64>,
        slope: f64,
        res: f64,
    ) -> Result<Option<Step>> {
        let phi0 = merit(&self.r);
        let mut t = 1.0;
        loop {
            let xt: Vec<f64> = self
                .x
                .iter()
                .zip(dx.iter())
                .map(|(a, b)| a + t * b)
                .collect();
            let trial = self.sys.residual(&xt);
            let bound = phi0 + 1e-4 * slope;
            if t == 1.0 && !matches!(&trial, Ok(rt) if merit(rt) <= bound) {
                if let Err(Error::Interrupted) = trial {
                    return Err(Error::Interrupted);
                }
                if self.limited(dx, bound, res)? {
                    return Ok(Some(Step::Moved));
                }
            }
            match trial {
                Ok(rt) => {
                    let phi = merit(&rt);
                    if t == 1.0
                        && phi.is_finite()
                        && phi > bound
                        && self.watchdog(&xt, &rt, bound)?
                    {
                        self.history.push((res, false));
                        return Ok(Some(Step::Moved));
                    }
                    if phi.is_finite() && (phi <= phi0 + 1e-4 * t * slope) {
                        let after = inf_norm(&rt);
                        self.x = xt;
                        self.r = rt;
                        self.history.push((res, t < 1.0));
                        if t < 1.0 {
                            // a damped step: the Jacobian is recomputed at the new point
                            self.jacobian = None;
                            self.slow = 0;
                        } else {
                            self.note_full_step(res, after);
                        }
                        return Ok(Some(Step::Moved));
                    }
                }
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(_) => {}
            }
            // plain halving: the residual is only C1 where a TCA's coils
            // touch, and a quadratic model there shrinks the step too far
            t *= 0.5;
            if t < self.opts.min_step || self.over_budget() {
                if t < self.opts.min_step && self.sys.refine(&self.x) {
                    self.jacobian = None;
                    return Ok(Some(Step::Redo));
                }
                return Ok(None);
            }
        }
    }

    /// The system's limited step ([`System::limit_step`]) in place of a
    /// full step `dx` that failed the Armijo bound `bound`: taken (`true`)
    /// if it meets that bound, with a fresh Jacobian next; else the
    /// watchdog pair is tried from the limited point (its Jacobian is that
    /// of the state the limited step reached, not of the overshoot).
    fn limited(&mut self, dx: &DVector<f64>, bound: f64, res: f64) -> Result<bool> {
        let Some(jac) = self.jacobian.as_ref() else {
            return Ok(false);
        };
        let Some(xl) = self.sys.limit_step(&self.x, dx.as_slice(), &self.r, jac) else {
            return Ok(false);
        };
        match self.sys.residual(&xl) {
            Ok(rl) if merit(&rl) <= bound => {
                self.x = xl;
                self.r = rl;
                self.jacobian = None;
                self.slow = 0;
                self.history.push((res, false));
                Ok(true)
            }
            Ok(rl) if merit(&rl).is_finite() => {
                let taken = self.watchdog(&xl, &rl, bound)?;
                if taken {
                    self.history.push((res, false));
                }
                Ok(taken)
            }
            Err(Error::Interrupted) => Err(Error::Interrupted),
            _ => Ok(false),
        }
    }

    /// Watchdog step (Chamberlain, Powell, Lemarechal and Pedersen, Math.
    /// Prog. Study 16, 1982): the full Newton step to `x1` (residual `r1`)
    /// failed the Armijo test; take it anyway, take one more full Newton
    /// step from `x1` with a fresh Jacobian, and keep the pair if it meets
    /// the Armijo bound `bound` of the first step from the current point.
    /// `Ok(false)`: it did not (the caller backtracks from the current point
    /// as usual). Where a force law's slope jumps between `x` and `x1` (a
    /// tendon going taut or slack, TCA coils touching), the Jacobian at `x`
    /// misjudges the step, and backtracking creeps along the kink with steps
    /// of about `1e-6` of the Newton step, for tens of iterations; the
    /// Jacobian at `x1` has the slope of the side the root lies on.
    /// Off after a failed attempt for [`WATCHDOG_COOLDOWN`] iterations, on
    /// non-square systems, for the last iteration, and in a run that takes
    /// full steps only ([`WATCHDOG_MIN_STEP`]).
    fn watchdog(&mut self, x1: &[f64], r1: &[f64], bound: f64) -> Result<bool> {
        if self.cooldown > 0
            || self.opts.min_step > WATCHDOG_MIN_STEP
            || self.iterations + 1 >= self.opts.max_iter
            || x1.len() != r1.len()
            || self.over_budget()
        {
            return Ok(false);
        }
        let jac = match self.sys.residual_and_jacobian(x1) {
            Ok((_, j)) => j,
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(_) => return Ok(self.watchdog_failed()),
        };
        let rv = DVector::from_column_slice(r1);
        let d = match jac.lu().solve(&(-&rv)) {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ => return Ok(self.watchdog_failed()),
        };
        let x2: Vec<f64> = x1.iter().zip(d.iter()).map(|(a, b)| a + b).collect();
        match self.sys.residual(&x2) {
            Ok(r2) if merit(&r2) <= bound => {
                self.x = x2;
                self.r = r2;
                self.iterations += 1;
                self.jacobian = None;
                self.slow = 0;
                Ok(true)
            }
            Err(Error::Interrupted) => Err(Error::Interrupted),
            _ => Ok(self.watchdog_failed()),
        }
    }

    fn watchdog_failed(&mut self) -> bool {
        self.cooldown = WATCHDOG_COOLDOWN;
        false
    }
}

/// Most chord steps with a kept coarse Jacobian (the warm neighbour's, or
/// an earlier round's) still needed, at the contraction of the last one,
/// for which the chord run goes on; beyond, Newton takes a fresh coarse
/// tangent. A coarse tangent costs 3.2 (Fig. 6) to 4.3 (steel) coarse IVPs
/// and Newton from it needs one or two steps, so four chord steps cost
/// about as much. (Newton's own chord rule refreshes only below a 4x
/// contraction: along a warm Fig. 6 sweep the neighbour's Jacobian, handed
/// on from step to step, contracted 5-6x a step, 12 chord steps a run.)
/// Judged from the first step on, although its contraction is also the
/// warm start's nonlinearity (steel +1 %: 39x, then 250x; the refresh
/// costs that solve one IVP more): judged from the second, a Fig. 6 warm
/// sweep's chord runs go on beyond the 12 iterations a step that
/// `tests/test_fig6.py` allows.
pub const CHORD_STEPS_LEFT: f64 = 4.0;

/// Margin of a chord step taken without evaluating its residual: the
/// step after an evaluated one that contracted `max |f|` from `res` to
/// `after` is predicted to reach `after^2 / res` (a chord iteration with a
/// fixed Jacobian converges linearly, at a rate that does not grow as it
/// nears the root), and is taken unevaluated when that is at most this
/// times the tolerance (or floor). Its residual is then not known: the
/// caller's next evaluation decides (the pre-solve's full-grid IVP, which
/// decides convergence in any case). E.g. a cold Fig. 6 solve's second
/// pre-solve round: `max |f|` 1.4e-6, then 4.6e-10 against a coarse
/// tolerance of 1e-11, so the second step is predicted at 1.5e-13 (an
/// evaluation there gives a point bit for bit the same and a residual
/// under 1e-11).
const UNEVALUATED_MARGIN: f64 = 0.1;

/// Chord steps from `x0` with the kept Jacobian `jac` (the coarse
/// pre-solve's, `super::presolve`) while at most
/// [`CHORD_STEPS_LEFT`] more are needed at their contraction; then, unless converged,
/// Newton ([`newton_from`]) from the point reached with a fresh Jacobian.
/// The result carries the Jacobian last used. Where a chord step's
/// contraction predicts that the next one converges with a margin
/// ([`UNEVALUATED_MARGIN`]), that step is taken without evaluating the
/// residual there: the result's `residual` is then empty and its `norm`
/// the prediction.
pub(crate) fn chord_then_newton<S: System>(
    sys: &mut S,
    x0: &[f64],
    jac: &DMatrix<f64>,
    nopts: &NewtonOptions,
) -> Result<NewtonResult> {
    let mut x = x0.to_vec();
    let mut r = sys.residual(&x)?;
    let mut res = inf_norm(&r);
    let lu = jac.clone().lu();
    let mut iterations = 0;
    // the next step's residual predicted from the last one's contraction
    let mut predicted = f64::INFINITY;
    loop {
        let floor = sys.floor(&x, &r);
        if res <= nopts.tol.max(floor) {
            return Ok(NewtonResult {
                x,
                residual: r,
                norm: res,
                floor,
                status: converged_status(res, nopts.tol),
                iterations,
                evaluations: sys.evaluations(),
                jacobian: Some(jac.clone()),
            });
        }
        if predicted <= UNEVALUATED_MARGIN * nopts.tol.max(floor) {
            if let Some(nr) = unevaluated_step(&lu, (x.as_slice(), &r), predicted, floor, jac) {
                return Ok(NewtonResult {
                    iterations: iterations + 1,
                    evaluations: sys.evaluations(),
                    status: converged_status(predicted, nopts.tol),
                    ..nr
                });
            }
        }
        if iterations + 1 >= nopts.max_iter || sys.evaluations() >= nopts.max_evaluations {
            break;
        }
        let rv = nalgebra::DVector::from_column_slice(&r);
        let Some(dx) = lu.solve(&(-rv)).filter(|d| d.iter().all(|v| v.is_finite())) else {
            break;
        };
        let xt: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
        let rt = match sys.residual(&xt) {
            Ok(rt) => rt,
            Err(e @ Error::Interrupted) => return Err(e),
            Err(_) => break,
        };
        let after = inf_norm(&rt);
        if !(after < res) {
            break;
        }
        iterations += 1;
        (x, r) = (xt, rt);
        // chord steps still needed at this contraction
        let needed = (after / nopts.tol).ln() / (res / after).ln();
        predicted = after * (after / res);
        res = after;
        if needed > CHORD_STEPS_LEFT {
            break;
        }
    }
    let rest = NewtonOptions {
        max_iter: nopts.max_iter.saturating_sub(iterations).max(1),
        ..*nopts
    };
    let mut nr = newton_from(sys, &x, &rest, "coarse pre-solve", None)?;
    nr.iterations += iterations;
    Ok(nr)
}

/// The chord step from `x` (residual `r`) with the factorised kept
/// Jacobian `lu` of `jac`, unevaluated: `residual` empty, `norm` the
/// `predicted` one (see [`UNEVALUATED_MARGIN`]); `None` if the step is
/// not finite. The counters are the caller's to set.
fn unevaluated_step(
    lu: &nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    (x, r): (&[f64], &[f64]),
    predicted: f64,
    floor: f64,
    jac: &DMatrix<f64>,
) -> Option<NewtonResult> {
    let dx = lu.solve(&(-DVector::from_column_slice(r)))?;
    if !dx.iter().all(|v| v.is_finite()) {
        return None;
    }
    Some(NewtonResult {
        x: x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect(),
        residual: Vec::new(),
        norm: predicted,
        floor,
        status: Status::Converged,
        iterations: 0,
        evaluations: 0,
        jacobian: Some(jac.clone()),
    })
}

/// [`Status::Converged`] if `norm <= tol`, else at the floor.
pub(crate) fn converged_status(norm: f64, tol: f64) -> Status {
    if norm <= tol {
        Status::Converged
    } else {
        Status::ConvergedAtFloor
    }
}
