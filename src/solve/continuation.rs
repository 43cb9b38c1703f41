//! Homotopy continuation for forward solves that fail from their initial
//! guess.
//!
//! Cold (no warm start): the homotopy `H(lambda)` runs from the reference
//! configuration (reference inputs, no loads: the straight or pre-curved,
//! unactuated body, an exact solution) to the problem, scaling the inputs'
//! departure from the reference and every dead load (gravity, distributed
//! force and moment, tip wrench) by `lambda`. Warm: from the warm solution's
//! inputs to the new ones at full load. Steps are adaptive: doubled after a
//! step that converged in at most [`EASY_ITERATIONS`] Newton iterations,
//! quartered after a failure, down to [`MIN_STEP`]. Each step starts from
//! a polynomial predictor through the last converged points
//! ([`PREDICTOR_POINTS`]). A step's Newton run is a
//! corrector: it converges only to [`INTERMEDIATE_TOL`] and gives up after
//! [`HOMOTOPY_STALL_WINDOW`] damped steps that do not halve the residual
//! (then the step is quartered); a predictor whose residual exceeds
//! [`PREDICTOR_REJECT`] is refused after its first IVP and the step
//! shortened at once; see those constants for their reasons. The path (the `lambda` of
//! each converged step) is recorded in `Solution::continuation_steps`.
//! A cold path runs on a coarse grid first and is finished on the full
//! grid ([`crate::solve::coarse_path`]); the full grid's path only if that
//! fails (from where the coarse path stalled, if it did).
//! (Pseudo-arclength continuation through folds is the stability module's.)

use super::cancel;
use super::coarse_path::coarse_path;
use super::corrector::correct;
use super::newton::NewtonResult;
use super::shooting::{
    is_input_error, reference_guess, solution_from, FinalIvp, Loads, Solution, SolveOptions, Work,
};
pub(crate) use super::track::{Track, Watch};
use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

