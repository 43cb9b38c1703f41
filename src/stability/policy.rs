//! What a solve does with the verdict: the stability policy.
//!
//! `solve` must never hand back an unstable equilibrium without saying so.
//! [`Policy::Report`] (the default) computes the verdict as part of the
//! solve and carries it with the solution; [`Policy::Require`] refuses an
//! unstable one; [`Policy::Continue`] moves from an unstable one to a stable
//! equilibrium at the same inputs ([`land`]) and records how;
//! [`Policy::Off`] skips the verdict (hot loops that check stability
//! themselves, or not at all).
//!
//! Cost: the verdict is one tangent integration ([`stability`]), the price
//! of one full-grid Newton Jacobian; where Newton's convergence is
//! predicted it is Newton's last residual evaluation, in place of a plain
//! IVP (see [`solve_checked`]); `Off` saves it.

use std::str::FromStr;

use super::landing::{land, Route};
use super::{stability, stability_profiled, verdict_of, Equilibrium, Stability};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{Loads, Solution, SolveOptions};
use crate::solve::equilibrium::refine_to_equilibrium;
use crate::solve::newton::NewtonResult;
use crate::solve::predict_warm::ChordPolicy;
use crate::solve::shooting::{
    solution_from, solve_along, solve_direct, FinalIvp, Keep, Solved, Work,
};
use crate::solve::solution::assemble_flat;

/// What a solve does with the stability verdict of the equilibrium found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Policy {
    /// No verdict (hot loops; the caller takes responsibility).
    Off,
    /// Compute the verdict and carry it with the solution (the default).
    #[default]
    Report,
    /// Refuse an unstable equilibrium (`NoSolution` naming the margin).
    Require,
    /// From an unstable equilibrium, continue to a stable one at the same
    /// inputs and loads ([`land`]).
    Continue,
}

impl Policy {
    /// The names accepted by [`Policy::from_str`].
    pub const NAMES: [&'static str; 4] = ["report", "require", "continue", "off"];
}

impl FromStr for Policy {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "off" => Ok(Policy::Off),
            "report" => Ok(Policy::Report),
            "require" => Ok(Policy::Require),
            "continue" => Ok(Policy::Continue),
            _ => Err(Error::input(
                "stability",
                format!("{s:?}: must be one of 'report', 'require', 'continue', 'off'"),
            )),
        }
    }
}

/// The unstable equilibrium a [`Policy::Continue`] solve found first, and
/// how it went on to the stable one.
#[derive(Debug, Clone)]
pub struct Continued {
    /// The unstable equilibrium Newton converged to.
    pub from: Solution,
    /// Its verdict.
    pub from_stability: Stability,
    /// How the stable equilibrium was reached.
    pub route: Route,
    /// Stable candidates found (the one nearest `from`'s tip is kept).
    pub candidates: usize,
    /// IVPs integrated to get there (verdicts included).
    pub evaluations: usize,
}

/// A solution with its verdict.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The equilibrium handed back (stable unless the policy is `Report`
    /// or `Off`). Its `evaluations` count the verdict's tangent IVP and, after
    /// a continuation, all the work of it.
    pub solution: Solution,
    /// Its verdict (`None` only with [`Policy::Off`]).
    pub stability: Option<Stability>,
    /// With [`Policy::Continue`], where it came from if the first
    /// equilibrium was unstable.
    pub continued: Option<Continued>,
}

/// [`solve_loaded`](crate::shooting::solve_loaded) (with the accuracy control of
/// [`SolveOptions::equilibrium_tol`]) under a stability [`Policy`] (free tip).
///
/// With a verdict, Newton's IVPs record no nodes: the verdict's tangent
/// integration at the solution (whose real part is the plain IVP, bit for
/// bit) gives the solution's profile. Where Newton's convergence is
/// predicted ([`Keep::Verdict`]) that integration is Newton's last
/// residual evaluation itself, in place of its plain IVP: the verdict then
/// costs no IVP more than the solve without it, only a tangent IVP in place
/// of a plain one; else it costs its own tangent IVP. With the accuracy
/// control on, the solution is recorded and refined first, and the verdict
/// taken on the refined one.
pub fn solve_checked(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    policy: Policy,
) -> Result<Checked> {
    checked_along(
        robot,
        inputs,
        loads,
        opts,
        warm,
        policy,
        ChordPolicy::SINGLE,
    )
}

