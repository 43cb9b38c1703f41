//! Landing on a stable equilibrium near a given (unstable, or just past a
//! jump) one: what the physical robot does when its equilibrium is lost.

use std::fmt;

use nalgebra::Vector3;

use super::{stability, Stability};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{
    initial_guess, reference_guess, solve_loaded, Loads, Solution, SolveOptions,
};

/// How a stable equilibrium was reached from another one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Route {
    /// Loading from rest with an imperfection, a tip wrench along the
    /// softest mode of the start, by continuation, then taking the
    /// imperfection away by a warm solve.
    Imperfection,
    /// Newton from the cold (reference) guess.
    Cold,
    /// Newton from the start itself.
    Start,
    /// Newton from the start with its scaled base curvature `L omega_k(0)`
    /// (`k` = 0 or 1, about the body's x or y axis) pushed by `push`.
    Pushed {
        /// Body axis of the pushed base curvature (0: x, 1: y).
        axis: usize,
        /// The push of `L omega_k(0)` \[-\].
        push: f64,
    },
}

impl fmt::Display for Route {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Route::Imperfection => write!(
                f,
                "loading from rest with a tip wrench along the softest mode, then removing it"
            ),
            Route::Cold => write!(f, "Newton from the reference configuration"),
            Route::Start => write!(f, "Newton from the start"),
            Route::Pushed { axis, push } => write!(
                f,
                "Newton from the start with L omega_{}(0) pushed by {push:+}",
                ["x", "y"][*axis]
            ),
        }
    }
}

/// A stable equilibrium reached by [`land`].
#[derive(Debug, Clone)]
pub struct Landing {
    /// The stable equilibrium.
    pub solution: Solution,
    /// Its verdict.
    pub stability: Stability,
    /// How it was reached.
    pub route: Route,
    /// Stable candidates found (the nearest one, by tip position, is kept).
    pub candidates: usize,
    /// IVPs integrated (tangent IVPs counted once), verdicts included.
    pub evaluations: usize,
}

/// A stable equilibrium of `robot` at `inputs` under `loads` near `before`
/// (an equilibrium at these or at nearby parameters): by loading from rest
/// with an imperfection, the tip wrench `(EI/L^2, EI/L) mode` along the
/// softest mode of the equilibrium continued from `before` (or `mode` if
/// given), then taking it away
/// ([`crate::solve::forward::solve_imperfect`]), and, if
/// `exhaustive` or that found nothing stable, by Newton from the cold guess,
/// from `before`, and from `before` with its scaled base curvature
/// `L omega(0)` pushed by +-0.03, 0.1, 0.3, 1 and 3 about each bending axis
/// (the tensions kept); among the stable results, the one whose tip is
/// nearest `before`'s. `NoSolution` if none is stable.
pub fn land(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    before: &Solution,
    mode: Option<[f64; 6]>,
    opts: &SolveOptions,
    exhaustive: bool,
) -> Result<Landing> {
    let mut evals = 0;
    let mut found: Vec<(Solution, Stability, Route)> = vec![];
    let consider = |found: &mut Vec<_>, s: Solution, route: Route, evals: &mut usize| {
        *evals += s.evaluations;
        if let Ok(st) = stability(robot, &s, &[]) {
            *evals += st.evaluations;
            if st.stable {
                found.push((s, st, route));
            }
        }
    };
    let mode = match mode {
        Some(m) => Some(m),
        None => solve_loaded(robot, inputs, loads, opts, Some(before))
            .ok()
            .and_then(|s| {
                evals += s.evaluations;
                stability(robot, &s, &[]).ok()
            })
            .map(|st| {
                evals += st.evaluations;
                st.mode
            }),
    };
    if let Some(mode) = mode {
        match imperfection(robot, inputs, loads, &mode, opts) {
            Ok(s) => consider(&mut found, s, Route::Imperfection, &mut evals),
            Err(e) if crate::solve::shooting::is_input_error(&e) => return Err(e),
            Err(_) => {}
        }
    }
    if exhaustive || found.is_empty() {
        for (g, route) in guesses(robot, inputs, before) {
            crate::solve::cancel::check()?;
            let mut w = before.clone();
            w.unknowns = g;
            if let Ok(s) = solve_loaded(robot, inputs, loads, opts, Some(&w)) {
                consider(&mut found, s, route, &mut evals);
            }
        }
    }
    crate::solve::cancel::check()?;
    let tip = before.tip_position();
    let candidates = found.len();
    found
        .into_iter()
        .min_by(|a, b| {
            (a.0.tip_position() - tip)
                .norm()
                .total_cmp(&(b.0.tip_position() - tip).norm())
        })
        .map(|(solution, stability, route)| Landing {
            solution,
            stability,
            route,
            candidates,
            evaluations: evals,
        })
        .ok_or_else(|| Error::NoSolution {
            reason: "no stable equilibrium found near the given one (loading with an \
                     imperfection along its softest mode, and perturbed Newton starts)"
                .into(),
        })
}

/// The equilibrium that loading from rest with an imperfection, the tip
/// wrench `(EI/L^2, EI/L) mode` along the softest mode of the unstable
/// equilibrium (the body's own force and moment units), ends on once the
/// imperfection is taken away again
/// ([`crate::solve::forward::solve_imperfect`]).
fn imperfection(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    mode: &[f64; 6],
    opts: &SolveOptions,
) -> Result<Solution> {
    let (force, moment) = robot.body.load_scales();
    let wrench = Loads {
        tip_force: Vector3::new(mode[0], mode[1], mode[2]) * force,
        tip_moment: Vector3::new(mode[3], mode[4], mode[5]) * moment,
    };
    crate::solve::forward::solve_imperfect(robot, inputs, loads, &wrench, opts)
}

/// Newton starts: the cold guess, `before`, and `before` with its base
/// curvature pushed about each bending axis.
fn guesses(robot: &Robot, inputs: &[f64], before: &Solution) -> Vec<(Vec<f64>, Route)> {
    let mut out = vec![
        (reference_guess(robot), Route::Cold),
        (initial_guess(robot, inputs, Some(before)), Route::Start),
    ];
    for push in [0.03, 0.1, 0.3, 1.0, 3.0] {
        for axis in [0usize, 1] {
            for sign in [-1.0, 1.0] {
                let mut g = before.unknowns.clone();
                g[3 + axis] += sign * push;
                out.push((
                    g,
                    Route::Pushed {
                        axis,
                        push: sign * push,
                    },
                ));
            }
        }
    }
    out
}
