//! A converged forward solution sampled at the integration nodes, its
//! assembly from the converged unknowns, and the tip-only result of batches.

use nalgebra::{DMatrix, Matrix3, Vector3};

use super::newton::Status;
use super::residual::{Loads, Shot};
use crate::error::Result;
use crate::rod::{IvpResult, Robot, RodState};

/// A converged forward solution, sampled at the integration nodes.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Arc length of each node \[m\].
    pub s: Vec<f64>,
    /// Centre-line positions \[m\], world frame.
    pub positions: Vec<Vector3<f64>>,
    /// Rotations (body to world).
    pub rotations: Vec<Matrix3<f64>>,
    /// Linear strains `nu` \[-\], body frame.
    pub nu: Vec<Vector3<f64>>,
    /// Angular strains `omega` \[1/m\], body frame.
    pub omega: Vec<Vector3<f64>>,
    /// Internal force `n = R K_nu (nu - nu*)` \[N\], world frame.
    pub internal_force: Vec<Vector3<f64>>,
    /// Internal moment `m = R K_omega (omega - omega*)` \[N m\], world frame.
    pub internal_moment: Vec<Vector3<f64>>,
    /// Elongation of each actuator up to each node \[m\] (`nodes x actuators`).
    pub elongation_profile: Vec<Vec<f64>>,
    /// Actuator paths `p + R r_i(s)` \[m\] at the nodes within each actuator's span.
    pub actuator_paths: Vec<Vec<Vector3<f64>>>,
    /// Actuator tensions \[N\] (negative: the actuator pushes).
    pub tensions: Vec<f64>,
    /// Actuator total elongations \[m\].
    pub elongations: Vec<f64>,
    /// Actuation inputs the solution is for.
    pub inputs: Vec<f64>,
    /// Force \[N\] the body and its actuators transmit to the base (world
    /// frame); the base reaction is its negative.
    pub base_force: Vector3<f64>,
    /// Moment \[N m\] about the base origin transmitted to the base.
    pub base_moment: Vector3<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// IVPs integrated.
    pub evaluations: usize,
    /// Final max-norm residual (dimensionless).
    pub residual: f64,
    /// Scaled shooting unknowns, for warm starts.
    pub unknowns: Vec<f64>,
    /// Tip loads the solution is for.
    pub loads: Loads,
    /// RK4 steps used.
    pub steps: usize,
    /// The exact shooting Jacobian (scaled residual by scaled unknowns) of
    /// the last Newton iteration; `None` if no iteration was needed.
    pub newton_jacobian: Option<DMatrix<f64>>,
    /// How Newton converged (to `tol`, or to the rounding floor above it).
    pub status: Status,
    /// Estimated rounding floor of the scaled residual at the solution.
    pub floor: f64,
    /// Homotopy parameters of the continuation path taken (each in (0, 1],
    /// ending at 1), empty if the direct solve converged.
    pub continuation_steps: Vec<f64>,
}

impl Solution {
    /// Tip position \[m\].
    pub fn tip_position(&self) -> Vector3<f64> {
        *self.positions.last().expect("a solution has nodes")
    }
    /// Tip rotation.
    pub fn tip_rotation(&self) -> Matrix3<f64> {
        *self.rotations.last().expect("a solution has nodes")
    }
}

/// Build a [`Solution`] by integrating once more from converged unknowns.
pub fn assemble(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
    iterations: usize,
    evaluations: usize,
) -> Result<Solution> {
    let (r, ivp, tau) = Shot::new(robot, inputs, loads, steps).residual(x, true)?;
    assemble_from(
        robot,
        inputs,
        loads,
        x,
        steps,
        iterations,
        evaluations,
        r,
        ivp,
        tau,
    )
}

