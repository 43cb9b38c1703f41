//! The shooting residual (eqs 32-33, scaled) of one forward problem and its
//! exact Jacobian from the tangents of the discrete RK4 map; the tension
//! slopes of the force laws, with their onsets of tension.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::error::{Error, Result};
use crate::rod::{
    integrate, integrate_flat, integrate_tangent, FlatNodes, IvpResult, IvpSpec, Robot, TangentIvp,
    TangentSeeds,
};

/// Residual, its exact Jacobian, the tangent IVP and the tensions of one evaluation.
type ResidualAndJacobian = (Vec<f64>, DMatrix<f64>, TangentIvp, Vec<f64>);

/// The taut piece of a slack actuator's law, extended to its elongation,
/// with the residual's response to its tension (for a semismooth step that
/// crosses the onset, [`crate::solve::system::Shooting`]'s `limit_step`).
#[derive(Debug, Clone)]
pub(crate) struct SlackTangent {
    /// The actuator.
    pub index: usize,
    /// The taut side's slope \[N/m\] at the onset.
    pub slope: f64,
    /// The onset's elongation \[m\] (zero tension, the taut side from there).
    pub onset: f64,
    /// `dr / d tau` of the scaled residual \[1/N\].
    pub response: DVector<f64>,
}

/// The Newton step `dx` (Jacobian `jac` at `x`, residual `r`) recomputed
/// where it carries a slack actuator taut (for
/// [`crate::solve::system::Shooting`]'s `limit_step`): a semismooth
/// Newton step (Qi and Sun, Math. Prog. 58, 1993) with the law's slope
/// of the side the step goes to, the taut piece extended to `x`,
/// `tau ~ k (d' - d0)` (`k` the taut slope, `d0` the onset): column
/// `6 + i` becomes `g k L - e_(6+i)` (`g = dr / d tau_i`, from the
/// Jacobian's tangent, [`SlackTangent`]) and the residual moves by `g k
/// (d - d0)`. The slack Jacobian predicts no tension, so its step
/// overshoots into a tension that throws the body far off (a tendon at its
/// onset then flips between slack and taut from one iteration to the next,
/// each line search accepting only a tiny step).
/// `slack`: the Jacobian's slack actuators (at `x`), `len` the body
/// length \[m\]. Taken only where the recomputed step also lands taut for
/// each actuator taken taut; one that it lands slack is taken slack again
/// and the step re-solved (the pieces chosen as a piecewise-linear solver
/// does, Katzenelson, Bell Syst. Tech. J. 44, 1965: with two tendons slack
/// at the Jacobian and the step carrying both taut, the taut model can
/// carry one back slack, and taking that one slack again keeps the
/// semismooth step for the other); `None` where no actuator is left taut.
pub(crate) fn taut_step(
    len: f64,
    slack: &[SlackTangent],
    x: &[f64],
    dx: &[f64],
    r: &[f64],
    jac: &DMatrix<f64>,
) -> Option<Vec<f64>> {
    if slack.is_empty() || jac.nrows() != jac.ncols() {
        return None;
    }
    let lands_taut = |s: &SlackTangent, step: &[f64]| {
        let c = 6 + s.index;
        (x[c] + step[c]) * len > s.onset
    };
    // the actuators taken taut: those the last step carries taut, until
    // the step's pieces agree with where it lands (Katzenelson's
    // iteration; at most one pass per slack actuator)
    let mut taut: Vec<bool> = slack.iter().map(|s| lands_taut(s, dx)).collect();
    for _ in 0..slack.len() {
        if !taut.contains(&true) {
            return None;
        }
        let step = taut_model_step(len, slack, &taut, x, r, jac)?;
        let landed: Vec<bool> = slack.iter().map(|s| lands_taut(s, &step)).collect();
        // an actuator taken slack that the step carries taut stays slack
        // (its slack piece is the Jacobian's own: the caller's step)
        let agree = taut.iter().zip(&landed).all(|(&t, &l)| !t || l);
        if agree {
            return Some(step);
        }
        for (t, l) in taut.iter_mut().zip(&landed) {
            *t &= *l;
        }
    }
    None
}

