//! The grasp temperature (eq 44): `mu n F(T) = m g` on the blocked-tip
//! finger, by the paper's incremental method (eq 43) or a direct solve.

use nalgebra::Vector3;

use super::{blocked_temperature, blocked_variable_from, Block, BlockedResult, Groups};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, SolveOptions};
use crate::stability::Policy;

/// How the grasp temperature is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GraspMethod {
    /// The paper's incremental inverse (eq 43) in this many force steps.
    Incremental(usize),
    /// One augmented Newton solve: the shooting unknowns plus the
    /// actuation variable, the residual plus the blocked-tip condition, the
    /// exact Jacobian, from the eq-43 predictor of the whole force
    /// ([`super::blocked_variable_from`]).
    Direct,
}

/// A gripper of `fingers` identical fingers holding `mass` \[kg\] by
/// friction `mu` \[-\] under `gravity` \[m/s^2\]; each fingertip touches
/// the object where it rests at the `contact` inputs (`None`: the
/// reference inputs) and presses along `normal`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grasp {
    pub normal: Vector3<f64>,
    pub mass: f64,
    pub mu: f64,
    pub fingers: usize,
    pub gravity: f64,
    pub contact: Option<Vec<f64>>,
    pub stability: Policy,
}

impl Grasp {
    /// Normal force \[N\] each finger must press with: `F = m g / (mu n)` (eq 44).
    pub fn force_per_finger(&self) -> Result<f64> {
        crate::error::positive("mass [kg]", self.mass)?;
        crate::error::positive("mu [-]", self.mu)?;
        crate::error::positive("gravity [m/s^2]", self.gravity)?;
        if self.fingers == 0 {
            return Err(Error::param("fingers", 0.0, ">= 1"));
        }
        Ok(self.mass * self.gravity / (self.mu * self.fingers as f64)) // eq (44)
    }

    /// The blocked result of one finger at the grasp temperature (its
    /// `evaluations` include the free solve at contact), and the point \[m\]
    /// where its tip is blocked (its free position at contact).
    pub fn solve(
        &self,
        robot: &Robot,
        groups: &Groups,
        method: GraspMethod,
        opts: &SolveOptions,
    ) -> Result<(BlockedResult, Vector3<f64>)> {
        let force = self.force_per_finger()?;
        let contact = match &self.contact {
            Some(c) => {
                robot.check_inputs(c)?;
                c.clone()
            }
            None => robot.reference_inputs(),
        };
        let start = solve_loaded(robot, &contact, &Loads::of(robot), opts, None)?;
        let block =
            Block::new(start.tip_position(), self.normal)?.with_stability(self.stability)?;
        let mut res = match method {
            GraspMethod::Incremental(increments) => {
                blocked_temperature(robot, groups, &block, &start, force, increments, opts)?
            }
            GraspMethod::Direct => {
                blocked_variable_from(robot, groups, &block, &start, force, opts)?
            }
        };
        res.evaluations += start.evaluations; // the free solve at contact
        Ok((res, block.point))
    }
}

/// Grasp temperature (eq 44) with the tip blocked where it rests at the
/// reference inputs, by `increments` eq-43 steps, with its stability
/// verdict (see [`Grasp`]).
#[allow(clippy::too_many_arguments)]
pub fn grasp(
    robot: &Robot,
    groups: &Groups,
    normal: &Vector3<f64>,
    mass: f64,
    mu: f64,
    fingers: usize,
    gravity: f64,
    increments: usize,
    opts: &SolveOptions,
) -> Result<BlockedResult> {
    let spec = Grasp {
        normal: *normal,
        mass,
        mu,
        fingers,
        gravity,
        contact: None,
        stability: Policy::Report,
    };
    Ok(spec
        .solve(robot, groups, GraspMethod::Incremental(increments), opts)?
        .0)
}