/// [`solve_checked`] with the warm run's chord steps under `chord`
/// ([`ChordPolicy::BATCH`] for a sweep's row).
fn checked_along(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    policy: Policy,
    chord: ChordPolicy,
) -> Result<Checked> {
    if policy == Policy::Off {
        let sol = solve_along(robot, inputs, loads, opts, warm, chord)?;
        return Ok(Checked {
            solution: refine_to_equilibrium(robot, inputs, opts, sol)?,
            stability: None,
            continued: None,
        });
    }
    // without the accuracy control Newton's solution is final, and its
    // profile comes from the verdict's pass: Newton records no nodes
    let final_newton = opts.equilibrium_tol.is_none();
    let keep = Keep::Verdict {
        tol: opts.tol,
        nodes: !final_newton,
    };
    let (sol, st) = match solve_direct(robot, inputs, loads, opts, warm, keep, chord)? {
        Solved::Newton(nr, last, work) if final_newton => {
            profiled(robot, inputs, loads, opts, nr, last, work)?
        }
        solved => {
            let (sol, pass) = match solved {
                Solved::Newton(nr, mut last, mut work) => {
                    let pass = last.as_mut().and_then(|l| l.verdict.take());
                    let sol = solution_from(robot, inputs, loads, opts, nr, last, &mut work)?;
                    (sol, pass)
                }
                Solved::Solution(sol) => (sol, None),
            };
            let steps = sol.steps;
            let mut sol = refine_to_equilibrium(robot, inputs, opts, sol)?;
            match pass {
                // not refined: the verdict of Newton's last evaluation
                Some(pass) if sol.steps == steps => (sol, verdict_of(robot, &pass)),
                _ => {
                    let st = stability(robot, &sol, &[])?;
                    sol.evaluations += st.evaluations;
                    (sol, st)
                }
            }
        }
    };
    if st.stable || policy == Policy::Report {
        return Ok(Checked {
            solution: sol,
            stability: Some(st),
            continued: None,
        });
    }
    if policy == Policy::Require {
        return Err(unstable_error(&sol, &st));
    }
    let l = land(robot, inputs, loads, &sol, Some(st.mode), opts, false)?;
    let mut solution = l.solution;
    solution.iterations += sol.iterations;
    solution.evaluations = sol.evaluations + l.evaluations;
    Ok(Checked {
        solution,
        stability: Some(l.stability),
        continued: Some(Continued {
            from: sol,
            from_stability: st,
            route: l.route,
            candidates: l.candidates,
            evaluations: l.evaluations,
        }),
    })
}

/// The solution of a converged Newton run `nr` (work `work`) and its
/// verdict, both from the verdict's recorded tangent IVP at `nr.x`: Newton's
/// last evaluation `last` if it was that IVP, else one more (the residual is
/// Newton's, from its last IVP there).
fn profiled(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    nr: NewtonResult,
    last: Option<FinalIvp>,
    work: Work,
) -> Result<(Solution, Stability)> {
    let (st, ivp, tau, evaluations) = match last {
        Some(FinalIvp {
            ivp,
            nodes,
            tensions,
            verdict: Some(pass),
            ..
        }) => {
            let nodes = nodes.unwrap_or_else(|| pass.ivp_nodes());
            (
                verdict_of(robot, &pass),
                (ivp, nodes),
                tensions,
                work.evaluations,
            )
        }
        _ => {
            let eq = Equilibrium {
                along: None,
                unknowns: &nr.x,
                inputs,
                loads: *loads,
                steps: opts.steps,
            };
            let (st, ivp, tau) = stability_profiled(robot, &eq)?;
            let evaluations = work.evaluations + st.evaluations;
            (st, ivp, tau, evaluations)
        }
    };
    let (x, steps, it) = (&nr.x, opts.steps, work.iterations);
    let r = nr.residual.clone();
    let mut sol = assemble_flat(
        robot,
        (inputs, loads, x),
        (steps, it, evaluations),
        r,
        ivp,
        tau,
    );
    sol.newton_jacobian = nr.jacobian;
    sol.status = nr.status;
    sol.floor = nr.floor;
    Ok((sol, st))
}

/// The error of [`Policy::Require`] for an unstable `sol`.
pub fn unstable_error(sol: &Solution, st: &Stability) -> Error {
    let p = sol.tip_position();
    Error::NoSolution {
        reason: format!(
            "the equilibrium found (tip at [{:.6}, {:.6}, {:.6}] m) is unstable: stability \
             margin {:.3e} < 0; ask for stability='continue' to move to a stable one",
            p.x, p.y, p.z, st.margin
        ),
    }
}

/// Solve along rows of `inputs`, each warm-started from the previous
/// solution handed back (its Jacobian taken on, [`ChordPolicy::BATCH`], as
/// in `shooting::sweep`), under `policy` (as `shooting::sweep`, which it
/// replaces when a verdict is wanted). With [`Policy::Continue`] the sweep
/// follows what a physical robot does quasi-statically: where its
/// equilibrium is lost it lands on a stable one and goes on from there.
pub fn sweep_checked(
    robot: &Robot,
    inputs: &[Vec<f64>],
    opts: &SolveOptions,
    policy: Policy,
) -> Result<Vec<Checked>> {
    let loads = Loads::of(robot);
    let mut out: Vec<Checked> = Vec::with_capacity(inputs.len());
    for q in inputs {
        crate::solve::cancel::check()?;
        let warm = out.last().map(|c| &c.solution);
        let c = checked_along(robot, q, &loads, opts, warm, policy, ChordPolicy::BATCH)?;
        out.push(c);
    }
    Ok(out)
}
