//! A cold homotopy path on the coarse grid that stopped short of
//! `lambda = 1` ([`super::coarse_path`]): on the full grid from its point
//! ([`on_full_grid`], after a failed grid check or at a fold), and at a
//! fold the coarse grid resolves, the body's snap-through to another
//! branch ([`snap`], then [`snapped`]).

use super::coarse_path::{ends_solve, finish, follow_coarse, path_grid, unless_final, WATCH_TOL};
use super::continuation::{at, follow_from, step_options};
use super::corrector::correct;
use super::options::SolveOptions;
use super::residual::Loads;
use super::shooting::{is_budget_error, Solution};
use super::system::{solution_from, Work};
use super::track::{tensions_at, Track, Watch};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// The coarse path goes on on the full grid from `track`, after its check
/// stopped it (see [`super::coarse_path::WATCH_LAMBDA`]) or, `at_fold`, after it stalled.
///
/// Stopped by its check: the point is corrected on the full grid
/// ([`regrid`]) and the path followed on from it; `None` (the full grid's
/// path from `lambda = 0` is run) if the correction or that path fails.
///
/// At a fold (`fold`: the coarse path's stall error, its steps quartered
/// below `MIN_STEP`: a fold of the path, or a kink the coarse grid does
/// not resolve) one full-grid IVP at the coarse point first
/// ([`resolves_fold`]). If its residual is within [`WATCH_TOL`] (the check
/// rule: the coarse grid resolves the path there) the fold is the full
/// grid's: the body snaps through to the branch past it, on the coarse
/// grid ([`snap`] from the coarse point and Jacobian, then [`snapped`]),
/// and if that fails `fold` is returned (the caller's last resort
/// follows). Else the point is corrected on the full grid and the path
/// goes on there; if it stalls too, its error is returned. `None` if the
/// path stalled at `lambda = 0` or the correction failed.
///
/// Why the snap: at a fold of the body's own (a body past self-weight
/// buckling, loaded up its upright branch) the full grid's path stalls at
/// the same fold, and the last resort's damped direct run can converge on
/// the branch through the fold, the upright one, unstable at
/// `lambda = 1` (see [`snap`]). Why on the coarse grid: the fold's point,
/// its null vector and the snap's correctors are resolved there (the
/// residual check above), at a fraction of a full-grid IVP each, and the
/// path from the snap's point is finished on the full grid, to the
/// equilibrium a full-grid snap reaches.
pub(super) fn on_full_grid(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    (mut track, fold): (Track, Option<Error>),
    work: &mut Work,
) -> Result<Option<Solution>> {
    let at_fold = fold.is_some();
    if at_fold && track.lam <= 0.0 {
        return Ok(None);
    }
    if let Some(e) = fold {
        if resolves_fold(robot, inputs, loads, opts, from, &track, work)? {
            // the full grid's fold: the body snaps through to another
            // branch, or the caller's last resort follows
            let copts = SolveOptions {
                steps: path_grid(opts).unwrap_or(opts.steps),
                ..*opts
            };
            if let Some(t) = snap(robot, inputs, loads, &copts, from, &track, work)? {
                if let Some(s) = snapped(robot, inputs, loads, opts, from, t, work)? {
                    return Ok(Some(s));
                }
            }
            return Err(e);
        }
    }
    if regrid(robot, inputs, loads, opts, from, &mut track, work)?.is_none() {
        return Ok(None);
    }
    let out = follow_from(robot, inputs, loads, opts, from, true, &mut track, work);
    // a path stalled at a fold on both grids is the solve's continuation failure
    let out = if at_fold {
        Some(out?)
    } else {
        unless_final(out)?
    };
    let Some((nr, last, path)) = out else {
        return Ok(None);
    };
    let mut s = solution_from(robot, inputs, loads, opts, nr, last, work)?;
    s.continuation_steps = path;
    Ok(Some(s))
}

/// Whether the full grid `opts.steps` resolves the coarse path at its
/// fold (`track`'s point): its `max |r|` (scaled) there, one IVP, within
/// [`WATCH_TOL`] (the rule of the path's check). A failed IVP is no
/// (the path goes on on the full grid, whose correction fails alike).
fn resolves_fold(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    track: &Track,
    work: &mut Work,
) -> Result<bool> {
    let (r, inp, l) = at(robot, from, inputs, loads, true, track.lam);
    let watch = Watch {
        lam: track.lam,
        steps: opts.steps,
        tol: WATCH_TOL,
        scaled: false,
    };
    match watch.check(&r, &inp, &l, &track.x, work) {
        Ok(()) => Ok(true),
        Err(e) if ends_solve(&e) => Err(e),
        Err(_) => Ok(false),
    }
}

/// Corrects `track`'s point on the full grid `opts.steps` (to the
/// intermediate tolerance, from the coarse Jacobian, backtracking in full)
/// and moves the track there (see [`Track::regrid`]); the full grid's
/// `max |r|` (scaled) at the point before the correction (the other grid's
/// error there), `None` if the correction failed.
pub(super) fn regrid(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    track: &mut Track,
    work: &mut Work,
) -> Result<Option<f64>> {
    let (r, inp, l) = at(robot, from, inputs, loads, true, track.lam);
    let sopts = step_options(opts, false, 0.0);
    let (x, jac) = (&track.x, track.jac.as_ref());
    let (out, r0) = correct(&r, &inp, &l, &sopts, x, jac, false, f64::INFINITY, work);
    let Some((nr, last)) = unless_final(out)? else {
        return Ok(None);
    };
    track.regrid(nr, last, &r, &inp)?;
    Ok(Some(r0.unwrap_or(f64::INFINITY)))
}

