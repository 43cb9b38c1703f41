//! The mixed (blocked-tip) boundary-value problem as one augmented Newton
//! system: the `6 + N` shooting unknowns plus one extra unknown (the
//! contact force, or the single actuation variable), the scaled shooting
//! residual (eqs 32-33 and the elongations) plus the blocked-tip condition
//! `n . (p(L) - point) / L = 0`, with the exact Jacobian from one tangent
//! IVP ([`crate::rod::integrate_tangent`]).
//!
//! The tangent IVP is seeded on the six base strains and on a unit tension
//! of each actuator (the elongation unknowns, the actuation variable and
//! nothing else move the state only through the tensions, and the tangent
//! IVP is linear in its seeds), so the augmented Jacobian costs what the
//! forward solve's does. A tip force moves no state at fixed unknowns: its
//! column is in closed form (`d r_F / dF = -R(L)^T` scaled, as in
//! [`super::sensitivities_exact`]).
//!
//! As in the forward solve ([`crate::solve::system::Shooting`]), the
//! Jacobian is first taken on a coarse grid (a tenth of the steps, at least
//! [`COARSE_JACOBIAN_MIN_STEPS`]) and refined to the full grid when Newton
//! contracts slowly or its line search fails; the residual is always that of
//! the full grid, so the root is the full grid's.

use nalgebra::{DMatrix, DVector, Vector3};

use super::{load_scales, Block, Groups};
use crate::error::Result;
use crate::rod::{integrate_tangent, FlatNodes, IvpResult, Robot, TangentSeeds};
use crate::shooting::{base_strains, residual_scales, Loads, Shot, System};

/// Fewest RK4 steps of the coarse-grid Newton Jacobian (below ten times
/// this, the Jacobian is taken on the full grid): the coarse grid's
/// tangents are a chord Jacobian, whose error (RK4's on ten times the
/// step) the chord iteration contracts away.
pub const COARSE_JACOBIAN_MIN_STEPS: usize = 10;

/// RK4 steps of the coarse-grid Jacobian for `steps` (a tenth, at least
/// [`COARSE_JACOBIAN_MIN_STEPS`]); `None`: too few steps, use the full grid.
pub(crate) fn coarse_steps(steps: usize) -> Option<usize> {
    let coarse = steps / 10;
    (coarse >= COARSE_JACOBIAN_MIN_STEPS).then_some(coarse)
}

/// The extra unknown of a mixed solve.
#[derive(Debug, Clone)]
pub(crate) enum Extra {
    /// The contact force \[N\] (scaled by `E I / L^2`) at fixed actuator `inputs`.
    Force { inputs: Vec<f64> },
    /// The single actuation variable (scaled by `scale`) at a fixed contact `force` \[N\].
    Variable { force: f64, scale: f64 },
}

/// The augmented system (see the module docs). Unknowns: the scaled
/// shooting unknowns, then the scaled extra unknown.
pub(crate) struct Mixed<'a> {
    robot: &'a Robot,
    groups: &'a Groups,
    block: &'a Block,
    extra: Extra,
    steps: usize,
    /// RK4 steps of the Jacobian until refined to the full grid (`None`).
    jacobian_steps: Option<usize>,
    /// IVPs integrated (plain and tangent, failed ones too).
    pub(crate) evaluations: usize,
    /// Tensions \[N\] of the last plain IVP (for the rounding floor).
    tau: Vec<f64>,
    /// Record the nodes of a plain IVP when the last residual's `max |r|`
    /// is at most this (0: never): from there Newton is expected to end
    /// within a step or two, and the recorded IVP at the root then serves
    /// as the solution's profile ([`Mixed::take_last`]) instead of one more
    /// IVP. A wrong guess costs the recording (~7 % of an IVP) or that IVP.
    pub(crate) record_below: f64,
    /// `max |r|` of the last plain IVP.
    last_norm: f64,
    /// The unknowns and [`Recorded`] evaluation of the last recorded IVP.
    last: Option<(Vec<f64>, Recorded)>,
    /// A residual already integrated at these unknowns ([`Mixed::prime`]).
    primed: Option<(Vec<f64>, Vec<f64>)>,
}

