//! Branch following on the solver's continuation: the path in inputs and
//! loads ([`LoadPath`]) between the problem at `opts.start` and at
//! `opts.end`, followed by pseudo-arclength continuation on the
//! multiple-shooting system ([`arclength::follow_with_events`]); each
//! accepted point is given its [`Solution`], its stability verdict and
//! `det G_x`, and the events between points are located afterwards
//! ([`super::locate`]).

use std::cell::RefCell;

use nalgebra::Quaternion;

use super::locate::locate;
use super::{Branch, BranchOptions, BranchPoint, EventKind, Problem};
use crate::error::{Error, Result};
use crate::shooting::{Solution, Status};
use crate::solve::arclength::{
    self, ArclengthOptions, ParametrisedSystem, PathPoint, Predictor, CORRECTOR_ITERATIONS,
};
use crate::solve::forward::{assemble, first_guess};
use crate::solve::homotopy::{Endpoint, LoadPath};
use crate::solve::ms::MultipleShooting;
use crate::solve::segments::segment_starts;

/// `det G_x` of each linearisation since the record was last cleared, with
/// the point `(x, lambda)` it was made at (`None`: singular).
pub(super) type Dets = RefCell<Vec<(Vec<f64>, f64, Option<f64>)>>;

/// The [`LoadPath`] of a branch, recording `det G_x` at every
/// linearisation: the continuation's last linearisation at an accepted point
/// is its tangent's, at that very point.
pub(super) struct Recorded<'a, 'd> {
    pub(super) path: LoadPath<'a>,
    pub(super) dets: &'d Dets,
}

impl ParametrisedSystem for Recorded<'_, '_> {
    fn dim(&self) -> usize {
        self.path.dim()
    }
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
        self.path.residual(x, lambda, f)
    }
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()> {
        self.path.linearise_bordered(x, lambda, row, f)?;
        let det = self.path.determinant();
        self.dets.borrow_mut().push((x.to_vec(), lambda, det));
        Ok(())
    }
    fn solve_bordered(
        &mut self,
        b: &[f64],
        b_last: f64,
        dx: &mut [f64],
        dlambda: &mut f64,
    ) -> Result<bool> {
        self.path.solve_bordered(b, b_last, dx, dlambda)
    }
    fn floor(&self, x: &[f64], f: &[f64]) -> f64 {
        self.path.floor(x, f)
    }
    fn work(&self) -> f64 {
        self.path.work()
    }
    fn domain(&self) -> (f64, f64) {
        self.path.domain()
    }
}

/// The branch's path: the problem, the parameter at its ends, and the
/// multiple-shooting grid its unknowns live on.
pub(super) struct Geometry<'p, 'r> {
    pub(super) pb: &'p Problem<'r>,
    pub(super) start: f64,
    pub(super) end: f64,
    pub(super) steps: usize,
    /// The correctors' tolerance.
    pub(super) tol: f64,
    pub(super) starts: Vec<usize>,
    pub(super) charts: Vec<Quaternion<f64>>,
}

impl Geometry<'_, '_> {
    /// The parameter at path parameter `lambda`: `start` at 0, `end` at 1,
    /// both exactly.
    pub(super) fn parameter(&self, lambda: f64) -> f64 {
        (1.0 - lambda) * self.start + lambda * self.end
    }

    /// `d parameter / d s` scaled by `|end - start|` from the tangent's
    /// `d lambda / d s`.
    pub(super) fn dparameter(&self, tangent_lambda: f64) -> f64 {
        tangent_lambda * (self.end - self.start).signum()
    }

    /// The [`Solution`] at the multiple-shooting unknowns `x` of path
    /// parameter `lambda` (one IVP: the residual evaluation recorded), with
    /// the rounding floor of its residual and, where its residual lies
    /// above `tol`, the status of a solve that stopped at that floor.
    pub(super) fn solution(&self, x: &[f64], lambda: f64) -> Result<Solution> {
        let (robot, inputs, loads) = self.pb.at(self.parameter(lambda))?;
        let charts = self.charts.clone();
        let mut ms =
            MultipleShooting::new(&robot, &inputs, loads, self.steps, &self.starts, charts)?;
        let mut sol = assemble(&mut ms, x, (0, 1))?;
        sol.floor = ms.rounding_floor(x);
        if sol.residual > self.tol {
            sol.status = Status::ConvergedAtFloor;
        }
        Ok(sol)
    }

