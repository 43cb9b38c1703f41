//! The boundary value problem (paper Section III, eqs 32-33) by Newton
//! shooting with the exact Jacobian.
//!
//! Unknowns (scaled to be dimensionless and of order one):
//! `x = [nu(0), L omega(0), delta_1/L, ..., delta_N/L]` where `delta_i` is
//! the guessed total elongation of actuator `i` that sets its tension.
//! Residuals: the tip force and moment balance (32)-(33) as strain errors,
//! `r_F L^2 / (E I)` and `r_M L / (E I)`, and the elongation agreement
//! `(delta_i(s_end) - delta_i) / L`. The conditions at actuator anchors inside
//! the body are met exactly by the point loads applied during integration.
//!
//! The Jacobian is exact ([`Shot::jacobian`]: tangents of the discrete RK4
//! map), the Newton solver is [`crate::solve::newton()`], and a cold solve that
//! fails falls back on homotopy continuation
//! ([`crate::solve::continuation`]).
//!
//! The parts live in [`super::options`], [`super::residual`],
//! [`super::solution`], [`super::guess`] and [`super::system`]; their public
//! names are re-exported here.

use std::time::{Duration, Instant};

use super::cancel;
use super::continuation::continuation;
use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

pub use super::guess::{initial_guess, linear_guess, reference_guess, warm_guess};
use super::newton::NewtonResult;
pub use super::newton::Status;
pub use super::options::{SolveOptions, DEFAULT_MAX_EVALUATIONS};
use super::predict_warm::ChordPolicy;
use super::presolve::{presolved_shooting, Warm};
pub use super::residual::{
    base_strains, residual_scales, tension_slope, tensions, Loads, Shot, ONSET_BAND,
};
pub use super::solution::{assemble, Solution, TipSolution};
pub(crate) use super::system::{solution_from, FinalIvp, Work};
pub use super::system::{Keep, Shooting, COARSE_JACOBIAN_MIN_STEPS, STALL_WINDOW};

/// Solve the forward kinetostatics for actuator `inputs` (temperature \[C\]
/// for TCAs, tension \[N\] or pull \[m\] for tendons).
///
/// Newton shooting with the exact Jacobian from [`initial_guess`] (warm from
/// `warm` if given); if that fails, homotopy continuation from the warm
/// solution's inputs (or, cold, from the reference configuration in the
/// inputs and the loads). The returned `iterations` and `evaluations` count
/// all the work done; `continuation_steps` records the path. With
/// `opts.equilibrium_tol` set, the grid is then refined until the global
/// equilibrium check holds to it ([`SolveOptions::equilibrium_tol`]).
///
/// ```
/// use tcarod::experiments::fig6_square;
/// use tcarod::shooting::{solve, SolveOptions};
/// let robot = fig6_square(true); // two TCA legs, gravity
/// let sol = solve(&robot, &[100.0, 100.0], &SolveOptions::default(), None).unwrap();
/// assert!(sol.residual <= 1e-10);
/// assert!(sol.tip_position().x < 0.0); // the heated extension TCAs bend it toward -x
/// ```
pub fn solve(
    robot: &Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    let sol = solve_loaded(robot, inputs, &Loads::of(robot), opts, warm)?;
    super::equilibrium::refine_to_equilibrium(robot, inputs, opts, sol)
}

pub(crate) fn is_budget_error(e: &Error) -> bool {
    matches!(
        e,
        Error::NotConverged {
            stop: StopReason::Budget,
            ..
        }
    )
}

pub(crate) fn is_input_error(e: &Error) -> bool {
    matches!(
        e,
        Error::InvalidParameter { .. } | Error::InvalidInput { .. } | Error::Interrupted
    )
}

/// [`solve`] with explicit tip loads.
pub fn solve_loaded(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    solve_along(robot, inputs, loads, opts, warm, ChordPolicy::SINGLE)
}

/// [`solve_loaded`] with the warm run's chord steps under `chord`
/// ([`ChordPolicy::BATCH`]: a row of a sweep, whose Jacobian the next
/// row takes on).
pub(crate) fn solve_along(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    chord: ChordPolicy,
) -> Result<Solution> {
    match solve_direct(robot, inputs, loads, opts, warm, Keep::Nodes, chord)? {
        Solved::Newton(nr, last, mut work) => {
            solution_from(robot, inputs, loads, opts, nr, last, &mut work)
        }
        Solved::Solution(s) => Ok(s),
    }
}

