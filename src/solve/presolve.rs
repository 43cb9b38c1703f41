//! Coarse-grid pre-solve with defect correction, the direct Newton run of
//! a forward solve (cold or warm).
//!
//! A plain IVP costs in proportion to its RK4 steps, and the shooting
//! residual of a grid of a tenth of the steps differs from the full grid's
//! by RK4's truncation error only: a *defect* `d(x) = r_full(x) - r_coarse(x)`
//! that is small (Fig. 6, 10 against 100 steps: ~1e-6) and varies slowly
//! with `x`. So:
//!
//! 1. Newton on the coarse grid (its exact tangents, a tenth of the cost)
//!    to `0.1 tol`, from the cold guess or the warm one. Warm, the coarse
//!    system carries the warm solution's defect `-r_coarse(x_warm)` (its
//!    full residual is within `tol` of zero), and the warm Jacobian's
//!    actuator columns are rescaled to the force laws' slopes at the new
//!    inputs ([`rescale_tension_columns`]: the IVP depends on an elongation
//!    only through its tension). A kept coarse Jacobian (the warm one, or
//!    an earlier round's) is used for chord steps only while they contract
//!    fast enough (`CHORD_STEPS_LEFT`); then a fresh coarse tangent.
//! 2. One full-grid IVP at that point: converged if `max |r_full| <=
//!    max(tol, floor)` (the same test, on the same grid, as Newton's);
//!    else the defect is updated to `r_full(x) - r_coarse(x)` and step 1
//!    repeated from `x` with the coarse Jacobian (a chord step or two). The
//!    full residual contracts by the defect's variation, about the coarse
//!    grid's error in the Jacobian (Fig. 6: 1.4e-6 to ~1e-10 per round).
//!    A cold start's first round converges the coarse run to 1e-5 only
//!    (`FIRST_ROUND_TOL`: its root is just a point at which to measure the
//!    defect, ~1e-7 to 1e-6) and takes `r_full` there not from a full-grid
//!    IVP but extrapolated from grids of two and three times the coarse
//!    steps ([`Shot::extrapolated`], half a full-grid IVP, error ~1e-5 of
//!    the defect); its convergence is then decided by the next round's
//!    full-grid IVP, the only one of a cold Fig. 6 or steel solve. Other
//!    full-grid IVPs of a cold first round (the extrapolation failed, or
//!    the guess was a coarse root) record no nodes.
//! 3. A failure anywhere (coarse Newton, a full residual that does not
//!    contract tenfold, [`MAX_ROUNDS`] used) falls back on full-grid
//!    Newton (`newton_shooting`) from the best point reached; its work is
//!    counted on top. Except in a cold solve's direct run
//!    (`Work::cold_direct`): there a failed first coarse run, from the
//!    guess, ends the run (`shooting::handed_over`), and the solve goes
//!    on by continuation.
//!
//! Every IVP counts as one evaluation, coarse ones included
//! (`Solution.evaluations`); the designs bench's IVP-equivalents are CPU
//! times and so weigh them by their cost.

use std::ops::ControlFlow;

use nalgebra::DMatrix;

use super::newton::{
    chord_then_newton, converged_status, newton_from, NewtonOptions, NewtonResult, System,
};
use super::options::SolveOptions;
pub use super::residual::rescale_tension_columns;
use super::residual::{Loads, Shot};
use super::shooting::handed_over;
use super::system::{newton_shooting, FinalIvp, Keep, Shooting, Work, COARSE_JACOBIAN_MIN_STEPS};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// Defect-correction rounds (full-grid IVPs) before falling back on
/// full-grid Newton.
pub const MAX_ROUNDS: usize = 4;

/// Largest full-grid residual of a pre-solve's point from which the
/// fallback's Newton starts (farther: from the guess, as without pre-solve).
const FALLBACK_NEAR: f64 = 1e-3;

/// Iteration limit of each coarse Newton run (a cold Fig. 6 solve takes 4;
/// a coarse run that needs more is cut short and the full-grid Newton
/// takes over).
const COARSE_MAX_ITER: usize = 20;

