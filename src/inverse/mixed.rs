//! The mixed (blocked-tip) boundary value problem on the forward solver's
//! formulation, multiple shooting ([`crate::solve::ms`]), by the bordering
//! method (Govaerts, *Numerical Methods for Bifurcations of Dynamical
//! Equilibria*, SIAM 2000, ch. 3).
//!
//! The free-tip problem `G(x, lambda) = 0` is the multiple-shooting system
//! of the robot with one scalar parameter `lambda`, the blocked solve's
//! extra unknown ([`Extra`]): the contact force, the tip force `-f n` added
//! to the loads (`lambda = f L^2 / EI`), or the single actuation variable
//! at a fixed contact force (`lambda = z / scale`). [`Blocked`] is that
//! system as a [`ParametrisedSystem`], linearised in the bordered form of
//! the continuation ([`crate::solve::arclength`]): the staircase LU of
//! `G_x` ([`crate::solve::abd`]) and block elimination with one step of
//! iterative refinement (Govaerts & Pryce, BIT 30, 1990). `G_lambda` is
//! exact for the force (the tip force enters the tip balance (32) alone,
//! as `-R(L)^T F`) and a one-sided difference for the variable (the law
//! coordinates are held, [`crate::solve::law_coordinate`], while the input
//! moves the tension and the elongation along the law).
//!
//! The blocked tip adds one scalar condition, `g(x, lambda) = n . (p(L) -
//! point) / L = 0`, with `p(L)` the last segment's end. [`Contact`] is the
//! square system `[G; g] = 0` in `(x, lambda)` for the damped Newton method
//! NLEQ-ERR ([`crate::solve::nleq`]): its Jacobian is `G`'s bordered by the
//! row `(grad_x g, g_lambda)`, whose `x` part is the last segment's exact
//! tangent ([`crate::solve::ms::MultipleShooting`]'s tip accessor), so each
//! Newton step is one bordered solve. Where the tip cannot reach the block
//! along `lambda` (the row is parallel to the null direction of `G`), the
//! bordered matrix is singular and the solve says so.

use nalgebra::{DMatrix, Quaternion, Vector3};

use super::{load_scales, Block, Groups};
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{residual_scales, Loads};
use crate::solve::arclength::ParametrisedSystem;
use crate::solve::bordered::Bordered;
use crate::solve::ms::MultipleShooting;
use crate::solve::nleq::NonlinearSystem;

/// The extra unknown of a mixed solve.
#[derive(Debug, Clone)]
pub(crate) enum Extra {
    /// The contact force \[N\] (scaled by `E I / L^2`) at fixed actuator `inputs`.
    Force { inputs: Vec<f64> },
    /// The single actuation variable (scaled by `scale`) at a fixed contact `force` \[N\].
    Variable { force: f64, scale: f64 },
}

/// The free-tip multiple-shooting system `G(x, lambda)` of a blocked solve
/// (see the module docs), on fixed segments and rotation charts.
pub(crate) struct Blocked<'a> {
    robot: &'a Robot,
    groups: &'a Groups,
    block: &'a Block,
    extra: Extra,
    steps: usize,
    starts: Vec<usize>,
    charts: Vec<Quaternion<f64>>,
    /// Where the next evaluation's law coordinates start their inversion.
    hints: Vec<f64>,
    /// `G_x` of the last linearisation with its border.
    lin: Bordered,
    /// `G_lambda` of the last linearisation.
    g_lambda: Vec<f64>,
    /// IVPs spent (a tangent IVP of `k` directions counts `1 + k / 8`).
    work: f64,
    /// The tip position \[m\] at the last evaluation, the rounding floor of
    /// `G` there, and after a linearisation the tip's derivatives along
    /// the last block's unknowns (from its offset) and along `lambda`.
    tip: Vector3<f64>,
    floor: f64,
    tip_x: (usize, DMatrix<f64>),
    tip_lambda: Vector3<f64>,
}

