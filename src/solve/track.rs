//! The state of a homotopy path between its steps ([`Track`]: the last
//! converged point, the earlier points of the predictor, the step and the
//! path so far) and the one check of a coarse path's grid ([`Watch`]); see
//! [`crate::solve::continuation`] and [`crate::solve::coarse_path`].

use super::coarse_path::{ends_solve, finish, follow_coarse};
use super::continuation::{at, predictor, step_options, PREDICTOR_POINTS};
use super::corrector::correct;
use super::newton::{NewtonResult, System};
use super::options::SolveOptions;
use super::shooting::{is_budget_error, tensions, FinalIvp, Loads, Solution, Work};
use super::system::Shooting;
use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

/// The last converged point of a homotopy: `lambda`, the unknowns, the
/// tensions \[N\] and the Newton Jacobian there, up to
/// [`PREDICTOR_POINTS`] - 1 earlier `(lambda, unknowns)`, oldest first,
/// the next step and the path so far (the `lambda` of each converged step).
#[derive(Clone)]
pub(crate) struct Track {
    pub lam: f64,
    pub x: Vec<f64>,
    pub tau: Vec<f64>,
    pub jac: Option<nalgebra::DMatrix<f64>>,
    pub prev: Vec<(f64, Vec<f64>)>,
    pub step: f64,
    pub path: Vec<f64>,
    /// A check of the grid at the first point past its `lambda` (see [`Watch`]).
    pub watch: Option<Watch>,
    /// The residual of the failed [`Watch`] the path stopped at.
    pub unresolved: Option<f64>,
}

/// A check of a coarse path's grid: at the first converged point at or
/// past `lam`, one IVP on `steps` RK4 steps; the path stops (an error) if
/// its `max |r|` there exceeds `tol`, or if `scaled`, `tol (lambda / lam)^2`
/// at the point's `lambda` (the grid's error grows about as `lambda^2`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Watch {
    pub lam: f64,
    pub steps: usize,
    pub tol: f64,
    /// Whether `tol` grows as `lambda^2` from `lam` to the checked point.
    pub scaled: bool,
}

impl Watch {
    /// The check at the converged `x` of the robot, inputs and loads there;
    /// its IVP is counted on `work`.
    pub(crate) fn check(
        &self,
        robot: &Robot,
        inputs: &[f64],
        loads: &Loads,
        x: &[f64],
        work: &mut Work,
    ) -> Result<()> {
        let mut sys = Shooting::new(robot, inputs, loads, self.steps, false);
        let r = sys.residual(x);
        work.evaluations += sys.evaluations();
        let n = r?.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if n <= self.tol {
            return Ok(());
        }
        Err(Error::NotConverged {
            solver: "forward shooting",
            iterations: work.iterations,
            evaluations: work.evaluations,
            residual: n,
            stop: StopReason::Other,
            reason: "the coarse grid does not resolve the path".into(),
        })
    }
}