/// Tolerance of a cold pre-solve's first coarse run (module docs): its
/// point need only be near enough the coarse root that the defect there is
/// the solution's to well within `tol` (it varies at ~2e-6 of `max |r|` on
/// Fig. 6: from 3.3e-4 a third round was needed). Against 1e-7: steel 7 ->
/// 6 IVPs (it stops at 1.8e-7), Fig. 6 the same 9, 1,000 designs 35,629 ->
/// 34,634 IVPs (1e-6: 35,108; 1e-4: 34,144, but 3x from Fig. 6's 3.3e-4).
const FIRST_ROUND_TOL: f64 = 1e-5;

/// The warm start of a pre-solve: the neighbouring solution's unknowns,
/// inputs and Newton Jacobian.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Warm<'a> {
    pub unknowns: &'a [f64],
    pub inputs: &'a [f64],
    pub jacobian: Option<&'a DMatrix<f64>>,
}

/// The coarse shooting residual plus a constant defect `d`, one system for
/// all rounds of a pre-solve (the defect changes between them). Remembers
/// its last coarse residual (before the defect), so that the first
/// evaluation of a round at the point where the last one stopped, or of
/// Newton at the point where a chord run stopped (`chord_then_newton`),
/// costs no IVP; and `max |r|` of a round's first evaluation. With
/// `tangent_first`, the first evaluation of a run that will take a fresh
/// Jacobian there (a cold start: [`newton_from`] evaluates the residual,
/// then the Jacobian at the same point) is the tangent IVP, whose residual
/// is the plain IVP's bit for bit, kept for the Jacobian's call: one
/// coarse IVP less.
struct Corrected<'a> {
    sys: Shooting<'a>,
    defect: Vec<f64>,
    /// The last coarse residual without the defect, at the unknowns.
    last: Option<(Vec<f64>, Vec<f64>)>,
    /// A tangent evaluation not yet asked for: unknowns, coarse residual
    /// without the defect, Jacobian.
    tangent: Option<(Vec<f64>, Vec<f64>, DMatrix<f64>)>,
    first: Option<f64>,
    tangent_first: bool,
}

impl Corrected<'_> {
    /// `r + defect`, noted as the round's first if it is.
    fn corrected(&mut self, r: &[f64]) -> Vec<f64> {
        let mut r = r.to_vec();
        r.iter_mut().zip(&self.defect).for_each(|(a, d)| *a += d);
        self.first.get_or_insert(inf_norm(&r));
        r
    }
}

impl System for Corrected<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        if let Some((xl, rl)) = &self.last {
            if xl == x {
                let rl = rl.clone();
                return Ok(self.corrected(&rl));
            }
        }
        let raw = if std::mem::take(&mut self.tangent_first) {
            let (raw, j) = self.sys.residual_and_jacobian(x)?;
            self.tangent = Some((x.to_vec(), raw.clone(), j));
            raw
        } else {
            self.sys.residual(x)?
        };
        let r = self.corrected(&raw);
        self.last = Some((x.to_vec(), raw));
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let (raw, j) = match self.tangent.take() {
            Some((xt, raw, j)) if xt == x => (raw, j),
            _ => self.sys.residual_and_jacobian(x)?,
        };
        Ok((self.corrected(&raw), j))
    }
    fn floor(&self, x: &[f64], r: &[f64]) -> f64 {
        self.sys.floor(x, r)
    }
    fn evaluations(&self) -> usize {
        self.sys.evaluations
    }
    fn refine(&mut self, x: &[f64]) -> bool {
        self.sys.refine(x)
    }
    fn limit_step(&self, x: &[f64], dx: &[f64], r: &[f64], jac: &DMatrix<f64>) -> Option<Vec<f64>> {
        self.sys.limit_step(x, dx, r, jac) // the force laws do not depend on the grid
    }
}

/// The problem of one pre-solve (see the module docs).
struct PreSolve<'a> {
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: &'a Loads,
    opts: &'a SolveOptions,
    coarse: usize,
}