/// What [`solve_direct`] found: a converged direct Newton run (its result,
/// the IVP at its solution if that was the last one integrated, and the
/// work so far), or a whole solution from the continuation fallback.
pub(crate) enum Solved {
    /// The direct Newton run converged; no solution is assembled yet.
    Newton(NewtonResult, Option<FinalIvp>, Work),
    /// The direct run failed and the continuation found this solution.
    Solution(Solution),
}

/// [`solve_loaded`] up to the direct Newton run's result: the solution is
/// not assembled, and `keep` says what Newton's IVPs record (with
/// [`Keep::Verdict`], the stability verdict's integration where Newton is
/// predicted to stop, from which [`crate::stability::solve_checked`]
/// assembles the solution).
pub(crate) fn solve_direct(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    keep: Keep,
    chord: ChordPolicy,
) -> Result<Solved> {
    validate(robot, inputs, loads, opts, warm)?;
    cancel::check()?;
    let mut work = Work::start(opts);
    let mut x0 = match warm {
        Some(w) => super::predict::predicted_guess(robot, inputs, w),
        None => initial_guess(robot, inputs, None),
    };
    if warm.is_none() {
        linear_guess(robot, inputs, loads, &mut x0);
    }
    let start = warm.map(|w| Warm {
        unknowns: &w.unknowns,
        inputs: &w.inputs,
        jacobian: w.newton_jacobian.as_ref(),
    });
    // a cold direct run that needs heavy damping hands over to continuation
    let cold_opts = SolveOptions {
        min_step: opts.min_step.max(DIRECT_MIN_STEP),
        ..*opts
    };
    let direct = match start {
        Some(w) => super::predict_warm::warm_shooting(
            robot,
            inputs,
            loads,
            opts,
            &x0,
            (w, chord),
            keep,
            &mut work,
        ),
        None => {
            (work.refine_within, work.cold_direct) = (DIRECT_REFINE_WITHIN, true);
            let out =
                presolved_shooting(robot, inputs, loads, &cold_opts, &x0, None, keep, &mut work);
            (work.refine_within, work.cold_direct) = (f64::INFINITY, false);
            out
        }
    };
    let first = match direct {
        Ok((nr, last)) => return Ok(Solved::Newton(nr, last, work)),
        Err(e) if is_input_error(&e) || is_budget_error(&e) => return Err(e),
        Err(first) => first,
    };
    let cont = match continuation(robot, inputs, loads, opts, warm, &mut work) {
        Ok(s) => return Ok(Solved::Solution(s)),
        Err(e) => e,
    };
    if warm.is_some()
        || cold_opts.min_step <= opts.min_step
        || is_input_error(&cont)
        || is_budget_error(&cont)
    {
        return Err(combined_error(first, cont, &work));
    }
    // the cut direct run's full damping (and stall window), the last resort
    work.stall_window = STALL_WINDOW;
    match presolved_shooting(robot, inputs, loads, opts, &x0, None, keep, &mut work) {
        Ok((nr, last)) => Ok(Solved::Newton(nr, last, work)),
        Err(e) if is_input_error(&e) || is_budget_error(&e) => Err(e),
        Err(_) => Err(combined_error(first, cont, &work)),
    }
}

