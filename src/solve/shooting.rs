//! The boundary value problem (paper Section III, eqs 32-33) by Newton
//! shooting with the exact Jacobian.
//!
//! Unknowns (scaled to be dimensionless and of order one):
//! `x = [nu(0), L omega(0), delta_1/L, ..., delta_N/L]` where `delta_i` is
//! the guessed total elongation of actuator `i` that sets its tension.
//! Residuals: the tip force and moment balance (32)-(33) as strain errors,
//! `r_F L^2 / (E I)` and `r_M L / (E I)`, and the elongation agreement
//! `(delta_i(s_end) - delta_i) / L`. The conditions at actuator anchors inside
//! the body are met exactly by the point loads applied during integration.
//!
//! The Jacobian is exact ([`shoot_jacobian`]: tangents of the discrete RK4
//! map), the Newton solver is [`crate::solve::newton()`], and a cold solve that
//! fails falls back on homotopy continuation
//! ([`crate::solve::continuation`]).

use std::time::{Duration, Instant};

use nalgebra::{DMatrix, Matrix3, Vector3};

use super::cancel;
use super::continuation::continuation;
use super::newton::{newton_from, NewtonOptions, NewtonResult, Status, System};
use crate::error::{Error, Result, StopReason};
use crate::rod::{
    integrate, integrate_tangent, IvpResult, IvpSpec, Robot, TangentIvp, TangentSeeds,
};

/// Residual, its exact Jacobian, the tangent IVP and the tensions of one evaluation.
type ResidualAndJacobian = (Vec<f64>, DMatrix<f64>, TangentIvp, Vec<f64>);
/// Unknowns, residual, IVP and tensions of the last evaluation, kept for the solution.
type LastEvaluation = (Vec<f64>, Vec<f64>, IvpResult, Vec<f64>);
/// Residual, IVP and tensions at the Newton solution (when it was the last one integrated).
type FinalIvp = (Vec<f64>, IvpResult, Vec<f64>);
/// Options of the Newton shooting solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    /// RK4 steps over the body length.
    pub steps: usize,
    /// Convergence tolerance on the max-norm of the dimensionless residual.
    pub tol: f64,
    /// Newton iteration limit (per Newton run: the direct solve and each
    /// continuation step).
    pub max_iter: usize,
    /// Smallest line-search step before giving up.
    pub min_step: f64,
    /// IVP budget of one solve, continuation included (a tangent IVP counts
    /// as one); exhausting it raises [`Error::NotConverged`] with
    /// [`crate::StopReason::Budget`].
    pub max_evaluations: usize,
    /// Wall-time limit of one solve (`None`: none); passing it raises
    /// [`Error::NotConverged`] with [`crate::StopReason::Budget`].
    pub time_limit: Option<Duration>,
}

/// Default IVP budget of one solve ([`SolveOptions::max_evaluations`]): 40
/// times the most a converging design of the issue-10 benchmark used
/// (5,252 IVPs before this budget existed), so that it only stops runaway
/// solves.
pub const DEFAULT_MAX_EVALUATIONS: usize = 20_000;

impl SolveOptions {
    /// The Newton options of these (the IVP budget, no deadline, no stall
    /// detection; a forward solve sets those per Newton run).
    pub fn newton(&self) -> NewtonOptions {
        NewtonOptions {
            max_evaluations: self.max_evaluations,
            ..NewtonOptions::new(self.tol, self.max_iter, self.min_step)
        }
    }
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            steps: 100,
            tol: 1e-10,
            max_iter: 50,
            min_step: 1e-6,
            max_evaluations: DEFAULT_MAX_EVALUATIONS,
            time_limit: None,
        }
    }
}

impl SolveOptions {
    /// Validate.
    pub fn validate(&self) -> Result<()> {
        if self.steps == 0 || self.steps > 10_000_000 {
            return Err(Error::param(
                "steps",
                self.steps as f64,
                "1 <= steps <= 1e7",
            ));
        }
        if !(self.tol.is_finite() && self.tol > 0.0) {
            return Err(Error::param("tol", self.tol, "finite and > 0"));
        }
        if self.max_iter == 0 {
            return Err(Error::param("max_iter", 0.0, ">= 1"));
        }
        if !(self.min_step > 0.0 && self.min_step < 1.0) {
            return Err(Error::param("min_step", self.min_step, "0 < min_step < 1"));
        }
        if self.max_evaluations == 0 {
            return Err(Error::param("max_evaluations", 0.0, ">= 1"));
        }
        if let Some(t) = self.time_limit {
            if t.is_zero() {
                return Err(Error::param("time_limit [s]", 0.0, "> 0"));
            }
        }
        Ok(())
    }
}

