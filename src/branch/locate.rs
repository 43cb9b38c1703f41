//! Event location on a followed branch: regula falsi (Illinois) on the
//! event's test function along the arclength from the point before it,
//! each trial point one continuation step from there.

use super::follow::{det_at, Collector, Recorded};
use super::{BranchPoint, Event, EventKind};
use crate::error::{Error, Result};
use crate::shooting::Solution;
use crate::solve::arclength::{self, ArclengthOptions, Heading, PathPoint};

/// Iterations of the regula falsi: the Illinois variant converges with
/// order 1.44 (Dowell & Jarratt, BIT 11, 1971), from a bracket of one step
/// to `1e-7` of it in well under 16.
const ITERATIONS: usize = 16;

/// Width of the bracket, relative to the step, at which the search stops:
/// the parameter is then known to `1e-7` of a step, far below the accuracy
/// of the grid's discretisation.
const BRACKET: f64 = 1e-7;

/// One trial point of the location: the continuation from `a` (its
/// tangent oriented as on the path) with a first step `s`, stopped at its
/// first point; that point and its arclength from `a` (`None` if the step
/// failed).
fn trial(
    sys: &mut Recorded<'_, '_>,
    (opts, target): (&ArclengthOptions, f64),
    a: &PathPoint,
    s: f64,
) -> Result<Option<PathPoint>> {
    if !(s.is_finite() && s > 0.0) {
        return Ok(None);
    }
    let heading = match a.tangent_lambda * (target - a.lambda) >= 0.0 {
        true => Heading::TowardTarget,
        false => Heading::AwayFromTarget,
    };
    let o = ArclengthOptions {
        initial_step: s,
        min_step: opts.min_step.min(s),
        max_step: opts.max_step.max(s),
        heading,
        // a step rejected a few times lands at a shorter arclength, which
        // the regula falsi takes as it is
        max_steps: 8,
        ..opts.clone()
    };
    sys.dets.borrow_mut().clear();
    let mut first = |_: &PathPoint, _: &PathPoint| true;
    let out =
        arclength::follow_with_events(sys, &a.x, a.lambda, target, &o, true, &mut [&mut first]);
    match out {
        Ok(path) if path.points.len() >= 2 => Ok(path.points.last().cloned()),
        Ok(_) => Ok(None),
        Err(Error::Interrupted) => Err(Error::Interrupted),
        Err(_) => Ok(None),
    }
}

/// The event of `kind` between branch points `i` and `i + 1`, located by
/// regula falsi on the arclength `s` from point `i`: a fold on
/// `d parameter / d s`; a bifurcation on the stability margin where it
/// changes sign between the points, else on `det G_x`. The event's
/// parameter and tip are those of the last trial point (of point `i + 1`
/// if no trial succeeded).
pub(super) fn locate(
    sys: &mut Recorded<'_, '_>,
    col: &mut Collector<'_, '_, '_>,
    (opts, target): (&ArclengthOptions, f64),
    kind: EventKind,
    i: usize,
) -> Result<Event> {
    let (a, ds) = (col.path[i].clone(), col.path[i + 1].step);
    let (pa, pb) = (&col.points[i], &col.points[i + 1]);
    let on_margin = pa.stability.margin * pb.stability.margin < 0.0;
    let test = |p: &BranchPoint| match kind {
        EventKind::Fold => p.dparameter,
        EventKind::Bifurcation if on_margin => p.stability.margin,
        EventKind::Bifurcation => p.jacobian_det,
    };
    let fallback = (pb.parameter, pb.solution.tip_position());
    let (mut s0, mut f0) = (0.0, test(pa));
    let (mut s1, mut f1) = (ds, test(pb));
    let mut best: Option<(PathPoint, Option<Solution>)> = None;
    // Illinois: halve the stale end's value so both ends move
    let mut side = 0i32;
    for _ in 0..ITERATIONS {
        // (a NaN product also stops the search)
        if !(f0 * f1 < 0.0) {
            break;
        }
        let sm = s0 - f0 * (s1 - s0) / (f1 - f0);
        let Some(p) = trial(sys, (opts, target), &a, sm)? else {
            break;
        };
        let det = det_at(sys.dets, &p);
        let fm = match kind {
            EventKind::Fold => col.geo.dparameter(p.tangent_lambda),
            EventKind::Bifurcation if on_margin => {
                col.work += 1;
                let sol = col.geo.solution(&p.x, p.lambda)?;
                let (point, work) = col.geo.point(&p, sol, det)?;
                col.work += work;
                let fm = test(&point);
                best = Some((p.clone(), Some(point.solution)));
                fm
            }
            EventKind::Bifurcation => det,
        };
        let sm = p.step;
        if !on_margin || kind == EventKind::Fold {
            best = Some((p, None));
        }
        if fm == 0.0 {
            break;
        }
        if fm * f0 > 0.0 {
            (s0, f0) = (sm, fm);
            if side == -1 {
                f1 *= 0.5;
            }
            side = -1;
        } else {
            (s1, f1) = (sm, fm);
            if side == 1 {
                f0 *= 0.5;
            }
            side = 1;
        }
        if (s1 - s0).abs() < BRACKET * ds {
            break;
        }
    }
    let (parameter, tip_position) = match best {
        Some((p, sol)) => {
            let sol = match sol {
                Some(sol) => sol,
                None => {
                    col.work += 1;
                    col.geo.solution(&p.x, p.lambda)?
                }
            };
            (col.geo.parameter(p.lambda), sol.tip_position())
        }
        None => fallback,
    };
    Ok(Event {
        kind,
        parameter,
        tip_position,
        after_point: i,
    })
}
