//! The Newton solver of the inverse problems with a blocked tip
//! ([`crate::inverse`]) and of branch following ([`crate::branch`]):
//! options, status, result, stop reasons; Armijo backtracking on a scaled
//! merit function; convergence against an estimated rounding floor. (The
//! forward solve's is the error-oriented [`super::nleq`].)
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
//! be integrated) counts as an infinite merit. Where the full step fails the
//! Armijo test, a watchdog step is tried (`Run::watchdog` in
//! `newton_steps.rs`): the full step and one more Newton step from there,
//! kept if together they meet the first step's Armijo bound (a
//! non-monotone step across a kink of a force law, where backtracking creeps).
//!
//! Convergence: `max |f_i| <= max(tol, floor)`, where `floor` is the
//! caller's estimate of the rounding floor of the residual at `x` (the
//! residual cannot be computed more accurately than that). A `tol` below
//! the floor converges to the floor with [`Status::ConvergedAtFloor`]. A
//! line search that fails within `FLOOR_MARGIN` times the floor is also
//! convergence at the floor (rounding noise, not a wrong Jacobian).

use std::time::Instant;

use nalgebra::DMatrix;

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
    /// Switch to a more accurate Jacobian at the current point `x`, if the
    /// system has one; `true` if it did (then a failed line search is
    /// retried with it).
    fn refine(&mut self, _x: &[f64]) -> bool {
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
    /// Smallest line-search step before giving up; above 1/2 (full steps
    /// only) the watchdog step is off too.
    pub min_step: f64,
    /// Evaluation budget (the system's [`System::evaluations`]); reaching it
    /// stops the solve with [`StopReason::Budget`].
    pub max_evaluations: usize,
    /// Wall-clock deadline; passing it stops the solve with [`StopReason::Budget`].
    pub deadline: Option<Instant>,
    /// Stall window `w` (0: off): stop with [`StopReason::LineSearch`] when
    /// the last `w` steps were all damped by the line search and together
    /// reduced `max |f|` by less than half. Such a run is creeping along a
    /// valley of the merit toward a local minimum that is no root; a caller
    /// with a fallback (continuation) should switch to it early.
    pub stall_window: usize,
}

impl NewtonOptions {
    /// `tol`, `max_iter` and `min_step`, no budget, no stall detection.
    pub fn new(tol: f64, max_iter: usize, min_step: f64) -> Self {
        NewtonOptions {
            tol,
            max_iter,
            min_step,
            max_evaluations: usize::MAX,
            deadline: None,
            stall_window: 0,
        }
    }
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

/// A full step whose contraction `max |f_new| / max |f|` exceeds this is slow
/// (an exact Newton step contracts quadratically near a root).
const SLOW_CONTRACTION: f64 = 0.25;

/// Consecutive slow full steps after which the system's Jacobian is refined
/// ([`System::refine`]): linear convergence at a fixed rate is the mark of
/// an inexact Jacobian (measured: a coarse-grid Jacobian on a helical
/// tendon contracted 3.4x per step, 22 iterations to 1e-8). Three, by
/// measurement on the first 300 benchmark designs: never refining gave a
/// worst case of 16,079 IVP-equivalents, refining after 2 slow steps a
/// median of 28.7 (full-grid tangents taken too early), after 3 a median
/// of 25.1 and a worst case of 1,933, with the same designs converged.
const SLOW_STEPS_BEFORE_REFINE: usize = 3;

/// Iterations without a watchdog step after a failed one (see `Run::watchdog`).
const WATCHDOG_COOLDOWN: usize = 2;

/// Largest `min_step` with a watchdog step (see `Run::watchdog`): a run
/// whose line search takes full steps only (`min_step` above 1/2) treats
/// a failed full step as the end of its reach (its caller has a cheaper
/// way on, a shorter continuation step), and near a fold the watchdog's
/// pairs cycle back to the same point.
const WATCHDOG_MIN_STEP: f64 = 0.5;

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

/// The state of one Newton run.
struct Run<'a, S: System> {
    sys: &'a mut S,
    opts: &'a NewtonOptions,
    solver: &'static str,
    x: Vec<f64>,
    r: Vec<f64>,
    iterations: usize,
    best: f64,
    /// The Jacobian to use next (kept from an earlier iteration, or `jac0`).
    jacobian: Option<DMatrix<f64>>,
    /// Whether the Jacobian in use was computed at the current point.
    fresh: bool,
    /// Consecutive slow full steps (see [`SLOW_CONTRACTION`]).
    slow: usize,
    /// `max |f|` before each fresh step and whether the step was damped.
    history: Vec<(f64, bool)>,
    /// Iterations left before the next watchdog attempt (see `Run::watchdog`).
    cooldown: usize,
}

