//! The predictor of a direct solve for the actuation variable from a
//! solution whose tip touches the block with no force (the grasp's
//! contact): the eq-43 step of the whole force with the rod linearised at
//! the start but the force law kept exact in the variable ([`predictor`]).
//! A TCA's tension is far from linear in its temperature (on the Table I
//! finger the linear step from ambient overshoots the grasp temperature by
//! 66 %; where its coils touch at ambient, `n^T J` is tiny at the start
//! and grows a hundredfold within a few C), while the rod, its tip held,
//! moves little: the law's nonlinearity is solved on the law alone, with
//! no IVP.
//!
//! The rod's linearisation is the exact single-shooting Jacobian of the
//! base unknowns, the variable and the tip's gap, from one tangent IVP
//! ([`crate::rod::integrate_tangent`]) seeded on the six base strains and
//! on a unit tension of each actuator (the elongations and the variable
//! move the state only through the tensions, and the tangent IVP is
//! linear in its seeds), on a coarse grid ([`coarse_steps`]): the
//! predictor is a first guess, which Newton on the multiple-shooting
//! system then corrects on the requested grid.

use nalgebra::{DMatrix, DVector, Vector3};

use super::{Block, Groups};
use crate::error::Result;
use crate::rod::{integrate_tangent, Robot, TangentSeeds};
use crate::shooting::{base_strains, residual_scales, Loads, Solution};

/// Fewest RK4 steps of the predictor's coarse grid (below ten times this,
/// it is the requested grid): RK4's error on ten times the step is far
/// below the predictor's own (the rod linearised at the start).
pub const COARSE_JACOBIAN_MIN_STEPS: usize = 10;

/// RK4 steps of the predictor's grid for `steps` (a tenth, at least
/// [`COARSE_JACOBIAN_MIN_STEPS`], else `steps`).
pub(crate) fn coarse_steps(steps: usize) -> usize {
    let coarse = steps / 10;
    if coarse >= COARSE_JACOBIAN_MIN_STEPS {
        coarse
    } else {
        steps
    }
}

/// The single-variable problem the predictor linearises: the robot held
/// by `block`, pressing with `force` \[N\], its variable scaled by `scale`.
pub(crate) struct Linearised<'a> {
    pub(crate) robot: &'a Robot,
    pub(crate) groups: &'a Groups,
    pub(crate) block: &'a Block,
    pub(crate) force: f64,
    pub(crate) scale: f64,
}

impl Linearised<'_> {
    fn scale(&self) -> f64 {
        self.scale
    }
    /// Inputs and tip loads at the augmented unknowns `x` (the base
    /// unknowns, then the scaled variable).
    fn problem(&self, x: &[f64]) -> Result<(Vec<f64>, Loads, f64)> {
        let e = x[6 + self.robot.actuators.len()] * self.scale;
        let inputs = self.groups.inputs(&[e]);
        self.robot.check_inputs(&inputs)?;
        Ok((inputs, self.block.loads(self.robot, self.force), self.force))
    }
    /// The blocked-tip residual `n . (p(L) - point) / L`.
    fn gap(&self, tip: &Vector3<f64>) -> f64 {
        self.block.normal.dot(&(tip - self.block.point)) / self.robot.body.length
    }
}

/// One augmented evaluation with its tangents.
struct Augmented {
    /// Its exact Jacobian, `(7 + N) x (7 + N)`.
    jacobian: DMatrix<f64>,
    /// Its derivative along a unit tension \[N\] of each actuator at fixed
    /// unknowns, `(7 + N) x N`.
    per_tension: DMatrix<f64>,
}

/// The augmented residual and its exact Jacobian from one tangent IVP on
/// `steps` RK4 steps (see the module docs).
fn augmented(sys: &Linearised<'_>, x: &[f64], steps: usize) -> Result<Augmented> {
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
    Ok(Augmented {
        jacobian: jac,
        per_tension,
    })
}

/// The actuator columns of the augmented Jacobian at `x` (and the
/// variable's) from the columns of a unit tension
/// `per_tension`: the force laws' slopes at `x` times them,
/// `d tau_i / d (scaled elongation)` and `d tau_i / d (scaled variable)`.
fn actuator_columns(
    sys: &Linearised<'_>,
    x: &[f64],
    per_tension: &DMatrix<f64>,
    jac: &mut DMatrix<f64>,
) -> Result<()> {
    let (robot, len) = (sys.robot, sys.robot.body.length);
    let nx = 6 + robot.actuators.len();
    let (inputs, _, _) = sys.problem(x)?;
    let scale = sys.scale();
    let variable = true;
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

/// The start of a direct solve for the actuation variable from `start`, an
/// equilibrium at zero contact force: the base unknowns and the scaled
/// variable after one predictor step to the full force (one tangent IVP on
/// `steps` RK4 steps; `start`'s own if a step cannot be taken).
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
    sys: &Linearised<'_>,
    start: &Solution,
    steps: usize,
    z0: f64,
) -> Result<Vec<f64>> {
    let robot = sys.robot;
    let nx = start.unknowns.len();
    let scale = sys.scale();
    let mut x = start.unknowns.clone();
    x.push(z0 / scale);
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
        return Ok(x);
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
        return Ok(x);
    };
    let inputs = sys.groups.inputs(&[z]);
    let mut c = r0;
    for (i, a) in robot.actuators.iter().enumerate() {
        let dtau = a.law.tension(start.elongations[i], inputs[i])? - start.tensions[i];
        c.axpy(dtau, &t.per_tension.column(i), 1.0);
    }
    if let Some(d) = lu.solve(&-c).filter(|d| d.iter().all(|v| v.is_finite())) {
        for (xi, di) in x.iter_mut().zip(d.iter()).take(nx) {
            *xi += di;
        }
        x[nx] = z / scale;
    }
    Ok(x)
}
