//! The boundary value problem (paper Section III, eqs 32-33) by Newton
//! shooting with a backtracking line search.
//!
//! Unknowns (scaled to be dimensionless and of order one):
//! `x = [nu(0), L omega(0), delta_1/L, ..., delta_N/L]` where `delta_i` is
//! the guessed total elongation of actuator `i` that sets its tension.
//! Residuals: the tip force and moment balance (32)-(33) as strain errors,
//! `r_F L^2 / (E I)` and `r_M L / (E I)`, and the elongation agreement
//! `(delta_i(s_end) - delta_i) / L`. The conditions at actuator anchors inside
//! the body are met exactly by the point loads applied during integration.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use crate::error::{Error, Result};
use crate::rod::{integrate, integrate_tangent, IvpResult, IvpSpec, Robot, TangentIvp, TangentSeeds};

/// Options of the Newton shooting solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    /// RK4 steps over the body length.
    pub steps: usize,
    /// Convergence tolerance on the max-norm of the dimensionless residual.
    pub tol: f64,
    /// Newton iteration limit.
    pub max_iter: usize,
    /// Smallest line-search step before giving up.
    pub min_step: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            steps: 100,
            tol: 1e-10,
            max_iter: 50,
            min_step: 1e-6,
        }
    }
}

impl SolveOptions {
    /// Validate.
    pub fn validate(&self) -> Result<()> {
        if self.steps == 0 || self.steps > 10_000_000 {
            return Err(Error::param("steps", self.steps as f64, "1 <= steps <= 1e7"));
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
        Ok(())
    }
}

/// Outcome of [`newton`].
#[derive(Debug, Clone)]
pub struct NewtonResult {
    /// Solution.
    pub x: Vec<f64>,
    /// Residual at `x`.
    pub residual: Vec<f64>,
    /// Newton iterations performed.
    pub iterations: usize,
    /// Residual evaluations (IVPs for shooting).
    pub evaluations: usize,
}

/// Largest `|f|^2` ratio at which a quasi-Newton (Broyden) step is accepted.
const QUASI_DECREASE: f64 = 0.5;

fn inf_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, x| m.max(x.abs()))
}

