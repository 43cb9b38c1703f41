//! The boundary value problem (paper Section III, eqs 32-33): its public
//! entry points and the names they use.
//!
//! The base unknowns (scaled to be dimensionless and of order one):
//! `x = [nu(0), L omega(0), delta_1/L, ..., delta_N/L]` where `delta_i` is
//! the total elongation of actuator `i` that sets its tension.
//! Residuals: the tip force and moment balance (32)-(33) as strain errors,
//! `r_F L^2 / (E I)` and `r_M L / (E I)`, and the elongation agreement
//! `(delta_i(s_end) - delta_i) / L`. The conditions at actuator anchors inside
//! the body are met exactly by the point loads applied during integration.
//! The solver is multiple shooting ([`crate::solve::forward`]), of which
//! these unknowns are the first block; a [`Solution`] records them with the
//! profile.
//!
//! The parts live in [`super::options`], [`super::residual`],
//! [`super::solution`] and [`super::guess`]; their public names are
//! re-exported here.

use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

pub use super::guess::{initial_guess, linear_guess, reference_guess, warm_guess};
pub use super::nleq::Status;
pub use super::options::{SolveOptions, DEFAULT_MAX_EVALUATIONS};
pub use super::residual::{
    base_strains, residual_scales, tension_slope, tensions, Loads, Shot, ONSET_BAND,
};
pub use super::solution::{assemble, Solution};

/// Solve the forward kinetostatics for actuator `inputs` (temperature \[C\]
/// for TCAs, tension \[N\] or pull \[m\] for tendons): the multiple-shooting
/// solve of [`crate::solve::forward::solve`] under the robot's own tip
/// loads, warm from `warm` if given. With `opts.equilibrium_tol` set, the
/// grid is refined until the global equilibrium check holds to it
/// ([`SolveOptions::equilibrium_tol`]).
///
/// ```
/// use tcarod::experiments::fig6_square;
/// use tcarod::shooting::{solve, SolveOptions};
/// let robot = fig6_square(true); // two TCA legs, gravity
/// let sol = solve(&robot, &[100.0, 100.0], &SolveOptions::default(), None).unwrap();
/// assert!(sol.residual <= 1e-10);
/// assert!(sol.tip_position().x < 0.0); // the heated extension TCAs bend it toward -x
/// ```
pub fn solve(
    robot: &Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    solve_loaded(robot, inputs, &Loads::of(robot), opts, warm)
}

/// [`solve`] with explicit tip loads: the multiple-shooting solve itself.
pub use super::forward::solve as solve_loaded;

pub(crate) fn is_budget_error(e: &Error) -> bool {
    matches!(
        e,
        Error::NotConverged {
            stop: StopReason::Budget,
            ..
        }
    )
}

pub(crate) fn is_input_error(e: &Error) -> bool {
    matches!(
        e,
        Error::InvalidParameter { .. } | Error::InvalidInput { .. } | Error::Interrupted
    )
}

/// The checks of a solve request: robot, inputs, options, a warm start's
/// size and finite tip loads.
pub(crate) fn validate(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<()> {
    robot.validate()?;
    robot.check_inputs(inputs)?;
    opts.validate()?;
    if let Some(w) = warm {
        if w.unknowns.len() != 6 + robot.actuators.len()
            || w.tensions.len() != robot.actuators.len()
        {
            return Err(Error::input(
                "warm_start",
                format!(
                    "solution of a robot with {} actuators, this one has {}",
                    w.tensions.len(),
                    robot.actuators.len()
                ),
            ));
        }
    }
    for (name, v) in [
        ("tip_force [N]", &loads.tip_force),
        ("tip_moment [N m]", &loads.tip_moment),
    ] {
        // (the name formatted only for the error: validated every solve)
        for (k, z) in v.iter().enumerate().filter(|(_, z)| !z.is_finite()) {
            crate::error::finite(&format!("{name}[{k}]"), *z)?;
        }
    }
    Ok(())
}

/// Solve along a sequence of input vectors, each warm-started from the
/// previous solution (natural-parameter continuation for temperature or
/// load sweeps). The solutions are those of [`solve`] to `tol`.
pub fn sweep(robot: &Robot, inputs: &[Vec<f64>], opts: &SolveOptions) -> Result<Vec<Solution>> {
    let mut out: Vec<Solution> = Vec::with_capacity(inputs.len());
    for q in inputs {
        super::cancel::check()?;
        let sol = solve(robot, q, opts, out.last())?;
        out.push(sol);
    }
    Ok(out)
}
