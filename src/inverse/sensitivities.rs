//! `J` and `C` (eqs 39-42): the paper's finite differences and the exact
//! tangents.

use nalgebra::{DMatrix, DVector, Matrix3, Quaternion, Vector3};

use super::{load_scales, pose_delta, Groups, Scheme, Sensitivities};
use crate::error::{Error, Result, StopReason};
use crate::rod::{integrate_tangent, Robot, TangentSeeds};
use crate::shooting::{base_strains, Loads, Shot, Solution};

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
    by_scheme(
        At::of(robot, sol, loads, groups, steps),
        scheme,
        Wrench::Differenced,
    )
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
    by_scheme(
        At::of(robot, sol, loads, groups, steps),
        scheme,
        Wrench::Exact,
    )
}

/// How the tip-wrench columns `E_W`, `B_W` of the differenced blocks are found.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Wrench {
    /// By differences of IVPs, the paper's way.
    Differenced,
    /// In closed form (see [`sensitivities_fast`]).
    Exact,
}

/// The forward problem at a converged solution, around which the blocks of
/// eq (40) are taken.
#[derive(Clone, Copy)]
struct At<'a> {
    robot: &'a Robot,
    sol: &'a Solution,
    loads: &'a Loads,
    groups: &'a Groups,
    steps: usize,
}

impl<'a> At<'a> {
    fn of(
        robot: &'a Robot,
        sol: &'a Solution,
        loads: &'a Loads,
        groups: &'a Groups,
        steps: usize,
    ) -> Self {
        At {
            robot,
            sol,
            loads,
            groups,
            steps,
        }
    }
}

/// The exact tangents for [`Scheme::Exact`], else differences with the
/// scheme's step.
fn by_scheme(at: At<'_>, scheme: Scheme, wrench: Wrench) -> Result<Sensitivities> {
    match scheme.relative_step() {
        None => sensitivities_exact(at.robot, at.sol, at.loads, at.groups, at.steps),
        Some(rel) => differenced(at, scheme == Scheme::Central, rel, wrench),
    }
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
        if let Some(k) = groups.variable_of(i) {
            chain[(i, nx + k)] = dt_dq; // a fixed input has no column
        }
    }
    let spec = loads.ivp(robot, &tau, steps);
    let (v0, u0) = base_strains(x, len);
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
    differenced(
        At::of(robot, sol, loads, groups, steps),
        scheme == Scheme::Central,
        rel,
        Wrench::Differenced,
    )
}

/// `J` and `C` from the blocks of eq (40) by finite differences (central or
/// forward) with relative step `rel`, columns `[u | q | W]` (eqs 41-42).
fn differenced(at: At<'_>, central: bool, rel: f64, wrench: Wrench) -> Result<Sensitivities> {
    at.groups.validate(at.robot)?;
    let (nx, nz) = (at.sol.unknowns.len(), at.groups.n_vars());
    let mut fd = Differences::new(at, central)?;
    fd.unknown_columns(rel)?;
    fd.variable_columns(rel)?;
    if wrench == Wrench::Exact {
        // tip wrench W = [F; M]: exact, no IVP. For fixed unknowns the wrench
        // moves no state (E_W = 0) and enters only the tip balance (32)-(33),
        // linearly: d r_F / dF = -(L^2/EI) R^T, d r_M / dM = -(L/EI) R^T
        // in the scaled residual of `Shot::residual`.
        let (fs, ms) = crate::shooting::residual_scales(at.robot);
        tip_wrench_columns(&mut fd.bm, &fd.r0, fs, ms, nx + nz);
    } else {
        fd.wrench_columns(nx + nz, rel)?;
    }
    eliminate_unknowns(&fd.e, &fd.bm, nx, nz, fd.evaluations)
}

/// Tip pose change `[dp; dtheta]` and scaled residual of one perturbed IVP.
type Column = ([f64; 6], Vec<f64>);

/// Finite differences of the tip pose (`E`) and of the scaled shooting
/// residual (`B`) around a converged solution, one column per perturbed
/// unknown, actuation variable or wrench component (eq 40).
struct Differences<'a> {
    at: At<'a>,
    /// Central differences (else forward).
    central: bool,
    /// Residual, tip position and tip rotation at the solution.
    b0: Vec<f64>,
    p0: Vector3<f64>,
    r0: Matrix3<f64>,
    e: DMatrix<f64>,
    bm: DMatrix<f64>,
    /// IVPs integrated.
    evaluations: usize,
}