/// Scaled unknowns `[nu*, L omega*, 0...]` of the reference (straight or
/// pre-curved, unactuated) configuration: the paper's initial guess.
pub fn reference_guess(robot: &Robot) -> Vec<f64> {
    let b = &robot.body;
    let mut x = vec![0.0; 6 + robot.actuators.len()];
    x[0..3].copy_from_slice(b.nu_star.as_slice());
    for k in 0..3 {
        x[3 + k] = b.omega_star[k] * b.length;
    }
    x
}

/// Tensions \[N\] of all actuators for guessed elongations `delta` \[m\].
pub fn tensions(robot: &Robot, inputs: &[f64], delta: &[f64]) -> Result<Vec<f64>> {
    robot
        .actuators
        .iter()
        .zip(inputs)
        .zip(delta)
        .map(|((a, &inp), &d)| a.law.tension(d, inp))
        .collect()
}

/// Tip loads and step count of one forward problem.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// Tip force \[N\], world frame.
    pub tip_force: Vector3<f64>,
    /// Tip moment \[N m\], world frame.
    pub tip_moment: Vector3<f64>,
}

impl Loads {
    /// The body's own tip loads.
    pub fn of(robot: &Robot) -> Self {
        Loads {
            tip_force: robot.body.tip_force,
            tip_moment: robot.body.tip_moment,
        }
    }
}

/// One IVP from scaled unknowns `x`, and its scaled residual.
pub fn shoot(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
    record: bool,
) -> Result<(Vec<f64>, IvpResult, Vec<f64>)> {
    let len = robot.body.length;
    let na = robot.actuators.len();
    let v0 = Vector3::new(x[0], x[1], x[2]);
    let u0 = Vector3::new(x[3], x[4], x[5]) / len;
    let delta: Vec<f64> = x[6..6 + na].iter().map(|d| d * len).collect();
    let tau = tensions(robot, inputs, &delta)?;
    let spec = IvpSpec {
        robot,
        tensions: &tau,
        tip_force: loads.tip_force,
        tip_moment: loads.tip_moment,
        steps,
    };
    let ivp = integrate(&spec, &v0, &u0, record)?;
    let (fs, ms) = residual_scales(robot);
    let ef = ivp.tip_force_residual * fs;
    let em = ivp.tip_moment_residual * ms;
    let mut r = Vec::with_capacity(6 + na);
    r.extend_from_slice(ef.as_slice());
    r.extend_from_slice(em.as_slice());
    for (e, d) in ivp.elongation.iter().zip(&delta[..na]) {
        r.push((e - d) / len);
    }
    Ok((r, ivp, tau))
}

/// One tangent IVP from scaled unknowns `x`: the scaled residual (as
/// [`shoot`]) and its EXACT Jacobian with respect to `x` (the derivative of
/// the discrete RK4 map, from the variational equations and the force laws'
/// derivatives), `(6 + N) x (6 + N)`. With `record`, the IVP's nodes carry
/// `d y(s) / d x` (see [`crate::rod::TangentNode`]).
pub fn shoot_jacobian(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
    record: bool,
) -> Result<ResidualAndJacobian> {
    Ok(shoot_jacobian_side(robot, inputs, loads, x, steps, record, false)?.0)
}