impl<'a> Blocked<'a> {
    /// The system of `robot` held by `block`, on `steps` RK4 steps with the
    /// segments starting at `starts` and the rotation charts `charts` (as
    /// [`MultipleShooting::new`]).
    pub(crate) fn new(
        (robot, groups, block): (&'a Robot, &'a Groups, &'a Block),
        extra: Extra,
        steps: usize,
        starts: Vec<usize>,
        charts: Vec<Quaternion<f64>>,
    ) -> Self {
        Blocked {
            robot,
            groups,
            block,
            extra,
            steps,
            starts,
            charts,
            hints: Vec::new(),
            lin: Bordered::default(),
            g_lambda: Vec::new(),
            work: 0.0,
            tip: Vector3::zeros(),
            floor: 0.0,
            tip_x: (0, DMatrix::zeros(3, 0)),
            tip_lambda: Vector3::zeros(),
        }
    }

    pub(crate) fn starts(&self) -> &[usize] {
        &self.starts
    }
    pub(crate) fn charts(&self) -> &[Quaternion<f64>] {
        &self.charts
    }

    /// Scale of `lambda`: `E I / L^2` \[N\] for the force, the variable's
    /// own scale otherwise.
    pub(crate) fn scale(&self) -> f64 {
        match &self.extra {
            Extra::Force { .. } => load_scales(self.robot).0,
            Extra::Variable { scale, .. } => *scale,
        }
    }

    /// Actuator inputs, tip loads and contact force \[N\] at `lambda`. An
    /// input outside its law's range cannot be evaluated, like an IVP that
    /// fails ([`Error::Integration`]): Newton damps its step.
    pub(crate) fn problem(&self, lambda: f64) -> Result<(Vec<f64>, Loads, f64)> {
        let e = lambda * self.scale();
        let (inputs, force) = match &self.extra {
            Extra::Force { inputs } => (inputs.clone(), e),
            Extra::Variable { force, .. } => {
                let inputs = self.groups.inputs(&[e]);
                if let Err(err) = self.robot.check_inputs(&inputs) {
                    return Err(Error::Integration {
                        s: 0.0,
                        reason: err.to_string(),
                    });
                }
                (inputs, *force)
            }
        };
        Ok((inputs, self.block.loads(self.robot, force), force))
    }

    /// The interval of `lambda` on which the variable's inputs lie within
    /// their laws' ranges (unbounded for the force).
    fn range(&self) -> (f64, f64) {
        match &self.extra {
            Extra::Force { .. } => (f64::NEG_INFINITY, f64::INFINITY),
            Extra::Variable { scale, .. } => {
                let (lo, hi) = self.groups.bounds(self.robot)[0];
                (lo / scale, hi / scale)
            }
        }
    }

    /// The gap `g = n . (p(L) - point) / L` at the last evaluation.
    pub(crate) fn gap(&self) -> f64 {
        self.block.normal.dot(&(self.tip - self.block.point)) / self.robot.body.length
    }

    /// `G(x, lambda)` into `f`, and with `jacobian` `G_x` factorised into
    /// `self.lu` and the tip's tangent kept.
    fn eval(&mut self, x: &[f64], lambda: f64, f: &mut [f64], jacobian: bool) -> Result<()> {
        let (inputs, loads, _) = self.problem(lambda)?;
        let (robot, steps, charts) = (self.robot, self.steps, self.charts.clone());
        let mut ms = MultipleShooting::new(robot, &inputs, loads, steps, &self.starts, charts)?;
        ms.set_hints(&self.hints);
        let out = match jacobian {
            true => ms.linearise(x, f).and_then(|_| self.lin.factorise(&ms)),
            false => ms.residual(x, f),
        };
        self.hints = ms.hints();
        self.work += ms.work;
        out?;
        let (end, tangent) = ms.tip_state().expect("an evaluated system has a tip");
        self.tip = end.p;
        if let Some(t) = tangent {
            self.tip_x = (ms.last_offset(), t.clone());
            if let Extra::Force { .. } = self.extra {
                // d r_F / d f = R(L)^T n (eq 32 under the tip force -f n),
                // scaled as the tip balance rows and per unit of lambda
                let (fs, _) = residual_scales(robot);
                let rn = crate::rod::rot(&end.q).transpose() * self.block.normal;
                let rows: usize = ms.rows()[..ms.segments() - 1].iter().sum();
                self.g_lambda = vec![0.0; f.len()];
                for k in 0..3 {
                    self.g_lambda[rows + k] = rn[k] * fs * self.scale();
                }
            }
        }
        self.floor = ms.rounding_floor(x);
        Ok(())
    }
}

impl ParametrisedSystem for Blocked<'_> {
    fn dim(&self) -> usize {
        crate::solve::ms::unknowns(self.robot.actuators.len(), self.starts.len())
    }
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
        crate::solve::cancel::check()?;
        self.eval(x, lambda, f, false)
    }
    /// `G_x` factorised as a staircase; `G_lambda` exact for the force,
    /// for the variable by a one-sided difference of step `sqrt(eps)`
    /// toward the middle of its range (error `~sqrt(eps)` relative, which
    /// leaves Newton's convergence quadratic to that level; one residual
    /// more per linearisation), which also gives the tip's `lambda`
    /// derivative.
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()> {
        crate::solve::cancel::check()?;
        self.eval(x, lambda, f, true)?;
        self.tip_lambda = Vector3::zeros();
        if let Extra::Variable { .. } = self.extra {
            let (lo, hi) = self.range();
            let h = f64::EPSILON.sqrt() * lambda.abs().max(1.0);
            let h = if lambda > 0.5 * (lo + hi) { -h } else { h };
            let (tip, floor) = (self.tip, self.floor);
            let mut fh = vec![0.0; f.len()];
            self.eval(x, lambda + h, &mut fh, false)?;
            self.g_lambda = fh.iter().zip(f.iter()).map(|(a, b)| (a - b) / h).collect();
            self.tip_lambda = (self.tip - tip) / h;
            (self.tip, self.floor) = (tip, floor);
        }
        self.lin.border(self.g_lambda.clone(), row)
    }
    /// [`Bordered::solve`].
    fn solve_bordered(
        &mut self,
        b: &[f64],
        b_last: f64,
        dx: &mut [f64],
        dlambda: &mut f64,
    ) -> Result<bool> {
        self.lin.solve(b, b_last, dx, dlambda)
    }
    fn floor(&self, _x: &[f64], _f: &[f64]) -> f64 {
        self.floor
    }
    fn work(&self) -> f64 {
        self.work
    }
    fn domain(&self) -> (f64, f64) {
        self.range()
    }
}