/// The Newton step of `jac dx = -r` with the slack actuators flagged in
/// `taut` re-linearised on their taut pieces (see [`taut_step`]); `None`
/// if singular or not finite.
fn taut_model_step(
    len: f64,
    slack: &[SlackTangent],
    taut: &[bool],
    x: &[f64],
    r: &[f64],
    jac: &DMatrix<f64>,
) -> Option<Vec<f64>> {
    let mut jm = jac.clone();
    let mut rm = DVector::from_column_slice(r);
    for (s, _) in slack.iter().zip(taut).filter(|(_, &t)| t) {
        let c = 6 + s.index;
        let (slope, shift) = (s.slope * len, s.slope * (x[c] * len - s.onset));
        super::limit::relinearise(&mut jm, &mut rm, c, &s.response, slope, shift);
    }
    let step = jm.lu().solve(&(-rm))?;
    step.iter()
        .all(|v| v.is_finite())
        .then(|| step.iter().copied().collect())
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

    /// [`Shot::residual`] with the IVP's nodes recorded flat (its own
    /// `nodes` empty).
    pub(crate) fn residual_flat(
        &self,
        x: &[f64],
    ) -> Result<(Vec<f64>, IvpResult, Vec<f64>, FlatNodes)> {
        let mut nodes = FlatNodes::default();
        let (r, ivp, tau) = self.residual_by(x, |spec, v0, u0| {
            let (ivp, flat) = integrate_flat(spec, v0, u0)?;
            nodes = flat;
            Ok(ivp)
        })?;
        Ok((r, ivp, tau, nodes))
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

    /// The residual at `x` on `steps` RK4 steps extrapolated from this
    /// problem's, `r` (on `c = self.steps`), and two plain IVPs on `2c`
    /// and `3c` steps (counted in `ivps`): RK4's error expansion
    /// `r_n = r_inf + a n^-4 + b n^-5` through the three grids, evaluated at
    /// `n = steps`. Its error is the expansion's next term, `n^-6`: at a
    /// cold Fig. 6 coarse root (defect `r_100 - r_10` 1.4e-6) measured
    /// 6.2e-12 with grids 10/20/40, 2.9e-12 with 10/20/50 and 2.0e-12 with
    /// 10/25/50, the latter two the `n^-6` term's prediction from the
    /// first; for 10/20/30 it predicts 1.5e-11 (two grids, `a` only:
    /// 20/40 1.6e-10, 25/50 4.9e-11). Steel robot: 3.9e-10, within its
    /// rounding floor 8.9e-10. The two IVPs cost half of one on 10c steps.
    pub fn extrapolated(
        &self,
        x: &[f64],
        r: &[f64],
        steps: usize,
        ivps: &mut usize,
    ) -> Result<Vec<f64>> {
        let c = self.steps;
        let mut rs = vec![r.to_vec()];
        for n in [2 * c, 3 * c] {
            *ivps += 1;
            rs.push(self.with_steps(n).residual(x, false)?.0);
        }
        // weights w with sum_k w_k f(n_k) = f(steps) for f = 1, n^-4, n^-5
        let basis = |n: usize| [1.0, (n as f64).powi(-4), (n as f64).powi(-5)];
        let grids = [c, 2 * c, 3 * c];
        let a = DMatrix::from_fn(3, 3, |i, k| basis(grids[k])[i]);
        let e = nalgebra::DVector::from_column_slice(&basis(steps));
        let w = a
            .lu()
            .solve(&e)
            .ok_or_else(|| Error::param("steps", c as f64, "> 0"))?;
        Ok((0..r.len())
            .map(|i| (0..3).map(|k| w[k] * rs[k][i]).sum())
            .collect())
    }

    /// One tangent IVP from scaled unknowns `x`: the scaled residual (as
    /// [`Shot::residual`]) and its EXACT Jacobian with respect to `x` (the
    /// derivative of the discrete RK4 map, from the variational equations and
    /// the force laws' derivatives), `(6 + N) x (6 + N)`. With `record`, the
    /// IVP's nodes carry `d y(s) / d x` (see [`crate::rod::TangentNode`]).
    pub fn jacobian(&self, x: &[f64], record: bool) -> Result<ResidualAndJacobian> {
        Ok(self.jacobian_side(x, record, false, false)?.0 .0)
    }

    /// [`Shot::jacobian`] with the side of the generalised derivative at an
    /// actuator's onset of tension (see [`tension_slope`]); also returns
    /// whether any actuator is at its onset. With `taut`, the tangent of a
    /// slack actuator (zero tension and slope) is seeded with its law's taut
    /// slope at the onset ([`crate::rod::ForceLaw::elongation`] of zero
    /// tension), its response `dr / d tau` returned, and its column reset to
    /// the slack one, `-e_(6+i)` (the columns are independent tangents: the
    /// Jacobian is the same as without).
    pub(crate) fn jacobian_side(
        &self,
        x: &[f64],
        record: bool,
        slack: bool,
        taut: bool,
    ) -> Result<((ResidualAndJacobian, bool), Vec<SlackTangent>)> {
        let len = self.robot.body.length;
        let na = self.robot.actuators.len();
        let nx = 6 + na;
        let (v0, u0) = base_strains(x, len);
        let mut tau = Vec::with_capacity(na);
        let mut seeds = TangentSeeds::zeros(na, nx);
        let mut onset = false;
        let mut slack_dirs = Vec::new();
        for k in 0..3 {
            seeds.nu0[(k, k)] = 1.0;
            seeds.omega0[(k, 3 + k)] = 1.0 / len;
        }
        for (i, a) in self.robot.actuators.iter().enumerate() {
            let (t, dt_de, at) =
                tension_slope(a.law.as_ref(), x[6 + i] * len, self.inputs[i], len, slack)?;
            onset |= at;
            tau.push(t);
            seeds.tensions[(i, 6 + i)] = dt_de * len;
            if taut && t == 0.0 && dt_de == 0.0 {
                if let Some(d0) = a.law.elongation(0.0, self.inputs[i]) {
                    match a.law.tension_derivatives(d0, self.inputs[i]) {
                        Ok((_, k, _)) if k > 0.0 && k.is_finite() && d0.is_finite() => {
                            seeds.tensions[(i, 6 + i)] = k * len;
                            slack_dirs.push(SlackTangent {
                                index: i,
                                slope: k,
                                onset: d0,
                                response: DVector::zeros(0),
                            });
                        }
                        _ => {}
                    }
                }
            }
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
        for sd in &mut slack_dirs {
            let c = 6 + sd.index;
            let mut g = jac.column(c).clone_owned();
            g[c] += 1.0;
            sd.response = g / (sd.slope * len);
            jac.column_mut(c).fill(0.0);
            jac[(c, c)] = -1.0;
        }
        Ok((((r, jac, tan, tau), onset), slack_dirs))
    }
}

/// `jac` (a Jacobian at `x_from`, inputs `from`) with each actuator column
/// rescaled to the tension slope at `x_to`, inputs `to`: column `6 + i` is
/// `(dr/dtau_i) (dtau_i/ddelta_i) L - e_(6+i)`, and `dr/dtau_i` is the
/// IVP's, which does not depend on the inputs. Columns of a slack actuator
/// (zero slope) are kept.
pub fn rescale_tension_columns(
    robot: &Robot,
    jac: &DMatrix<f64>,
    (x_from, from): (&[f64], &[f64]),
    (x_to, to): (&[f64], &[f64]),
) -> DMatrix<f64> {
    let len = robot.body.length;
    let mut j = jac.clone();
    for (i, a) in robot.actuators.iter().enumerate() {
        let c = 6 + i;
        let slope = |x: &[f64], u: &[f64]| {
            tension_slope(a.law.as_ref(), x[c] * len, u[i], len, false).map(|s| s.1)
        };
        let (Ok(s0), Ok(s1)) = (slope(x_from, from), slope(x_to, to)) else {
            continue;
        };
        if s0 == 0.0 || !(s1 / s0).is_finite() || c >= j.ncols() || c >= j.nrows() {
            continue;
        }
        j[(c, c)] += 1.0;
        j.column_mut(c).scale_mut(s1 / s0);
        j[(c, c)] -= 1.0;
    }
    j
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
/// no first-order decrease), so a failed line search is
/// retried with the other side ([`crate::solve::system::Shooting`]'s `refine`).
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

#[cfg(test)]
#[path = "residual_tests.rs"]
mod tests;