/// The checks of a solve request: robot, inputs, options, a warm start's
/// size and finite tip loads.
pub(crate) fn validate(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<()> {
    robot.validate()?;
    robot.check_inputs(inputs)?;
    opts.validate()?;
    if let Some(w) = warm {
        if w.unknowns.len() != 6 + robot.actuators.len()
            || w.tensions.len() != robot.actuators.len()
        {
            return Err(Error::input(
                "warm_start",
                format!(
                    "solution of a robot with {} actuators, this one has {}",
                    w.tensions.len(),
                    robot.actuators.len()
                ),
            ));
        }
    }
    for (name, v) in [
        ("tip_force [N]", &loads.tip_force),
        ("tip_moment [N m]", &loads.tip_moment),
    ] {
        // (the name formatted only for the error: validated every solve)
        for (k, z) in v.iter().enumerate().filter(|(_, z)| !z.is_finite()) {
            crate::error::finite(&format!("{name}[{k}]"), *z)?;
        }
    }
    Ok(())
}

/// Smallest line-search step of a cold solve's direct Newton run (the
/// options' `min_step` if larger): a direct run that backtracks further
/// hands over to continuation at once, which is then the cheaper way: a
/// run that needs deeper damping is far from its root, and backtracking
/// down to `t = 1e-6` costs an IVP per halving, tens of IVPs in a run
/// that mostly fails all the same. Should the continuation fail too, the
/// direct run is repeated with the options' own `min_step`: a body past
/// self-weight buckling, whose homotopy path can meet a fold, may converge
/// directly only with heavy damping. A larger bound saves more work but
/// lets the direct run's long steps carry a body past buckling onto
/// another equilibrium branch than the damped run's; at `0.1` the
/// converged tips are those of full backtracking, to rounding. A tuning
/// constant, chosen by experiment on the tuning seed
/// ([`crate::problems::TUNING_SEED`]) of the design benchmark
/// (`benches/designs.rs`).
pub const DIRECT_MIN_STEP: f64 = 0.1;

/// Largest scaled `max |r|` at which a cold solve's direct Newton run takes
/// the full grid's Jacobian after a line search failed with the coarse
/// grid's (see `Shooting::refine`); a run that has not come this near a
/// root hands over to continuation instead. Far from a root a failed line
/// search is the residual's nonlinearity, not the coarse Jacobian's error
/// (~1e-4 relative), and the full grid's tangents (several IVP times each)
/// do not cure it: a run whose `max |r|` wanders between a few units and
/// tens takes one full-grid tangent after another and fails all the same.
/// Near a root the coarse Jacobian's error can be what fails the line
/// search, and there the full grid's tangent spares the solve a
/// continuation (never refining sends such runs to continuation). The
/// bound moves which way a solve converges, not where (the converged tips
/// agree to rounding). A tuning constant, chosen by experiment on the
/// tuning seed of the design benchmark (`benches/designs.rs`).
pub const DIRECT_REFINE_WITHIN: f64 = 5.0;

/// The error with which a cold direct run ends when its first coarse
/// Newton run, from the guess, failed with `e` (`work` holds its IVPs; a
/// Newton failure is given the solve's totals): the direct run hands over
/// to continuation without full-grid Newton from the guess. Where the
/// coarse grid resolves the design, that Newton run retraces the coarse
/// iterates and fails alike, with each of its Jacobians (coarse, full,
/// slack side), a large share of a hard solve's work. The
/// few runs that would converge on the full grid converge through
/// continuation instead, to the same equilibrium (tips agreeing to
/// rounding), at a moderate extra cost. A coarse run that failed in an IVP
/// (anchor loads unconverged on coarse steps longer than a tendon's
/// bending length) is handed over alike, since the full grid's Newton run
/// from the same guess meets the same strongly bent body. Finer rules
/// (handing over only from a coarse best `max |r|` above a bound, or only
/// where the full grid's residual at the guess is within 10 % of the
/// coarse one, for an IVP more) keep more of the retracing runs; the plain
/// rule is a tuning choice, made by experiment on the tuning seed of the
/// design benchmark (`benches/designs.rs`).
pub(crate) fn handed_over(e: Error, work: &mut Work) -> Error {
    match e {
        Error::NotConverged {
            iterations,
            residual,
            stop,
            reason,
            ..
        } => {
            work.iterations += iterations;
            Error::NotConverged {
                solver: "forward shooting",
                iterations: work.iterations,
                evaluations: work.evaluations,
                residual,
                stop,
                reason: format!("{reason} (coarse grid, from the cold guess)"),
            }
        }
        e => e,
    }
}

/// The error of a solve whose direct Newton run failed with `first` and
/// whose continuation failed with `cont`: the budget's if the continuation
/// ran out of it, else the one with the smaller best residual.
fn combined_error(first: Error, cont: Error, work: &Work) -> Error {
    let r0 = match &first {
        Error::NotConverged { residual, .. } => *residual,
        _ => f64::INFINITY,
    };
    match cont {
        Error::NotConverged {
            stop: StopReason::Budget,
            residual,
            reason,
            ..
        } => Error::NotConverged {
            solver: "forward shooting",
            iterations: work.iterations,
            evaluations: work.evaluations,
            residual: r0.min(residual),
            stop: StopReason::Budget,
            reason,
        },
        Error::NotConverged {
            residual,
            stop,
            reason,
            ..
        } => match first {
            Error::NotConverged {
                stop: s0,
                reason: why0,
                solver,
                ..
            } if r0 <= residual => Error::NotConverged {
                solver,
                iterations: work.iterations,
                evaluations: work.evaluations,
                residual: r0,
                stop: s0,
                reason: format!("{why0}; continuation failed too"),
            },
            _ => Error::NotConverged {
                solver: "forward shooting",
                iterations: work.iterations,
                evaluations: work.evaluations,
                residual,
                stop,
                reason: format!("continuation: {reason}"),
            },
        },
        Error::Interrupted => cont,
        _ => first,
    }
}

/// [`solve_loaded`] returning only the tip pose (no profile is recorded,
/// which saves an IVP and its allocations). `warm`: a neighbouring tip
/// solution, from which the start is predicted as [`solve`]'s is. Cold,
/// the same direct run (cut at [`DIRECT_MIN_STEP`]), continuation and
/// repeat as a single cold solve's (`solve_direct`). Warm, falls back on
/// [`solve_loaded`] (with its continuation) when the direct Newton solve
/// fails. Inputs are not validated here: call `robot.check_inputs` first.
pub fn solve_tip(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&TipSolution>,
) -> Result<TipSolution> {
    let Some(w) = warm else {
        return match solve_direct(
            robot,
            inputs,
            loads,
            opts,
            None,
            Keep::Tip,
            ChordPolicy::SINGLE,
        )? {
            Solved::Newton(nr, last, work) => {
                tip_solution(robot, inputs, loads, opts, (nr, last), work)
            }
            Solved::Solution(s) => Ok(TipSolution::from_solution(s)),
        };
    };
    let mut work = Work::start(opts);
    match super::predict_warm::tip_shooting(robot, inputs, loads, opts, w, &mut work) {
        Ok(out) => tip_solution(robot, inputs, loads, opts, out, work),
        Err(e) if is_input_error(&e) || is_budget_error(&e) => Err(e),
        Err(_) => {
            // the fallback gets what is left of the budget
            let rest = SolveOptions {
                max_evaluations: opts.max_evaluations.saturating_sub(work.evaluations).max(1),
                time_limit: work.deadline.map(|d| {
                    d.saturating_duration_since(Instant::now())
                        .max(Duration::from_nanos(1))
                }),
                ..*opts
            };
            let w = assemble(robot, &w.inputs, loads, &w.unknowns, opts.steps, 0, 0)?;
            let mut s =
                TipSolution::from_solution(solve_loaded(robot, inputs, loads, &rest, Some(&w))?);
            s.iterations += work.iterations;
            s.evaluations += work.evaluations;
            Ok(s)
        }
    }
}

/// The tip solution of a converged direct run: the tip of its last IVP if
/// that was at the solution, else of one more (counted).
fn tip_solution(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    (nr, last): (NewtonResult, Option<FinalIvp>),
    mut work: Work,
) -> Result<TipSolution> {
    let (ivp, tau) = match last {
        Some(last) => (last.ivp, last.tensions),
        None => {
            work.evaluations += 1;
            let (_, ivp, tau) =
                Shot::new(robot, inputs, loads, opts.steps).residual(&nr.x, false)?;
            (ivp, tau)
        }
    };
    Ok(TipSolution {
        position: ivp.tip.p,
        rotation: ivp.tip.rotation(),
        unknowns: nr.x,
        tensions: tau,
        inputs: inputs.to_vec(),
        iterations: work.iterations,
        evaluations: work.evaluations,
        newton_jacobian: nr.jacobian,
    })
}

/// Solve along a sequence of input vectors, each warm-started from the
/// previous solution (natural-parameter continuation for temperature or
/// load sweeps).
///
/// Each row hands its Jacobian on to the next, as a batch row does, so its
/// chord steps refresh the Jacobian sooner than a single warm solve's
/// ([`ChordPolicy::BATCH`]): along a sweep the next row is near, so a
/// fresh Jacobian serves it too (`examples/warm_counts.rs`, `--batch`,
/// counts the IVPs a row). The solutions are those of [`solve`] to `tol`.
pub fn sweep(robot: &Robot, inputs: &[Vec<f64>], opts: &SolveOptions) -> Result<Vec<Solution>> {
    let loads = Loads::of(robot);
    let mut out: Vec<Solution> = Vec::with_capacity(inputs.len());
    for q in inputs {
        cancel::check()?;
        let sol = solve_along(robot, q, &loads, opts, out.last(), ChordPolicy::BATCH)?;
        out.push(super::equilibrium::refine_to_equilibrium(
            robot, q, opts, sol,
        )?);
    }
    Ok(out)
}
