//! The shooting residual (eqs 32-33, scaled) of one forward problem and its
//! exact Jacobian from the tangents of the discrete RK4 map; the tension
//! slopes of the force laws, with their onsets of tension.

use nalgebra::{DMatrix, Vector3};

use crate::error::Result;
use crate::rod::{
    integrate, integrate_tangent, IvpResult, IvpSpec, Robot, TangentIvp, TangentSeeds,
};

/// Residual, its exact Jacobian, the tangent IVP and the tensions of one evaluation.
type ResidualAndJacobian = (Vec<f64>, DMatrix<f64>, TangentIvp, Vec<f64>);

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

    /// The IVP of `robot` under these tip loads, with the actuator
    /// `tensions` \[N\], on `steps` RK4 steps.
    pub fn ivp<'a>(&self, robot: &'a Robot, tensions: &'a [f64], steps: usize) -> IvpSpec<'a> {
        IvpSpec {
            robot,
            tensions,
            tip_force: self.tip_force,
            tip_moment: self.tip_moment,
            steps,
        }
    }
}

/// The base strains of the scaled unknowns `x`: `nu(0) = x[0..3]` \[-\] and
/// `omega(0) = x[3..6] / L` \[1/m\] (`len` = L \[m\]).
pub fn base_strains(x: &[f64], len: f64) -> (Vector3<f64>, Vector3<f64>) {
    let v0 = Vector3::new(x[0], x[1], x[2]);
    (v0, Vector3::new(x[3], x[4], x[5]) / len)
}

/// The shooting problem of one forward problem at fixed inputs: `robot` at
/// actuator `inputs` under tip `loads`, integrated on `steps` RK4 steps.
/// Its scaled unknowns `x` are the base strains and the scaled guessed
/// elongations (see [`base_strains`]).
#[derive(Debug, Clone, Copy)]
pub struct Shot<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Actuator inputs, one per actuator (units of each force law).
    pub inputs: &'a [f64],
    /// Tip loads.
    pub loads: &'a Loads,
    /// RK4 steps of the IVP.
    pub steps: usize,
}

impl<'a> Shot<'a> {
    /// The shooting problem of `robot` at `inputs` under `loads` on `steps` RK4 steps.
    pub fn new(robot: &'a Robot, inputs: &'a [f64], loads: &'a Loads, steps: usize) -> Self {
        Shot {
            robot,
            inputs,
            loads,
            steps,
        }
    }

    /// This problem on `steps` RK4 steps.
    pub fn with_steps(self, steps: usize) -> Self {
        Shot { steps, ..self }
    }

    /// One IVP from scaled unknowns `x`: the scaled residual, the IVP (with
    /// its nodes if `record`) and the tensions \[N\].
    pub fn residual(&self, x: &[f64], record: bool) -> Result<(Vec<f64>, IvpResult, Vec<f64>)> {
        self.residual_by(x, |spec, v0, u0| integrate(spec, v0, u0, record))
    }

    /// The residual at `x` of the IVP `ivp(spec, v0, u0)`.
    fn residual_by(
        &self,
        x: &[f64],
        ivp: impl FnOnce(&IvpSpec<'_>, &Vector3<f64>, &Vector3<f64>) -> Result<IvpResult>,
    ) -> Result<(Vec<f64>, IvpResult, Vec<f64>)> {
        let len = self.robot.body.length;
        let na = self.robot.actuators.len();
        let (v0, u0) = base_strains(x, len);
        let delta: Vec<f64> = x[6..6 + na].iter().map(|d| d * len).collect();
        let tau = tensions(self.robot, self.inputs, &delta)?;
        let spec = self.loads.ivp(self.robot, &tau, self.steps);
        let ivp = ivp(&spec, &v0, &u0)?;
        let r = scaled_residual(self.robot, &ivp, &delta);
        Ok((r, ivp, tau))
    }

    /// One tangent IVP from scaled unknowns `x`: the scaled residual (as
    /// [`Shot::residual`]) and its EXACT Jacobian with respect to `x` (the
    /// derivative of the discrete RK4 map, from the variational equations and
    /// the force laws' derivatives), `(6 + N) x (6 + N)`. With `record`, the
    /// IVP's nodes carry `d y(s) / d x` (see [`crate::rod::TangentNode`]).
    pub fn jacobian(&self, x: &[f64], record: bool) -> Result<ResidualAndJacobian> {
        let len = self.robot.body.length;
        let na = self.robot.actuators.len();
        let nx = 6 + na;
        let (v0, u0) = base_strains(x, len);
        let mut tau = Vec::with_capacity(na);
        let mut seeds = TangentSeeds::zeros(na, nx);
        for k in 0..3 {
            seeds.nu0[(k, k)] = 1.0;
            seeds.omega0[(k, 3 + k)] = 1.0 / len;
        }
        for (i, a) in self.robot.actuators.iter().enumerate() {
            let (t, dt_de, _) =
                tension_slope(a.law.as_ref(), x[6 + i] * len, self.inputs[i], len, false)?;
            tau.push(t);
            seeds.tensions[(i, 6 + i)] = dt_de * len;
        }
        let spec = self.loads.ivp(self.robot, &tau, self.steps);
        let tan = integrate_tangent(&spec, &v0, &u0, &seeds, record)?;
        let (fs, ms) = residual_scales(self.robot);
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
        Ok((r, jac, tan, tau))
    }
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
/// Newton directions (along it the merit grows like `t^2` from `t = 0`:
/// no first-order decrease); the taut side is the one the Newton
/// Jacobian takes.
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
    let ei = b.bending_stiffness();
    (b.length * b.length / ei, b.length / ei)
}

/// The scaled shooting residual of an IVP whose elongations were guessed as
/// `delta` \[m\]: tip force and moment balance (32)-(33) as strain errors,
/// then `(delta_i(s_end) - delta_i) / L` (see [`crate::shooting`]).
pub(crate) fn scaled_residual(robot: &Robot, ivp: &IvpResult, delta: &[f64]) -> Vec<f64> {
    let (na, len) = (robot.actuators.len(), robot.body.length);
    let (fs, ms) = residual_scales(robot);
    let ef = ivp.tip_force_residual * fs;
    let em = ivp.tip_moment_residual * ms;
    let mut r = Vec::with_capacity(6 + na);
    r.extend_from_slice(ef.as_slice());
    r.extend_from_slice(em.as_slice());
    for (e, d) in ivp.elongation.iter().zip(&delta[..na]) {
        r.push((e - d) / len);
    }
    r
}
