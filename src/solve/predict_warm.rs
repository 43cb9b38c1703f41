//! The direct Newton run of a warm forward solve: from the first-order
//! prediction ([`super::predict`]), defect correction on the coarse grid
//! with the defect measured AT the prediction.
//!
//! The coarse-grid pre-solve ([`super::presolve`]) takes the defect
//! `d = r_full - r_coarse` of the warm neighbour, integrates a coarse IVP
//! for it, converges the coarse system from the guess and only then finds,
//! in its first full-grid IVP, how far the defect moved between the
//! neighbour and the new solution (Fig. 6, 95 to 100 C: 1.5e-7, so a
//! second coarse run and a second full IVP follow). From a prediction
//! already within ~1e-6 of the solution the order is turned round:
//!
//! 1. a full-grid IVP at the point `x` (converged if `max |r_full| <=
//!    max(tol, floor)`, Newton's test) and a coarse one there, so that
//!    `d = r_full(x) - r_coarse(x)` holds exactly at `x` and moves between
//!    `x` and the solution by the coarse grid's error in the Jacobian
//!    times that short distance;
//! 2. chord steps on `r_coarse + d` with the neighbour's Jacobian (actuator
//!    columns rescaled to the new tension slopes,
//!    [`super::presolve::rescale_tension_columns`]) from the known value
//!    `r_full(x)`, to `max(0.1 tol, coarse floor)`, while at most
//!    [`CHORD_STEPS_LEFT`] more steps are needed at their contraction
//!    (beyond, once, with a fresh coarse tangent at the point reached);
//! 3. back to 1 (at most [`MAX_ROUNDS`] full IVPs).
//!
//! Batch rows ([`crate::shooting::solve_tip`]) take the same run from a
//! neighbouring tip solution (`tip_shooting`), with a policy that refreshes
//! the Jacobian sooner ([`ChordPolicy::BATCH`]): a row hands its Jacobian
//! to the next one, so a refresh pays over several rows, while the
//! neighbour's Jacobian, handed on unchanged, ages row by row.
//!
//! Any failure (a step that does not contract enough, a full residual that
//! does not fall tenfold, an integration error) hands the solve to the
//! pre-solve (`presolved_shooting`) from the point
//! reached, as without the prediction; the work done counts on top. Every
//! IVP counts as one evaluation.

use nalgebra::{DMatrix, DVector};

use super::newton::{NewtonResult, Status, System};
use super::options::SolveOptions;
use super::predict::predict;
use super::presolve::{presolved_shooting, rescale_tension_columns, Warm};
use super::residual::Loads;
use super::solution::TipSolution;
use super::system::{FinalIvp, Keep, Shooting, Work, COARSE_JACOBIAN_MIN_STEPS};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// Full-grid IVPs of the warm run before it hands over to the pre-solve.
pub const MAX_ROUNDS: usize = 3;

/// Most chord steps still needed, at the contraction of the last one, for
/// which the chord run goes on: the pre-solve's rule, defined once in
/// [`mod@crate::solve::newton`] (the same cost argument: a fresh coarse
/// tangent costs about four coarse IVPs).
pub use super::newton::CHORD_STEPS_LEFT;

/// When the warm run's chord steps replace their Jacobian by a fresh coarse
/// tangent, and where they stop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChordPolicy {
    /// Most chord steps still needed, at the last step's contraction, for
    /// which the chord steps go on with the Jacobian they have.
    pub steps_left: f64,
    /// Chord steps after which, not yet converged, the Jacobian is
    /// refreshed whatever their contraction (`usize::MAX`: never).
    pub refresh_after: usize,
    /// The chord steps' tolerance on `r_coarse + d`, as a fraction of the
    /// solve's `tol`.
    pub tol_fraction: f64,
}

impl ChordPolicy {
    /// A single warm solve: a refresh (about four coarse IVPs) only when
    /// more than [`CHORD_STEPS_LEFT`] chord steps are still needed, chord
    /// steps to `0.1 tol` (Fig. 6 warm 5 C away: 4 chord steps at 39x
    /// each, no refresh, 7 IVPs; refreshing after two steps: 6 IVPs but
    /// 3.12-3.37 IVP times against 2.98-3.20).
    pub const SINGLE: ChordPolicy = ChordPolicy {
        steps_left: CHORD_STEPS_LEFT,
        refresh_after: usize::MAX,
        tol_fraction: 0.1,
    };
    /// A batch row, whose Jacobian (refreshed or not) is the next row's: a
    /// refresh once two chord steps have not converged, or when more than
    /// two are still needed, and chord steps to `0.5 tol`. Along a sweep a
    /// row's step is small, so the full residual after the chord steps is
    /// theirs plus a defect change of ~1e-12 (Fig. 6 every 1 C), which
    /// `0.5 tol` leaves room for; at `0.1 tol` every other row ended at
    /// 1.0-1.5e-11 and refreshed for the last tenth. Measured (IVPs a warm
    /// row, `warm_counts --batch`): Fig. 6 every 1 C 7.82 -> 5.64, every
    /// 5 C 8.85 -> 6.63, steel every 1 % 5.42 -> 5.04.
    pub const BATCH: ChordPolicy = ChordPolicy {
        steps_left: 2.0,
        refresh_after: 2,
        tol_fraction: 0.5,
    };
}