impl<'a> PreSolve<'a> {
    /// The coarse system of all rounds, at zero defect.
    fn coarse_system(&self, n: usize) -> Corrected<'a> {
        Corrected {
            sys: Shooting::new(self.robot, self.inputs, self.loads, self.coarse, false),
            defect: vec![0.0; n],
            last: None,
            tangent: None,
            first: None,
            tangent_first: false,
        }
    }

    /// The coarse runs' tolerance: `0.1 tol`, or in a cold first round
    /// `FIRST_ROUND_TOL`.
    fn tol(&self, cold_first: bool) -> f64 {
        match cold_first {
            true => FIRST_ROUND_TOL.max(0.1 * self.opts.tol),
            false => 0.1 * self.opts.tol,
        }
    }

    /// The full-grid residual of a round at the coarse run's point `x`,
    /// where the coarse residual is `rc`; with `estimate` (a cold first
    /// round) extrapolated if it can be, and whether it was. `None`: the
    /// IVP failed. A full-grid IVP of an `estimate` round records no nodes.
    fn full_residual(
        &self,
        full: &mut Shooting<'_>,
        (x, rc): (&[f64], &[f64]),
        (estimate, record): (bool, Keep),
        work: &mut Work,
    ) -> Result<Option<(Vec<f64>, bool)>> {
        if estimate {
            let shot = Shot::new(self.robot, self.inputs, self.loads, self.coarse);
            let mut ivps = 0;
            let r = shot.extrapolated(x, rc, self.opts.steps, &mut ivps);
            work.evaluations += ivps;
            if let Some(r) = unless_interrupted(r)? {
                return Ok(Some((r, true)));
            }
        }
        full.set_keep(if estimate { record.tip_only() } else { record });
        Ok(unless_interrupted(full.residual(x))?.map(|r| (r, false)))
    }

    /// Coarse Newton on `r_coarse + defect` (`sys`, its defect set) from
    /// `x0`; its result, the coarse IVPs used and `max |r_coarse + defect|`
    /// at `x0`.
    fn coarse_run(
        &self,
        sys: &mut Corrected<'a>,
        x0: &[f64],
        jac0: Option<&DMatrix<f64>>,
        tol: f64,
        work: &Work,
    ) -> (Result<NewtonResult>, usize, f64) {
        let before = sys.sys.evaluations;
        sys.first = None;
        // a cold start away from the last point takes a Jacobian at x0
        sys.tangent_first = jac0.is_none() && !matches!(&sys.last, Some((xl, _)) if xl == x0);
        let nopts = NewtonOptions {
            tol,
            max_iter: COARSE_MAX_ITER.min(self.opts.max_iter),
            ..work.newton_options(self.opts)
        };
        let out = match jac0 {
            Some(jac) => chord_then_newton(sys, x0, jac, &nopts),
            _ => newton_from(sys, x0, &nopts, "coarse pre-solve", jac0),
        };
        sys.tangent_first = false;
        sys.tangent = None;
        let first = sys.first.unwrap_or(f64::INFINITY);
        (out, sys.sys.evaluations - before, first)
    }
}

fn inf_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The coarse system's initial defect and Jacobian: warm, the warm
/// solution's defect (its full residual is ~0: `-r_coarse(x_warm)`, one
/// coarse IVP) and its Jacobian at the new tension slopes; cold, zero and
/// none.
fn warm_start(
    robot: &Robot,
    loads: &Loads,
    coarse: usize,
    x0: &[f64],
    inputs: &[f64],
    warm: Option<Warm<'_>>,
    work: &mut Work,
) -> (Vec<f64>, Option<DMatrix<f64>>) {
    let mut defect = vec![0.0; x0.len()];
    let Some(w) = warm else {
        return (defect, None);
    };
    work.evaluations += 1;
    if let Ok((rw, _, _)) = Shot::new(robot, w.inputs, loads, coarse).residual(w.unknowns, false) {
        defect = rw.iter().map(|r| -r).collect();
    }
    let jac = w
        .jacobian
        .map(|j| rescale_tension_columns(robot, j, (w.unknowns, w.inputs), (x0, inputs)));
    (defect, jac)
}

