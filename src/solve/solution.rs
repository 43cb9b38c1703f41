//! A converged forward solution sampled at the integration nodes, and its
//! assembly from the converged unknowns.

use nalgebra::{DMatrix, Matrix3, Quaternion, Vector3};

use super::nleq::Status;
use super::residual::Loads;
use crate::error::Result;
use crate::rod::{rot, FlatNodes, IvpResult, Robot, BASE_STATES};

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
    /// Elongation of each actuator up to each node \[m\] (`nodes x
    /// actuators`: row `k` is node `k`).
    pub elongation_profile: DMatrix<f64>,
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
    let len = robot.body.length;
    let delta: Vec<f64> = x[6..].iter().map(|d| d * len).collect();
    let tau = super::residual::tensions(robot, inputs, &delta)?;
    let counts = (iterations, evaluations);
    assemble_at_tensions(robot, inputs, loads, x, &tau, steps, counts.0, counts.1)
}

/// [`assemble`] under the actuator tensions `tau` \[N\] (those of the
/// solve that found `x`, which a force law's inverse may give to the last
/// bit otherwise): the solution's IVP with its own arithmetic, so that a
/// solution rebuilt from its unknowns and tensions (a pickled one) is the
/// same bit for bit.
#[allow(clippy::too_many_arguments)]
pub fn assemble_at_tensions(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    tau: &[f64],
    steps: usize,
    iterations: usize,
    evaluations: usize,
) -> Result<Solution> {
    let len = robot.body.length;
    let (v0, u0) = super::residual::base_strains(x, len);
    let spec = loads.ivp(robot, tau, steps);
    let (ivp, nodes) = crate::rod::integrate_flat(&spec, &v0, &u0)?;
    let delta: Vec<f64> = x[6..].iter().map(|d| d * len).collect();
    let r = super::residual::scaled_residual(robot, &ivp, &delta);
    let counts = (steps, iterations, evaluations);
    Ok(assemble_flat(
        robot,
        (inputs, loads, x),
        counts,
        r,
        (ivp, nodes),
        tau.to_vec(),
    ))
}

/// [`assemble`] from the IVP at `x` with its nodes recorded flat (residual
/// `r`, tensions `tau`); `counts`: RK4 steps, iterations, evaluations.
pub(crate) fn assemble_flat(
    robot: &Robot,
    (inputs, loads, x): (&[f64], &Loads, &[f64]),
    (steps, iterations, evaluations): (usize, usize, usize),
    r: Vec<f64>,
    (ivp, nodes): (IvpResult, FlatNodes),
    tau: Vec<f64>,
) -> Solution {
    let body = &robot.body;
    let (kse, kbt) = body.stiffness();
    let (base_force, base_moment) = match nodes.is_empty() {
        false => base_wrench(robot, nodes.state(0), &tau),
        true => (Vector3::zeros(), Vector3::zeros()),
    };
    let rotations: Vec<Matrix3<f64>> = field(&nodes, |y| rot(&quat(y)));
    let tol = 1e-12 * body.length;
    let actuator_paths = robot
        .actuators
        .iter()
        .map(|a| {
            let span = |s: f64| s >= a.s_start - tol && s <= a.s_end + tol;
            (nodes.s.iter().zip(nodes.states()).zip(&rotations))
                .filter(|((s, _), _)| span(**s))
                .map(|((s, y), rm)| vec3(y, 0) + rm * a.routing.eval(*s).0)
                .collect()
        })
        .collect();
    // (R (K w), not (R K) w: the 3x3 product per node is not needed)
    let load = |k: &Matrix3<f64>, at: usize, w0: &Vector3<f64>| {
        (nodes.states().zip(&rotations))
            .map(|(y, rm)| rm * (k * (vec3(y, at) - w0)))
            .collect()
    };
    let na = robot.actuators.len();
    let elongation_profile =
        DMatrix::from_fn(nodes.len(), na, |k, i| nodes.state(k)[BASE_STATES + i]);
    Solution {
        positions: field(&nodes, |y| vec3(y, 0)),
        nu: field(&nodes, |y| vec3(y, 7)),
        omega: field(&nodes, |y| vec3(y, 10)),
        internal_force: load(&kse, 7, &body.nu_star),
        internal_moment: load(&kbt, 10, &body.omega_star),
        s: nodes.s,
        rotations,
        actuator_paths,
        elongation_profile,
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
        status: Status::Converged,
        floor: 0.0,
        continuation_steps: Vec::new(),
    }
}

/// The 3-vector at `y[at..at + 3]`.
#[inline(always)]
fn vec3(y: &[f64], at: usize) -> Vector3<f64> {
    Vector3::new(y[at], y[at + 1], y[at + 2])
}

/// The orientation quaternion of a state vector `y`.
#[inline(always)]
fn quat(y: &[f64]) -> Quaternion<f64> {
    Quaternion::new(y[3], y[4], y[5], y[6])
}

/// `f` of every node's state vector, in order (one tight pass per field
/// of a [`Solution`]).
fn field<T>(nodes: &FlatNodes, f: impl Fn(&[f64]) -> T) -> Vec<T> {
    nodes.states().map(f).collect()
}

/// Wrench (force \[N\], moment \[N m\] about the base origin, world frame)
/// transmitted to the base by the body at its first node (state vector
/// `y0`) and the strings anchored there, each pulling the base toward the
/// tip with `tau t`.
fn base_wrench(robot: &Robot, y0: &[f64], tau: &[f64]) -> (Vector3<f64>, Vector3<f64>) {
    let body = &robot.body;
    let (kse, kbt) = body.stiffness();
    let tol = 1e-12 * body.length;
    let (p0, v0, u0) = (vec3(y0, 0), vec3(y0, 7), vec3(y0, 10));
    let r0 = rot(&quat(y0));
    let mut f = r0 * kse * (v0 - body.nu_star);
    let mut m = r0 * kbt * (u0 - body.omega_star) + p0.cross(&f);
    for (i, a) in robot.actuators.iter().enumerate() {
        if a.s_start <= tol {
            let (ri, rp, _) = a.routing.eval(0.0);
            let pb = v0 + u0.cross(&ri) + rp;
            let t = r0 * pb / pb.norm();
            f += t * tau[i];
            m += (p0 + r0 * ri).cross(&(t * tau[i]));
        }
    }
    (f, m)
}