/// [`shoot_jacobian`] with the side of the generalised derivative at an
/// actuator's onset of tension (see [`tension_slope`]); also returns whether
/// any actuator is at its onset.
#[allow(clippy::too_many_arguments)] // the shooting problem's parts
pub(crate) fn shoot_jacobian_side(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    x: &[f64],
    steps: usize,
    record: bool,
    slack: bool,
) -> Result<(ResidualAndJacobian, bool)> {
    let len = robot.body.length;
    let na = robot.actuators.len();
    let nx = 6 + na;
    let v0 = Vector3::new(x[0], x[1], x[2]);
    let u0 = Vector3::new(x[3], x[4], x[5]) / len;
    let mut tau = Vec::with_capacity(na);
    let mut seeds = TangentSeeds::zeros(na, nx);
    let mut onset = false;
    for k in 0..3 {
        seeds.nu0[(k, k)] = 1.0;
        seeds.omega0[(k, 3 + k)] = 1.0 / len;
    }
    for (i, a) in robot.actuators.iter().enumerate() {
        let (t, dt_de, at) = tension_slope(a.law.as_ref(), x[6 + i] * len, inputs[i], len, slack)?;
        onset |= at;
        tau.push(t);
        seeds.tensions[(i, 6 + i)] = dt_de * len;
    }
    let spec = IvpSpec {
        robot,
        tensions: &tau,
        tip_force: loads.tip_force,
        tip_moment: loads.tip_moment,
        steps,
    };
    let tan = integrate_tangent(&spec, &v0, &u0, &seeds, record)?;
    let (fs, ms) = residual_scales(robot);
    let ivp = &tan.ivp;
    let mut r = Vec::with_capacity(nx);
    r.extend((ivp.tip_force_residual * fs).iter());
    r.extend((ivp.tip_moment_residual * ms).iter());
    for i in 0..na {
        r.push((ivp.elongation[i] - x[6 + i] * len) / len);
    }
    let mut jac = DMatrix::zeros(nx, nx);
    jac.rows_mut(0, 3)
        .copy_from(&(&tan.tip_force_residual * fs));
    jac.rows_mut(3, 3)
        .copy_from(&(&tan.tip_moment_residual * ms));
    for i in 0..na {
        for j in 0..nx {
            jac[(6 + i, j)] = tan.elongation[(i, j)] / len;
        }
        jac[(6 + i, 6 + i)] -= 1.0;
    }
    Ok(((r, jac, tan, tau), onset))
}

/// Relative band (of the body length) of elongation within which a slack
/// actuator counts as at its onset of tension (see [`tension_slope`]).
pub const ONSET_BAND: f64 = 1e-12;

/// Tension \[N\] and its slope \[N/m\] in the elongation for the Newton
/// Jacobian, and whether the law is at the onset of its tension (a kink
/// between a slack side, zero tension and slope, and a taut side within
/// [`ONSET_BAND`]` L` of elongation). At the onset the slope is a
/// generalised (Clarke) derivative: the taut side's (`slack == false`) or
/// zero (`slack == true`). A cold guess sits exactly at the onset of a
/// linear tendon (zero tension), where rounding of `pull + elongation`
/// decides the side; there the merit has no descent along one of the two
/// Newton directions (measured on designs #532 and #719 of the benchmark:
/// the merit grows like `t^2` from `t = 0`), so a failed line search is
/// retried with the other side ([`Shooting`]'s `refine`).
pub fn tension_slope(
    law: &dyn crate::rod::ForceLaw,
    elongation: f64,
    input: f64,
    length: f64,
    slack: bool,
) -> Result<(f64, f64, bool)> {
    let (t, dt, _) = law.tension_derivatives(elongation, input)?;
    let h = ONSET_BAND * length;
    let onset = if t == 0.0 && dt == 0.0 {
        // slack: is the taut side within the band?
        match law.tension_derivatives(elongation + h, input) {
            Ok((_, dtp, _)) if dtp > 0.0 => Some(dtp),
            _ => None,
        }
    } else if dt > 0.0 && t >= 0.0 {
        // taut: is the slack side within the band?
        match law.tension_derivatives(elongation - h, input) {
            Ok((tm, dtm, _)) if tm == 0.0 && dtm == 0.0 => Some(dt),
            _ => None,
        }
    } else {
        None
    };
    Ok(match onset {
        Some(taut) => (t, if slack { 0.0 } else { taut }, true),
        None => (t, dt, false),
    })
}