/// Shooting residual (without the gap), the IVP with its nodes (flat) and
/// tensions \[N\] of one recorded evaluation.
pub(crate) type Recorded = (Vec<f64>, (IvpResult, FlatNodes), Vec<f64>);

impl<'a> Mixed<'a> {
    /// The system of `robot` held by `block`, on `steps` RK4 steps.
    pub(crate) fn new(
        robot: &'a Robot,
        groups: &'a Groups,
        block: &'a Block,
        extra: Extra,
        steps: usize,
    ) -> Self {
        Mixed {
            robot,
            groups,
            block,
            extra,
            steps,
            jacobian_steps: coarse_steps(steps),
            evaluations: 0,
            tau: vec![0.0; robot.actuators.len()],
            record_below: 0.0,
            last_norm: f64::INFINITY,
            last: None,
            primed: None,
        }
    }

    /// Answer the next [`System::residual`] at `x` with `r`, the residual
    /// of the last IVP (the coarse pre-solve's full-grid check).
    pub(crate) fn prime(&mut self, x: &[f64], r: Vec<f64>) {
        self.primed = Some((x.to_vec(), r));
    }

    /// The last recorded IVP if it was at the augmented unknowns `x`:
    /// `(shooting residual, (ivp, its nodes), tensions)`.
    pub(crate) fn take_last(&mut self, x: &[f64]) -> Option<Recorded> {
        match self.last.take() {
            Some((xl, rec)) if xl == x => Some(rec),
            _ => None,
        }
    }

    pub(crate) fn robot(&self) -> &'a Robot {
        self.robot
    }
    pub(crate) fn groups(&self) -> &'a Groups {
        self.groups
    }
    pub(crate) fn block(&self) -> &'a Block {
        self.block
    }

    /// Scale of the extra unknown: `E I / L^2` \[N\] for the force, the
    /// variable's own scale otherwise.
    fn scale(&self) -> f64 {
        match &self.extra {
            Extra::Force { .. } => load_scales(self.robot).0,
            Extra::Variable { scale, .. } => *scale,
        }
    }

    /// Actuator inputs, tip loads and contact force \[N\] at the augmented
    /// unknowns `x` (an input out of range is an error: the line search
    /// treats it as an infinite merit).
    pub(crate) fn problem(&self, x: &[f64]) -> Result<(Vec<f64>, Loads, f64)> {
        let e = x[6 + self.robot.actuators.len()] * self.scale();
        let (inputs, force) = match &self.extra {
            Extra::Force { inputs } => (inputs.clone(), e),
            Extra::Variable { force, .. } => {
                let inputs = self.groups.inputs(&[e]);
                self.robot.check_inputs(&inputs)?;
                (inputs, *force)
            }
        };
        Ok((inputs, self.block.loads(self.robot, force), force))
    }

    /// The blocked-tip residual `n . (p(L) - point) / L`.
    fn gap(&self, tip: &Vector3<f64>) -> f64 {
        self.block.normal.dot(&(tip - self.block.point)) / self.robot.body.length
    }
}