/// The direct Newton run of a forward solve warm from `warm`, starting at
/// the predicted guess `x0`, its chord steps under `policy`
/// ([`ChordPolicy::SINGLE`] for a single solve, [`ChordPolicy::BATCH`]
/// along a sweep): the same contract as [`presolved_shooting`], which it
/// is without a warm Jacobian, without the pre-solve or on a grid too
/// short for a coarse one.
#[allow(clippy::too_many_arguments)] // the shooting problem's parts, as presolved_shooting's
pub(crate) fn warm_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    (warm, policy): (Warm<'_>, ChordPolicy),
    keep: Keep,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let run = WarmStart {
        x0,
        warm,
        keep,
        policy,
    };
    warm_run(robot, inputs, loads, opts, run, work)
}

/// Where a warm run starts and how its chord steps go.
struct WarmStart<'a> {
    x0: &'a [f64],
    warm: Warm<'a>,
    keep: Keep,
    policy: ChordPolicy,
}

/// [`warm_shooting`] under any [`ChordPolicy`].
fn warm_run(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    start: WarmStart<'_>,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let WarmStart {
        x0,
        warm,
        keep,
        policy,
    } = start;
    let coarse = opts.steps / 10;
    let Some(jac) = warm
        .jacobian
        .filter(|j| j.nrows() == x0.len() && j.ncols() == x0.len())
    else {
        return presolved_shooting(robot, inputs, loads, opts, x0, Some(warm), keep, work);
    };
    if coarse < COARSE_JACOBIAN_MIN_STEPS || !opts.presolve {
        return presolved_shooting(robot, inputs, loads, opts, x0, Some(warm), keep, work);
    }
    let j = rescale_tension_columns(robot, jac, (warm.unknowns, warm.inputs), (x0, inputs));
    let mut run = WarmRun {
        full: Shooting::new(robot, inputs, loads, opts.steps, keep),
        coarse: Shooting::new(robot, inputs, loads, coarse, Keep::Tip),
        x: x0.to_vec(),
        iterations: 0,
        policy,
    };
    let out = run.correct(opts, j, work);
    work.evaluations += run.evaluations();
    work.iterations += run.iterations;
    match out {
        Ok(Some((mut nr, last))) => {
            nr.evaluations = work.evaluations;
            nr.iterations = run.iterations;
            Ok((nr, last))
        }
        Err(e @ Error::Interrupted) => Err(e),
        _ => presolved_shooting(robot, inputs, loads, opts, &run.x, Some(warm), keep, work),
    }
}

/// [`warm_shooting`] for a batch row warm from the tip solution `w`, from
/// its first-order prediction ([`super::predict::predict`]); nothing but
/// the tip is recorded.
pub(crate) fn tip_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    w: &TipSolution,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let jacobian = w.newton_jacobian.as_ref();
    let x0 = predict(
        robot,
        inputs,
        (&w.unknowns, &w.tensions, &w.inputs),
        jacobian,
    );
    let start = WarmStart {
        x0: &x0,
        warm: Warm {
            unknowns: &w.unknowns,
            inputs: &w.inputs,
            jacobian,
        },
        keep: Keep::Tip,
        policy: ChordPolicy::BATCH,
    };
    warm_run(robot, inputs, loads, opts, start, work)
}

/// The state of one warm run: the full and coarse systems (each counts its
/// IVPs), the point reached and the chord steps taken.
struct WarmRun<'a> {
    full: Shooting<'a>,
    coarse: Shooting<'a>,
    x: Vec<f64>,
    iterations: usize,
    policy: ChordPolicy,
}

fn inf_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