/// Factors that make the tip balance dimensionless: force residuals \[N\] are
/// multiplied by `L^2 / (E I)` and moment residuals \[N m\] by `L / (E I)`
/// (`E I` the smaller bending stiffness), so that both measure the same thing,
/// a tip load relative to what bends the body by order one. (Scaling the
/// force by `K_nu^-1` instead made the line search blind to force errors of
/// axially stiff bodies.)
pub fn residual_scales(robot: &Robot) -> (f64, f64) {
    let b = &robot.body;
    let (_, ix, iy, _) = b.section.properties();
    let ei = b.youngs_modulus * ix.min(iy);
    (b.length * b.length / ei, b.length / ei)
}

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
    let (r, ivp, tau) = shoot(robot, inputs, loads, x, steps, true)?;
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
    let na = robot.actuators.len();
    let mut sol = Solution {
        s: Vec::with_capacity(ivp.nodes.len()),
        positions: Vec::new(),
        rotations: Vec::new(),
        nu: Vec::new(),
        omega: Vec::new(),
        internal_force: Vec::new(),
        internal_moment: Vec::new(),
        elongation_profile: Vec::new(),
        actuator_paths: vec![Vec::new(); na],
        tensions: tau.clone(),
        elongations: ivp.elongation.clone(),
        inputs: inputs.to_vec(),
        base_force: Vector3::zeros(),
        base_moment: Vector3::zeros(),
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
    };
    let tol = 1e-12 * body.length;
    for (s, st) in &ivp.nodes {
        let rm = st.rotation();
        sol.s.push(*s);
        sol.positions.push(st.p);
        sol.rotations.push(rm);
        sol.nu.push(st.v);
        sol.omega.push(st.u);
        sol.internal_force.push(rm * kse * (st.v - body.nu_star));
        sol.internal_moment
            .push(rm * kbt * (st.u - body.omega_star));
        sol.elongation_profile.push(st.delta.clone());
        for (i, a) in robot.actuators.iter().enumerate() {
            if *s >= a.s_start - tol && *s <= a.s_end + tol {
                let (ri, _, _) = a.routing.eval(*s);
                sol.actuator_paths[i].push(st.p + rm * ri);
            }
        }
    }
    // Wrench transmitted to the base: body (n, m at s = 0) plus the strings
    // anchored there, each pulling the base toward the tip with tau t.
    let st0 = &ivp.nodes[0].1;
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
    sol.base_force = f;
    sol.base_moment = m;
    Ok(sol)
}

/// Initial guess at `inputs`: the strains of `warm` (a nearby solution) or of
/// the reference configuration, and actuator elongations that keep the warm
/// solution's tensions (cold: zero tension, i.e. each actuator's free
/// elongation). Keeping tensions rather than elongations matters: a TCA is
/// far stiffer than a silicone body, so at a new temperature the old
/// elongation would imply a very different force, while the old force is
/// close to the new one.
pub fn initial_guess(robot: &Robot, inputs: &[f64], warm: Option<&Solution>) -> Vec<f64> {
    let len = robot.body.length;
    let mut x = match warm {
        Some(w) => w.unknowns.clone(),
        None => reference_guess(robot),
    };
    for (i, a) in robot.actuators.iter().enumerate() {
        let tension = warm.map_or(0.0, |w| w.tensions[i]);
        if let Some(d) = a.law.elongation(tension, inputs[i]) {
            if d.is_finite() {
                x[6 + i] = d / len;
            }
        }
    }
    x
}