impl System for Mixed<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        if let Some((_, r)) = self.primed.take().filter(|(xp, _)| xp == x) {
            return Ok(r);
        }
        self.evaluations += 1;
        let nx = 6 + self.robot.actuators.len();
        let (inputs, loads, _) = self.problem(x)?;
        let record = self.last_norm <= self.record_below;
        let shot = Shot::new(self.robot, &inputs, &loads, self.steps);
        let (mut r, ivp, tau, nodes) = match record {
            true => shot.residual_flat(&x[..nx])?,
            false => {
                let (r, ivp, tau) = shot.residual(&x[..nx], false)?;
                (r, ivp, tau, FlatNodes::default())
            }
        };
        let gap = self.gap(&ivp.tip.p);
        // kept only if recorded: the shooting residual without the gap
        self.last = record.then(|| (x.to_vec(), (r.clone(), (ivp, nodes), tau.clone())));
        r.push(gap);
        self.last_norm = r.iter().fold(0.0, |m, v| m.max(v.abs()));
        self.tau = tau;
        Ok(r)
    }

    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.evaluations += 1;
        let steps = self.jacobian_steps.unwrap_or(self.steps);
        let t = augmented(self, x, steps)?;
        Ok((t.residual, t.jacobian))
    }

    fn refine(&mut self, _x: &[f64]) -> bool {
        self.jacobian_steps.take().is_some()
    }

    /// The forward solve's floor ([`crate::solve::system::Shooting`]): the
    /// rounding of the largest terms of the tip balance in the scaled
    /// residual, `4 eps max(fs (k_nu |nu| + |F| + sum |tau|), ms (k_omega |omega| L + |M| + sum |r_i| |tau_i|))`.
    fn floor(&self, x: &[f64], _r: &[f64]) -> f64 {
        let robot = self.robot;
        let (kse, kbt) = robot.body.stiffness();
        let (fs, ms) = residual_scales(robot);
        let len = robot.body.length;
        let Ok((_, loads, _)) = self.problem(x) else {
            return 0.0;
        };
        let vmax = x[..3].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let umax = x[3..6].iter().fold(0.0_f64, |m, v| m.max(v.abs())) / len;
        let st: f64 = self.tau.iter().map(|t| t.abs()).sum();
        let srt: f64 = robot
            .actuators
            .iter()
            .zip(&self.tau)
            .map(|(a, t)| a.routing.eval(len).0.norm() * t.abs())
            .sum();
        let f = fs * (kse.max() * vmax + loads.tip_force.amax() + st);
        let m = ms * (kbt.max() * umax * len + loads.tip_moment.amax() + srt);
        4.0 * f64::EPSILON * f.max(m)
    }

    fn evaluations(&self) -> usize {
        self.evaluations
    }
}

/// One augmented evaluation with its tangents.
struct Augmented {
    /// The augmented residual.
    residual: Vec<f64>,
    /// Its exact Jacobian, `(7 + N) x (7 + N)`.
    jacobian: DMatrix<f64>,
    /// Its derivative along a unit tension \[N\] of each actuator at fixed
    /// unknowns, `(7 + N) x N`.
    per_tension: DMatrix<f64>,
}

/// The augmented residual and its exact Jacobian from one tangent IVP on
/// `steps` RK4 steps (see the module docs).
fn augmented(sys: &Mixed<'_>, x: &[f64], steps: usize) -> Result<Augmented> {
    let robot = sys.robot;
    let len = robot.body.length;
    let na = robot.actuators.len();
    let nx = 6 + na;
    let (inputs, loads, _) = sys.problem(x)?;
    let mut seeds = TangentSeeds::zeros(na, nx);
    for k in 0..3 {
        seeds.nu0[(k, k)] = 1.0;
        seeds.omega0[(k, 3 + k)] = 1.0 / len;
    }
    let mut tau = Vec::with_capacity(na);
    for (i, a) in robot.actuators.iter().enumerate() {
        tau.push(a.law.tension(x[6 + i] * len, inputs[i])?);
        seeds.tensions[(i, 6 + i)] = 1.0;
    }
    let spec = loads.ivp(robot, &tau, steps);
    let (v0, u0) = base_strains(x, len);
    let tan = integrate_tangent(&spec, &v0, &u0, &seeds, false)?;
    let (fs, ms) = residual_scales(robot);
    let ivp = &tan.ivp;
    // rows of the raw tangents: tip force, tip moment, elongations, gap;
    // columns: strains, unit tensions
    let mut raw = DMatrix::<f64>::zeros(nx + 1, nx);
    raw.rows_mut(0, 3)
        .copy_from(&(&tan.tip_force_residual * fs));
    raw.rows_mut(3, 3)
        .copy_from(&(&tan.tip_moment_residual * ms));
    raw.rows_mut(6, na).copy_from(&(&tan.elongation / len));
    let n = sys.block.normal;
    for c in 0..nx {
        raw[(nx, c)] = (0..3).map(|k| n[k] * tan.tip[(k, c)]).sum::<f64>() / len;
    }
    let mut jac = DMatrix::<f64>::zeros(nx + 1, nx + 1);
    jac.columns_mut(0, 6).copy_from(&raw.columns(0, 6));
    let per_tension = raw.columns(6, na).into_owned();
    actuator_columns(sys, x, &per_tension, &mut jac)?;
    if let Extra::Force { .. } = &sys.extra {
        // loads: tip force -f n; d r_F / d F = -(L^2/EI) R^T
        let rn = ivp.tip.rotation().transpose() * n * (fs * sys.scale());
        for k in 0..3 {
            jac[(k, nx)] = rn[k];
        }
    }
    Ok(Augmented {
        residual: scaled_residual(sys, ivp, x),
        jacobian: jac,
        per_tension,
    })
}