/// The blocked tip's square system `[G(x, lambda); g(x, lambda)] = 0` in
/// `z = (x, lambda)` (see the module docs), for [`crate::solve::nleq`].
pub(crate) struct Contact<'s, 'a> {
    pub(crate) sys: &'s mut Blocked<'a>,
}

impl NonlinearSystem for Contact<'_, '_> {
    fn dim(&self) -> usize {
        self.sys.dim() + 1
    }
    fn residual(&mut self, z: &[f64], f: &mut [f64]) -> Result<()> {
        let n = z.len() - 1;
        self.sys.residual(&z[..n], z[n], &mut f[..n])?;
        f[n] = self.sys.gap();
        Ok(())
    }
    /// `G`'s bordered linearisation with the row `(grad_x g, g_lambda)`:
    /// `n^T dp(L) / L` from the last segment's tangent and the `lambda`
    /// derivative of the tip.
    fn linearise(&mut self, z: &[f64], f: &mut [f64]) -> Result<()> {
        let n = z.len() - 1;
        let zero = vec![0.0; n];
        self.sys
            .linearise_bordered(&z[..n], z[n], (&zero, 0.0), &mut f[..n])?;
        let (nrm, len) = (self.sys.block.normal, self.sys.robot.body.length);
        let (o, t) = &self.sys.tip_x;
        let mut row = zero;
        for c in 0..t.ncols() {
            row[o + c] = (0..3).map(|j| nrm[j] * t[(j, c)]).sum::<f64>() / len;
        }
        let rl = nrm.dot(&self.sys.tip_lambda) / len;
        self.sys.lin.set_row((&row, rl));
        f[n] = self.sys.gap();
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dz: &mut [f64]) -> Result<bool> {
        let n = b.len() - 1;
        let (dx, dl) = dz.split_at_mut(n);
        self.sys.solve_bordered(&b[..n], b[n], dx, &mut dl[0])
    }
    /// The floor of `G` and the gap's: `4 eps` times the positions compared.
    fn floor(&self, _z: &[f64], _f: &[f64]) -> f64 {
        let b = self.sys.block;
        let gap = 4.0 * f64::EPSILON * self.sys.tip.amax().max(b.point.amax())
            / self.sys.robot.body.length;
        self.sys.floor.max(gap)
    }
    fn work(&self) -> f64 {
        self.sys.work
    }
}

#[cfg(test)]
#[path = "mixed_tests.rs"]
mod tests;