/// Steps `(d lambda, t)` of the snap-through at a fold ([`snap`]): the
/// corrector at `lambda + d lambda` from the fold's point moved by `t v`,
/// `v` the Jacobian's right singular vector of its smallest singular value
/// (scaled unknowns), each `t` with both signs (the vector's sign is
/// arbitrary), first with the sign along the path's last move ([`ahead`]).
/// A small `d lambda` takes the corrector just past the fold, where the
/// path's own branch has no point, and the move `t v` along the fold's
/// null direction (the direction in which the equilibrium is lost) starts
/// it toward the branch the body snaps to, which may lie at a distance of
/// order one (scaled unknowns); the larger pair is a second try. The pairs
/// are tuning constants, chosen by experiment on the bodies past
/// self-weight buckling of the tuning seed
/// ([`crate::problems::TUNING_SEED`]) of the design benchmark
/// (`benches/designs.rs`).
const SNAP_STEPS: [(f64, f64); 4] = [(1e-3, 0.2), (1e-3, -0.2), (1e-2, 0.4), (1e-2, -0.4)];

/// The first step of the path from the snap's point, `1/64`: a cold
/// path's first step, 0.25, leaves the new branch's neighbourhood before
/// the step control has measured its curvature.
const SNAP_PATH_STEP: f64 = 1.0 / 64.0;

/// A corrector's point this far (`max |dx|`, scaled unknowns) from the
/// fold's is on another branch (past the fold the path's own branch has no
/// point near it; this only rejects a corrector that did not move).
const SNAP_MIN_JUMP: f64 = 0.05;

/// The snap-through at a fold of a homotopy path (where its step control
/// stalled, `track` at the fold's point on `opts.steps`, with its Jacobian):
/// the body, loaded past the fold, leaves the path's branch (which turns
/// back in `lambda`) for another one, as a real body snaps. The point on
/// that branch at a `lambda` just past the fold ([`SNAP_STEPS`]) starts a
/// new track (no earlier points, the path so far kept); `None` if no
/// corrector there converged (or no Jacobian is known). A past-buckling
/// body's branch through the fold is the upright one, unstable at
/// `lambda = 1` (a conjugate point along the body, see
/// [`crate::stability`]), and a damped direct run from the straight guess
/// can converge there; the branch past the snap is the one the loaded
/// body reaches as it buckles.
fn snap(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    track: &Track,
    work: &mut Work,
) -> Result<Option<Track>> {
    let Some(jac) = track.jac.as_ref() else {
        return Ok(None);
    };
    let svd = jac.clone().svd(false, true);
    let Some(v_t) = svd.v_t.as_ref() else {
        return Ok(None);
    };
    let k = svd.singular_values.imin();
    let sopts = step_options(opts, false, 0.0);
    let sign = ahead(track, v_t.row(k).iter());
    for (dl, t) in SNAP_STEPS.map(|(dl, t)| (dl, sign * t)) {
        let lt = (track.lam + dl).min(1.0);
        let (r, inp, l) = at(robot, from, inputs, loads, true, lt);
        let x0: Vec<f64> = track
            .x
            .iter()
            .zip(v_t.row(k).iter())
            .map(|(a, b)| a + t * b)
            .collect();
        let (out, _) = correct(&r, &inp, &l, &sopts, &x0, None, false, f64::INFINITY, work);
        let (nr, last) = match out {
            Ok(v) => v,
            Err(e) if ends_solve(&e) => return Err(e),
            Err(_) => continue,
        };
        let jump =
            nr.x.iter()
                .zip(&track.x)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if jump < SNAP_MIN_JUMP {
            continue;
        }
        let tau = match last {
            Some(last) => last.tensions,
            None => tensions_at(&r, &inp, &nr.x, r.body.length)?,
        };
        let mut snapped = Track::new(lt, nr.x, tau, nr.jacobian, SNAP_PATH_STEP);
        snapped.path = track.path.clone();
        snapped.path.push(lt);
        return Ok(Some(snapped));
    }
    Ok(None)
}

/// The sign (`1` or `-1`) of the null vector `v` ([`SNAP_STEPS`]) along the
/// path's last move (`track`'s point minus the one before it; `1` if there
/// is none): a body loaded past a fold snaps on in the direction it was
/// moving. A corrector started against that motion heads back toward the
/// path's own branch, which has no point past the fold, and fails only
/// after many IVPs; so it is tried second.
fn ahead<'a>(track: &Track, v: impl Iterator<Item = &'a f64>) -> f64 {
    let Some((_, p)) = track.prev.last() else {
        return 1.0;
    };
    let moved = track.x.iter().zip(p).map(|(a, b)| a - b);
    match v.zip(moved).map(|(v, d)| v * d).sum::<f64>() < 0.0 {
        true => -1.0,
        false => 1.0,
    }
}

/// The path from the point past a fold's snap-through ([`snap`], on the
/// coarse grid) to `lambda = 1` on the coarse grid (capped as the coarse
/// path is), finished on the full grid (see `coarse_path::finish`); `None`
/// if either fails (the fold's error is returned and the solve's last
/// resort follows).
fn snapped(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    from: &[f64],
    mut track: Track,
    work: &mut Work,
) -> Result<Option<Solution>> {
    let Some(out) = follow_coarse(robot, inputs, loads, opts, from, &mut track, work) else {
        return Ok(None);
    };
    match out {
        Err(e) if is_budget_error(&e) && !work.exhausted() => Ok(None),
        Err(e) if ends_solve(&e) => Err(e),
        Err(_) => Ok(None),
        Ok((nr, _, path)) => finish(robot, inputs, loads, opts, nr.x, path, work),
    }
}