/// The actuator columns of the augmented Jacobian at `x` (and the
/// variable's, for [`Extra::Variable`]) from the columns of a unit tension
/// `per_tension`: the force laws' slopes at `x` times them,
/// `d tau_i / d (scaled elongation)` and `d tau_i / d (scaled variable)`.
fn actuator_columns(
    sys: &Mixed<'_>,
    x: &[f64],
    per_tension: &DMatrix<f64>,
    jac: &mut DMatrix<f64>,
) -> Result<()> {
    let (robot, len) = (sys.robot, sys.robot.body.length);
    let nx = 6 + robot.actuators.len();
    let (inputs, _, _) = sys.problem(x)?;
    let scale = sys.scale();
    let variable = matches!(sys.extra, Extra::Variable { .. });
    if variable {
        jac.column_mut(nx).fill(0.0);
    }
    for (i, a) in robot.actuators.iter().enumerate() {
        let (_, dt_de, dt_dq) = a.law.tension_derivatives(x[6 + i] * len, inputs[i])?;
        jac.column_mut(6 + i)
            .axpy(dt_de * len, &per_tension.column(i), 0.0);
        jac[(6 + i, 6 + i)] -= 1.0;
        // the variable moves only the actuators it drives (fixed inputs stay)
        if variable && sys.groups.variable_of(i).is_some() {
            jac.column_mut(nx)
                .axpy(dt_dq * scale, &per_tension.column(i), 1.0);
        }
    }
    Ok(())
}

/// The augmented residual at `x` from its IVP: the scaled tip force and
/// moment residuals, the elongation mismatches `/ L` and the tip gap.
fn scaled_residual(sys: &Mixed<'_>, ivp: &IvpResult, x: &[f64]) -> Vec<f64> {
    let (robot, len) = (sys.robot, sys.robot.body.length);
    let (fs, ms) = residual_scales(robot);
    let mut r = Vec::with_capacity(x.len());
    r.extend((ivp.tip_force_residual * fs).iter());
    r.extend((ivp.tip_moment_residual * ms).iter());
    for (i, e) in ivp.elongation.iter().enumerate() {
        r.push((e - x[6 + i] * len) / len);
    }
    r.push(sys.gap(&ivp.tip.p));
    r
}

