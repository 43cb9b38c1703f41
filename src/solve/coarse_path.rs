//! A cold homotopy path on a coarse grid, finished on the full grid.
//!
//! A continuation's correctors integrate many IVPs (tens of steps at
//! several IVPs a corrector on a strongly bent path), each on the full
//! grid, although every point of the path but the last only starts the next
//! step's predictor ([`super::continuation::INTERMEDIATE_TOL`]). So a cold
//! continuation first runs its whole path on a grid of
//! `steps / PATH_GRID_DIVISOR` RK4 steps, to [`PATH_END_TOL`] at
//! `lambda = 1`, and then finishes on the full grid from the coarse root
//! with the direct run's coarse-to-full hand-over (`presolve::presolved_shooting`:
//! defect correction on the same coarse grid, convergence decided by a
//! full-grid IVP). Where the coarse root is outside the finish's reach
//! (the coarse grid's RK4 error at `lambda = 1` leaves a full-grid
//! residual of order one or more there, see [`WATCH_LAMBDA`]), Newton on
//! an intermediate grid of `steps / HOP_GRID_DIVISOR` steps moves it first,
//! and the finish from there takes its Jacobians on that grid
//! (`solve::hop_finish`).
//! The coarse grid does not resolve every design's path: where its error
//! (the full grid's residual at a coarse point) is large early, it would
//! be out of the finish's reach at `lambda = 1`. So the path checks it
//! once, with one full-grid IVP at `lambda = 1/8` ([`WATCH_LAMBDA`]), and
//! if it exceeds [`WATCH_TOL`] goes on on a finer grid from there (from
//! `lambda = 0` if the point is beyond a corrector's reach,
//! [`RESUME_MAX`]): first on the middle grids of
//! [`MIDDLE_GRID_DIVISORS`], each checked in the same way and finished on
//! the full grid, and only if they fail on the full grid
//! (`fold::on_full_grid`). A coarse grid that does not
//! resolve the body (its steps longer than a tendon's bending length, see
//! [`MIDDLE_GRID_DIVISORS`]) ends in a root several units of residual from
//! the full grid's, or makes its path creep to its cap; the check finds
//! this at one full-grid IVP's cost instead of after the whole coarse path
//! and a failed finish.
//! If the coarse path stalls (its step quartered below the smallest: a
//! fold of the path), one full-grid IVP at its point checks the grid; if
//! the coarse grid resolves the point (to [`WATCH_TOL`]) the fold is the
//! full grid's too, and the body snaps through to another branch
//! (`fold::snap`, on the coarse grid, and the path on from there) or, if
//! that fails, the solve's continuation has failed at once; else the
//! point is corrected on the full grid and the path goes on there
//! (`fold::on_full_grid`), and if it stalls there too, the continuation has
//! failed. Either way without a full-grid path from `lambda = 0`: where
//! the coarse grid resolves the point, the fold is the body's (a limit
//! point of the loading, as past self-weight buckling), not the grid's,
//! and a full-grid path from `lambda = 0` stalls near it too, after paying
//! full-grid correctors the whole way there; where it does not, the
//! corrected point already lies on the full grid's path. The snap runs on
//! the coarse grid for the same reason as the path: its correctors only
//! lead to a point that the full grid then corrects.
//! If the coarse path reaches its IVP cap, or the finish does not
//! converge, the caller runs the path on the full grid from `lambda = 0`
//! (its work counted on top), so that no design converging on the full
//! grid's path is lost.
//!
//! A coarse IVP costs more than a tenth of a full one: the anchors' load
//! iterations cost the same on any grid, so only the RK4 steps between
//! them scale with the grid.

use super::continuation::{follow, follow_from, start, PathEnd, Track, Watch, CORRECTOR_MIN_STEP};
use super::fold::{on_full_grid, regrid};
use super::hop_finish::finish_on_grid;
use super::options::SolveOptions;
use super::presolve::presolved_shooting;
use super::residual::Loads;
use super::shooting::{is_budget_error, is_input_error, Solution};
use super::system::{newton_shooting, solution_from, Keep, Work, COARSE_JACOBIAN_MIN_STEPS};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// The coarse path's grid: `steps / PATH_GRID_DIVISOR` RK4 steps, the
/// pre-solve's coarse grid (so the finish's first coarse run starts at a
/// root). A coarser grid makes every corrector cheaper but leaves a larger
/// RK4 error at the coarse root for the finish to remove (RK4's error falls
/// as `h^4`); a finer one costs more per corrector on a path whose length
/// in `lambda` is the same. A tuning constant, chosen by experiment on the
/// tuning seed ([`crate::problems::TUNING_SEED`]) of the design benchmark
/// (`benches/designs.rs`).
pub const PATH_GRID_DIVISOR: usize = 10;