/// Cold start: replace the base strains of `x` by those of the problem
/// linearised about the straight reference configuration, where the base
/// section carries the dead loads' resultant (eq 9 integrated along the
/// straight centre line: `n(0) = F + L f`, `m(0) = M + L l + L e3 x F +
/// L^2/2 e3 x f`) minus the pull of the strings through it (tensions at the
/// guessed elongations): `nu(0) = nu* + K_nu^-1 (n(0) - sum tau t)`,
/// `omega(0) = omega* + K_omega^-1 (m(0) - sum r x tau t)`. Exact for a straight
/// weightless body bent by straight constant-tension tendons to the tip (then
/// Newton needs one iteration); where the body is soft and loaded this puts
/// Newton on the branch continuation from the reference would follow.
pub fn linear_guess(robot: &Robot, inputs: &[f64], loads: &Loads, x: &mut [f64]) {
    let b = &robot.body;
    if b.omega_star != Vector3::zeros() || b.nu_star != Vector3::z() {
        return; // a pre-curved body: keep its reference strains
    }
    let len = b.length;
    let f = b.distributed_load();
    let e3 = Vector3::z();
    let mut n0 = loads.tip_force + f * len;
    let mut m0 = loads.tip_moment
        + b.distributed_moment * len
        + e3.cross(&loads.tip_force) * len
        + e3.cross(&f) * (0.5 * len * len);
    let tol = 1e-12 * len;
    for (i, a) in robot.actuators.iter().enumerate() {
        if a.s_start > tol {
            continue;
        }
        let tau = match a.law.tension(x[6 + i] * len, inputs[i]) {
            Ok(t) if t.is_finite() => t,
            _ => continue,
        };
        let (r, rp, _) = a.routing.eval(0.0);
        let pb = e3 + rp;
        let t = pb / pb.norm();
        n0 -= t * tau;
        m0 -= r.cross(&t) * tau;
    }
    let (kse, kbt) = b.stiffness();
    let v = b.nu_star + n0.component_div(&kse.diagonal());
    let u = b.omega_star + m0.component_div(&kbt.diagonal());
    if v.z > 0.1 && v.iter().chain(u.iter()).all(|z| z.is_finite()) {
        x[0..3].copy_from_slice(v.as_slice());
        for k in 0..3 {
            x[3 + k] = u[k] * len;
        }
    }
}

/// Tip pose of a forward solution, without the sampled profile (for batches).
#[derive(Debug, Clone)]
pub struct TipSolution {
    /// Tip position \[m\].
    pub position: Vector3<f64>,
    /// Tip rotation (body to world).
    pub rotation: Matrix3<f64>,
    /// Scaled shooting unknowns.
    pub unknowns: Vec<f64>,
    /// Actuator tensions \[N\].
    pub tensions: Vec<f64>,
    /// Inputs the solution is for.
    pub inputs: Vec<f64>,
    /// Newton iterations.
    pub iterations: usize,
    /// IVPs integrated (coarse-grid ones included).
    pub evaluations: usize,
    /// Final Newton Jacobian, for warm starts.
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

/// The shooting residual of one forward problem as a Newton [`System`]:
/// plain IVPs for residuals, tangent IVPs for the exact Jacobian. Counts
/// every IVP (failed ones too) and keeps the last plain one (at the point
/// Newton returns, so that it can serve as the solution's profile).
pub struct Shooting<'a> {
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: &'a Loads,
    steps: usize,
    record: bool,
    /// IVPs integrated (plain and tangent).
    pub evaluations: usize,
    /// Tangent IVPs among them.
    pub tangent_evaluations: usize,
    /// RK4 steps of the Newton Jacobian: a tenth of `steps` (at least
    /// [`COARSE_JACOBIAN_MIN_STEPS`]) until [`System::refine`] switches to
    /// the exact Jacobian of the full grid (`None`).
    jacobian_steps: Option<usize>,
    last: Option<LastEvaluation>,
    /// Whether the last Jacobian had an actuator at its onset of tension.
    at_onset: bool,
    /// Take the slack side's derivative at an onset (see [`tension_slope`]).
    slack_onset: bool,
}

/// Fewest RK4 steps of the coarse-grid Newton Jacobian (below ten times
/// this, the Jacobian is taken on the full grid).
pub const COARSE_JACOBIAN_MIN_STEPS: usize = 10;

impl<'a> Shooting<'a> {
    /// The system of `robot` at `inputs` under `loads` on `steps` RK4 steps;
    /// `record`: keep the nodes of the last IVP.
    pub fn new(
        robot: &'a Robot,
        inputs: &'a [f64],
        loads: &'a Loads,
        steps: usize,
        record: bool,
    ) -> Self {
        let coarse = steps / 10;
        let jacobian_steps = if coarse >= COARSE_JACOBIAN_MIN_STEPS {
            Some(coarse)
        } else {
            None
        };
        Shooting {
            robot,
            inputs,
            loads,
            steps,
            record,
            evaluations: 0,
            tangent_evaluations: 0,
            jacobian_steps,
            last: None,
            at_onset: false,
            slack_onset: false,
        }
    }
    /// The last plain IVP if it was at `x`: `(residual, ivp, tensions)`.
    fn take_last(&mut self, x: &[f64]) -> Option<(Vec<f64>, IvpResult, Vec<f64>)> {
        match self.last.take() {
            Some((xl, r, ivp, tau)) if xl == x => Some((r, ivp, tau)),
            _ => None,
        }
    }
}