impl WarmRun<'_> {
    /// Steps 1-3 of the module docs; `Ok(None)`: hand over to the pre-solve.
    fn correct(
        &mut self,
        opts: &SolveOptions,
        mut jac: DMatrix<f64>,
        work: &Work,
    ) -> Result<Option<(NewtonResult, Option<FinalIvp>)>> {
        let mut last_norm = f64::INFINITY;
        for _ in 0..MAX_ROUNDS {
            if self.spent(work) {
                return Ok(None);
            }
            if last_norm.is_finite() {
                // Round 2's full IVP is predicted to be the last (so, under
                // a stability verdict, it is the verdict's recorded pass):
                // the chord has converged `r_coarse + d` to 0.1 tol, so the
                // full residual left is the defect's change over a step of
                // size ~|r| <= 0.1 of round 1's (Fig. 6 warm 5 C: 1.9e-6 ->
                // 3.9e-12). A wrong guess costs a tangent IVP in place of a
                // plain one, less than a missed one (the verdict's own pass).
                self.full.expect_convergence();
            }
            let sys = &mut self.full;
            let rf = sys.residual(&self.x)?;
            let norm = inf_norm(&rf);
            let floor = sys.floor(&self.x, &rf);
            if norm <= opts.tol.max(floor) {
                let last = sys.take_last(&self.x);
                let status = if norm <= opts.tol {
                    Status::Converged
                } else {
                    Status::ConvergedAtFloor
                };
                let nr = NewtonResult {
                    x: self.x.clone(),
                    residual: rf,
                    norm,
                    floor,
                    status,
                    iterations: 0,
                    evaluations: 0,
                    jacobian: Some(jac),
                };
                return Ok(Some((nr, last)));
            }
            if !(norm <= 0.1 * last_norm) {
                return Ok(None);
            }
            last_norm = norm;
            let rc = self.coarse.residual(&self.x)?;
            let defect: Vec<f64> = rf.iter().zip(&rc).map(|(f, c)| f - c).collect();
            if !self.chord(opts, &mut jac, &defect, rf, work)? {
                return Ok(None);
            }
        }
        Ok(None)
    }

    /// Chord steps on `r_coarse + defect` from `self.x`, where it is `r`;
    /// whether they reached the coarse tolerance. When a step does not
    /// contract enough (more than the policy's `steps_left` still needed)
    /// or `refresh_after` steps have not converged, the Jacobian is
    /// replaced, once, by a fresh coarse tangent at the point reached (so
    /// that along a sweep, where each solve hands its Jacobian on,
    /// staleness does not pile up), and the chord steps go on with it.
    fn chord(
        &mut self,
        opts: &SolveOptions,
        jac: &mut DMatrix<f64>,
        defect: &[f64],
        mut r: Vec<f64>,
        work: &Work,
    ) -> Result<bool> {
        let policy = self.policy;
        let tol = policy.tol_fraction * opts.tol;
        let mut steps = 0;
        let mut res = inf_norm(&r);
        let mut lu = jac.clone().lu();
        let mut refreshed = false;
        while self.iterations < opts.max_iter && !self.spent(work) {
            let Some(dx) = lu
                .solve(&(-DVector::from_column_slice(&r)))
                .filter(|d| d.iter().all(|v| v.is_finite()))
            else {
                return Ok(false);
            };
            let xt: Vec<f64> = self.x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
            let mut rt = self.coarse.residual(&xt)?;
            rt.iter_mut().zip(defect).for_each(|(a, d)| *a += d);
            let after = inf_norm(&rt);
            let accepted = after < res;
            if accepted {
                self.iterations += 1;
                steps += 1;
                (self.x, r) = (xt, rt);
                if after <= tol.max(self.coarse.floor(&self.x, &r)) {
                    return Ok(true);
                }
            }
            // chord steps still needed at this contraction
            let left = (after / tol).ln() / (res / after).ln();
            if refreshed {
                // a fresh Jacobian that contracts slowly: the hand-over
                // rule of a single solve, whatever the policy
                if !accepted || left > CHORD_STEPS_LEFT {
                    return Ok(false);
                }
            } else if !accepted || left > policy.steps_left || steps >= policy.refresh_after {
                let (rc, fresh) = self.coarse.residual_and_jacobian(&self.x)?;
                r = rc.iter().zip(defect).map(|(a, d)| a + d).collect();
                *jac = fresh;
                lu = jac.clone().lu();
                refreshed = true;
            }
            res = inf_norm(&r);
        }
        Ok(false)
    }

    /// IVPs integrated by the run.
    fn evaluations(&self) -> usize {
        self.full.evaluations + self.coarse.evaluations
    }

    /// Whether the solve's IVP budget or deadline is spent.
    fn spent(&self, work: &Work) -> bool {
        let used = work.evaluations + self.evaluations();
        (work.max_evaluations > 0 && used >= work.max_evaluations)
            || work
                .deadline
                .is_some_and(|d| std::time::Instant::now() >= d)
    }
}