/// Newton iterations under which the next homotopy step doubles.
pub const EASY_ITERATIONS: usize = 4;
/// Tolerance of the intermediate homotopy steps (scaled residual). A
/// step's solution only starts the next step's predictor, which lands
/// within the next corrector's reach as long as this error is small against
/// the predictor's own (the quadratic predictor's `O(dl^3)` error, of
/// order 1e-2 to 1 at the steps a strongly bent path takes): a tighter
/// tolerance spends corrector iterations whose gain the next predictor's
/// error swamps. A looser one lets the points' errors into the predictor
/// polynomial, whose extrapolation amplifies them (one step beyond three
/// equally spaced points the Lagrange weights are `1, -3, 3`). A tuning
/// constant, chosen by experiment on the tuning seed
/// ([`crate::problems::TUNING_SEED`]) of the design benchmark
/// (`benches/designs.rs`).
pub const INTERMEDIATE_TOL: f64 = 1e-4;
/// Points of the homotopy's predictor polynomial (the current converged
/// point and up to this many minus one before it): 3, a quadratic. The
/// paths of soft, heavily loaded bodies bend strongly in `lambda`, and
/// single shooting reaches only a small neighbourhood of them (exact
/// undamped Newton can diverge from an error of a few hundredths in the
/// base curvature `L omega`), so the predictor's order sets the step: the
/// secant's error is `O(dl^2)`, the quadratic's `O(dl^3)`, and at the same
/// step the quadratic predictor lands within reach where the secant's
/// Newton run diverges. A tangent (Euler) predictor, from the exact
/// Jacobian, is also `O(dl^2)` and costs an IVP more. `examples/
/// trace_homotopy.rs` follows a bent path accurately and compares the
/// predictors from points on it (`docs/choices.md`, the quadratic
/// predictor).
pub const PREDICTOR_POINTS: usize = 3;
/// Smallest line-search step of a homotopy corrector's first attempt at a
/// step (see `step_options`): 0.6 allows the full step only (then the
/// full-grid Jacobian, [`crate::solve::newton::System::refine`]). A
/// predictor from which the full Newton step fails the Armijo test lies
/// outside the corrector's reach, and backtracking from there costs an
/// IVP per halving and ends, mostly, in a failed step all the same; so
/// the step is quartered at once, and a shorter step's predictor is
/// nearer. A retry after a failure backtracks further, to
/// [`RETRY_MIN_STEP`]: a path with a kink (see there) needs a damped step
/// across it, so the full step alone on retries too would lose such paths.
/// A tuning constant, chosen by experiment on the tuning seed of the
/// design benchmark (`benches/designs.rs`), with the quadratic predictor
/// ([`PREDICTOR_POINTS`]).
pub const CORRECTOR_MIN_STEP: f64 = 0.6;
/// Smallest line-search step of a homotopy corrector's retry, after a
/// failed attempt at a longer step (see `step_options`): 0.3 allows one
/// halving. Where the path has a kink (a tendon going taut or slack, coils
/// touching) a retry's full step may overshoot it, and one halving brings
/// it back to the near side. Kinks are handled by the watchdog and the
/// limited step of `newton_steps`, not by deep backtracking: backtracking
/// further mostly creeps where no point is within reach (near a fold of
/// the path a retry accepts steps at `t` = 1/16 to 1/128, each an IVP per
/// halving, and fails after tens of IVPs). A tuning constant, chosen by
/// experiment on the tuning seed of the design benchmark
/// (`benches/designs.rs`); over the range of smaller values it moves no
/// converged tip, only the work.
pub const RETRY_MIN_STEP: f64 = 0.3;
/// Smallest homotopy step.
pub const MIN_STEP: f64 = 1e-4;
/// Largest predictor residual `max |r(x0)|` (scaled) a corrector is run
/// from; a farther predictor is refused after its one IVP, and the step
/// shortened by `rejected_step_factor` (once per point: the retry runs
/// in full, since across a kink of the path no step is short enough).
/// A corrector started ten or more units of scaled residual from the path
/// almost never converges, and fails only after some ten IVPs; refusing
/// the predictor at one IVP's cost saves them. The bound is loose on
/// purpose: a path with a kink near `lambda = 0` can fail from predictor
/// residuals far below one and pass only on some step sequences, and a tighter
/// bound, by changing the sequence, can lose it. A tuning constant, chosen
/// by experiment on the tuning seed of the design benchmark
/// (`benches/designs.rs`).
pub const PREDICTOR_REJECT: f64 = 30.0;

/// The factor that shortens a step whose predictor residual `r0` exceeded
/// [`PREDICTOR_REJECT`]: `r0^(-1/3)` (the quadratic predictor's error is
/// `O(dl^3)`, so this aims at a predictor residual of order one), within
/// `[1/16, 1/2]`. The aim (order one rather than smaller) is a tuning
/// choice, made by experiment on the tuning seed of the design benchmark
/// (`benches/designs.rs`): a predictor of order one is within the
/// corrector's reach, and a shorter step costs path points.
fn rejected_step_factor(r0: f64) -> f64 {
    r0.powf(-1.0 / 3.0).clamp(0.0625, 0.5)
}
/// Stall window of every homotopy step's Newton run (see
/// [`crate::solve::newton::NewtonOptions::stall_window`]): a corrector
/// whose damped steps creep (no halving of `max |f|` over 2 of them) is
/// stopped, and the homotopy step quartered. Backtracking in a valley of
/// the merit costs 10-20 IVPs an iteration (an IVP per halving, some 17
/// halvings down to `t = 1e-5`), and a creeping corrector runs to its
/// iteration limit at that price, while a quartered step's predictor is
/// nearer the path. A tuning constant, chosen by experiment on the tuning
/// seed of the design benchmark (`benches/designs.rs`), with
/// [`INTERMEDIATE_TOL`].
pub const HOMOTOPY_STALL_WINDOW: usize = 2;