impl System for Shooting<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        self.evaluations += 1;
        let (r, ivp, tau) = shoot(
            self.robot,
            self.inputs,
            self.loads,
            x,
            self.steps,
            self.record,
        )?;
        self.last = Some((x.to_vec(), r.clone(), ivp, tau));
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.evaluations += 1;
        self.tangent_evaluations += 1;
        // the tangents of a grid of a tenth of the steps: a tenth of the cost,
        // and a Jacobian within RK4's coarse-grid error (~1e-4) of the exact
        // one, which Newton's convergence test on the full grid absorbs in a
        // chord step or two; the full-grid Jacobian after a failed line search
        let steps = self.jacobian_steps.unwrap_or(self.steps);
        let ((r, j, _, _), onset) = shoot_jacobian_side(
            self.robot,
            self.inputs,
            self.loads,
            x,
            steps,
            false,
            self.slack_onset,
        )?;
        self.at_onset = onset;
        Ok((r, j))
    }
    /// First the full grid's Jacobian; then, if an actuator was at its
    /// onset of tension, the slack side's derivative there (see
    /// [`tension_slope`]).
    fn refine(&mut self) -> bool {
        if self.jacobian_steps.take().is_some() {
            return true;
        }
        if self.at_onset && !self.slack_onset {
            self.slack_onset = true;
            return true;
        }
        false
    }
    /// `4 eps max(fs (k_nu |nu| + |F| + sum |tau|), ms (k_omega |omega| L + |M| + sum |r_i| |tau_i|))`:
    /// the rounding of the largest terms of the tip balance (32)-(33),
    /// `K (strain - strain*)` with strains of order one, in the scaled
    /// residual. (For a steel rod `EA L^2 / EI` makes this ~1e-9.)
    fn floor(&self, x: &[f64], _r: &[f64]) -> f64 {
        let robot = self.robot;
        let (kse, kbt) = robot.body.stiffness();
        let (fs, ms) = residual_scales(robot);
        let len = robot.body.length;
        let tau: Vec<f64> = match &self.last {
            Some((_, _, _, tau)) => tau.clone(),
            None => vec![0.0; robot.actuators.len()],
        };
        let vmax = x[0].abs().max(x[1].abs()).max(x[2].abs());
        let umax = x[3].abs().max(x[4].abs()).max(x[5].abs()) / len;
        let st: f64 = tau.iter().map(|t| t.abs()).sum();
        let srt: f64 = robot
            .actuators
            .iter()
            .zip(&tau)
            .map(|(a, t)| a.routing.eval(len).0.norm() * t.abs())
            .sum();
        let f = fs * (kse.max() * vmax + self.loads.tip_force.amax() + st);
        let m = ms * (kbt.max() * umax * len + self.loads.tip_moment.amax() + srt);
        4.0 * f64::EPSILON * f.max(m)
    }
    fn evaluations(&self) -> usize {
        self.evaluations
    }
}

/// Work counters carried through a solve and its fallbacks, and the solve's
/// budget.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Work {
    pub iterations: usize,
    pub evaluations: usize,
    /// IVP budget of the whole solve (0: none).
    pub max_evaluations: usize,
    /// Deadline of the whole solve.
    pub deadline: Option<Instant>,
}

impl Work {
    /// Counters at zero and the budget of `opts` from now.
    pub fn start(opts: &SolveOptions) -> Self {
        Work {
            max_evaluations: opts.max_evaluations,
            deadline: opts.time_limit.map(|t| Instant::now() + t),
            ..Default::default()
        }
    }
    fn add(&mut self, sys: &Shooting<'_>, iterations: usize) {
        self.iterations += iterations;
        self.evaluations += sys.evaluations;
    }
    /// Whether the budget is spent.
    pub fn exhausted(&self) -> bool {
        (self.max_evaluations > 0 && self.evaluations >= self.max_evaluations)
            || self.deadline.is_some_and(|d| Instant::now() >= d)
    }
    /// The Newton options of one run within the remaining budget.
    fn newton_options(&self, opts: &SolveOptions) -> NewtonOptions {
        let max_evaluations = if self.max_evaluations == 0 {
            usize::MAX
        } else {
            self.max_evaluations.saturating_sub(self.evaluations)
        };
        NewtonOptions {
            max_evaluations,
            deadline: self.deadline,
            stall_window: STALL_WINDOW,
            ..opts.newton()
        }
    }
}

