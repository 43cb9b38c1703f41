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
//! of one full-grid Newton Jacobian; `Off` saves it.

use std::str::FromStr;

use super::landing::{land, Route};
use super::{stability, Stability};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, Solution, SolveOptions};

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
/// [`SolveOptions::equilibrium_tol`]) under a stability [`Policy`] (free tip):
/// the verdict is one tangent integration at the solution ([`stability`]),
/// counted in the solution's `evaluations`.
pub fn solve_checked(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    policy: Policy,
) -> Result<Checked> {
    let mut sol = solve_loaded(robot, inputs, loads, opts, warm)?;
    if policy == Policy::Off {
        return Ok(Checked {
            solution: sol,
            stability: None,
            continued: None,
        });
    }
    let st = stability(robot, &sol, &[])?;
    sol.evaluations += st.evaluations;
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
/// solution handed back, under `policy` (as `shooting::sweep`, which it
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
        let c = solve_checked(robot, q, &loads, opts, warm, policy)?;
        out.push(c);
    }
    Ok(out)
}
