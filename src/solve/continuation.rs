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
//! the previous solution's strains and tensions. The path (the `lambda` of
//! each converged step) is recorded in `Solution::continuation_steps`.
//! (Pseudo-arclength continuation through folds is the stability module's.)

use super::cancel;
use super::shooting::{
    is_input_error, newton_shooting, reference_guess, solution_from, tensions, Loads, Solution,
    SolveOptions, Work,
};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// Newton iterations under which the next homotopy step doubles.
pub const EASY_ITERATIONS: usize = 4;
/// Tolerance of the intermediate homotopy steps (scaled residual).
pub const INTERMEDIATE_TOL: f64 = 1e-8;
/// Smallest homotopy step.
pub const MIN_STEP: f64 = 1e-4;

/// The robot, inputs and loads at homotopy parameter `lam` in `[0, 1]`.
fn at(
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

/// Continuation to `inputs` under `loads` (see the module docs); adds its
/// work to `work`.
pub(crate) fn continuation(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    work: &mut Work,
) -> Result<Solution> {
    let len = robot.body.length;
    let cold = warm.is_none();
    let from = match warm {
        Some(w) => w.inputs.clone(),
        None => robot.reference_inputs(),
    };
    let mut x = match warm {
        Some(w) => w.unknowns.clone(),
        None => reference_guess(robot),
    };
    let mut tau = match warm {
        Some(w) => w.tensions.clone(),
        None => vec![0.0; robot.actuators.len()],
    };
    let mut jac = warm.and_then(|w| w.newton_jacobian.clone());
    let mut lam = 0.0;
    let mut step: f64 = if cold { 0.25 } else { 0.5 };
    let mut path = Vec::new();
    let mut last_err: Option<Error> = None;
    while lam < 1.0 {
        cancel::check()?;
        let lt = (lam + step).min(1.0);
        let (r, inp, l) = at(robot, &from, inputs, loads, cold, lt);
        // keep the tensions of the previous step (see `initial_guess`)
        let mut x0 = x.clone();
        for (i, a) in r.actuators.iter().enumerate() {
            if let Some(d) = a.law.elongation(tau[i], inp[i]) {
                if d.is_finite() {
                    x0[6 + i] = d / len;
                }
            }
        }
        // intermediate steps are predictors: converged to 1e-8 (or tol if looser)
        let step_opts = if lt >= 1.0 {
            *opts
        } else {
            SolveOptions {
                tol: opts.tol.max(INTERMEDIATE_TOL),
                ..*opts
            }
        };
        match newton_shooting(&r, &inp, &l, &step_opts, &x0, jac.as_ref(), lt >= 1.0, work) {
            Ok((nr, last)) => {
                lam = lt;
                path.push(lt);
                if lam >= 1.0 {
                    let mut s = solution_from(robot, inputs, loads, opts, nr, last, work)?;
                    s.continuation_steps = path;
                    return Ok(s);
                }
                if nr.iterations <= EASY_ITERATIONS {
                    step *= 2.0;
                }
                tau = match last {
                    Some((_, _, t)) => t,
                    None => {
                        let delta: Vec<f64> = nr.x[6..].iter().map(|d| d * len).collect();
                        tensions(&r, &inp, &delta)?
                    }
                };
                x = nr.x;
                if nr.jacobian.is_some() {
                    jac = nr.jacobian;
                }
            }
            Err(e) if is_input_error(&e) => return Err(e),
            Err(e) => {
                last_err = Some(e);
                step *= 0.25;
                if step < MIN_STEP {
                    break;
                }
            }
        }
    }
    Err(match last_err {
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
    })
}