impl<'a> Differences<'a> {
    fn new(at: At<'a>, central: bool) -> Result<Self> {
        let (sol, nx) = (at.sol, at.sol.unknowns.len());
        let ncol = nx + at.groups.n_vars() + 6;
        let (b0, ivp0, _) =
            Shot::new(at.robot, &sol.inputs, at.loads, at.steps).residual(&sol.unknowns, false)?;
        Ok(Differences {
            at,
            central,
            b0,
            p0: ivp0.tip.p,
            r0: ivp0.tip.rotation(),
            e: DMatrix::zeros(6, ncol),
            bm: DMatrix::zeros(nx, ncol),
            evaluations: 1,
        })
    }

    /// Pose change and residual at unknowns `x`, inputs and loads `l`.
    fn column(&mut self, x: &[f64], inputs: &[f64], l: &Loads) -> Result<Column> {
        let (b, ivp, _) = Shot::new(self.at.robot, inputs, l, self.at.steps).residual(x, false)?;
        self.evaluations += 1;
        Ok((
            pose_delta(&self.p0, &self.r0, &ivp.tip.p, &ivp.tip.rotation()),
            b,
        ))
    }

    /// Column `col` of `E` and `B` from the IVP at `+h` and, central, at `-h`.
    fn put(&mut self, col: usize, plus: Column, minus: Option<Column>, h: f64) {
        // the other end: the IVP at -h (central) or the solution (forward),
        // where the pose change is zero
        let (width, pose, residual) = match &minus {
            Some(m) => (2.0 * h, m.0, &m.1),
            None => (h, [0.0; 6], &self.b0),
        };
        for (i, (p, m)) in plus.0.iter().zip(pose).enumerate() {
            self.e[(i, col)] = (p - m) / width;
        }
        for (i, (p, m)) in plus.1.iter().zip(residual).enumerate() {
            self.bm[(i, col)] = (p - m) / width;
        }
    }

    /// Columns of the shooting unknowns `u`.
    fn unknown_columns(&mut self, rel: f64) -> Result<()> {
        let (sol, loads) = (self.at.sol, self.at.loads);
        for j in 0..sol.unknowns.len() {
            // Typical sizes: strains ~1; actuator elongations / L ~1e-2. The
            // elongation columns are the most nonlinear (a TCA is far stiffer
            // than the body, so micrometres of elongation move the tip a lot), so
            // they get a step scaled to their size rather than to 1.
            let typical = if j < 6 { 1.0 } else { 1e-2 };
            let h = rel * sol.unknowns[j].abs().max(typical);
            let mut xp = sol.unknowns.clone();
            xp[j] += h;
            let plus = self.column(&xp, &sol.inputs, loads)?;
            let minus = if self.central {
                xp[j] = sol.unknowns[j] - h;
                Some(self.column(&xp, &sol.inputs, loads)?)
            } else {
                None
            };
            self.put(j, plus, minus, h);
        }
        Ok(())
    }

    /// Columns of the actuation variables `q` (one-sided away from a bound).
    fn variable_columns(&mut self, rel: f64) -> Result<()> {
        let (sol, loads, groups) = (self.at.sol, self.at.loads, self.at.groups);
        let nx = sol.unknowns.len();
        let z0 = groups.vars(&sol.inputs);
        let bounds = groups.bounds(self.at.robot);
        for k in 0..z0.len() {
            let h0 = rel * z0[k].abs().max(1.0);
            let (lo, hi) = bounds[k];
            let mut zp = z0.clone();
            let (h, minus) = if self.central && z0[k] - h0 >= lo && z0[k] + h0 <= hi {
                zp[k] = z0[k] - h0;
                (
                    h0,
                    Some(self.column(&sol.unknowns, &groups.inputs(&zp), loads)?),
                )
            } else {
                (if z0[k] + h0 <= hi { h0 } else { -h0 }, None)
            };
            zp[k] = z0[k] + h;
            let plus = self.column(&sol.unknowns, &groups.inputs(&zp), loads)?;
            self.put(nx + k, plus, minus, h);
        }
        Ok(())
    }

    /// Columns `col0..col0 + 6` of the tip wrench `W = [F; M]` by differences,
    /// the paper's way.
    fn wrench_columns(&mut self, col0: usize, rel: f64) -> Result<()> {
        let (sol, loads) = (self.at.sol, self.at.loads);
        let (fc, mc) = load_scales(self.at.robot);
        for k in 0..6 {
            let (scale, w0) = if k < 3 {
                (fc, loads.tip_force[k])
            } else {
                (mc, loads.tip_moment[k - 3])
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
            let plus = self.column(&sol.unknowns, &sol.inputs, &perturbed(h))?;
            let minus = if self.central {
                Some(self.column(&sol.unknowns, &sol.inputs, &perturbed(-h))?)
            } else {
                None
            };
            self.put(col0 + k, plus, minus, h);
        }
        Ok(())
    }
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