/// Stall window of forward Newton runs (see
/// [`NewtonOptions::stall_window`]): they have continuation to fall back on.
pub const STALL_WINDOW: usize = 4;

/// Newton shooting from `x0`; returns the Newton result and the IVP at its
/// solution (if it was the last one integrated). Adds the work to `work`
/// (also on failure).
#[allow(clippy::too_many_arguments)] // the shooting problem's parts, passed through to `Shooting::new`
pub(crate) fn newton_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    record: bool,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let mut sys = Shooting::new(robot, inputs, loads, opts.steps, record);
    let nopts = work.newton_options(opts);
    let out = newton_from(&mut sys, x0, &nopts, "forward shooting", jac0);
    match out {
        Ok(nr) => {
            work.add(&sys, nr.iterations);
            let last = sys.take_last(&nr.x);
            Ok((nr, last))
        }
        Err(Error::NotConverged {
            solver,
            iterations,
            evaluations: _,
            residual,
            stop,
            reason,
        }) => {
            work.add(&sys, iterations);
            Err(Error::NotConverged {
                solver,
                iterations: work.iterations,
                evaluations: work.evaluations,
                residual,
                stop,
                reason,
            })
        }
        Err(e) => {
            work.add(&sys, 0);
            Err(e)
        }
    }
}

/// A [`Solution`] from a converged Newton result (integrating once more,
/// recorded, unless the last IVP at the solution is given).
pub(crate) fn solution_from(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    nr: NewtonResult,
    last: Option<(Vec<f64>, IvpResult, Vec<f64>)>,
    work: &mut Work,
) -> Result<Solution> {
    let mut s = match last {
        Some((r, ivp, tau)) if !ivp.nodes.is_empty() => {
            assemble_from(robot, inputs, loads, &nr.x, opts.steps, 0, 0, r, ivp, tau)?
        }
        _ => {
            work.evaluations += 1;
            assemble(robot, inputs, loads, &nr.x, opts.steps, 0, 0)?
        }
    };
    s.iterations = work.iterations;
    s.evaluations = work.evaluations;
    s.newton_jacobian = nr.jacobian;
    s.status = nr.status;
    s.floor = nr.floor;
    Ok(s)
}

/// Solve the forward kinetostatics for actuator `inputs` (temperature \[C\]
/// for TCAs, tension \[N\] or pull \[m\] for tendons).
///
/// Newton shooting with the exact Jacobian from [`initial_guess`] (warm from
/// `warm` if given); if that fails, homotopy continuation from the warm
/// solution's inputs (or, cold, from the reference configuration in the
/// inputs and the loads). The returned `iterations` and `evaluations` count
/// all the work done; `continuation_steps` records the path.
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

/// [`solve`] with explicit tip loads.
pub fn solve_loaded(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
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
        for (k, z) in v.iter().enumerate() {
            crate::error::finite(&format!("{name}[{k}]"), *z)?;
        }
    }
    cancel::check()?;
    let mut work = Work::start(opts);
    let mut x0 = initial_guess(robot, inputs, warm);
    if warm.is_none() {
        linear_guess(robot, inputs, loads, &mut x0);
    }
    let jac0 = warm.and_then(|w| w.newton_jacobian.as_ref());
    match newton_shooting(robot, inputs, loads, opts, &x0, jac0, true, &mut work) {
        Ok((nr, last)) => solution_from(robot, inputs, loads, opts, nr, last, &mut work),
        Err(e) if is_input_error(&e) || is_budget_error(&e) => Err(e),
        Err(first) => {
            continuation(robot, inputs, loads, opts, warm, &mut work).map_err(|e| match e {
                Error::Interrupted => e,
                Error::NotConverged {
                    stop: StopReason::Budget,
                    residual,
                    reason,
                    ..
                } => Error::NotConverged {
                    solver: "forward shooting",
                    iterations: work.iterations,
                    evaluations: work.evaluations,
                    residual: match &first {
                        Error::NotConverged { residual: r0, .. } => r0.min(residual),
                        _ => residual,
                    },
                    stop: StopReason::Budget,
                    reason,
                },
                Error::NotConverged {
                    residual,
                    stop,
                    reason,
                    ..
                } => match first {
                    Error::NotConverged {
                        residual: r0,
                        stop: s0,
                        reason: why0,
                        solver,
                        ..
                    } if r0 <= residual => Error::NotConverged {
                        solver,
                        iterations: work.iterations,
                        evaluations: work.evaluations,
                        residual: r0,
                        stop: s0,
                        reason: format!("{why0}; continuation failed too"),
                    },
                    _ => Error::NotConverged {
                        solver: "forward shooting",
                        iterations: work.iterations,
                        evaluations: work.evaluations,
                        residual,
                        stop,
                        reason: format!("continuation: {reason}"),
                    },
                },
                _ => first,
            })
        }
    }
}

