//! Branch following (beyond the paper; `docs/stability.md`): Keller's
//! pseudo-arclength continuation (Keller 1977, "Numerical solution of
//! bifurcation and nonlinear eigenvalue problems") of the
//! shooting equilibria in one scalar parameter, through limit points, with
//! folds, bifurcations and the stability of each point; and a sweep that
//! stays on stable equilibria and reports where the physical robot jumps.
//!
//! The path is `y(sigma) = (x, lambda / scale)` with `x` the scaled shooting
//! unknowns of [`crate::shooting`]; each step predicts along the unit tangent
//! `t` (the null vector of `[F_x, F_lambda]`, oriented by `t_prev . t > 0`)
//! and corrects on the hyperplane `t . (y - y_pred) = 0`. A fold (limit point)
//! is a sign change of `d lambda / d sigma`; a bifurcation is a sign change
//! of `det F_x` not explained by a fold, or a change of the stability verdict
//! without a fold (a symmetric double root leaves `det F_x` positive).
//! Events are located by regula falsi on the arclength.

use nalgebra::Vector3;

use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{assemble, solve_loaded, Loads, Shot, Solution, SolveOptions};
use crate::stability::{stability, Stability};

mod follow;
mod sweep;

pub use follow::follow_branch;
pub use sweep::{sweep_stable, Jump, StableSweep};

/// The continuation parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum Parameter {
    /// The inputs of the listed actuators, all set to the parameter
    /// (temperature \[C\], tension \[N\] or pull \[m\]).
    Inputs(Vec<usize>),
    /// Scale [-] of the body's tip force and moment.
    TipLoadScale,
    /// Scale [-] of the body's gravity vector.
    GravityScale,
}

/// The problem at one parameter value: robot, inputs, tip loads.
pub struct Problem<'a> {
    robot: &'a Robot,
    parameter: Parameter,
    inputs: Vec<f64>,
}

impl<'a> Problem<'a> {
    /// `inputs`: the actuator inputs (those named by `Parameter::Inputs` are
    /// overridden by the parameter).
    pub fn new(robot: &'a Robot, parameter: Parameter, inputs: &[f64]) -> Result<Self> {
        robot.validate()?;
        if inputs.len() != robot.actuators.len() {
            return Err(Error::input(
                "inputs",
                format!(
                    "expected {} values, got {}",
                    robot.actuators.len(),
                    inputs.len()
                ),
            ));
        }
        if let Parameter::Inputs(idx) = &parameter {
            if idx.is_empty() {
                return Err(Error::input("parameter", "names no actuator"));
            }
            for &i in idx {
                if i >= robot.actuators.len() {
                    return Err(Error::param(
                        "parameter actuator index",
                        i as f64,
                        format!("0 <= index < {}", robot.actuators.len()),
                    ));
                }
            }
        }
        Ok(Problem {
            robot,
            parameter,
            inputs: inputs.to_vec(),
        })
    }

    /// Robot, inputs and loads at parameter value `lambda`.
    pub fn at(&self, lambda: f64) -> Result<(Robot, Vec<f64>, Loads)> {
        crate::error::finite("parameter", lambda)?;
        let mut robot = self.robot.clone();
        let mut inputs = self.inputs.clone();
        let mut loads = Loads::of(self.robot);
        match &self.parameter {
            Parameter::Inputs(idx) => {
                for &i in idx {
                    inputs[i] = lambda;
                }
            }
            Parameter::TipLoadScale => {
                loads.tip_force *= lambda;
                loads.tip_moment *= lambda;
            }
            Parameter::GravityScale => robot.body.gravity *= lambda,
        }
        robot.check_inputs(&inputs)?;
        Ok((robot, inputs, loads))
    }

    /// Scaled shooting residual at `(x, lambda)`.
    fn residual(&self, x: &[f64], lambda: f64, steps: usize) -> Result<Vec<f64>> {
        let (robot, inputs, loads) = self.at(lambda)?;
        Shot::new(&robot, &inputs, &loads, steps)
            .residual(x, false)
            .map(|t| t.0)
    }