/// The direct Newton run of a forward solve with the coarse-grid pre-solve
/// (see the module docs); the same contract as [`newton_shooting`], which it
/// falls back on (and which it is when `opts.steps` is below ten times
/// [`COARSE_JACOBIAN_MIN_STEPS`]).
#[allow(clippy::too_many_arguments)] // the shooting problem's parts, as newton_shooting's
pub(crate) fn presolved_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    warm: Option<Warm<'_>>,
    record: Keep,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let jac0 = warm.and_then(|w| w.jacobian);
    let coarse = opts.steps / 10;
    if coarse < COARSE_JACOBIAN_MIN_STEPS || !opts.presolve {
        return newton_shooting(robot, inputs, loads, opts, x0, jac0, record, work);
    }
    let pre = PreSolve {
        robot,
        inputs,
        loads,
        opts,
        coarse,
    };
    let mut rounds = Rounds::start(&pre, x0, warm, record, work);
    for round in 0..MAX_ROUNDS {
        match rounds.round(&pre, round, warm.is_none(), record, work)? {
            ControlFlow::Break(Some(out)) => return Ok(out),
            ControlFlow::Break(None) => break,
            ControlFlow::Continue(()) => {}
        }
    }
    // fall back on full-grid Newton: from the last point if it came near
    // (it is then as good a start as any), else from the guess
    work.evaluations += rounds.full.evaluations;
    work.iterations += rounds.iterations;
    let (from, jac) = match rounds.last_norm <= FALLBACK_NEAR {
        true => (rounds.x.as_slice(), rounds.jac.as_ref()),
        false => (x0, jac0),
    };
    newton_shooting(robot, inputs, loads, opts, from, jac, record, work)
}

/// A converged direct run: Newton's result and the IVP at its solution if
/// that was the last one integrated.
type Direct = (NewtonResult, Option<FinalIvp>);

/// The state of a pre-solve's rounds: the full-grid system (its IVPs
/// counted on `work` at the end), the one coarse system, the defect and
/// Jacobian the next round starts with, the point reached and the history
/// of `max |r|`.
struct Rounds<'a> {
    full: Shooting<'a>,
    coarse: Corrected<'a>,
    defect: Vec<f64>,
    jac: Option<DMatrix<f64>>,
    x: Vec<f64>,
    iterations: usize,
    /// The last round's full-grid `max |r|`.
    last_norm: f64,
    /// `max |r_coarse + d|` at the start of the first round.
    start_norm: f64,
    /// Warm: `max |d|` of the warm solution's defect.
    warm_defect: Option<f64>,
}

impl<'a> Rounds<'a> {
    /// Before the first round, from `x0` (warm: its defect and Jacobian).
    fn start(
        pre: &PreSolve<'a>,
        x0: &[f64],
        warm: Option<Warm<'_>>,
        record: Keep,
        work: &mut Work,
    ) -> Self {
        let (defect, jac) =
            warm_start(pre.robot, pre.loads, pre.coarse, x0, pre.inputs, warm, work);
        Rounds {
            full: Shooting::new(pre.robot, pre.inputs, pre.loads, pre.opts.steps, record),
            coarse: pre.coarse_system(x0.len()),
            warm_defect: warm.map(|_| inf_norm(&defect)),
            defect,
            jac,
            x: x0.to_vec(),
            iterations: 0,
            last_norm: f64::INFINITY,
            start_norm: f64::INFINITY,
        }
    }