/// The robot, inputs and loads at homotopy parameter `lam` in `[0, 1]`:
/// inputs linear from `from` (the reference inputs) to `inputs`, and with
/// `scale_loads` the gravity, distributed and tip loads scaled by `lam`
/// (exactly the given problem at `lam >= 1`).
pub fn at(
    robot: &Robot,
    from: &[f64],
    inputs: &[f64],
    loads: &Loads,
    scale_loads: bool,
    lam: f64,
) -> (Robot, Vec<f64>, Loads) {
    if lam >= 1.0 {
        return (robot.clone(), inputs.to_vec(), *loads);
    }
    let mut r = robot.clone();
    let mut l = *loads;
    if scale_loads {
        r.body.gravity *= lam;
        r.body.distributed_force *= lam;
        r.body.distributed_moment *= lam;
        l.tip_force *= lam;
        l.tip_moment *= lam;
    }
    let inp = from
        .iter()
        .zip(inputs)
        .map(|(a, b)| a + lam * (b - a))
        .collect();
    (r, inp, l)
}

/// Initial guess of a homotopy step from the converged `x` (tensions
/// `tau`) at `lam` to `lt`: the polynomial through the last converged
/// points (`prev`: up to two earlier `(lambda, unknowns)`, most recent
/// last, and `(lam, x)`) extrapolated to `lt` when there are any (see
/// [`PREDICTOR_POINTS`]), else `x` with the actuator elongations that keep
/// the tensions `tau` at the step's inputs (see `initial_guess`).
pub(crate) fn predictor(
    robot: &Robot,
    inputs: &[f64],
    x: &[f64],
    tau: &[f64],
    prev: &[(f64, Vec<f64>)],
    lam: f64,
    lt: f64,
) -> Vec<f64> {
    if !prev.is_empty() {
        // Lagrange extrapolation through (prev..., (lam, x))
        let mut pts: Vec<(f64, &[f64])> = prev.iter().map(|(l, v)| (*l, v.as_slice())).collect();
        pts.push((lam, x));
        let mut out = vec![0.0; x.len()];
        for (i, &(li, xi)) in pts.iter().enumerate() {
            let w: f64 = pts
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, &(lj, _))| (lt - lj) / (li - lj))
                .product();
            out.iter_mut().zip(xi).for_each(|(o, v)| *o += w * v);
        }
        return out;
    }
    let len = robot.body.length;
    let mut x0 = x.to_vec();
    for (i, a) in robot.actuators.iter().enumerate() {
        if let Some(d) = a.law.elongation(tau[i], inputs[i]) {
            if d.is_finite() {
                x0[6 + i] = d / len;
            }
        }
    }
    x0
}

/// The budget error of a continuation stopped at `lam`; `residual`: the
/// best residual of its failed Newton runs (infinite if none failed; the
/// caller then reports its direct attempt's).
fn budget_error(work: &Work, lam: f64, residual: f64) -> Error {
    Error::NotConverged {
        solver: "forward shooting",
        iterations: work.iterations,
        evaluations: work.evaluations,
        residual,
        stop: StopReason::Budget,
        reason: format!(
            "work budget (IVPs or time limit) exhausted; continuation at lambda = {lam:.4}"
        ),
    }
}

/// Continuation to `inputs` under `loads` (see the module docs); adds its
/// work to `work`. A cold one runs its path on the coarse grid first
/// ([`coarse_path`]), and the full-grid path only if that fails.
pub(crate) fn continuation(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    work: &mut Work,
) -> Result<Solution> {
    if warm.is_none() {
        if let Some(s) = coarse_path(robot, inputs, loads, opts, work)? {
            return Ok(s);
        }
    }
    let (nr, last, path) = follow(robot, inputs, loads, opts, warm, work)?;
    let mut s = solution_from(robot, inputs, loads, opts, nr, last, work)?;
    s.continuation_steps = path;
    Ok(s)
}