/// [`assemble`] from the recorded IVP at `x` (residual `r`, tensions `tau`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn assemble_from(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
    iterations: usize,
    evaluations: usize,
    r: Vec<f64>,
    ivp: IvpResult,
    tau: Vec<f64>,
) -> Result<Solution> {
    let body = &robot.body;
    let (kse, kbt) = body.stiffness();
    let (base_force, base_moment) = match ivp.nodes.first() {
        Some((_, st0)) => base_wrench(robot, st0, &tau),
        None => (Vector3::zeros(), Vector3::zeros()),
    };
    let nodes = ivp.nodes;
    let rotations: Vec<Matrix3<f64>> = field(&nodes, |st| st.rotation());
    let tol = 1e-12 * body.length;
    let actuator_paths = robot
        .actuators
        .iter()
        .map(|a| {
            let span = |s: f64| s >= a.s_start - tol && s <= a.s_end + tol;
            (nodes.iter().zip(&rotations))
                .filter(|((s, _), _)| span(*s))
                .map(|((s, st), rm)| st.p + rm * a.routing.eval(*s).0)
                .collect()
        })
        .collect();
    // (R (K w), not (R K) w: the 3x3 product per node is not needed)
    let load = |k: &Matrix3<f64>, w: fn(&RodState, &crate::rod::Body) -> Vector3<f64>| {
        (nodes.iter().zip(&rotations))
            .map(|((_, st), rm)| rm * (k * w(st, body)))
            .collect()
    };
    Ok(Solution {
        s: nodes.iter().map(|(s, _)| *s).collect(),
        positions: field(&nodes, |st| st.p),
        nu: field(&nodes, |st| st.v),
        omega: field(&nodes, |st| st.u),
        internal_force: load(&kse, |st, b| st.v - b.nu_star),
        internal_moment: load(&kbt, |st, b| st.u - b.omega_star),
        rotations,
        actuator_paths,
        elongation_profile: nodes.into_iter().map(|(_, st)| st.delta).collect(),
        tensions: tau,
        elongations: ivp.elongation,
        inputs: inputs.to_vec(),
        base_force,
        base_moment,
        iterations,
        evaluations,
        residual: r.iter().fold(0.0, |m: f64, x| m.max(x.abs())),
        unknowns: x.to_vec(),
        loads: *loads,
        steps,
        newton_jacobian: None,
        status: Status::Converged,
        floor: 0.0,
        continuation_steps: Vec::new(),
    })
}

/// `f` of every node's state, in order (one tight pass per field of a
/// [`Solution`]).
fn field<T>(nodes: &[(f64, RodState)], f: impl Fn(&RodState) -> T) -> Vec<T> {
    nodes.iter().map(|(_, st)| f(st)).collect()
}

/// Wrench (force \[N\], moment \[N m\] about the base origin, world frame)
/// transmitted to the base by the body at its first node `st0` and the
/// strings anchored there, each pulling the base toward the tip with
/// `tau t`.
fn base_wrench(robot: &Robot, st0: &RodState, tau: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    let body = &robot.body;
    let (kse, kbt) = body.stiffness();
    let tol = 1e-12 * body.length;
    let r0 = st0.rotation();
    let mut f = r0 * kse * (st0.v - body.nu_star);
    let mut m = r0 * kbt * (st0.u - body.omega_star) + st0.p.cross(&f);
    for (i, a) in robot.actuators.iter().enumerate() {
        if a.s_start <= tol {
            let (ri, rp, _) = a.routing.eval(0.0);
            let pb = st0.v + st0.u.cross(&ri) + rp;
            let t = r0 * pb / pb.norm();
            f += t * tau[i];
            m += (st0.p + r0 * ri).cross(&(t * tau[i]));
        }
    }
    (f, m)
}

/// Tip pose of a forward solution, without the sampled profile (for
/// batches): `position` and `rotation` are [`Solution::tip_position`] and
/// [`Solution::tip_rotation`]; every other field means what the
/// [`Solution`] field of the same name means.
#[derive(Debug, Clone)]
pub struct TipSolution {
    pub position: Vector3<f64>,
    pub rotation: Matrix3<f64>,
    pub unknowns: Vec<f64>,
    pub tensions: Vec<f64>,
    pub inputs: Vec<f64>,
    pub iterations: usize,
    pub evaluations: usize,
    pub newton_jacobian: Option<DMatrix<f64>>,
}

impl TipSolution {
    pub(crate) fn from_solution(s: Solution) -> Self {
        TipSolution {
            position: s.tip_position(),
            rotation: s.tip_rotation(),
            unknowns: s.unknowns,
            tensions: s.tensions,
            inputs: s.inputs,
            iterations: s.iterations,
            evaluations: s.evaluations,
            newton_jacobian: s.newton_jacobian,
        }
    }
}