/// The intermediate grid (`steps / HOP_GRID_DIVISOR`) of a finish whose
/// first attempt from the coarse root failed (see the module docs): fine
/// enough that its root lies within the full-grid finish's reach where the
/// coarse root does not (RK4's error a `(10/4)^4 ~ 39`th of the coarse
/// grid's), coarse enough that its Newton run costs a fraction of a
/// full-grid one. A tuning constant, chosen by experiment on the tuning
/// seed of the design benchmark (`benches/designs.rs`).
pub const HOP_GRID_DIVISOR: usize = 4;

/// Most IVPs of a coarse path (beyond, the full grid's path is run). It
/// bounds the work lost on a coarse grid that does not resolve the body: a
/// tendon whose bending length is shorter than the coarse steps makes the
/// path creep (short steps that converge, far from `lambda = 1`) rather
/// than fail. The cap lies above the length of a coarse path that resolves
/// its body and below the cost of a creeping one: a tuning constant, chosen
/// by experiment on the tuning seed of the design benchmark
/// (`benches/designs.rs`).
pub const PATH_MAX_IVPS: usize = 300;

/// The coarse path checks its grid once, at its first converged point at
/// or past this `lambda`: one full-grid IVP there, whose `max |r|` (scaled)
/// is the coarse grid's error at that point of the path. That error grows
/// along the path roughly as `lambda^2` (the loads, and with them the
/// curvature the RK4 steps must follow, grow with `lambda`), and the
/// finish reaches coarse roots up to a full-grid `max |r|` of about 1; a
/// coarse grid that resolves the body shows an error below [`WATCH_TOL`]
/// there, one that does not, an error well above it. An
/// early check loses less of a coarse path that must be abandoned; at `1/8`
/// its bound `1/64` still lies two orders above the noise of the
/// intermediate points (converged to
/// [`super::continuation::INTERMEDIATE_TOL`], 1e-4). Every continuation
/// that passes the check pays its one IVP. A tuning constant, chosen by
/// experiment on the tuning seed of the design benchmark
/// (`benches/designs.rs`).
pub const WATCH_LAMBDA: f64 = 0.125;

/// Largest full-grid `max |r|` (scaled) at the check ([`WATCH_LAMBDA`])
/// under which the coarse path goes on: `WATCH_LAMBDA^2`, so that its
/// error, growing as `lambda^2`, stays within the finish's reach of about
/// 1 at `lambda = 1`.
pub const WATCH_TOL: f64 = WATCH_LAMBDA * WATCH_LAMBDA;

/// Largest check residual from which a coarse path stopped by its check
/// resumes on the full grid at the checked point (`fold::on_full_grid`); beyond, the
/// full grid's path runs from `lambda = 0`. Within about one unit of
/// scaled residual a full-grid corrector converges from the coarse point in
/// a few IVPs (the finish's reach, see [`WATCH_LAMBDA`]); from several
/// units it fails after many, and the path from `lambda = 0` is cheaper. A
/// tuning constant, chosen by experiment on the tuning seed of the design
/// benchmark (`benches/designs.rs`).
pub const RESUME_MAX: f64 = 1.0;

/// The middle grids (`steps / d` RK4 steps, in turn) of a path whose coarse
/// grid failed its check (see `on_middle_grid`): each goes on from the
/// last checked point (or from `lambda = 0`), checks itself against the
/// full grid once (to `lambda^2` at the checked point, the rule of
/// [`WATCH_TOL`]), and is finished on the full grid by Newton from its
/// root; a grid that fails its check hands over to the next, the last to
/// the full grid's path. Each middle grid must carry the body's shortest
/// bending length: a tendon whose bending length `sqrt(EI / tau)` is
/// 2.3 mm is not resolved by the coarse grid's 7.3 mm steps nor by a
/// quarter's 2.9 mm (its check residual above `lambda^2`), and is by a
/// half's 1.5 mm; RK4 is stable up to about 2.8 bending lengths per step.
/// A quarter first, and a half only where the quarter fails its check,
/// spends the finer grid only on the bodies that need it; a finish by
/// Newton (the middle grid's root already near the full grid's) takes
/// fewer IVPs than one by defect correction on the middle grid. The order
/// of the grids is a tuning choice, made by experiment on the tuning seed
/// of the design benchmark (`benches/designs.rs`).
pub const MIDDLE_GRID_DIVISORS: [usize; 2] = [4, 2];

/// Tolerance (scaled residual) of the coarse path's last corrector, at
/// `lambda = 1`: below the pre-solve's first-round tolerance (1e-5), whose
/// coarse run then takes no step.
pub const PATH_END_TOL: f64 = 1e-8;

