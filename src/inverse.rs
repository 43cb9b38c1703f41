//! Inverse kinetostatics (paper Section IV, eqs 34-43): actuation Jacobian,
//! compliance, tip-position inverse, blocked-tip force and grasping.
//!
//! Tip pose perturbations are measured in the world frame as
//! `[dp; dtheta]`, `dtheta` the rotation vector of `R1 R0^T`. Actuation
//! variables `z` map to actuator inputs through `groups` (actuator `i` takes
//! variable `groups\[i\]`): the two legs of a U-shaped TCA share one
//! temperature. Tip wrenches `W = [F; M]` are in the world frame.

use nalgebra::{DMatrix, DVector, Matrix3, Quaternion, Rotation3, Vector3};

use crate::error::StopReason;
use crate::error::{Error, Result};
use crate::rod::{integrate_tangent, IvpSpec, Robot, TangentSeeds};
use crate::shooting::{
    assemble, initial_guess, shoot, solve_loaded, Loads, Solution, SolveOptions,
};
use crate::solve::{newton, FnSystem};

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

fn pose_delta(
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
    let b = &robot.body;
    let (_, ix, iy, _) = b.section.properties();
    let ei = b.youngs_modulus * ix.min(iy);
    (ei / (b.length * b.length), ei / b.length)
}

/// `J` and `C` at a converged solution, from finite differences of IVPs
/// around it (eqs 41-42), the paper's way.
pub fn sensitivities(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
    scheme: Scheme,
) -> Result<Sensitivities> {
    let Some(rel) = scheme.relative_step() else {
        return sensitivities_exact(robot, sol, loads, groups, steps);
    };
    sensitivities_with_step(robot, sol, loads, groups, steps, scheme, rel)
}

/// [`sensitivities`] with the wrench columns exact instead of differenced:
/// for fixed unknowns a tip wrench moves no state and enters the tip balance
/// (32)-(33) linearly, so `B_W` is known in closed form and `E_W = 0`. Needs
/// `1 + 6 + N + n_vars` IVPs (forward) instead of the paper's `12 + 2N`;
/// `C` has no truncation error from the wrench steps.
pub fn sensitivities_fast(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
    scheme: Scheme,
) -> Result<Sensitivities> {
    let Some(rel) = scheme.relative_step() else {
        return sensitivities_exact(robot, sol, loads, groups, steps);
    };
    sensitivities_impl(robot, sol, loads, groups, steps, scheme, rel, true)
}