impl Track {
    /// The start of a path at `lam` (no earlier points, no path yet).
    pub(crate) fn new(
        lam: f64,
        x: Vec<f64>,
        tau: Vec<f64>,
        jac: Option<nalgebra::DMatrix<f64>>,
        step: f64,
    ) -> Self {
        Track {
            lam,
            x,
            tau,
            jac,
            prev: Vec::new(),
            step,
            path: Vec::new(),
            watch: None,
            unresolved: None,
        }
    }
    /// The predictor at `lt` (see [`predictor`]) for the robot and inputs there.
    pub(crate) fn predictor(&self, robot: &Robot, inputs: &[f64], lt: f64) -> Vec<f64> {
        predictor(robot, inputs, &self.x, &self.tau, &self.prev, self.lam, lt)
    }
    /// Move to the converged point `nr` at `lt` (robot and inputs there;
    /// `last`: its last IVP, whose tensions are taken if it is at `nr.x`).
    pub(crate) fn advance(
        &mut self,
        lt: f64,
        nr: NewtonResult,
        last: Option<FinalIvp>,
        robot: &Robot,
        inputs: &[f64],
    ) -> Result<()> {
        let tau = match last {
            Some(last) => last.tensions,
            None => tensions_at(robot, inputs, &nr.x, robot.body.length)?,
        };
        self.prev
            .push((self.lam, std::mem::replace(&mut self.x, nr.x)));
        if self.prev.len() >= PREDICTOR_POINTS {
            self.prev.remove(0);
        }
        self.lam = lt;
        self.tau = tau;
        if nr.jacobian.is_some() {
            self.jac = nr.jacobian;
        }
        Ok(())
    }
    /// The grid check ([`Watch`]) at the point just reached, if it is the
    /// first at or past the check's `lambda` (robot, inputs and loads
    /// there): an error if it fails, with its residual in `unresolved`
    /// (infinite if its IVP failed: not a fold, so never handed over as one).
    pub(crate) fn check_grid(
        &mut self,
        robot: &Robot,
        inputs: &[f64],
        loads: &Loads,
        work: &mut Work,
    ) -> Result<()> {
        let Some(w) = self.watch.filter(|w| self.lam >= w.lam) else {
            return Ok(());
        };
        self.watch = None;
        let w = match w.scaled {
            true => Watch {
                tol: w.tol * (self.lam / w.lam).powi(2),
                ..w
            },
            false => w,
        };
        let checked = w.check(robot, inputs, loads, &self.x, work);
        self.unresolved = match &checked {
            Ok(()) => None,
            Err(Error::NotConverged { residual, .. }) => Some(*residual),
            Err(_) => Some(f64::INFINITY),
        };
        checked
    }
    /// Move the point to `nr`, the same point corrected on another grid
    /// (robot and inputs at `self.lam`): the earlier points move by the
    /// same correction (the grids' difference varies slowly along the path).
    pub(crate) fn regrid(
        &mut self,
        nr: NewtonResult,
        last: Option<FinalIvp>,
        robot: &Robot,
        inputs: &[f64],
    ) -> Result<()> {
        let shift: Vec<f64> = nr.x.iter().zip(&self.x).map(|(a, b)| a - b).collect();
        for (_, p) in self.prev.iter_mut() {
            p.iter_mut().zip(&shift).for_each(|(v, s)| *v += s);
        }
        self.tau = match last {
            Some(last) => last.tensions,
            None => tensions_at(robot, inputs, &nr.x, robot.body.length)?,
        };
        self.x = nr.x;
        if nr.jacobian.is_some() {
            self.jac = nr.jacobian;
        }
        Ok(())
    }
}

/// Actuator tensions \[N\] at the scaled unknowns `x` (elongations `x[6..] L`).
fn tensions_at(robot: &Robot, inputs: &[f64], x: &[f64], len: f64) -> Result<Vec<f64>> {
    let delta: Vec<f64> = x[6..].iter().map(|d| d * len).collect();
    tensions(robot, inputs, &delta)
}

/// Steps `(d lambda, t)` of the snap-through at a fold ([`snap`]): the
/// corrector at `lambda + d lambda` from the fold's point moved by `t v`,
/// `v` the Jacobian's right singular vector of its smallest singular value
/// (scaled unknowns), each `t` with both signs (the vector's sign is
/// arbitrary), first with the sign along the path's last move ([`ahead`]).
/// Traced on benchmark design #25 (stop 31, full grid, fold
/// at `lambda = 0.55312`): from `d lambda = 1e-3`, `|t| = 0.2` reaches the
/// other branch (0.89 from the fold's point); from `1e-2`, `|t| = 0.4`.
/// On the coarse grid (where the snap runs now, see
/// `coarse_path::on_full_grid`) the first step reaches it too.
const SNAP_STEPS: [(f64, f64); 4] = [(1e-3, 0.2), (1e-3, -0.2), (1e-2, 0.4), (1e-2, -0.4)];

/// The first step of the path from the snap's point, `1/64` (on #25 a
/// cold path's first step, 0.25, and the snap from `d lambda = 1e-2`
/// first took 462 IVPs, against 357).
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
/// `lambda = 1`: on benchmark design #25 the last resort's damped direct
/// run converged there (stability margin -3.25, a conjugate point at
/// 0.078 m), while the branch past the snap is stable at `lambda = 1`
/// (margin +0.62).
pub(crate) fn snap(
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
/// moving. On benchmark design #25 the corrector from `-0.2 v` (that
/// sign) reaches the branch past the fold in 12 IVPs (full grid; 13 on
/// the coarse grid); the one from `+0.2 v`, tried first before, failed
/// after 28 (357 -> 329 IVPs).
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
pub(super) fn snapped(
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
