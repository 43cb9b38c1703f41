//! Unpickling a `Solution`: rebuilt from its robot and converged unknowns.

use nalgebra::Vector3;
use pyo3::prelude::*;

use super::robot::PyRobot;
use super::solution::{checked_solution, PySolution};
use crate::error::Error;
use crate::shooting::Status;

/// Rebuild a `Solution` from its robot and converged unknowns (pickle
/// support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_solution",
    signature = (robot, inputs, unknowns, tip_force, tip_moment, steps, iterations, evaluations, outcome=None, blocked=None, tensions=None, segments=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn restore_solution(
    py: Python<'_>,
    robot: Bound<'_, PyRobot>,
    inputs: Vec<f64>,
    unknowns: Vec<f64>,
    tip_force: [f64; 3],
    tip_moment: [f64; 3],
    steps: usize,
    iterations: usize,
    evaluations: usize,
    outcome: Option<(i64, f64, Vec<f64>)>,
    blocked: Option<Vec<[f64; 3]>>,
    tensions: Option<Vec<f64>>,
    segments: Option<Vec<Vec<f64>>>,
) -> PyResult<PySolution> {
    let r = robot.get().inner.clone();
    let na = r.actuators.len();
    if inputs.len() != na
        || unknowns.len() != 6 + na
        || steps == 0
        || steps > crate::limits::MAX_STEPS
    {
        return Err(Error::input("state", "does not belong to this robot").into());
    }
    r.check_inputs(&inputs)?;
    let loads = crate::shooting::Loads {
        tip_force: Vector3::from(tip_force),
        tip_moment: Vector3::from(tip_moment),
    };
    if tensions
        .as_ref()
        .is_some_and(|t| t.len() != na || t.iter().any(|v| !v.is_finite()))
    {
        return Err(Error::input("state", "tensions of the wrong size or not finite").into());
    }
    let states = segments.map(|v| rod_states(&v, na)).transpose()?;
    let mut sol = py.detach(|| {
        let counts = (steps, iterations, evaluations);
        if let Some(states) = &states {
            let at = (&r, &inputs[..], &loads);
            let sol = crate::solve::forward::from_segment_states(
                at.0, at.1, at.2, steps, &unknowns, states,
            );
            return sol.and_then(|mut s| {
                (s.iterations, s.evaluations) = (iterations, evaluations);
                checked_solution(s)
            });
        }
        if crate::solve::segments::segment_starts(&r, &loads, steps).len() > 1 {
            let why = "a solution on several shooting segments without their states";
            return Err(Error::input("state", why));
        }
        match &tensions {
            // the solve's own tensions: the same IVP, bit for bit
            Some(tau) => crate::solve::solution::assemble_at_tensions(
                &r, &inputs, &loads, &unknowns, tau, counts.0, counts.1, counts.2,
            ),
            None => crate::shooting::assemble(
                &r, &inputs, &loads, &unknowns, counts.0, counts.1, counts.2,
            ),
        }
        .and_then(checked_solution)
    })?;
    if let Some((code, floor, path)) = outcome {
        sol.status = match code {
            0 => Status::Converged,
            1 => Status::ConvergedAtFloor,
            _ => return Err(Error::input("state", "unknown status").into()),
        };
        if !(floor.is_finite() && floor >= 0.0) || path.iter().any(|l| !(*l > 0.0 && *l <= 1.0)) {
            return Err(Error::input("state", "floor or continuation path out of range").into());
        }
        sol.floor = floor;
        sol.continuation_steps = path;
    }
    let mut out = PySolution::new(sol, robot.unbind());
    out.blocked = blocked
        .unwrap_or_default()
        .into_iter()
        .map(Vector3::from)
        .collect();
    if out
        .blocked
        .iter()
        .any(|b| !(b.iter().all(|x| x.is_finite()) && b.norm() > 0.0))
    {
        return Err(Error::input("state", "blocked directions must be finite and non-zero").into());
    }
    Ok(out)
}

/// The rod states of a pickle's `segments` (see `segment_states` in
/// `solution.rs`: `p`, `q`, `nu`, `omega`, the `na` elongations), each
/// quaternion normalised; an error for a wrong length, a value that is not
/// finite or a zero quaternion.
fn rod_states(segments: &[Vec<f64>], na: usize) -> PyResult<Vec<crate::rod::RodState>> {
    let state = |v: &Vec<f64>| {
        let q = nalgebra::Quaternion::new(v[3], v[4], v[5], v[6]);
        let fine = v.iter().all(|x| x.is_finite()) && q.norm() > 0.0;
        fine.then(|| crate::rod::RodState {
            p: Vector3::new(v[0], v[1], v[2]),
            q: q.normalize(),
            v: Vector3::new(v[7], v[8], v[9]),
            u: Vector3::new(v[10], v[11], v[12]),
            delta: v[13..].to_vec(),
        })
    };
    let bad = || Error::input("state", "segment states of the wrong size or not finite");
    let states = segments.iter().map(|v| match v.len() == 13 + na {
        true => state(v).ok_or_else(bad),
        false => Err(bad()),
    });
    Ok(states.collect::<Result<_, _>>()?)
}