/// `J` and `C` (eqs 39-42) exactly, from one tangent IVP at the solution
/// along the `6 + N` shooting unknowns and the `n_vars` actuation variables:
/// `E_u, E_q` are the tangents of the tip pose (`dtheta = 2 vec(dq q^-1)`,
/// world frame), `B_u, B_q` those of the scaled residual, `E_W = 0` and
/// `B_W` in closed form (see [`sensitivities_fast`]).
pub fn sensitivities_exact(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
) -> Result<Sensitivities> {
    groups.validate(robot)?;
    let len = robot.body.length;
    let na = robot.actuators.len();
    let nx = 6 + na;
    let nz = groups.n_vars();
    let x = &sol.unknowns;
    let mut tau = Vec::with_capacity(na);
    // The elongation unknowns and the actuation variables move the state
    // only through the tensions, so the 6 + N directions (initial strains,
    // unit tension of each actuator) give every column: the tangent IVP is
    // linear in its seeds. `chain[(i, c)]`: d tau_i / d column c.
    let mut seeds = TangentSeeds::zeros(na, nx);
    let mut chain = DMatrix::<f64>::zeros(na, nx + nz);
    for k in 0..3 {
        seeds.nu0[(k, k)] = 1.0;
        seeds.omega0[(k, 3 + k)] = 1.0 / len;
    }
    for (i, a) in robot.actuators.iter().enumerate() {
        let (t, dt_de, dt_dq) = a.law.tension_derivatives(x[6 + i] * len, sol.inputs[i])?;
        tau.push(t);
        seeds.tensions[(i, 6 + i)] = 1.0;
        chain[(i, 6 + i)] = dt_de * len;
        chain[(i, nx + groups.0[i])] = dt_dq;
    }
    let spec = IvpSpec {
        robot,
        tensions: &tau,
        tip_force: loads.tip_force,
        tip_moment: loads.tip_moment,
        steps,
    };
    let v0 = Vector3::new(x[0], x[1], x[2]);
    let u0 = Vector3::new(x[3], x[4], x[5]) / len;
    let mut tan = integrate_tangent(&spec, &v0, &u0, &seeds, false)?;
    let ncol = nx + nz;
    // columns per unknown and variable: strain columns as seeded, the
    // others through the tensions
    let expand = |m: &DMatrix<f64>| {
        let mut out = DMatrix::<f64>::zeros(m.nrows(), ncol);
        out.columns_mut(0, 6).copy_from(&m.columns(0, 6));
        out.columns_mut(6, ncol - 6)
            .copy_from(&(m.columns(6, na) * chain.columns(6, ncol - 6)));
        out
    };
    tan.tip = expand(&tan.tip);
    tan.elongation = expand(&tan.elongation);
    tan.tip_force_residual = expand(&tan.tip_force_residual);
    tan.tip_moment_residual = expand(&tan.tip_moment_residual);
    // pose tangents: dp, and dtheta = 2 vec(dq conj(q)) for a unit q
    let q = tan.ivp.tip.q;
    let mut e = DMatrix::<f64>::zeros(6, ncol + 6);
    for c in 0..ncol {
        for k in 0..3 {
            e[(k, c)] = tan.tip[(k, c)];
        }
        let dq = Quaternion::new(
            tan.tip[(3, c)],
            tan.tip[(4, c)],
            tan.tip[(5, c)],
            tan.tip[(6, c)],
        );
        let w = dq * q.conjugate() * 2.0;
        e[(3, c)] = w.i;
        e[(4, c)] = w.j;
        e[(5, c)] = w.k;
    }
    let (fs, ms) = crate::shooting::residual_scales(robot);
    let mut bm = DMatrix::<f64>::zeros(nx, ncol + 6);
    for c in 0..ncol {
        for k in 0..3 {
            bm[(k, c)] = tan.tip_force_residual[(k, c)] * fs;
            bm[(3 + k, c)] = tan.tip_moment_residual[(k, c)] * ms;
        }
        for i in 0..na {
            bm[(6 + i, c)] = tan.elongation[(i, c)] / len - if c == 6 + i { 1.0 } else { 0.0 };
        }
    }
    let r0 = tan.ivp.tip.rotation();
    for k in 0..6 {
        for i in 0..3 {
            let (row, val) = if k < 3 {
                (i, -r0[(k, i)] * fs)
            } else {
                (3 + i, -r0[(k - 3, i)] * ms)
            };
            bm[(row, ncol + k)] = val;
        }
    }
    let lu = bm.columns(0, nx).into_owned().lu();
    let singular = || Error::NotConverged {
        solver: "sensitivities",
        iterations: 0,
        evaluations: 1,
        residual: f64::INFINITY,
        stop: StopReason::SingularJacobian,
        reason: "B_u is singular".into(),
    };
    let eu = e.columns(0, nx).into_owned();
    let jac = e.columns(nx, nz).into_owned()
        - &eu
            * lu.solve(&bm.columns(nx, nz).into_owned())
                .ok_or_else(singular)?; // (41)
    let comp = -(&eu
        * lu.solve(&bm.columns(ncol, 6).into_owned())
            .ok_or_else(singular)?); // (42), E_W = 0
    Ok(Sensitivities {
        jacobian: jac,
        compliance: comp,
        evaluations: 1,
    })
}