/// [`solve_loaded`] returning only the tip pose (no profile is recorded,
/// which saves an IVP and its allocations). `warm`: a neighbouring tip
/// solution. Falls back on [`solve_loaded`] (with its continuation) when the
/// direct Newton solve fails. Inputs are not validated here: call
/// `robot.check_inputs` first.
pub fn solve_tip(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&TipSolution>,
) -> Result<TipSolution> {
    let len = robot.body.length;
    let mut x0 = match warm {
        Some(w) => w.unknowns.clone(),
        None => reference_guess(robot),
    };
    for (i, a) in robot.actuators.iter().enumerate() {
        let tension = warm.map_or(0.0, |w| w.tensions[i]);
        if let Some(d) = a.law.elongation(tension, inputs[i]) {
            if d.is_finite() {
                x0[6 + i] = d / len;
            }
        }
    }
    if warm.is_none() {
        linear_guess(robot, inputs, loads, &mut x0);
    }
    let mut work = Work::start(opts);
    let jac0 = warm.and_then(|w| w.newton_jacobian.as_ref());
    match newton_shooting(robot, inputs, loads, opts, &x0, jac0, false, &mut work) {
        Ok((nr, last)) => {
            let (ivp, tau) = match last {
                Some((_, ivp, tau)) => (ivp, tau),
                None => {
                    work.evaluations += 1;
                    let (_, ivp, tau) = shoot(robot, inputs, loads, &nr.x, opts.steps, false)?;
                    (ivp, tau)
                }
            };
            Ok(TipSolution {
                position: ivp.tip.p,
                rotation: ivp.tip.rotation(),
                unknowns: nr.x,
                tensions: tau,
                inputs: inputs.to_vec(),
                iterations: work.iterations,
                evaluations: work.evaluations,
                newton_jacobian: nr.jacobian,
            })
        }
        Err(e) if is_input_error(&e) || is_budget_error(&e) => Err(e),
        Err(_) => {
            // the fallback gets what is left of the budget
            let rest = SolveOptions {
                max_evaluations: opts.max_evaluations.saturating_sub(work.evaluations).max(1),
                time_limit: work.deadline.map(|d| {
                    d.saturating_duration_since(Instant::now())
                        .max(Duration::from_nanos(1))
                }),
                ..*opts
            };
            let w = match warm {
                Some(w) => Some(assemble(
                    robot,
                    &w.inputs,
                    loads,
                    &w.unknowns,
                    opts.steps,
                    0,
                    0,
                )?),
                None => None,
            };
            let mut s =
                TipSolution::from_solution(solve_loaded(robot, inputs, loads, &rest, w.as_ref())?);
            s.iterations += work.iterations;
            s.evaluations += work.evaluations;
            Ok(s)
        }
    }
}

/// Solve along a sequence of input vectors, each warm-started from the
/// previous solution (continuation helper for temperature or load sweeps).
pub fn sweep(robot: &Robot, inputs: &[Vec<f64>], opts: &SolveOptions) -> Result<Vec<Solution>> {
    let mut out: Vec<Solution> = Vec::with_capacity(inputs.len());
    for q in inputs {
        cancel::check()?;
        let sol = solve(robot, q, opts, out.last())?;
        out.push(sol);
    }
    Ok(out)
}