    /// Equilibrium with its profile at `lambda` from unknowns `x`.
    pub fn assemble(&self, x: &[f64], lambda: f64, steps: usize) -> Result<Solution> {
        let (robot, inputs, loads) = self.at(lambda)?;
        assemble(&robot, &inputs, &loads, x, steps, 0, 0)
    }

    /// Stability verdict of `sol` at `lambda` (free tip).
    pub fn stability(&self, sol: &Solution, lambda: f64) -> Result<Stability> {
        let (robot, ..) = self.at(lambda)?;
        stability(&robot, sol, &[])
    }

    /// Newton solve at fixed `lambda` from `warm` (or cold).
    pub fn solve(
        &self,
        lambda: f64,
        opts: &SolveOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        let (robot, inputs, loads) = self.at(lambda)?;
        solve_loaded(&robot, &inputs, &loads, opts, warm)
    }
}

/// Options of [`follow_branch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchOptions {
    /// Parameter value to start from.
    pub start: f64,
    /// Parameter value to reach (the path stops once it leaves the interval
    /// between `start` and `end`).
    pub end: f64,
    /// Initial arclength step, in units of `|end - start|` (the path norm
    /// is that of `(x, lambda / |end - start|)`).
    pub step: f64,
    /// Largest arclength step (same units).
    pub max_step: f64,
    /// Smallest arclength step before giving up.
    pub min_step: f64,
    /// Largest number of points.
    pub max_points: usize,
    /// Stop at the first point that is not stable or lies past a fold (sweep mode).
    pub stop_when_unstable: bool,
    /// Shooting options (grid, tolerance, iterations of each corrector).
    pub solve: SolveOptions,
}

impl Default for BranchOptions {
    fn default() -> Self {
        BranchOptions {
            start: 0.0,
            end: 1.0,
            step: 0.02,
            max_step: 0.1,
            min_step: 1e-6,
            max_points: 500,
            stop_when_unstable: false,
            solve: SolveOptions::default(),
        }
    }
}

impl BranchOptions {
    /// Validate.
    pub fn validate(&self) -> Result<()> {
        crate::error::finite("start", self.start)?;
        crate::error::finite("end", self.end)?;
        if self.start == self.end {
            return Err(Error::param("end", self.end, "!= start"));
        }
        if !(self.min_step > 0.0
            && self.min_step <= self.step
            && self.step <= self.max_step
            && self.max_step.is_finite())
        {
            return Err(Error::param(
                "step",
                self.step,
                "0 < min_step <= step <= max_step < inf",
            ));
        }
        if self.max_points < 2 || self.max_points > 1_000_000 {
            return Err(Error::param(
                "max_points",
                self.max_points as f64,
                "2 <= max_points <= 1e6",
            ));
        }
        self.solve.validate()
    }
}

/// One point of a branch.
#[derive(Debug, Clone)]
pub struct BranchPoint {
    /// Parameter value.
    pub parameter: f64,
    /// The equilibrium (profile included).
    pub solution: Solution,
    /// Its stability.
    pub stability: Stability,
    /// `d lambda / d sigma` (scaled) of the path tangent.
    pub dparameter: f64,
    /// `det F_x`, the determinant of the (scaled) shooting Jacobian at fixed
    /// parameter (exact, from the tangent IVP).
    pub jacobian_det: f64,
}

/// Kind of a located event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// Limit point (snap-through when stability is lost there).
    Fold,
    /// Branch point (or a stability change without a fold).
    Bifurcation,
}

/// A located fold or bifurcation.
#[derive(Debug, Clone)]
pub struct Event {
    /// Fold or bifurcation.
    pub kind: EventKind,
    /// Parameter value at the event.
    pub parameter: f64,
    /// Tip position \[m\] at the event.
    pub tip_position: Vector3<f64>,
    /// Index of the branch point just before the event.
    pub after_point: usize,
}

/// A followed branch.
#[derive(Debug, Clone)]
pub struct Branch {
    /// Points in path order.
    pub points: Vec<BranchPoint>,
    /// Located folds and bifurcations, in path order.
    pub events: Vec<Event>,
    /// IVPs integrated.
    pub evaluations: usize,
}