/// The converged end of a homotopy path: Newton's result at `lambda = 1`,
/// its last IVP and the path (the `lambda` of each converged step).
pub(crate) type PathEnd = (NewtonResult, Option<FinalIvp>, Vec<f64>);

/// The homotopy path to `inputs` under `loads` on `opts.steps` (see the
/// module docs); adds its work to `work`.
pub(crate) fn follow(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    work: &mut Work,
) -> Result<PathEnd> {
    let cold = warm.is_none();
    let (from, x, tau, jac) = start(robot, warm);
    let mut track = Track::new(0.0, x, tau, jac, if cold { 0.25 } else { 0.5 });
    follow_from(robot, inputs, loads, opts, &from, cold, &mut track, work)
}

/// The homotopy path from `track`'s point on (inputs from `from`, loads
/// scaled if `cold`) on `opts.steps`; adds its work to `work`. On return
/// (either way) `track` holds the last converged point before `lambda = 1`,
/// the step and the path so far.
#[allow(clippy::too_many_arguments)]
pub(crate) fn follow_from(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    cold: bool,
    at_lam: &mut Track,
    work: &mut Work,
) -> Result<PathEnd> {
    work.stall_window = HOMOTOPY_STALL_WINDOW;
    let mut last_err: Option<Error> = None;
    let mut best = f64::INFINITY; // of the failed Newton runs (for the budget error)
    let mut retry = false; // the last step failed: its retry backtracks further
    let mut reject = PREDICTOR_REJECT; // refused once at a point: the retry runs in full
    let mut failed: Vec<f64> = Vec::new(); // lambdas < 1 of failed retries (`retried_before`)
    while at_lam.lam < 1.0 {
        cancel::check()?;
        let lam = at_lam.lam;
        if work.exhausted() {
            return Err(budget_error(work, lam, best));
        }
        let lt = (lam + at_lam.step).min(1.0);
        if retry && retried_before(&failed, lt) {
            at_lam.step *= 0.25;
            if at_lam.step < MIN_STEP {
                break;
            }
            continue;
        }
        let (r, inp, l) = at(robot, from, inputs, loads, cold, lt);
        let x0 = at_lam.predictor(&r, &inp, lt);
        let least = if retry {
            RETRY_MIN_STEP
        } else {
            CORRECTOR_MIN_STEP
        };
        let step_opts = step_options(opts, lt >= 1.0, least);
        let (jac, last) = (at_lam.jac.as_ref(), lt >= 1.0);
        let (out, first) = correct(&r, &inp, &l, &step_opts, &x0, jac, last, reject, work);
        if let Some(r0) = first.filter(|&r0| r0 > reject) {
            reject = f64::INFINITY;
            at_lam.step = (at_lam.step * rejected_step_factor(r0)).max(MIN_STEP);
            continue;
        }
        reject = PREDICTOR_REJECT;
        match out {
            Ok((nr, last)) => {
                retry = false;
                if lt >= 1.0 {
                    let mut path = at_lam.path.clone();
                    path.push(lt);
                    return Ok((nr, last, path));
                }
                at_lam.path.push(lt);
                if nr.iterations <= EASY_ITERATIONS {
                    at_lam.step *= 2.0;
                }
                at_lam.advance(lt, nr, last, &r, &inp)?;
                at_lam.check_grid(&r, &inp, &l, work)?;
            }
            Err(e) if is_input_error(&e) => return Err(e),
            Err(Error::NotConverged {
                stop: StopReason::Budget,
                residual,
                ..
            }) => return Err(budget_error(work, lam, best.min(residual))),
            Err(e) => {
                if let Error::NotConverged { residual, .. } = &e {
                    best = best.min(*residual);
                }
                last_err = Some(e);
                failed.extend((retry && lt < 1.0).then_some(lt));
                retry = true;
                at_lam.step *= 0.25;
                if at_lam.step < MIN_STEP {
                    break;
                }
            }
        }
    }
    Err(stall_error(last_err, work, at_lam.lam))
}