/// [`sensitivities`] with a chosen relative step (for studies of step-size error).
#[allow(clippy::too_many_arguments)]
pub fn sensitivities_with_step(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
    scheme: Scheme,
    rel: f64,
) -> Result<Sensitivities> {
    sensitivities_impl(robot, sol, loads, groups, steps, scheme, rel, false)
}

#[allow(clippy::too_many_arguments)]
fn sensitivities_impl(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
    scheme: Scheme,
    rel: f64,
    exact_wrench: bool,
) -> Result<Sensitivities> {
    groups.validate(robot)?;
    let nx = sol.unknowns.len();
    let nz = groups.n_vars();
    let z0 = groups.vars(&sol.inputs);
    let bounds = groups.bounds(robot);
    let (b0, ivp0, _) = shoot(robot, &sol.inputs, loads, &sol.unknowns, steps, false)?;
    let p0 = ivp0.tip.p;
    let r0 = ivp0.tip.rotation();
    let mut evals = 1;
    // Evaluate pose and residual at a perturbation; returns (E column, B column).
    let mut column = |x: &[f64], inputs: &[f64], l: &Loads| -> Result<([f64; 6], Vec<f64>)> {
        let (b, ivp, _) = shoot(robot, inputs, l, x, steps, false)?;
        evals += 1;
        Ok((pose_delta(&p0, &r0, &ivp.tip.p, &ivp.tip.rotation()), b))
    };
    let mut e = DMatrix::<f64>::zeros(6, nx + nz + 6);
    let mut bm = DMatrix::<f64>::zeros(nx, nx + nz + 6);
    let mut put =
        |col: usize, plus: ([f64; 6], Vec<f64>), minus: Option<([f64; 6], Vec<f64>)>, h: f64| {
            for i in 0..6 {
                e[(i, col)] = match &minus {
                    Some(m) => (plus.0[i] - m.0[i]) / (2.0 * h),
                    None => plus.0[i] / h,
                };
            }
            for i in 0..nx {
                bm[(i, col)] = match &minus {
                    Some(m) => (plus.1[i] - m.1[i]) / (2.0 * h),
                    None => (plus.1[i] - b0[i]) / h,
                };
            }
        };
    // unknowns u
    for j in 0..nx {
        // Typical sizes: strains ~1; actuator elongations / L ~1e-2. The
        // elongation columns are the most nonlinear (a TCA is far stiffer
        // than the body, so micrometres of elongation move the tip a lot), so
        // they get a step scaled to their size rather than to 1.
        let typical = if j < 6 { 1.0 } else { 1e-2 };
        let h = rel * sol.unknowns[j].abs().max(typical);
        let mut xp = sol.unknowns.clone();
        xp[j] += h;
        let plus = column(&xp, &sol.inputs, loads)?;
        let minus = if scheme == Scheme::Central {
            xp[j] = sol.unknowns[j] - h;
            Some(column(&xp, &sol.inputs, loads)?)
        } else {
            None
        };
        put(j, plus, minus, h);
    }
    // actuation variables q (one-sided away from a bound)
    for k in 0..nz {
        let h0 = rel * z0[k].abs().max(1.0);
        let (lo, hi) = bounds[k];
        let mut zp = z0.clone();
        let (h, minus) = if scheme == Scheme::Central && z0[k] - h0 >= lo && z0[k] + h0 <= hi {
            zp[k] = z0[k] - h0;
            (h0, Some(column(&sol.unknowns, &groups.inputs(&zp), loads)?))
        } else {
            (if z0[k] + h0 <= hi { h0 } else { -h0 }, None)
        };
        zp[k] = z0[k] + h;
        let plus = column(&sol.unknowns, &groups.inputs(&zp), loads)?;
        put(nx + k, plus, minus, h);
    }
    if exact_wrench {
        // tip wrench W = [F; M]: exact, no IVP. For fixed unknowns the wrench
        // moves no state (E_W = 0) and enters only the tip balance (32)-(33),
        // linearly: d r_F / dF = -(L^2/EI) R^T, d r_M / dM = -(L/EI) R^T
        // in the scaled residual of `shoot`.
        let (fs, ms) = crate::shooting::residual_scales(robot);
        for k in 0..6 {
            let col = nx + nz + k;
            for i in 0..3 {
                let (row, val) = if k < 3 {
                    (i, -r0[(k, i)] * fs)
                } else {
                    (3 + i, -r0[(k - 3, i)] * ms)
                };
                bm[(row, col)] = val;
            }
        }
    } else {
        // tip wrench W = [F; M] by differences, the paper's way
        let (fc, mc) = load_scales(robot);
        for k in 0..6 {
            let scale = if k < 3 { fc } else { mc };
            let w0 = if k < 3 {
                loads.tip_force[k]
            } else {
                loads.tip_moment[k - 3]
            };
            let h = rel * (w0.abs() / scale).max(1.0) * scale;
            let perturbed = |d: f64| {
                let mut l = *loads;
                if k < 3 {
                    l.tip_force[k] += d;
                } else {
                    l.tip_moment[k - 3] += d;
                }
                l
            };
            let plus = column(&sol.unknowns, &sol.inputs, &perturbed(h))?;
            let minus = if scheme == Scheme::Central {
                Some(column(&sol.unknowns, &sol.inputs, &perturbed(-h))?)
            } else {
                None
            };
            put(nx + nz + k, plus, minus, h);
        }
    }
    let bu = bm.columns(0, nx).into_owned();
    let lu = bu.lu();
    let solve_b = |rhs: DMatrix<f64>| {
        lu.solve(&rhs).ok_or_else(|| Error::NotConverged {
            solver: "sensitivities",
            iterations: 0,
            evaluations: 0,
            residual: f64::INFINITY,
            stop: StopReason::SingularJacobian,
            reason: "B_u is singular".into(),
        })
    };
    let eu = e.columns(0, nx).into_owned();
    let jac = e.columns(nx, nz).into_owned() - &eu * solve_b(bm.columns(nx, nz).into_owned())?;
    let comp =
        e.columns(nx + nz, 6).into_owned() - &eu * solve_b(bm.columns(nx + nz, 6).into_owned())?;
    Ok(Sensitivities {
        jacobian: jac,
        compliance: comp,
        evaluations: evals,
    })
}

