//! The stable sweep: follow the branch while stable, jump where the physical
//! robot would.

use super::{follow_branch, BranchOptions, BranchPoint, EventKind, Problem};
use crate::error::{Error, Result};
use crate::shooting::Solution;
use crate::stability::land;

/// A jump of the physical robot in a stable sweep.
#[derive(Debug, Clone)]
pub struct Jump {
    /// Parameter at which the stable branch ends (fold or stability loss).
    pub parameter: f64,
    /// The last stable equilibrium before the jump.
    pub before: Solution,
    /// The stable equilibrium the robot lands on, just past the jump.
    pub after: Solution,
}

/// Result of [`sweep_stable`].
#[derive(Debug, Clone)]
pub struct StableSweep {
    /// Stable points in parameter order.
    pub points: Vec<BranchPoint>,
    /// Jumps, in order.
    pub jumps: Vec<Jump>,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// Sweep the parameter from `opts.start` to `opts.end` staying on stable
/// equilibria: follow the branch until it loses stability (fold or
/// bifurcation) or turns back in the parameter (a fold), then land on a stable equilibrium just beyond (the nearest
/// one, by tip position, among those reached from a few perturbed starts)
/// and go on. Equilibria that are unstable from the start are refused.
pub fn sweep_stable(
    pb: &Problem<'_>,
    opts: &BranchOptions,
    start: Option<&Solution>,
) -> Result<StableSweep> {
    opts.validate()?;
    let mut o = *opts;
    o.stop_when_unstable = true;
    let mut points: Vec<BranchPoint> = vec![];
    let mut jumps = vec![];
    let mut evals = 0;
    let mut from: Option<Solution> = start.cloned();
    let dir = (opts.end - opts.start).signum();
    for _ in 0..20 {
        let br = follow_branch(pb, &o, from.as_ref())?;
        evals += br.evaluations;
        let n0 = points.len();
        // the sweep ends early at a loss of stability or at a fold (the
        // parameter cannot run back)
        let folded = br.events.iter().any(|e| e.kind == EventKind::Fold);
        let ended_early = folded || br.points.last().is_some_and(|p| !p.stability.stable);
        let within = |l: f64| (l - opts.end) * dir <= 0.0;
        for p in br.points.into_iter() {
            let ahead = points.last().map_or(true, |q: &BranchPoint| {
                (p.parameter - q.parameter) * dir > 0.0
            });
            if p.stability.stable && within(p.parameter) && ahead {
                points.push(p);
            }
        }
        if points.len() == n0 {
            return Err(Error::input(
                "start",
                "the equilibrium at the start of the sweep is not stable",
            ));
        }
        if !ended_early {
            break;
        }
        let before = points.last().expect("non-empty").solution.clone();
        let lam_c = br
            .events
            .last()
            .map_or(points.last().expect("non-empty").parameter, |e| e.parameter);
        if !within(lam_c) {
            break;
        }
        let past = lam_c + dir * 3e-3 * (opts.end - opts.start).abs();
        let (robot, inputs, loads) = pb.at(past)?;
        let landing = land(&robot, &inputs, &loads, &before, None, &opts.solve, true)?;
        evals += landing.evaluations;
        let after = landing.solution;
        jumps.push(Jump {
            parameter: lam_c,
            before,
            after: after.clone(),
        });
        o.start = past;
        from = Some(after);
        if !within(past) {
            break;
        }
    }
    Ok(StableSweep {
        points,
        jumps,
        evaluations: evals,
    })
}