    /// The branch point at `p` with its solution `solution` and `det G_x`;
    /// its stability's work.
    pub(super) fn point(
        &self,
        p: &PathPoint,
        solution: Solution,
        det: f64,
    ) -> Result<(BranchPoint, usize)> {
        let parameter = self.parameter(p.lambda);
        let stability = self.pb.stability(&solution, parameter)?;
        let work = stability.evaluations;
        let point = BranchPoint {
            parameter,
            solution,
            stability,
            dparameter: self.dparameter(p.tangent_lambda),
            jacobian_det: det,
        };
        Ok((point, work))
    }
}

/// `det G_x` recorded at `p` (NaN if none was).
pub(super) fn det_at(dets: &Dets, p: &PathPoint) -> f64 {
    let dets = dets.borrow();
    let at = dets
        .iter()
        .rev()
        .find(|(x, l, _)| *l == p.lambda && *x == p.x);
    at.and_then(|d| d.2).unwrap_or(f64::NAN)
}

/// The event between two consecutive branch points, by its test functions:
/// a fold (sign change of `d parameter / d s`), else a bifurcation (sign
/// change of `det G_x`, or of the verdict: a symmetric double root leaves
/// the sign of `det G_x`).
fn classify(a: &BranchPoint, b: &BranchPoint) -> Option<EventKind> {
    if a.dparameter * b.dparameter < 0.0 {
        Some(EventKind::Fold)
    } else if a.jacobian_det * b.jacobian_det < 0.0 || a.stability.stable != b.stability.stable {
        Some(EventKind::Bifurcation)
    } else {
        None
    }
}

/// The continuation's event: each accepted point becomes a branch point,
/// and the pairs with an event are noted for [`locate`]. It stops the
/// path at `max_points`, where the path leaves the interval behind its
/// start (`lambda < 0`, after a fold), and in sweep mode at the first
/// point that is unstable or past a fold.
pub(super) struct Collector<'g, 'p, 'r> {
    pub(super) geo: &'g Geometry<'p, 'r>,
    pub(super) dets: &'g Dets,
    /// The first point's unknowns and its solution (the start's solve).
    first: Option<(Vec<f64>, Solution)>,
    pub(super) path: Vec<PathPoint>,
    pub(super) points: Vec<BranchPoint>,
    /// `(kind, i)`: an event between points `i` and `i + 1`.
    pending: Vec<(EventKind, usize)>,
    /// IVPs spent on solutions and verdicts.
    pub(super) work: usize,
    max_points: usize,
    sweep: bool,
    failed: Option<Error>,
}

impl Collector<'_, '_, '_> {
    /// Add the branch point at `p`.
    fn add(&mut self, p: &PathPoint) -> Result<()> {
        let solution = match self.first.take() {
            Some((x, sol)) if x == p.x && p.lambda == 0.0 => sol,
            _ => {
                self.work += 1;
                self.geo.solution(&p.x, p.lambda)?
            }
        };
        let det = det_at(self.dets, p);
        let (point, work) = self.geo.point(p, solution, det)?;
        self.work += work;
        self.points.push(point);
        self.path.push(p.clone());
        Ok(())
    }

    /// The event of [`arclength::follow_with_events`]: `true` stops the path.
    fn pair(&mut self, a: &PathPoint, b: &PathPoint) -> bool {
        let added = match self.points.is_empty() {
            true => self.add(a).and_then(|_| self.add(b)),
            false => self.add(b),
        };
        self.dets.borrow_mut().clear();
        if let Err(e) = added {
            self.failed = Some(e);
            return true;
        }
        let n = self.points.len();
        let (pa, pb) = (&self.points[n - 2], &self.points[n - 1]);
        let kind = classify(pa, pb);
        self.pending.extend(kind.map(|k| (k, n - 2)));
        let fold = kind == Some(EventKind::Fold);
        let unstable = !pb.stability.stable;
        n >= self.max_points || b.lambda < 0.0 || (self.sweep && (unstable || fold))
    }
}

