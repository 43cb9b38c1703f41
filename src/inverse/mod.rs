//! Inverse kinetostatics (paper Section IV, eqs 34-43): actuation Jacobian,
//! compliance, tip-position inverse, blocked-tip force and grasping.
//!
//! Tip pose perturbations are measured in the world frame as
//! `[dp; dtheta]`, `dtheta` the rotation vector of `R1 R0^T`. Actuation
//! variables `z` map to actuator inputs through `groups` (actuator `i` takes
//! variable `groups\[i\]`): the two legs of a U-shaped TCA share one
//! temperature. Tip wrenches `W = [F; M]` are in the world frame.

use nalgebra::{DMatrix, Matrix3, Rotation3, Vector3};

use crate::error::{Error, Result};
use crate::rod::Robot;

mod blocked;
mod grasp;
mod mixed;
mod mixed_presolve;
mod sensitivities;
mod tip;

pub use blocked::{
    blocked_force, blocked_temperature, blocked_variable_direct, blocked_variable_from, Block,
    BlockedResult,
};
pub use grasp::{grasp, Grasp, GraspMethod};
pub(crate) use sensitivities::{exact_blocks, ExactBlocks};
pub use sensitivities::{
    sensitivities, sensitivities_exact, sensitivities_fast, sensitivities_with_step,
};
pub use tip::{tip_position_inverse, InverseOptions, InverseResult};

/// Finite-difference scheme for [`sensitivities`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// Forward differences, step `sqrt(eps) max(1, |z|/z_c) z_c`: `12 + 2N` IVPs (the paper's count).
    Forward,
    /// Central differences, step `cbrt(eps) max(1, |z|/z_c) z_c`: twice the IVPs, `O(h^2)` error.
    Central,
    /// Exact: one tangent IVP ([`crate::rod::integrate_tangent`]) along the
    /// unknowns and the actuation variables, the wrench columns in closed
    /// form; no step size, no truncation error (the TCA law's temperature
    /// slope is differenced inside the law, see
    /// [`crate::rod::ForceLaw::tension_derivatives`]).
    Exact,
}

impl Scheme {
    /// Relative finite-difference step by rule: `sqrt(eps)` forward, `cbrt(eps)`
    /// central; `None` for the exact tangents.
    fn relative_step(self) -> Option<f64> {
        match self {
            Scheme::Forward => Some(f64::EPSILON.sqrt()),
            Scheme::Central => Some(f64::EPSILON.cbrt()),
            Scheme::Exact => None,
        }
    }
}

/// Actuation Jacobian and compliance at a solution.
#[derive(Debug, Clone)]
pub struct Sensitivities {
    /// `J = E_q - E_u B_u^-1 B_q` (eq 41): tip pose [m; rad] per unit of each
    /// actuation variable (per C for TCA temperatures), `6 x n_vars`.
    pub jacobian: DMatrix<f64>,
    /// `C = E_W - E_u B_u^-1 B_W` (eq 42): tip pose per unit tip wrench
    /// `[F (N); M (N m)]`, `6 x 6`.
    pub compliance: DMatrix<f64>,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// Map of actuation variables to actuator inputs.
#[derive(Debug, Clone)]
pub struct Groups(pub Vec<usize>);

impl Groups {
    /// One variable per actuator.
    pub fn identity(n: usize) -> Self {
        Groups((0..n).collect())
    }
    /// Number of variables.
    pub fn n_vars(&self) -> usize {
        self.0.iter().max().map_or(0, |m| m + 1)
    }
    /// Validate against a robot.
    pub fn validate(&self, robot: &Robot) -> Result<()> {
        if self.0.len() != robot.actuators.len() {
            return Err(Error::input(
                "groups",
                format!(
                    "expected one entry per actuator ({}), got {}",
                    robot.actuators.len(),
                    self.0.len()
                ),
            ));
        }
        let n = self.n_vars();
        for k in 0..n {
            if !self.0.contains(&k) {
                return Err(Error::input(
                    "groups",
                    format!("variable {k} drives no actuator (use 0..n without gaps)"),
                ));
            }
        }
        Ok(())
    }
    /// Inputs from variables.
    pub fn inputs(&self, z: &[f64]) -> Vec<f64> {
        self.0.iter().map(|&g| z[g]).collect()
    }
    /// Variables from inputs (first actuator of each group).
    pub fn vars(&self, inputs: &[f64]) -> Vec<f64> {
        let mut z = vec![0.0; self.n_vars()];
        for (i, &g) in self.0.iter().enumerate().rev() {
            z[g] = inputs[i];
        }
        z
    }
    /// Bounds of each variable: the intersection of its actuators' input bounds.
    pub fn bounds(&self, robot: &Robot) -> Vec<(f64, f64)> {
        let mut b = vec![(f64::NEG_INFINITY, f64::INFINITY); self.n_vars()];
        for (a, &g) in robot.actuators.iter().zip(&self.0) {
            let (lo, hi) = a.law.input_bounds();
            b[g].0 = b[g].0.max(lo);
            b[g].1 = b[g].1.min(hi);
        }
        b
    }
}

/// Rotation vector (log map) of a rotation matrix, accurate for tiny angles:
/// `theta = atan2(|w|, (tr R - 1) / 2)` with `w = vee((R - R^T) / 2) = sin(theta) axis`.
/// (An `acos` of the trace loses all digits of angles below ~1e-8 rad, which
/// finite differences produce.)
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let w = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) * 0.5;
    let sn = w.norm();
    let cs = 0.5 * (r.trace() - 1.0);
    if sn < 1e-300 {
        if cs > 0.0 {
            return Vector3::zeros();
        }
        // theta = pi: fall back on nalgebra's eigen-based axis
        return Rotation3::from_matrix_unchecked(*r).scaled_axis();
    }
    let th = sn.atan2(cs);
    if th > 3.1 {
        return Rotation3::from_matrix_unchecked(*r).scaled_axis();
    }
    w * (th / sn)
}

pub(crate) fn pose_delta(
    p0: &Vector3<f64>,
    r0: &Matrix3<f64>,
    p1: &Vector3<f64>,
    r1: &Matrix3<f64>,
) -> [f64; 6] {
    let dp = p1 - p0;
    let th = rotation_vector(&(r1 * r0.transpose()));
    [dp.x, dp.y, dp.z, th.x, th.y, th.z]
}

/// Characteristic force \[N\] and moment \[N m\] of a body: `E I / L^2`, `E I / L`.
pub fn load_scales(robot: &Robot) -> (f64, f64) {
    robot.body.load_scales()
}