fn sq_norm(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// Newton's method on `f(x) = 0` with a forward-difference Jacobian (step
/// `sqrt(eps) max(1, |x_j|)`) and Armijo backtracking on `|f|^2`. A trial
/// point where `f` fails (e.g. the IVP cannot be integrated) counts as an
/// infinite residual, so the line search backs off from it.
///
/// Between finite-difference Jacobians the Jacobian is updated by Broyden's
/// rank-one formula (see [`newton_with_jacobian`]).
pub fn newton<F>(x0: &[f64], f: F, opts: &SolveOptions, solver: &'static str) -> Result<NewtonResult>
where
    F: FnMut(&[f64]) -> Result<Vec<f64>>,
{
    newton_with_jacobian(x0, f, opts, solver, None).map(|(nr, _)| nr)
}

/// Forward-difference Jacobian of `f` at `x` with `r = f(x)` (one-sided step
/// into the other direction where `f` fails). Adds the evaluations to `evals`.
fn fd_jacobian<F>(x: &[f64], r: &[f64], f: &mut F, evals: &mut usize) -> Result<DMatrix<f64>>
where
    F: FnMut(&[f64]) -> Result<Vec<f64>>,
{
    let (n, m) = (x.len(), r.len());
    let h0 = f64::EPSILON.sqrt();
    let mut jac = DMatrix::<f64>::zeros(m, n);
    let mut xp = x.to_vec();
    for j in 0..n {
        let h = h0 * x[j].abs().max(1.0);
        xp[j] = x[j] + h;
        let h = xp[j] - x[j];
        *evals += 1;
        let col: Vec<f64> = match f(&xp) {
            Ok(rp) => rp.iter().zip(r).map(|(a, b)| (a - b) / h).collect(),
            Err(_) => {
                // one-sided step into a failing region: step the other way
                xp[j] = x[j] - h;
                *evals += 1;
                let rm = f(&xp)?;
                r.iter().zip(&rm).map(|(a, b)| (a - b) / h).collect()
            }
        };
        for i in 0..m {
            jac[(i, j)] = col[i];
        }
        xp[j] = x[j];
    }
    Ok(jac)
}

/// [`newton`] from an optional initial Jacobian `jac0` (e.g. the final
/// Jacobian of a neighbouring solve, for warm starts); returns the final
/// Jacobian too.
///
/// Quasi-Newton: a Jacobian by forward differences (or `jac0`) is updated by
/// Broyden's rank-one formula after every accepted step, and re-differenced
/// only when a full step fails to decrease `|f|^2` by a quarter. With a fresh
/// finite-difference Jacobian the step is Newton's with the usual
/// backtracking. The convergence test is the same as Newton's, so a converged
/// result meets the same tolerance.
pub fn newton_with_jacobian<F>(x0: &[f64], mut f: F, opts: &SolveOptions, solver: &'static str, jac0: Option<&DMatrix<f64>>) -> Result<(NewtonResult, DMatrix<f64>)>
where
    F: FnMut(&[f64]) -> Result<Vec<f64>>,
{
    let n = x0.len();
    let mut x = x0.to_vec();
    let mut evals = 1;
    let mut r = f(&x)?;
    let m = r.len();
    let mut jac = match jac0 {
        Some(j) if j.nrows() == m && j.ncols() == n && j.iter().all(|v| v.is_finite()) => Some(j.clone()),
        _ => None,
    };
    let mut fresh = false;
    let mut iterations = 0;
    loop {
        let res = inf_norm(&r);
        if res <= opts.tol {
            let jac = match jac {
                Some(j) => j,
                None => DMatrix::zeros(m, n),
            };
            return Ok((
                NewtonResult {
                    x,
                    residual: r,
                    iterations,
                    evaluations: evals,
                },
                jac,
            ));
        }
        if iterations >= opts.max_iter {
            return Err(Error::NotConverged {
                solver,
                iterations,
                residual: res,
                reason: "iteration limit reached".into(),
            });
        }
        iterations += 1;
        if jac.is_none() {
            jac = Some(fd_jacobian(&x, &r, &mut f, &mut evals)?);
            fresh = true;
        }
        let j = jac.as_ref().expect("set above");
        let rhs = -DVector::from_column_slice(&r);
        let dx = if m == n { j.clone().lu().solve(&rhs) } else { j.clone().svd(true, true).solve(&rhs, 1e-14).ok() };
        let dx = match dx {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ if !fresh => {
                jac = None;
                iterations -= 1;
                continue;
            }
            _ => {
                return Err(Error::NotConverged {
                    solver,
                    iterations,
                    residual: res,
                    reason: "singular Jacobian".into(),
                })
            }
        };
        let phi0 = sq_norm(&r);
        let mut t = 1.0;
        let mut accepted = None;
        loop {
            let xt: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + t * b).collect();
            evals += 1;
            if let Ok(rt) = f(&xt) {
                let phi = sq_norm(&rt);
                // a quasi-Newton step must do clearly better than Armijo, or
                // the Jacobian is refreshed
                let bound = if fresh { 1.0 - 1e-4 * t } else { QUASI_DECREASE };
                if phi.is_finite() && phi <= bound * phi0 {
                    accepted = Some((xt, rt));
                    break;
                }
            }
            if !fresh {
                break;
            }
            t *= 0.5;
            if t < opts.min_step {
                return Err(Error::NotConverged {
                    solver,
                    iterations,
                    residual: res,
                    reason: "line search failed to reduce the residual".into(),
                });
            }
        }
        match accepted {
            Some((xt, rt)) => {
                // Broyden: J += (dr - J s) s^T / (s^T s)
                let s = DVector::from_iterator(n, xt.iter().zip(&x).map(|(a, b)| a - b));
                let dr = DVector::from_iterator(m, rt.iter().zip(&r).map(|(a, b)| a - b));
                let ss = s.dot(&s);
                if ss > 0.0 {
                    let jm = jac.as_mut().expect("set above");
                    let corr = (dr - &*jm * &s) / ss;
                    jm.ger(1.0, &corr, &s, 1.0);
                }
                fresh = false;
                x = xt;
                r = rt;
            }
            None => {
                // stale Jacobian: re-difference at x and retry this iteration
                jac = None;
                iterations -= 1;
            }
        }
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

/// Tensions [N] of all actuators for guessed elongations `delta` [m].
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
    /// Tip force [N], world frame.
    pub tip_force: Vector3<f64>,
    /// Tip moment [N m], world frame.
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
pub fn shoot(robot: &Robot, inputs: &[f64], loads: &Loads, x: &[f64], steps: usize, record: bool) -> Result<(Vec<f64>, IvpResult, Vec<f64>)> {
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
    for i in 0..na {
        r.push((ivp.elongation[i] - delta[i]) / len);
    }
    Ok((r, ivp, tau))
}

/// One tangent IVP from scaled unknowns `x`: the scaled residual (as
/// [`shoot`]) and its EXACT Jacobian with respect to `x` (the derivative of
/// the discrete RK4 map, from the variational equations and the force laws'
/// derivatives), `(6 + N) x (6 + N)`. With `record`, the IVP's nodes carry
/// `d y(s) / d x` (see [`crate::rod::TangentNode`]).
pub fn shoot_jacobian(robot: &Robot, inputs: &[f64], loads: &Loads, x: &[f64], steps: usize, record: bool) -> Result<(Vec<f64>, DMatrix<f64>, TangentIvp, Vec<f64>)> {
    let len = robot.body.length;
    let na = robot.actuators.len();
    let nx = 6 + na;
    let v0 = Vector3::new(x[0], x[1], x[2]);
    let u0 = Vector3::new(x[3], x[4], x[5]) / len;
    let mut tau = Vec::with_capacity(na);
    let mut seeds = TangentSeeds::zeros(na, nx);
    for k in 0..3 {
        seeds.nu0[(k, k)] = 1.0;
        seeds.omega0[(k, 3 + k)] = 1.0 / len;
    }
    for (i, a) in robot.actuators.iter().enumerate() {
        let (t, dt_de, _) = a.law.tension_derivatives(x[6 + i] * len, inputs[i])?;
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
    jac.rows_mut(0, 3).copy_from(&(&tan.tip_force_residual * fs));
    jac.rows_mut(3, 3).copy_from(&(&tan.tip_moment_residual * ms));
    for i in 0..na {
        for j in 0..nx {
            jac[(6 + i, j)] = tan.elongation[(i, j)] / len;
        }
        jac[(6 + i, 6 + i)] -= 1.0;
    }
    Ok((r, jac, tan, tau))
}

/// Factors that make the tip balance dimensionless: force residuals [N] are
/// multiplied by `L^2 / (E I)` and moment residuals [N m] by `L / (E I)`
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
    /// Arc length of each node [m].
    pub s: Vec<f64>,
    /// Centre-line positions [m], world frame.
    pub positions: Vec<Vector3<f64>>,
    /// Rotations (body to world).
    pub rotations: Vec<Matrix3<f64>>,
    /// Linear strains `nu` [-], body frame.
    pub nu: Vec<Vector3<f64>>,
    /// Angular strains `omega` [1/m], body frame.
    pub omega: Vec<Vector3<f64>>,
    /// Internal force `n = R K_nu (nu - nu*)` [N], world frame.
    pub internal_force: Vec<Vector3<f64>>,
    /// Internal moment `m = R K_omega (omega - omega*)` [N m], world frame.
    pub internal_moment: Vec<Vector3<f64>>,
    /// Elongation of each actuator up to each node [m] (`nodes x actuators`).
    pub elongation_profile: Vec<Vec<f64>>,
    /// Actuator paths `p + R r_i(s)` [m] at the nodes within each actuator's span.
    pub actuator_paths: Vec<Vec<Vector3<f64>>>,
    /// Actuator tensions [N] (negative: the actuator pushes).
    pub tensions: Vec<f64>,
    /// Actuator total elongations [m].
    pub elongations: Vec<f64>,
    /// Actuation inputs the solution is for.
    pub inputs: Vec<f64>,
    /// Force [N] the body and its actuators transmit to the base (world
    /// frame); the base reaction is its negative.
    pub base_force: Vector3<f64>,
    /// Moment [N m] about the base origin transmitted to the base.
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
    /// The shooting Jacobian (scaled residual by scaled unknowns) of the last
    /// Newton iteration, finite-difference or Broyden-updated; `None` if no
    /// iteration was needed. Reused as the initial Jacobian of solves
    /// warm-started from this one.
    pub newton_jacobian: Option<DMatrix<f64>>,
}

impl Solution {
    /// Tip position [m].
    pub fn tip_position(&self) -> Vector3<f64> {
        *self.positions.last().expect("a solution has nodes")
    }
    /// Tip rotation.
    pub fn tip_rotation(&self) -> Matrix3<f64> {
        *self.rotations.last().expect("a solution has nodes")
    }
}

/// Build a [`Solution`] by integrating once more from converged unknowns.
pub fn assemble(robot: &Robot, inputs: &[f64], loads: &Loads, x: &[f64], steps: usize, iterations: usize, evaluations: usize) -> Result<Solution> {
    let (r, ivp, tau) = shoot(robot, inputs, loads, x, steps, true)?;
    assemble_from(robot, inputs, loads, x, steps, iterations, evaluations, r, ivp, tau)
}

/// [`assemble`] from the recorded IVP at `x` (residual `r`, tensions `tau`).
#[allow(clippy::too_many_arguments)]
fn assemble_from(
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
        residual: inf_norm(&r),
        unknowns: x.to_vec(),
        loads: *loads,
        steps,
        newton_jacobian: None,
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
        sol.internal_moment.push(rm * kbt * (st.u - body.omega_star));
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

/// Solve the forward kinetostatics for actuator `inputs` (temperature [C]
/// for TCAs, tension [N] or pull [m] for tendons).
///
/// Starts from [`initial_guess`] (warm from `warm` if given). If Newton fails
/// from there, falls back to continuation in the inputs from the warm
/// solution's inputs (or the reference inputs) in halving steps. The returned
/// `iterations` and `evaluations` count all Newton work done.
pub fn solve(robot: &Robot, inputs: &[f64], opts: &SolveOptions, warm: Option<&Solution>) -> Result<Solution> {
    solve_loaded(robot, inputs, &Loads::of(robot), opts, warm)
}

/// Newton shooting on two grids: converge on a grid of a tenth of the steps
/// (a tenth of the cost per IVP), then polish on the full grid from that
/// solution with a finite-difference Jacobian taken on the coarse grid.
/// (At least 1 step; grids under 10 steps are solved directly.)
#[allow(clippy::too_many_arguments)]
fn two_level(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    work: &mut (usize, usize),
    record: bool,
) -> Result<(Vec<f64>, Option<DMatrix<f64>>, LastTip)> {
    // Two levels: converge on a grid of a tenth of the steps (a tenth of the
    // cost per IVP; RK4's error there is ~1e-4 of the fine one's strains), then
    // polish on the full grid from that solution and its Jacobian.
    let coarse = if opts.steps >= 10 {
        // the coarse solution is only a predictor: converge it to 1e-6, well
        // below the coarse grid's own discretisation error
        let copts = SolveOptions { steps: (opts.steps / 10).max(1), tol: opts.tol.max(1e-6), ..*opts };
        // cold: the coarse problem is itself solved on two grids, down to one
        // step; warm (a Jacobian given): one coarse grid is enough
        let coarse = match jac0 {
            None => two_level(robot, inputs, loads, &copts, x0, jac0, work, false).map(|(x, j, _)| (x, j)),
            Some(_) => newton_from(robot, inputs, loads, &copts, x0, jac0, work),
        };
        coarse.ok().and_then(|(xc, _)| {
            // a finite-difference Jacobian at the coarse solution (cheap IVPs)
            // for the fine polish: Broyden's matrix is no accurate Jacobian
            let mut f = |x: &[f64]| shoot(robot, inputs, loads, x, copts.steps, false).map(|t| t.0);
            let rc = f(&xc).ok()?;
            let mut ev = 1;
            let jc = fd_jacobian(&xc, &rc, &mut f, &mut ev).ok()?;
            work.1 += ev;
            Some((xc, Some(jc)))
        })
    } else {
        None
    };
    match &coarse {
        Some((xc, jc)) => newton_from_tip(robot, inputs, loads, opts, xc, jc.as_ref(), work, record)
            .or_else(|_| newton_from_tip(robot, inputs, loads, opts, x0, jac0, work, record)),
        None => newton_from_tip(robot, inputs, loads, opts, x0, jac0, work, record),
    }
}

/// Tip pose of a forward solution, without the sampled profile (for batches).
#[derive(Debug, Clone)]
pub struct TipSolution {
    /// Tip position [m].
    pub position: Vector3<f64>,
    /// Tip rotation (body to world).
    pub rotation: Matrix3<f64>,
    /// Scaled shooting unknowns.
    pub unknowns: Vec<f64>,
    /// Actuator tensions [N].
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
    fn from_solution(s: Solution) -> Self {
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

/// [`solve_loaded`] returning only the tip pose (no profile is recorded,
/// which saves an IVP and its allocations). `warm`: a neighbouring tip
/// solution. Falls back on [`solve_loaded`] (with its continuation) when the
/// direct Newton solve fails. Inputs are not validated here: call
/// `robot.check_inputs` first.
pub fn solve_tip(robot: &Robot, inputs: &[f64], loads: &Loads, opts: &SolveOptions, warm: Option<&TipSolution>) -> Result<TipSolution> {
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
    let mut work = (0usize, 0usize);
    let jac0 = warm.and_then(|w| w.newton_jacobian.as_ref());
    match two_level(robot, inputs, loads, opts, &x0, jac0, &mut work, false) {
        Ok((x, jac, Some((_, ivp, tau)))) => Ok(TipSolution {
            position: ivp.tip.p,
            rotation: ivp.tip.rotation(),
            unknowns: x,
            tensions: tau,
            inputs: inputs.to_vec(),
            iterations: work.0,
            evaluations: work.1,
            newton_jacobian: jac,
        }),
        Err(e) if is_input_error(&e) => Err(e),
        _ => {
            let w = match warm {
                Some(w) => Some(assemble(robot, &w.inputs, loads, &w.unknowns, opts.steps, 0, 0)?),
                None => None,
            };
            let mut s = TipSolution::from_solution(solve_loaded(robot, inputs, loads, opts, w.as_ref())?);
            s.iterations += work.0;
            s.evaluations += work.1;
            Ok(s)
        }
    }
}

fn is_input_error(e: &Error) -> bool {
    matches!(e, Error::InvalidParameter { .. } | Error::InvalidInput { .. })
}

/// [`solve`] with explicit tip loads.
pub fn solve_loaded(robot: &Robot, inputs: &[f64], loads: &Loads, opts: &SolveOptions, warm: Option<&Solution>) -> Result<Solution> {
    robot.validate()?;
    robot.check_inputs(inputs)?;
    opts.validate()?;
    if let Some(w) = warm {
        if w.unknowns.len() != 6 + robot.actuators.len() || w.tensions.len() != robot.actuators.len() {
            return Err(Error::input(
                "warm_start",
                format!("solution of a robot with {} actuators, this one has {}", w.tensions.len(), robot.actuators.len()),
            ));
        }
    }
    for (name, v) in [("tip_force [N]", &loads.tip_force), ("tip_moment [N m]", &loads.tip_moment)] {
        for (k, z) in v.iter().enumerate() {
            crate::error::finite(&format!("{name}[{k}]"), *z)?;
        }
    }
    let mut work = (0usize, 0usize);
    let jac0 = warm.and_then(|w| w.newton_jacobian.as_ref());
    let x0 = initial_guess(robot, inputs, warm);
    // the last IVP of Newton is at its solution: recorded, it is the profile
    match two_level(robot, inputs, loads, opts, &x0, jac0, &mut work, true) {
        Ok((x, jac, last)) => {
            let sol = match last {
                Some((r, ivp, tau)) if !ivp.nodes.is_empty() => assemble_from(robot, inputs, loads, &x, opts.steps, work.0, work.1, r, ivp, tau),
                _ => assemble(robot, inputs, loads, &x, opts.steps, work.0, work.1),
            };
            sol.map(|mut s| {
                s.newton_jacobian = jac;
                s
            })
        }
        Err(e) if is_input_error(&e) => Err(e),
        Err(first) => {
            let (from, start) = match warm {
                Some(w) => (w.inputs.clone(), w.clone()),
                None => {
                    let r = robot.reference_inputs();
                    let (x, jac) = newton_from(robot, &r, loads, opts, &initial_guess(robot, &r, None), None, &mut work)?;
                    let mut s = assemble(robot, &r, loads, &x, opts.steps, 0, 0)?;
                    s.newton_jacobian = jac;
                    (r.clone(), s)
                }
            };
            match continuation(robot, loads, &from, inputs, &start, opts, 10, &mut work) {
                Ok(mut s) => {
                    s.iterations = work.0;
                    s.evaluations = work.1;
                    Ok(s)
                }
                Err(_) => Err(first),
            }
        }
    }
}

/// Tip position, rotation and actuator tensions of the last IVP integrated.
type LastTip = Option<(Vec<f64>, IvpResult, Vec<f64>)>;

/// Newton from `x0`; returns the solution, the final Jacobian and the tip of
/// the solution (the last IVP Newton integrates is at the point it returns).
#[allow(clippy::too_many_arguments)]
fn newton_from_tip(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    work: &mut (usize, usize),
    record: bool,
) -> Result<(Vec<f64>, Option<DMatrix<f64>>, LastTip)> {
    let mut last: LastTip = None;
    let r = newton_with_jacobian(
        x0,
        |x| {
            shoot(robot, inputs, loads, x, opts.steps, record).map(|(r, ivp, tau)| {
                last = Some((r.clone(), ivp, tau));
                r
            })
        },
        opts,
        "forward shooting",
        jac0,
    );
    match r {
        Ok((nr, jac)) => {
            work.0 += nr.iterations;
            work.1 += nr.evaluations;
            let jac = if nr.iterations > 0 { Some(jac) } else { jac0.cloned() };
            Ok((nr.x, jac, last))
        }
        Err(Error::NotConverged { solver, iterations, residual, reason }) => {
            work.0 += iterations;
            Err(Error::NotConverged {
                solver,
                iterations: work.0,
                residual,
                reason,
            })
        }
        Err(e) => Err(e),
    }
}

fn newton_from(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    work: &mut (usize, usize),
) -> Result<(Vec<f64>, Option<DMatrix<f64>>)> {
    newton_from_tip(robot, inputs, loads, opts, x0, jac0, work, false).map(|(x, j, _)| (x, j))
}

/// Reach `target` inputs from a solution `start` at inputs `from` by halving
/// the input step (at most `depth` times), each step warm-started.
#[allow(clippy::too_many_arguments)]
fn continuation(
    robot: &Robot,
    loads: &Loads,
    from: &[f64],
    target: &[f64],
    start: &Solution,
    opts: &SolveOptions,
    depth: usize,
    work: &mut (usize, usize),
) -> Result<Solution> {
    let x0 = initial_guess(robot, target, Some(start));
    match newton_from(robot, target, loads, opts, &x0, start.newton_jacobian.as_ref(), work) {
        Ok((x, jac)) => assemble(robot, target, loads, &x, opts.steps, 0, 0).map(|mut s| {
            s.newton_jacobian = jac;
            s
        }),
        Err(e) if depth == 0 || is_input_error(&e) => Err(e),
        Err(_) => {
            let mid: Vec<f64> = from.iter().zip(target).map(|(a, b)| 0.5 * (a + b)).collect();
            let half = continuation(robot, loads, from, &mid, start, opts, depth - 1, work)?;
            continuation(robot, loads, &mid, target, &half, opts, depth - 1, work)
        }
    }
}

/// Solve along a sequence of input vectors, each warm-started from the
/// previous solution (continuation helper for temperature or load sweeps).
pub fn sweep(robot: &Robot, inputs: &[Vec<f64>], opts: &SolveOptions) -> Result<Vec<Solution>> {
    let mut out: Vec<Solution> = Vec::with_capacity(inputs.len());
    for q in inputs {
        let sol = solve(robot, q, opts, out.last())?;
        out.push(sol);
    }
    Ok(out)
}
