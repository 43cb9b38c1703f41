//! `J` and `C` (eqs 39-42): the paper's finite differences and the exact
//! tangents.

use nalgebra::{DMatrix, DVector, Matrix3, Quaternion, Vector3};

use super::{load_scales, pose_delta, Groups, Scheme, Sensitivities};
use crate::error::{Error, Result, StopReason};
use crate::rod::{integrate_tangent, IvpSpec, Robot, TangentSeeds};
use crate::shooting::{shoot, Loads, Solution};

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
    exact_blocks(robot, sol, loads, groups, steps)?.sensitivities()
}

/// The exact derivative blocks of eq (40) at a solution, columns
/// `[u (6 + N) | q (n_vars) | W (6)]`: `e` those of the tip pose (`E`),
/// `bm` those of the scaled shooting residual (`B`).
pub(crate) struct ExactBlocks {
    pub(crate) e: DMatrix<f64>,
    pub(crate) bm: DMatrix<f64>,
    nx: usize,
    nz: usize,
}

impl ExactBlocks {
    /// `J = E_q - E_u B_u^-1 B_q` (41) and `C = -E_u B_u^-1 B_W` (42, `E_W = 0`).
    pub(crate) fn sensitivities(&self) -> Result<Sensitivities> {
        let (nx, nz) = (self.nx, self.nz);
        let lu = self.bm.columns(0, nx).into_owned().lu();
        let sol = lu
            .solve(&self.bm.columns(nx, nz + 6).into_owned())
            .ok_or_else(|| Error::NotConverged {
                solver: "sensitivities",
                iterations: 0,
                evaluations: 1,
                residual: f64::INFINITY,
                stop: StopReason::SingularJacobian,
                reason: "B_u is singular".into(),
            })?;
        let eu = self.e.columns(0, nx);
        let jac = self.e.columns(nx, nz) - eu * sol.columns(0, nz); // (41)
        let comp = -(eu * sol.columns(nz, 6)); // (42), E_W = 0
        Ok(Sensitivities {
            jacobian: jac,
            compliance: comp,
            evaluations: 1,
        })
    }

    /// `B_u`, the exact shooting Jacobian at the solution.
    pub(crate) fn bu(&self) -> DMatrix<f64> {
        self.bm.columns(0, self.nx).into_owned()
    }

    /// First-order change of the unknowns for changes `dz` of the
    /// variables and `dw` of the tip wrench: `-B_u^-1 (B_q dz + B_W dW)`.
    pub(crate) fn predict(&self, dz: &[f64], dw: &[f64; 6]) -> Option<DVector<f64>> {
        let (nx, nz) = (self.nx, self.nz);
        let mut rhs = DVector::zeros(nx);
        for (k, d) in dz.iter().enumerate() {
            rhs += self.bm.column(nx + k) * *d;
        }
        for (k, d) in dw.iter().enumerate() {
            rhs += self.bm.column(nx + nz + k) * *d;
        }
        self.bm.columns(0, nx).into_owned().lu().solve(&(-rhs))
    }
}

/// The blocks of [`sensitivities_exact`], from one tangent IVP seeded on
/// the 6 initial strains and the N tensions.
pub(crate) fn exact_blocks(
    robot: &Robot,
    sol: &Solution,
    loads: &Loads,
    groups: &Groups,
    steps: usize,
) -> Result<ExactBlocks> {
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
    let tan = integrate_tangent(&spec, &v0, &u0, &seeds, false)?;
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
    let (tip, elong) = (expand(&tan.tip), expand(&tan.elongation));
    let (tf, tm) = (
        expand(&tan.tip_force_residual),
        expand(&tan.tip_moment_residual),
    );
    let e = pose_tangents(&tip, tan.ivp.tip.q, ncol);
    let (fs, ms) = crate::shooting::residual_scales(robot);
    let mut bm = DMatrix::<f64>::zeros(nx, ncol + 6);
    for c in 0..ncol {
        for k in 0..3 {
            bm[(k, c)] = tf[(k, c)] * fs;
            bm[(3 + k, c)] = tm[(k, c)] * ms;
        }
        for i in 0..na {
            bm[(6 + i, c)] = elong[(i, c)] / len - if c == 6 + i { 1.0 } else { 0.0 };
        }
    }
    tip_wrench_columns(&mut bm, &tan.ivp.tip.rotation(), fs, ms, ncol);
    Ok(ExactBlocks { e, bm, nx, nz })
}

/// Tip pose tangents `[dp; dtheta]` (6 x (ncol + 6), the wrench columns
/// zero) from the state tangents: `dtheta = 2 vec(dq conj(q))` for a unit `q`.
fn pose_tangents(tip: &DMatrix<f64>, q: Quaternion<f64>, ncol: usize) -> DMatrix<f64> {
    let mut e = DMatrix::<f64>::zeros(6, ncol + 6);
    for c in 0..ncol {
        for k in 0..3 {
            e[(k, c)] = tip[(k, c)];
        }
        let dq = Quaternion::new(tip[(3, c)], tip[(4, c)], tip[(5, c)], tip[(6, c)]);
        let w = dq * q.conjugate() * 2.0;
        e[(3, c)] = w.i;
        e[(4, c)] = w.j;
        e[(5, c)] = w.k;
    }
    e
}

/// The scaled tip-balance residual (eqs 32-33) on a world-frame tip wrench:
/// `-R(L)^T` times the force / moment scales `fs`, `ms`, in columns `ncol..ncol + 6`.
fn tip_wrench_columns(bm: &mut DMatrix<f64>, r0: &Matrix3<f64>, fs: f64, ms: f64, ncol: usize) {
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
        tip_wrench_columns(&mut bm, &r0, fs, ms, nx + nz);
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
    eliminate_unknowns(&e, &bm, nx, nz, evals)
}

/// J and C from the pose blocks `E = [E_u E_q E_W]` and the residual blocks
/// `B = [B_u B_q B_W]`: `J = E_q - E_u B_u^-1 B_q` (eq 41), `C = E_W - E_u B_u^-1 B_W` (eq 42).
fn eliminate_unknowns(
    e: &DMatrix<f64>,
    bm: &DMatrix<f64>,
    nx: usize,
    nz: usize,
    evaluations: usize,
) -> Result<Sensitivities> {
    let lu = bm.columns(0, nx).into_owned().lu();
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
        evaluations,
    })
}