/// The grid (RK4 steps) of a cold continuation's coarse path under `opts`,
/// `None` if it runs on the full grid only (the pre-solve off, or fewer
/// than ten times [`COARSE_JACOBIAN_MIN_STEPS`] steps).
pub fn path_grid(opts: &SolveOptions) -> Option<usize> {
    let steps = opts.steps / PATH_GRID_DIVISOR;
    (opts.presolve && steps >= COARSE_JACOBIAN_MIN_STEPS).then_some(steps)
}

/// Whether `e` ends the solve (no fallback): bad input, budget, interrupt.
pub(crate) fn ends_solve(e: &Error) -> bool {
    is_input_error(e) || is_budget_error(e) || matches!(e, Error::Interrupted)
}

/// `Ok(Some(v))`, `Ok(None)` for an error the caller falls back from, or
/// the error if it ends the solve.
pub(super) fn unless_final<T>(r: Result<T>) -> Result<Option<T>> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(e) if ends_solve(&e) => Err(e),
        Err(_) => Ok(None),
    }
}

/// The cold continuation on the coarse grid, finished on the full grid
/// (see the module docs); `None` if the caller is to run the full grid's
/// path (its work is in `work`), an error if the solve must stop or the
/// path stalled at a fold on both grids (see [`on_full_grid`]).
pub(crate) fn coarse_path(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    work: &mut Work,
) -> Result<Option<Solution>> {
    if path_grid(opts).is_none() {
        return Ok(None);
    }
    let (from, x, tau, jac) = start(robot, None);
    let mut track = Track::new(0.0, x, tau, jac, 0.25);
    track.watch = Some(Watch {
        lam: WATCH_LAMBDA,
        steps: opts.steps,
        tol: WATCH_TOL,
        scaled: false,
    });
    let Some(out) = follow_coarse(robot, inputs, loads, opts, &from, &mut track, work) else {
        return Ok(None);
    };
    match out {
        Err(e) if is_budget_error(&e) && !work.exhausted() => Ok(None),
        Err(e) if ends_solve(&e) => Err(e),
        Err(e) => match track.unresolved {
            Some(r) => on_middle_grid(robot, inputs, loads, opts, &from, (track, r), work),
            None => on_full_grid(robot, inputs, loads, opts, &from, (track, Some(e)), work),
        },
        Ok((nr, _, path)) => finish(robot, inputs, loads, opts, nr.x, path, work),
    }
}

/// `track` followed on the coarse grid ([`path_grid`], to at least
/// [`PATH_END_TOL`]) within the coarse path's own IVP cap
/// ([`PATH_MAX_IVPS`]) inside the solve's budget; `None` without a coarse
/// grid. Shared by the path from `lambda = 0` and the one past a fold's
/// snap-through (`fold::snapped`).
pub(super) fn follow_coarse(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    track: &mut Track,
    work: &mut Work,
) -> Option<Result<PathEnd>> {
    let steps = path_grid(opts)?;
    let copts = SolveOptions {
        steps,
        tol: opts.tol.max(PATH_END_TOL),
        ..*opts
    };
    let budget = work.max_evaluations;
    let cap = work.evaluations + PATH_MAX_IVPS;
    work.max_evaluations = if budget == 0 { cap } else { budget.min(cap) };
    let out = follow_from(robot, inputs, loads, &copts, from, true, track, work);
    work.max_evaluations = budget;
    Some(out)
}

/// The finish on the full grid from the coarse root `x` (see the module
/// docs); `path`: the coarse path's.
pub(super) fn finish(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    mut x: Vec<f64>,
    path: Vec<f64>,
    work: &mut Work,
) -> Result<Option<Solution>> {
    // the finish backtracks as a first corrector attempt does
    let fopts = SolveOptions {
        min_step: opts.min_step.max(CORRECTOR_MIN_STEP),
        ..*opts
    };
    let keep = Keep::Nodes;
    // after a hop: its grid and Jacobian (see `hop_finish`)
    let mut hopped = None;
    for hop in [false, true] {
        if hop {
            let hopts = SolveOptions {
                steps: opts.steps / HOP_GRID_DIVISOR,
                tol: opts.tol.max(PATH_END_TOL),
                ..fopts
            };
            let out = newton_shooting(robot, inputs, loads, &hopts, &x, None, false, work);
            let Some((nr, _)) = unless_final(out)? else {
                return Ok(None);
            };
            x = nr.x;
            hopped = Some((hopts.steps, nr.jacobian));
        }
        let out = match &hopped {
            Some((s, j)) => {
                finish_on_grid(robot, inputs, loads, &fopts, &x, j.as_ref(), *s, keep, work)
            }
            None => presolved_shooting(robot, inputs, loads, &fopts, &x, None, keep, work),
        };
        if let Some((nr, last)) = unless_final(out)? {
            let mut s = solution_from(robot, inputs, loads, opts, nr, last, work)?;
            s.continuation_steps = path;
            return Ok(Some(s));
        }
    }
    Ok(None)
}