/// The start of a direct solve for the actuation variable (`sys` with
/// [`Extra::Variable`]) from `start`, an equilibrium at zero contact force:
/// the augmented unknowns after one predictor step to the full force, and
/// the augmented Jacobian at `start` (one tangent IVP on the Jacobian's
/// grid), for Newton's first iterations.
///
/// The predictor is the eq-43 step with the rod linearised at `start` but
/// the force law kept exact in the variable: a TCA's tension is far from
/// linear in the temperature (on the Table I finger the linear step from
/// ambient overshoots the grasp temperature by 66 %), while the rod, its tip
/// held, moves little. With `y^T = e_z^T J^-1` (the row of `J^-1` of the
/// variable), the residual model `r0 + J du + T dtau(z) = 0` (`T` the
/// columns of a unit tension, `dtau_i(z) = tau_i(delta_i, z) - tau_i` at the
/// start's elongations, `r0` the start's residual under the full force) has a
/// solution `du` with no change of the variable column iff
/// `g(z) = y^T (r0 + T dtau(z)) = 0`, a scalar equation solved on the law
/// alone (no IVP); then `du` solves `J du = -(r0 + T dtau(z))`.
pub(crate) fn predictor(
    sys: &mut Mixed<'_>,
    start: &crate::shooting::Solution,
    z0: f64,
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let robot = sys.robot;
    let nx = start.unknowns.len();
    let scale = sys.scale();
    let mut x = start.unknowns.clone();
    x.push(z0 / scale);
    let steps = sys.jacobian_steps.unwrap_or(sys.steps);
    sys.evaluations += 1;
    let t = augmented(sys, &x, steps)?;
    // the start's full-grid residual is zero but for the contact force and the gap
    let (_, loads, _) = sys.problem(&x)?;
    let (fs, _) = residual_scales(robot);
    let rf = start.tip_rotation().transpose() * (robot.body.tip_force - loads.tip_force) * fs;
    let mut r0 = DVector::<f64>::zeros(nx + 1);
    r0.rows_mut(0, 3).copy_from(&rf);
    r0[nx] = sys.gap(&start.tip_position());
    let lu = t.jacobian.clone().lu();
    let mut ez = DVector::<f64>::zeros(nx + 1);
    ez[nx] = 1.0;
    let Some(y) = t.jacobian.transpose().lu().solve(&ez) else {
        return Ok((x, t.jacobian));
    };
    let weights = t.per_tension.tr_mul(&y); // y^T T
                                            // g(z) from the law alone; NaN where an input is refused
    let g = |z: f64| -> f64 {
        let inputs = sys.groups.inputs(&[z]);
        let dtau = robot.actuators.iter().enumerate().map(|(i, a)| {
            a.law
                .tension(start.elongations[i], inputs[i])
                .map(|t| t - start.tensions[i])
        });
        dtau.zip(weights.iter())
            .try_fold(y.dot(&r0), |acc, (d, w)| d.map(|d| acc + w * d))
            .unwrap_or(f64::NAN)
    };
    let (lo, hi) = sys.groups.bounds(robot)[0];
    // a force out of reach keeps the start's variable: Newton reports it
    let Some(z) = crate::roots::brent(g, lo, hi, 1e-12 * (hi - lo).max(1.0)) else {
        return Ok((x, t.jacobian));
    };
    let inputs = sys.groups.inputs(&[z]);
    let mut c = r0;
    for (i, a) in robot.actuators.iter().enumerate() {
        let dtau = a.law.tension(start.elongations[i], inputs[i])? - start.tensions[i];
        c.axpy(dtau, &t.per_tension.column(i), 1.0);
    }
    let mut jac = t.jacobian;
    if let Some(d) = lu.solve(&-c).filter(|d| d.iter().all(|v| v.is_finite())) {
        for (xi, di) in x.iter_mut().zip(d.iter()).take(nx) {
            *xi += di;
        }
        x[nx] = z / scale;
        // the force laws' slopes at the predicted point (a TCA's slope in
        // its elongation and temperature changes with the temperature; the
        // rod's columns change little): Newton's first chord step from `x`
        // then contracts (on the Table I grasp the start's slopes instead
        // make that step grow the residual, 2.7e-2 to 3.6e-2, so that a
        // fresh Jacobian is needed)
        let mut at_x = jac.clone();
        if actuator_columns(sys, &x, &t.per_tension, &mut at_x).is_ok() {
            jac = at_x;
        }
    }
    Ok((x, jac))
}

#[cfg(test)]
#[path = "mixed_tests.rs"]
mod tests;
