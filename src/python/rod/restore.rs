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
    signature = (robot, inputs, unknowns, tip_force, tip_moment, steps, iterations, evaluations, jacobian, outcome=None, blocked=None, tensions=None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
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
    jacobian: Option<(usize, usize, Vec<f64>)>,
    outcome: Option<(i64, f64, Vec<f64>)>,
    blocked: Option<Vec<[f64; 3]>>,
    tensions: Option<Vec<f64>>,
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
    let jac = match jacobian {
        Some((m, n, v)) if m * n == v.len() && m == unknowns.len() && n == unknowns.len() => {
            Some(nalgebra::DMatrix::from_vec(m, n, v))
        }
        Some(_) => return Err(Error::input("state", "Jacobian of the wrong size").into()),
        None => None,
    };
    if tensions
        .as_ref()
        .is_some_and(|t| t.len() != na || t.iter().any(|v| !v.is_finite()))
    {
        return Err(Error::input("state", "tensions of the wrong size or not finite").into());
    }
    let mut sol = py.detach(|| {
        let counts = (steps, iterations, evaluations);
        if crate::solve::segments::segment_starts(&r, &loads, steps).len() > 1 {
            return several_segments(&r, &inputs, &loads, &unknowns, counts);
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
    sol.newton_jacobian = jac;
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

/// The solution of a body solved on several shooting segments (a heavy
/// one, whose single IVP from the base amplifies rounding past the
/// solution's accuracy): solved again, cold, on the same grid, and
/// accepted where its base unknowns are the pickled ones to `1e-6` (the
/// same equilibrium); else an error, never an unfaithful profile.
fn several_segments(
    r: &crate::rod::Robot,
    inputs: &[f64],
    loads: &crate::shooting::Loads,
    unknowns: &[f64],
    (steps, iterations, evaluations): (usize, usize, usize),
) -> crate::error::Result<crate::shooting::Solution> {
    let opts = crate::shooting::SolveOptions {
        steps,
        ..Default::default()
    };
    let mut sol = crate::shooting::solve_loaded(r, inputs, loads, &opts, None)?;
    let apart =
        (sol.unknowns.iter().zip(unknowns)).any(|(a, b)| (a - b).abs() > 1e-6 * (1.0 + b.abs()));
    if apart {
        return Err(Error::input(
            "state",
            "a solution on several shooting segments whose equilibrium a cold solve does not \
             reach again (pickle the robot and its inputs and solve again instead)",
        ));
    }
    (sol.iterations, sol.evaluations) = (iterations, evaluations);
    checked_solution(sol)
}