/// Whether a retry (backtracking further) to `lt` failed before on this path
/// (`failed`: the `lambda` of each failed retry short of 1): a retry is
/// then not run again (the step is quartered as after its failure). Steps
/// halve and double by powers of two, so a path quartering its way to a
/// fold aims its retries at the same `lambda` from successive points, and
/// past the fold each of them fails alike (the target lies beyond the
/// fold, where the path has no point), at the cost of a full retry each
/// (tens of IVPs). A retry is therefore run once per target; a path that
/// could pass it from a nearer point quarters its way there instead.
/// Skipping every step at or past the smallest `lambda` of a failed retry
/// (not only the same target, and first attempts too) would lose paths
/// with a kink: a retry failing at a kink of the path is passed later from
/// a nearer point.
/// The test is exact equality on purpose: a repeat is the same sum of
/// the same dyadic steps, the same float (a step shortened by a refused
/// predictor's factor rarely lands on one again, and then the retry runs).
fn retried_before(failed: &[f64], lt: f64) -> bool {
    failed.contains(&lt)
}

/// Options of one homotopy step: intermediate steps are predictors,
/// converged to [`INTERMEDIATE_TOL`] (or `tol` if looser) within half of `max_iter`; the
/// last one to `tol` within `max_iter`. A Newton run from a first-order
/// predictor that needs more than half the iteration limit is creeping
/// (the path bends within the step); quartering the step is cheaper than
/// finishing it. Half (rather than a fixed small number) leaves room for
/// correctors that converge slowly but surely on a strongly bent path; the
/// fraction is a tuning choice, made by experiment on the tuning seed of
/// the design benchmark (`benches/designs.rs`).
/// The line search backtracks down to `least_step` (or the options'
/// `min_step`, if larger): [`CORRECTOR_MIN_STEP`] on a step's first
/// attempt, [`RETRY_MIN_STEP`] on a retry, `0` (in full) where a point is
/// corrected in place (a grid's change, a fold's snap-through).
pub(crate) fn step_options(opts: &SolveOptions, last: bool, least_step: f64) -> SolveOptions {
    let min_step = opts.min_step.max(least_step);
    if last {
        SolveOptions { min_step, ..*opts }
    } else {
        SolveOptions {
            tol: opts.tol.max(INTERMEDIATE_TOL),
            max_iter: (opts.max_iter / 2).max(EASY_ITERATIONS + 1),
            min_step,
            ..*opts
        }
    }
}

/// The start of the path: the inputs, unknowns, tensions and Jacobian of
/// the warm solution, or of the reference configuration.
pub(crate) type Start = (Vec<f64>, Vec<f64>, Vec<f64>, Option<nalgebra::DMatrix<f64>>);

pub(crate) fn start(robot: &Robot, warm: Option<&Solution>) -> Start {
    match warm {
        Some(w) => (
            w.inputs.clone(),
            w.unknowns.clone(),
            w.tensions.clone(),
            w.newton_jacobian.clone(),
        ),
        None => (
            robot.reference_inputs(),
            reference_guess(robot),
            vec![0.0; robot.actuators.len()],
            None,
        ),
    }
}

/// The error of a path that stalled at `lam` (its last Newton failure).
fn stall_error(last_err: Option<Error>, work: &Work, lam: f64) -> Error {
    match last_err {
        Some(Error::NotConverged {
            solver,
            residual,
            stop,
            reason,
            ..
        }) => Error::NotConverged {
            solver,
            iterations: work.iterations,
            evaluations: work.evaluations,
            residual,
            stop,
            reason: format!("{reason}; continuation stalled at lambda = {lam:.4}"),
        },
        Some(e) => e,
        None => Error::input("inputs", "continuation made no step"),
    }
}