/// What a step did.
enum Step {
    /// Moved to a new point.
    Moved,
    /// Redo the iteration with a fresh Jacobian at the same point.
    Redo,
}

impl<S: System> Run<'_, S> {
    fn fail(&self, stop: StopReason, detail: &str) -> Error {
        Error::NotConverged {
            solver: self.solver,
            iterations: self.iterations,
            evaluations: self.sys.evaluations(),
            residual: self.best,
            stop,
            reason: detail.into(),
        }
    }

    fn done(&mut self, res: f64, floor: f64, status: Status) -> NewtonResult {
        NewtonResult {
            x: std::mem::take(&mut self.x),
            residual: std::mem::take(&mut self.r),
            norm: res,
            floor,
            status,
            iterations: self.iterations,
            evaluations: self.sys.evaluations(),
            jacobian: self.jacobian.take(),
        }
    }

    fn over_budget(&self) -> bool {
        self.sys.evaluations() >= self.opts.max_evaluations
            || self.opts.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// The convergence, limit and budget tests at the current point.
    fn check(&mut self) -> Result<Option<NewtonResult>> {
        let res = inf_norm(&self.r);
        if !res.is_finite() {
            return Err(self.fail(StopReason::NonFinite, "non-finite residual"));
        }
        self.best = self.best.min(res);
        let floor = self.sys.floor(&self.x, &self.r);
        if res <= self.opts.tol.max(floor) {
            let status = if res <= self.opts.tol {
                Status::Converged
            } else {
                Status::ConvergedAtFloor
            };
            return Ok(Some(self.done(res, floor, status)));
        }
        if self.iterations >= self.opts.max_iter {
            return Err(self.fail(StopReason::IterationLimit, "iteration limit reached"));
        }
        if self.over_budget() {
            return Err(self.fail(
                StopReason::Budget,
                "work budget (IVPs or time limit) exhausted",
            ));
        }
        if self.stalled() {
            return Err(self.fail(
                StopReason::LineSearch,
                "stalled: damped steps no longer reduce the residual",
            ));
        }
        Ok(None)
    }

    /// See [`NewtonOptions::stall_window`].
    fn stalled(&self) -> bool {
        let w = self.opts.stall_window;
        let h = &self.history;
        w > 0
            && h.len() >= w
            && h[h.len() - w..].iter().all(|&(_, damped)| damped)
            && inf_norm(&self.r) > 0.5 * h[h.len() - w].0
    }
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
    let r = sys.residual(x0)?;
    let jacobian = jac0
        .filter(|j| {
            j.nrows() == r.len() && j.ncols() == x0.len() && j.iter().all(|v| v.is_finite())
        })
        .cloned();
    let mut run = Run {
        best: inf_norm(&r),
        sys,
        opts,
        solver,
        x: x0.to_vec(),
        r,
        iterations: 0,
        jacobian,
        fresh: false,
        slow: 0,
        history: Vec::new(),
        cooldown: 0,
    };
    loop {
        if let Some(done) = run.check()? {
            return Ok(done);
        }
        cancel::check()?;
        run.iterations += 1;
        run.cooldown = run.cooldown.saturating_sub(1);
        let res = inf_norm(&run.r);
        let jac = match run.jacobian.take() {
            Some(j) => j,
            None => {
                run.fresh = true;
                // keep the plain residual (the Jacobian's is equal to rounding)
                run.sys.residual_and_jacobian(&run.x)?.1
            }
        };
        let Some((dx, slope)) = run.direction(&jac)? else {
            // a kept Jacobian gone singular or not descending: recompute it
            run.iterations -= 1;
            continue;
        };
        run.jacobian = Some(jac);
        let step = if !run.fresh {
            run.chord_step(&dx, res)?
        } else {
            run.fresh = false;
            match run.line_search(&dx, slope, res)? {
                Some(step) => step,
                None => {
                    let floor = run.sys.floor(&run.x, &run.r);
                    if res <= FLOOR_MARGIN * floor {
                        return Ok(run.done(res, floor, Status::ConvergedAtFloor));
                    }
                    if run.over_budget() {
                        return Err(run.fail(
                            StopReason::Budget,
                            "work budget (IVPs or time limit) exhausted",
                        ));
                    }
                    return Err(run.fail(
                        StopReason::LineSearch,
                        "line search failed to reduce the residual",
                    ));
                }
            }
        };
        if let Step::Redo = step {
            run.iterations -= 1;
        }
    }
}

pub use super::fn_system::FnSystem;

#[path = "newton_steps.rs"]
mod steps;

#[cfg(test)]
#[path = "newton_tests.rs"]
mod tests;