/// Outcome of [`tip_position_inverse`].
#[derive(Debug, Clone)]
pub struct InverseResult {
    /// Final forward solution (the closest reachable one if not `reached`).
    pub solution: Solution,
    /// Final actuation variables.
    pub variables: Vec<f64>,
    /// Distance \[m\] from the target (and angle \[rad\] if orientation was asked).
    pub error: f64,
    /// Iterations (Jacobian evaluations).
    pub iterations: usize,
    /// Whether the target was reached to tolerance.
    pub reached: bool,
    /// Variables resting on a bound at the end.
    pub at_bound: Vec<bool>,
    /// IVPs integrated in total.
    pub evaluations: usize,
}

/// Options of the inverse solvers.
#[derive(Debug, Clone, Copy)]
pub struct InverseOptions {
    /// Forward solver options.
    pub forward: SolveOptions,
    /// Position tolerance \[m\].
    pub tol: f64,
    /// Iteration limit.
    pub max_iter: usize,
    /// Damping `lambda` [m per unit variable] of the damped least squares.
    pub damping: f64,
}

impl Default for InverseOptions {
    fn default() -> Self {
        InverseOptions {
            forward: SolveOptions::default(),
            tol: 1e-7,
            max_iter: 50,
            damping: 1e-6,
        }
    }
}