/// The outcome of a path on a middle grid (see `on_middle_grid`).
enum Middle {
    /// Converged, finished on the full grid.
    Done(Box<Solution>),
    /// Its check failed at the track's point (residual in `unresolved`).
    Unresolved(Track),
    /// Its path or its finish failed otherwise.
    Failed,
}

/// The path after the coarse grid's check failed with residual `r` at
/// `track`'s point (see [`MIDDLE_GRID_DIVISORS`]): on each middle grid in
/// turn, from the last checked point if it is within a corrector's reach
/// ([`RESUME_MAX`]), else from `lambda = 0`, until one passes its check and
/// is finished on the full grid. If none is, the coarse path's own
/// fallback: the full grid's path from the coarse point (`fold::on_full_grid`) or,
/// `None`, from `lambda = 0`.
fn on_middle_grid(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    (track, r): (Track, f64),
    work: &mut Work,
) -> Result<Option<Solution>> {
    let mut at = (track.clone(), r);
    for div in MIDDLE_GRID_DIVISORS {
        match middle_path(robot, inputs, loads, opts, from, &at, div, work)? {
            Middle::Done(s) => return Ok(Some(*s)),
            Middle::Unresolved(t) => {
                let rt = t.unresolved.unwrap_or(f64::INFINITY);
                if rt <= RESUME_MAX {
                    at = (t, rt);
                }
            }
            Middle::Failed => break,
        }
    }
    match r <= RESUME_MAX {
        true => on_full_grid(robot, inputs, loads, opts, from, (track, None), work),
        false => Ok(None),
    }
}

/// The path on the middle grid `opts.steps / div` from `track`'s point
/// (corrected there, if its check residual `r` is within [`RESUME_MAX`]) or
/// from `lambda = 0`, checked against the full grid at its first point past
/// the start (at least [`WATCH_LAMBDA`]) to `lambda^2` there, and finished on
/// the full grid by Newton from its root with its Jacobian.
#[allow(clippy::too_many_arguments)]
fn middle_path(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    (track, r): &(Track, f64),
    div: usize,
    work: &mut Work,
) -> Result<Middle> {
    let mopts = SolveOptions {
        steps: opts.steps / div,
        tol: opts.tol.max(PATH_END_TOL),
        ..*opts
    };
    let (_, x, tau, jac) = start(robot, None);
    let mut mid = Track::new(0.0, x, tau, jac, 0.25);
    if *r <= RESUME_MAX {
        let mut t = track.clone();
        t.unresolved = None;
        if regrid(robot, inputs, loads, &mopts, from, &mut t, work)?.is_some() {
            mid = t;
        }
    }
    let lam = mid.lam.max(WATCH_LAMBDA);
    mid.watch = Some(Watch {
        lam,
        steps: opts.steps,
        tol: lam * lam,
        scaled: true,
    });
    let (nr, _, path) = match follow_from(robot, inputs, loads, &mopts, from, true, &mut mid, work)
    {
        Err(e) if ends_solve(&e) => return Err(e),
        Err(_) if mid.unresolved.is_some() => return Ok(Middle::Unresolved(mid)),
        Err(_) => return Ok(Middle::Failed),
        Ok(v) => v,
    };
    // the finish backtracks as a first corrector attempt does
    let fopts = SolveOptions {
        min_step: opts.min_step.max(CORRECTOR_MIN_STEP),
        ..*opts
    };
    let jac = nr.jacobian.as_ref().or(mid.jac.as_ref());
    let out = newton_shooting(robot, inputs, loads, &fopts, &nr.x, jac, Keep::Nodes, work);
    let Some((nr, last)) = unless_final(out)? else {
        return Ok(Middle::Failed);
    };
    let mut s = solution_from(robot, inputs, loads, opts, nr, last, work)?;
    s.continuation_steps = path;
    Ok(Middle::Done(Box::new(s)))
}

/// The cold homotopy path alone (no direct run, no finish) on `opts.steps`:
/// the unknowns it reaches at `lambda = 1` (to `opts.tol`) and the path
/// (the `lambda` of each converged step). A cold continuation with a
/// coarse path (see [`path_grid`]) takes exactly this path on
/// `path_grid(opts)` steps with `tol` [`PATH_END_TOL`]; for tests and
/// diagnostics.
pub fn cold_path(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut work = Work::start(opts);
    let (nr, _, path) = follow(robot, inputs, loads, opts, None, &mut work)?;
    Ok((nr.x, path))
}