    /// Round `round` (from 0; `cold`: no warm start): the coarse run, then
    /// the full-grid residual at its point. `Break(Some)`: converged;
    /// `Break(None)`: fall back; `Continue`: another round, its defect set.
    fn round(
        &mut self,
        pre: &PreSolve<'a>,
        round: usize,
        cold: bool,
        record: Keep,
        work: &mut Work,
    ) -> Result<ControlFlow<Option<Direct>>> {
        self.coarse.defect.clone_from(&self.defect);
        // (a cold start's first round: see the module docs)
        let cold_first = round == 0 && cold;
        let tol = pre.tol(cold_first);
        let (out, evals, first) =
            pre.coarse_run(&mut self.coarse, &self.x, self.jac.as_ref(), tol, work);
        if round == 0 {
            self.start_norm = first;
        }
        let history = round_history(round, self.warm_defect, self.start_norm, self.last_norm);
        if let Some((older, newer)) = history {
            self.full.set_history(older, newer);
        }
        work.evaluations += evals;
        let out = match out {
            Err(e) if cold_first && work.cold_direct => return Err(handed_over(e, work)),
            out => out,
        };
        let Some(nr) = unless_interrupted(out)? else {
            return Ok(ControlFlow::Break(None));
        };
        self.iterations += nr.iterations;
        self.x = nr.x;
        self.jac = nr.jacobian.or(self.jac.take());
        // extrapolated unless the guess was a coarse root already (a
        // uniform strain, which RK4 integrates exactly)
        let estimate = cold_first && nr.iterations > 0 && !nr.residual.is_empty();
        let xr = (self.x.as_slice(), nr.residual.as_slice());
        let Some((r, estimated)) =
            pre.full_residual(&mut self.full, xr, (estimate, record), work)?
        else {
            return Ok(ControlFlow::Break(None));
        };
        let norm = inf_norm(&r);
        let floor = self.full.floor(&self.x, &r);
        if norm <= pre.opts.tol.max(floor) && !estimated {
            let out = self.converged(r, (norm, floor), pre.opts.tol, work);
            return Ok(ControlFlow::Break(Some(out)));
        }
        if !(norm <= 0.1 * self.last_norm) {
            return Ok(ControlFlow::Break(None));
        }
        self.last_norm = norm;
        // (the coarse run's last chord step unevaluated: its residual now)
        work.evaluations += usize::from(nr.residual.is_empty());
        let rc = match nr.residual.is_empty() {
            true => unless_interrupted(self.coarse.residual(&self.x))?,
            false => Some(nr.residual),
        };
        let Some(rc) = rc else {
            return Ok(ControlFlow::Break(None));
        };
        // the new defect: r_full(x) - r_coarse(x), r_coarse(x) = rc - defect
        for ((d, rf), rc) in self.defect.iter_mut().zip(&r).zip(&rc) {
            *d += rf - rc;
        }
        Ok(ControlFlow::Continue(()))
    }

    /// The result of a round whose full-grid residual `residual` converged
    /// (`max |r|` `norm`, rounding floor `floor`), all work counted.
    fn converged(
        &mut self,
        residual: Vec<f64>,
        (norm, floor): (f64, f64),
        tol: f64,
        work: &mut Work,
    ) -> Direct {
        work.evaluations += self.full.evaluations;
        work.iterations += self.iterations;
        let last = self.full.take_last(&self.x);
        let nr = NewtonResult {
            x: std::mem::take(&mut self.x),
            residual,
            norm,
            floor,
            status: converged_status(norm, tol),
            iterations: self.iterations,
            evaluations: work.evaluations,
            jacobian: self.jac.take(),
        };
        (nr, last)
    }
}

/// The `max |r|` history from which the full-grid evaluation of round
/// `round` (from 0) is predicted to converge under a stability verdict
/// ([`Shooting::predicts_convergence`]: `newer^2 / older`), where the
/// rounds' own evaluations are not enough (`None` from the third on).
/// Round 0 warm: the full residual at the coarse root is the defect's
/// change since the warm solution, predicted no larger than the warm
/// defect `warm_defect` itself (`[d, d]`); cold, nothing to predict from.
/// Round 1: round 0 taken as one step of an at least linearly convergent
/// iteration from the coarse run's first residual `start` (the full
/// residual at the start to within the defect) to `last`, the first
/// full-grid residual (`[start, last]`). On the fixtures of
/// `tests/stability_policy.rs` it predicts every run that converges in
/// two rounds; it errs early where the second round's residual is held
/// up by rounding just above the floor (steel robot cold at 14 N: 1.2e-7,
/// 9.1e-10 against a floor of 8.9e-10, then 3.6e-11), which costs a
/// tangent IVP in place of a plain one.
fn round_history(
    round: usize,
    warm_defect: Option<f64>,
    start: f64,
    last: f64,
) -> Option<(f64, f64)> {
    match round {
        0 => warm_defect.map(|d| (d, d)),
        1 => Some((start, last)),
        _ => None,
    }
}

/// `Ok(Some(value))`, `Ok(None)` for an error the pre-solve falls back from,
/// or the error if it is an interrupt (which ends the solve).
fn unless_interrupted<T>(r: Result<T>) -> Result<Option<T>> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(e @ Error::Interrupted) => Err(e),
        Err(_) => Ok(None),
    }
}
