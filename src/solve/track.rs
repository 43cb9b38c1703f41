//! The state of a homotopy path between its steps ([`Track`]: the last
//! converged point, the earlier points of the predictor, the step and the
//! path so far) and the one check of a coarse path's grid ([`Watch`]); see
//! [`crate::solve::continuation`] and [`crate::solve::coarse_path`].

use super::continuation::{predictor, PREDICTOR_POINTS};
use super::newton::{NewtonResult, System};
use super::shooting::{tensions, FinalIvp, Loads, Work};
use super::system::Shooting;
use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

/// The last converged point of a homotopy: `lambda`, the unknowns, the
/// tensions \[N\] and the Newton Jacobian there, up to
/// [`PREDICTOR_POINTS`] - 1 earlier `(lambda, unknowns)`, oldest first,
/// the next step and the path so far (the `lambda` of each converged step).
#[derive(Clone)]
pub(crate) struct Track {
    pub lam: f64,
    pub x: Vec<f64>,
    pub tau: Vec<f64>,
    pub jac: Option<nalgebra::DMatrix<f64>>,
    pub prev: Vec<(f64, Vec<f64>)>,
    pub step: f64,
    pub path: Vec<f64>,
    /// A check of the grid at the first point past its `lambda` (see [`Watch`]).
    pub watch: Option<Watch>,
    /// The residual of the failed [`Watch`] the path stopped at.
    pub unresolved: Option<f64>,
}

/// A check of a coarse path's grid: at the first converged point at or
/// past `lam`, one IVP on `steps` RK4 steps; the path stops (an error) if
/// its `max |r|` there exceeds `tol`, or if `scaled`, `tol (lambda / lam)^2`
/// at the point's `lambda` (the grid's error grows about as `lambda^2`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Watch {
    pub lam: f64,
    pub steps: usize,
    pub tol: f64,
    /// Whether `tol` grows as `lambda^2` from `lam` to the checked point.
    pub scaled: bool,
}

impl Watch {
    /// The check at the converged `x` of the robot, inputs and loads there;
    /// its IVP is counted on `work`.
    pub(crate) fn check(
        &self,
        robot: &Robot,
        inputs: &[f64],
        loads: &Loads,
        x: &[f64],
        work: &mut Work,
    ) -> Result<()> {
        let mut sys = Shooting::new(robot, inputs, loads, self.steps, false);
        let r = sys.residual(x);
        work.evaluations += sys.evaluations();
        let n = r?.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if n <= self.tol {
            return Ok(());
        }
        Err(Error::NotConverged {
            solver: "forward shooting",
            iterations: work.iterations,
            evaluations: work.evaluations,
            residual: n,
            stop: StopReason::Other,
            reason: "the coarse grid does not resolve the path".into(),
        })
    }
}

impl Track {
    /// The start of a path at `lam` (no earlier points, no path yet).
    pub(crate) fn new(
        lam: f64,
        x: Vec<f64>,
        tau: Vec<f64>,
        jac: Option<nalgebra::DMatrix<f64>>,
        step: f64,
    ) -> Self {
        Track {
            lam,
            x,
            tau,
            jac,
            prev: Vec::new(),
            step,
            path: Vec::new(),
            watch: None,
            unresolved: None,
        }
    }
    /// The predictor at `lt` (see [`predictor`]) for the robot and inputs there.
    pub(crate) fn predictor(&self, robot: &Robot, inputs: &[f64], lt: f64) -> Vec<f64> {
        predictor(robot, inputs, &self.x, &self.tau, &self.prev, self.lam, lt)
    }
    /// Move to the converged point `nr` at `lt` (robot and inputs there;
    /// `last`: its last IVP, whose tensions are taken if it is at `nr.x`).
    pub(crate) fn advance(
        &mut self,
        lt: f64,
        nr: NewtonResult,
        last: Option<FinalIvp>,
        robot: &Robot,
        inputs: &[f64],
    ) -> Result<()> {
        let tau = match last {
            Some(last) => last.tensions,
            None => tensions_at(robot, inputs, &nr.x, robot.body.length)?,
        };
        self.prev
            .push((self.lam, std::mem::replace(&mut self.x, nr.x)));
        if self.prev.len() >= PREDICTOR_POINTS {
            self.prev.remove(0);
        }
        self.lam = lt;
        self.tau = tau;
        if nr.jacobian.is_some() {
            self.jac = nr.jacobian;
        }
        Ok(())
    }
    /// The grid check ([`Watch`]) at the point just reached, if it is the
    /// first at or past the check's `lambda` (robot, inputs and loads
    /// there): an error if it fails, with its residual in `unresolved`
    /// (infinite if its IVP failed: not a fold, so never handed over as one).
    pub(crate) fn check_grid(
        &mut self,
        robot: &Robot,
        inputs: &[f64],
        loads: &Loads,
        work: &mut Work,
    ) -> Result<()> {
        let Some(w) = self.watch.filter(|w| self.lam >= w.lam) else {
            return Ok(());
        };
        self.watch = None;
        let w = match w.scaled {
            true => Watch {
                tol: w.tol * (self.lam / w.lam).powi(2),
                ..w
            },
            false => w,
        };
        let checked = w.check(robot, inputs, loads, &self.x, work);
        self.unresolved = match &checked {
            Ok(()) => None,
            Err(Error::NotConverged { residual, .. }) => Some(*residual),
            Err(_) => Some(f64::INFINITY),
        };
        checked
    }
    /// Move the point to `nr`, the same point corrected on another grid
    /// (robot and inputs at `self.lam`): the earlier points move by the
    /// same correction (the grids' difference varies slowly along the path).
    pub(crate) fn regrid(
        &mut self,
        nr: NewtonResult,
        last: Option<FinalIvp>,
        robot: &Robot,
        inputs: &[f64],
    ) -> Result<()> {
        let shift: Vec<f64> = nr.x.iter().zip(&self.x).map(|(a, b)| a - b).collect();
        for (_, p) in self.prev.iter_mut() {
            p.iter_mut().zip(&shift).for_each(|(v, s)| *v += s);
        }
        self.tau = match last {
            Some(last) => last.tensions,
            None => tensions_at(robot, inputs, &nr.x, robot.body.length)?,
        };
        self.x = nr.x;
        if nr.jacobian.is_some() {
            self.jac = nr.jacobian;
        }
        Ok(())
    }
}

/// Actuator tensions \[N\] at the scaled unknowns `x` (elongations `x[6..] L`).
pub(super) fn tensions_at(robot: &Robot, inputs: &[f64], x: &[f64], len: f64) -> Result<Vec<f64>> {
    let delta: Vec<f64> = x[6..].iter().map(|d| d * len).collect();
    tensions(robot, inputs, &delta)
}