/// Reach a target tip position `target` \[m\] (and orientation: rotation matrix
/// `target_rotation`, weighted by `orientation_weight` \[m/rad\]) by iterating
/// the local inverse `dz = J^+ dx` (damped least squares) with variables kept
/// within their bounds (ambient to the material's limit for TCAs).
///
/// An unreachable target ends at the closest configuration found with
/// `reached = false`, not with an error.
#[allow(clippy::too_many_arguments)]
pub fn tip_position_inverse(
    robot: &Robot,
    groups: &Groups,
    target: &Vector3<f64>,
    target_rotation: Option<(&Matrix3<f64>, f64)>,
    z_start: &[f64],
    opts: &InverseOptions,
) -> Result<InverseResult> {
    groups.validate(robot)?;
    for (k, v) in target.iter().enumerate() {
        crate::error::finite(&format!("target[{k}] [m]"), *v)?;
    }
    let nz = groups.n_vars();
    if z_start.len() != nz {
        return Err(Error::input(
            "start",
            format!("expected {nz} variables, got {}", z_start.len()),
        ));
    }
    let bounds = groups.bounds(robot);
    let mut z: Vec<f64> = z_start
        .iter()
        .zip(&bounds)
        .map(|(v, (lo, hi))| v.clamp(*lo, *hi))
        .collect();
    let loads = Loads::of(robot);
    let mut sol = solve_loaded(robot, &groups.inputs(&z), &loads, &opts.forward, None)?;
    let mut evals = sol.evaluations;
    let rows = if target_rotation.is_some() { 6 } else { 3 };
    let err_vec = |s: &Solution| -> DVector<f64> {
        let dp = target - s.tip_position();
        let mut e = DVector::zeros(rows);
        e.rows_mut(0, 3).copy_from(&dp);
        if let Some((rt, w)) = target_rotation {
            let th = rotation_vector(&(rt * s.tip_rotation().transpose()));
            e.rows_mut(3, 3).copy_from(&(th * w));
        }
        e
    };
    let mut err = err_vec(&sol);
    let mut best = (err.norm(), sol.clone(), z.clone());
    let mut iterations = 0;
    while err.norm() > opts.tol && iterations < opts.max_iter {
        iterations += 1;
        let sens = sensitivities_fast(
            robot,
            &sol,
            &loads,
            groups,
            opts.forward.steps,
            Scheme::Forward,
        )?;
        evals += sens.evaluations;
        let mut jr = sens.jacobian.rows(0, rows).into_owned();
        if let Some((_, w)) = target_rotation {
            for c in 0..nz {
                for r in 3..6 {
                    jr[(r, c)] *= w;
                }
            }
        }
        // Variables on a bound whose step would push past it are frozen.
        let mut free: Vec<bool> = vec![true; nz];
        let mut dz = DVector::zeros(nz);
        for _ in 0..=nz {
            let cols: Vec<usize> = (0..nz).filter(|&k| free[k]).collect();
            if cols.is_empty() {
                break;
            }
            let jf = DMatrix::from_fn(rows, cols.len(), |r, c| jr[(r, cols[c])]);
            let lam2 = opts.damping * opts.damping;
            let a = jf.transpose() * &jf + DMatrix::identity(cols.len(), cols.len()) * lam2;
            let step = a
                .lu()
                .solve(&(jf.transpose() * &err))
                .unwrap_or_else(|| DVector::zeros(cols.len()));
            dz = DVector::zeros(nz);
            for (c, &k) in cols.iter().enumerate() {
                dz[k] = step[c];
            }
            let mut changed = false;
            for k in 0..nz {
                let (lo, hi) = bounds[k];
                if free[k] && ((z[k] <= lo && dz[k] < 0.0) || (z[k] >= hi && dz[k] > 0.0)) {
                    free[k] = false;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        // backtrack on the tip error, clamping to bounds
        let mut t = 1.0;
        let mut accepted = false;
        while t > 1e-4 {
            let zt: Vec<f64> = (0..nz)
                .map(|k| (z[k] + t * dz[k]).clamp(bounds[k].0, bounds[k].1))
                .collect();
            if let Ok(st) = solve_loaded(
                robot,
                &groups.inputs(&zt),
                &loads,
                &opts.forward,
                Some(&sol),
            ) {
                evals += st.evaluations;
                let et = err_vec(&st);
                if et.norm() < err.norm() {
                    z = zt;
                    sol = st;
                    err = et;
                    accepted = true;
                    break;
                }
            }
            t *= 0.5;
        }
        if err.norm() < best.0 {
            best = (err.norm(), sol.clone(), z.clone());
        }
        if !accepted {
            break; // no descent: closest reachable configuration
        }
    }
    let (e, s, zb) = best;
    let at_bound = zb
        .iter()
        .zip(&bounds)
        .map(|(v, (lo, hi))| *v <= *lo || *v >= *hi)
        .collect();
    Ok(InverseResult {
        solution: s,
        variables: zb,
        error: e,
        iterations,
        reached: e <= opts.tol,
        at_bound,
        evaluations: evals,
    })
}

/// A blocked tip: the tip's displacement along `normal` (unit, world) is held
/// at `point`; the environment pushes on the tip with force `-f normal`,
/// `f >= 0` (the tip presses along `+normal`).
#[derive(Debug, Clone, Copy)]
pub struct Block {
    /// A point of the blocking plane \[m\].
    pub point: Vector3<f64>,
    /// Unit normal: the direction the tip presses in.
    pub normal: Vector3<f64>,
}

impl Block {
    /// Validate and normalise.
    pub fn new(point: Vector3<f64>, normal: Vector3<f64>) -> Result<Self> {
        for k in 0..3 {
            crate::error::finite(&format!("point[{k}] [m]"), point[k])?;
            crate::error::finite(&format!("normal[{k}]"), normal[k])?;
        }
        let n = normal.norm();
        if !(n > 0.0) {
            return Err(Error::input("normal", "must be a non-zero vector"));
        }
        Ok(Block {
            point,
            normal: normal / n,
        })
    }
    fn loads(&self, robot: &Robot, f: f64) -> Loads {
        let mut l = Loads::of(robot);
        l.tip_force -= self.normal * f;
        l
    }
}

/// A blocked-tip solution.
#[derive(Debug, Clone)]
pub struct BlockedResult {
    /// The forward solution with the contact force applied at the tip.
    pub solution: Solution,
    /// Contact force magnitude \[N\] (the tip presses with it along the normal).
    pub force: f64,
    /// Actuation variables.
    pub variables: Vec<f64>,
    /// IVPs integrated.
    pub evaluations: usize,
    /// Iterations (increments for the incremental method, Newton iterations for the direct one).
    pub iterations: usize,
}

/// Direct solve with the tip held (mixed boundary condition): at given
/// actuation variables `z`, the contact force `f` \[N\] is an extra unknown and
/// `normal . (p(L) - point) = 0` an extra residual. `f` may come out negative
/// if the tip would pull away from the block (the caller decides whether
/// contact holds).
pub fn blocked_force(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    z: &[f64],
    opts: &SolveOptions,
    warm: Option<(&Solution, f64)>,
) -> Result<BlockedResult> {
    groups.validate(robot)?;
    let inputs = groups.inputs(z);
    robot.check_inputs(&inputs)?;
    let (fc, _) = load_scales(robot);
    let len = robot.body.length;
    let nx = 6 + robot.actuators.len();
    let mut x0 = initial_guess(robot, &inputs, warm.map(|w| w.0));
    x0.push(warm.map_or(0.0, |w| w.1) / fc);
    let f = |x: &[f64]| -> Result<Vec<f64>> {
        let l = block.loads(robot, x[nx] * fc);
        let (mut r, ivp, _) = shoot(robot, &inputs, &l, &x[..nx], opts.steps, false)?;
        r.push(block.normal.dot(&(ivp.tip.p - block.point)) / len);
        Ok(r)
    };
    let mut sys = FnSystem::new(f);
    let nr = newton(&mut sys, &x0, &opts.newton(), "blocked-tip shooting")?;
    let force = nr.x[nx] * fc;
    let l = block.loads(robot, force);
    let sol = assemble(
        robot,
        &inputs,
        &l,
        &nr.x[..nx],
        opts.steps,
        nr.iterations,
        nr.evaluations,
    )?;
    Ok(BlockedResult {
        solution: sol,
        force,
        variables: z.to_vec(),
        evaluations: nr.evaluations,
        iterations: nr.iterations,
    })
}

/// Direct solve for the single actuation variable at which the blocked tip
/// presses with `force` \[N\] (the variable is an extra unknown). Independent
/// check of [`blocked_temperature`].
pub fn blocked_variable_direct(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    force: f64,
    z_guess: f64,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<BlockedResult> {
    groups.validate(robot)?;
    if groups.n_vars() != 1 {
        return Err(Error::input(
            "groups",
            "a blocked-force temperature needs exactly one actuation variable",
        ));
    }
    crate::error::finite("force [N]", force)?;
    let (lo, hi) = groups.bounds(robot)[0];
    let zs = (hi - lo).clamp(1.0, 1e3);
    let len = robot.body.length;
    let nx = 6 + robot.actuators.len();
    let l = block.loads(robot, force);
    let mut x0 = initial_guess(robot, &groups.inputs(&[z_guess]), warm);
    x0.push(z_guess / zs);
    let f = |x: &[f64]| -> Result<Vec<f64>> {
        let z = x[nx] * zs;
        let inputs = groups.inputs(&[z]);
        robot.check_inputs(&inputs)?;
        let (mut r, ivp, _) = shoot(robot, &inputs, &l, &x[..nx], opts.steps, false)?;
        r.push(block.normal.dot(&(ivp.tip.p - block.point)) / len);
        Ok(r)
    };
    let mut sys = FnSystem::new(f);
    let nr = newton(
        &mut sys,
        &x0,
        &opts.newton(),
        "blocked-tip temperature shooting",
    )?;
    let z = nr.x[nx] * zs;
    let sol = assemble(
        robot,
        &groups.inputs(&[z]),
        &l,
        &nr.x[..nx],
        opts.steps,
        nr.iterations,
        nr.evaluations,
    )?;
    Ok(BlockedResult {
        solution: sol,
        force,
        variables: vec![z],
        evaluations: nr.evaluations,
        iterations: nr.iterations,
    })
}

/// The paper's incremental method (eq 43 with `dx = 0`): starting from a
/// solution `start` whose tip touches the block with zero force, raise the
/// contact force to `force` \[N\] in `increments` steps, each
/// `dq = -(n^T J)^-1 n^T C dW`, followed by one forward solve and a
/// position correction `dq = (n^T J)^-1 n^T (point - p)` so that the tip stays
/// on the block. Needs exactly one actuation variable. A force that needs
/// an input outside the actuator's range is [`Error::NoSolution`]; a step that
/// overshoots a bound by linearisation error (a tenth of the step at most) is
/// clamped to it.
pub fn blocked_temperature(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    start: &Solution,
    force: f64,
    increments: usize,
    opts: &SolveOptions,
) -> Result<BlockedResult> {
    groups.validate(robot)?;
    if groups.n_vars() != 1 {
        return Err(Error::input(
            "groups",
            "a blocked-force temperature needs exactly one actuation variable",
        ));
    }
    crate::error::finite("force [N]", force)?;
    if increments == 0 {
        return Err(Error::param("increments", 0.0, ">= 1"));
    }
    let (lo, hi) = groups.bounds(robot)[0];
    let n = block.normal;
    let mut z = groups.vars(&start.inputs)[0];
    let mut sol = start.clone();
    let mut f = 0.0;
    let mut evals = 0;
    let mut pushed_out = false;
    let df = force / increments as f64;
    for k in 0..increments + 3 {
        let l = block.loads(robot, f);
        let sens = sensitivities_fast(robot, &sol, &l, groups, opts.steps, Scheme::Forward)?;
        evals += sens.evaluations;
        let nj: f64 = (0..3).map(|i| n[i] * sens.jacobian[(i, 0)]).sum();
        if nj.abs() < 1e-300 {
            return Err(Error::NotConverged {
                solver: "blocked-tip increments",
                iterations: k,
                evaluations: evals,
                residual: f64::INFINITY,
                stop: StopReason::SingularJacobian,
                reason: "the actuator cannot move the tip along the block normal (n^T J = 0)"
                    .into(),
            });
        }
        // wrench increment on the tip: -df n (force only)
        let step = if k < increments { df } else { 0.0 };
        let nc_dw: f64 = (0..3)
            .map(|i| {
                (0..3)
                    .map(|j| n[i] * sens.compliance[(i, j)] * (-n[j] * step))
                    .sum::<f64>()
            })
            .sum();
        let gap = n.dot(&(block.point - sol.tip_position()));
        let dz = (-nc_dw + gap) / nj;
        z += dz;
        f += step;
        // Near a bound (e.g. the blocked force at 160 C, fed back), a step may
        // overshoot the bound by its linearisation error, a small fraction of
        // the step: clamp it and let the next position correction decide.
        // Beyond that (more than a tenth of the step plus rounding, 1e-9 of
        // the range), or twice in a row in the corrections at the final
        // force, the force needs an input outside the range.
        let slack = 1e-9 * (hi - lo).clamp(1.0, 1e3);
        let over = (lo - z).max(z - hi).max(0.0);
        let outside = over > slack;
        if over > 0.1 * dz.abs() + slack || (outside && step == 0.0 && pushed_out) {
            return Err(Error::NoSolution {
                reason: format!("the blocked force {force:.6e} N needs an input outside [{lo}, {hi}] (reached {z:.3} at force {f:.6e} N)"),
            });
        }
        pushed_out = outside && step == 0.0;
        z = z.clamp(lo, hi);
        let l = block.loads(robot, f);
        sol = solve_loaded(robot, &groups.inputs(&[z]), &l, opts, Some(&sol))?;
        evals += sol.evaluations;
        let gap = n.dot(&(block.point - sol.tip_position()));
        if k + 1 >= increments && gap.abs() < 1e-9 * robot.body.length {
            return Ok(BlockedResult {
                solution: sol,
                force: f,
                variables: vec![z],
                evaluations: evals,
                iterations: k + 1,
            });
        }
    }
    Err(Error::NotConverged {
        solver: "blocked-tip increments",
        iterations: increments + 3,
        evaluations: evals,
        stop: StopReason::IterationLimit,
        residual: n.dot(&(block.point - sol.tip_position())).abs() / robot.body.length,
        reason: "tip did not settle on the block".into(),
    })
}

/// Grasp temperature (eq 44): the actuation variable at which `fingers`
/// identical fingers with friction coefficient `mu` hold a mass `mass` \[kg\],
/// `mu n F(T) = m g`, each finger's tip blocked at its reference position
/// and pressing along `normal`. Returns the blocked result for one finger.
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
    crate::error::positive("mass [kg]", mass)?;
    crate::error::positive("mu [-]", mu)?;
    crate::error::positive("gravity [m/s^2]", gravity)?;
    if fingers == 0 {
        return Err(Error::param("fingers", 0.0, ">= 1"));
    }
    let reference = robot.reference_inputs();
    let start = solve_loaded(robot, &reference, &Loads::of(robot), opts, None)?;
    let block = Block::new(start.tip_position(), *normal)?;
    let force = mass * gravity / (mu * fingers as f64);
    blocked_temperature(robot, groups, &block, &start, force, increments, opts)
}