/// The continuation's options for `opts`: the path parameter `lambda`
/// runs over `[0, 1]` as the parameter over `[start, end]`, so a step of
/// `opts` (in units of `|end - start|`) is the same arclength in the norm
/// `|z|_w^2 = |x|^2 / n + lambda^2` ([`arclength`]'s with weight 1), where a
/// step along the parameter alone is its change over `|end - start|`. The
/// tangent predictor resolves every fold with points on both sides
/// ([`Predictor::Tangent`]); each corrector has `opts.solve.tol` and at most
/// `opts.solve.max_iter` iterations. The path is bounded by `max_points`
/// and `min_step`, not by a step count.
pub(super) fn arclength_options(opts: &BranchOptions) -> ArclengthOptions {
    ArclengthOptions {
        tol: opts.solve.tol,
        initial_step: opts.step,
        min_step: opts.min_step,
        max_step: opts.max_step,
        max_steps: usize::MAX,
        predictor: Predictor::Tangent,
        corrector_iterations: opts.solve.max_iter.min(CORRECTOR_ITERATIONS),
        ..Default::default()
    }
}

/// Follow the branch through `start` (a converged equilibrium at
/// `opts.start`, or a cold solve there) toward `opts.end`.
///
/// The parameter enters the problem linearly ([`super::Parameter`]), so the
/// branch is the continuation of the multiple-shooting system along the
/// straight path in inputs and loads between the problem at `opts.start`
/// and at `opts.end` ([`LoadPath`]), on the segments of the end with the
/// larger loads ([`segment_starts`]), from the equilibrium at `opts.start`.
/// It ends at `opts.end` exactly, where an input leaves its force law's
/// range, where it turns back behind `opts.start` (the point beyond
/// included), at `max_points`, or where the step falls below `min_step`
/// (with the points so far; an error if there are none past the first).
pub fn follow_branch(
    pb: &Problem<'_>,
    opts: &BranchOptions,
    start: Option<&Solution>,
) -> Result<Branch> {
    opts.validate()?;
    let sol0 = pb.solve(opts.start, &opts.solve, start)?;
    let steps = opts.solve.steps;
    let (ra, ia, la) = pb.at(opts.start)?;
    let (rb, ib, lb) = pb.unchecked(opts.end);
    let (sa, sb) = (
        segment_starts(&ra, &la, steps),
        segment_starts(&rb, &lb, steps),
    );
    let starts = if sb.len() > sa.len() { sb } else { sa };
    let (ms, x0) = first_guess(&ra, &ia, la, steps, (&starts, &sol0.unknowns), Some(&sol0))?;
    let charts = ms.charts().to_vec();
    let ends = (
        Endpoint::loaded(&ra, &ia, la),
        Endpoint::loaded(&rb, &ib, lb),
    );
    let dets = Dets::default();
    let path = LoadPath::new(pb.robot, ends, steps, starts.clone(), charts.clone());
    let mut sys = Recorded { path, dets: &dets };
    let target = sys.domain().1.min(1.0);
    let geo = Geometry {
        pb,
        start: opts.start,
        end: opts.end,
        steps,
        tol: opts.solve.tol,
        starts,
        charts,
    };
    let aopts = arclength_options(opts);
    let mut col = Collector {
        geo: &geo,
        dets: &dets,
        first: Some((x0.clone(), sol0.clone())),
        path: Vec::new(),
        points: Vec::new(),
        pending: Vec::new(),
        work: sol0.evaluations,
        max_points: opts.max_points,
        sweep: opts.stop_when_unstable,
        failed: None,
    };
    let out = {
        let mut event = |a: &PathPoint, b: &PathPoint| col.pair(a, b);
        arclength::follow_with_events(&mut sys, &x0, 0.0, target, &aopts, true, &mut [&mut event])
    };
    match (out, col.failed.take()) {
        (Err(Error::Interrupted), _) => return Err(Error::Interrupted),
        (_, Some(e)) | (Err(e), None) if col.points.len() < 2 => return Err(e),
        (Ok(path), None) if col.points.is_empty() => col.add(&path.points[0])?,
        _ => {}
    }
    let mut events = Vec::new();
    for (kind, i) in std::mem::take(&mut col.pending) {
        events.push(locate(&mut sys, &mut col, (&aopts, target), kind, i)?);
    }
    Ok(Branch {
        points: col.points,
        events,
        evaluations: col.work + sys.work().ceil() as usize,
    })
}
