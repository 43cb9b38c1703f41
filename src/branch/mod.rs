//! Branch following (beyond the paper; `docs/stability.md`): the
//! equilibria in one scalar parameter, through limit points, with folds,
//! bifurcations and the stability of each point; and a sweep that stays on
//! stable equilibria and reports where the physical robot jumps.
//!
//! Every parameter enters the problem linearly (the inputs it sets, the tip
//! wrench or the gravity load `psi A g` it scales), so a branch is the
//! solver's own pseudo-arclength continuation (Keller 1977; Allgower &
//! Georg, *Introduction to Numerical Continuation Methods*, SIAM 2003;
//! [`crate::solve::arclength`]) of the multiple-shooting system along the
//! straight path in inputs and loads between the problem at the two ends of
//! the parameter's interval ([`crate::solve::homotopy::LoadPath`]),
//! `parameter = start + lambda (end - start)`, `lambda` in `[0, 1]`. A fold
//! (limit point) is a sign change of `d lambda / d s`; a bifurcation is a
//! sign change of `det G_x` (the multiple-shooting Jacobian at fixed
//! parameter, from its staircase factors) not explained by a fold, or a
//! change of the stability verdict without a fold (a symmetric double root
//! leaves the sign of `det G_x`). Events are located by regula falsi on the
//! arclength.

use nalgebra::Vector3;

use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{assemble, solve_loaded, Loads, Solution, SolveOptions};
use crate::stability::{stability, Stability};

mod follow;
mod locate;
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
        let (robot, inputs, loads) = self.unchecked(lambda);
        robot.check_inputs(&inputs)?;
        Ok((robot, inputs, loads))
    }

    /// [`Problem::at`] without the check of the inputs against their force
    /// laws' ranges (the far end of a path that leaves a range on its way).
    fn unchecked(&self, lambda: f64) -> (Robot, Vec<f64>, Loads) {
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
        (robot, inputs, loads)
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
    /// Initial arclength step, in units of `|end - start|`: the path norm
    /// is `|z|^2 = |x|^2 / n + lambda^2` with `x` the `n` scaled
    /// multiple-shooting unknowns and `lambda = (parameter - start) / (end -
    /// start)`, so a step along the parameter alone is its change over
    /// `|end - start|`.
    pub step: f64,
    /// Largest arclength step (same units).
    pub max_step: f64,
    /// Smallest arclength step before giving up.
    pub min_step: f64,
    /// Largest number of points.
    pub max_points: usize,
    /// Stop at the first point that is not stable or lies past a fold (sweep mode).
    pub stop_when_unstable: bool,
    /// Shooting options (grid, tolerance, iterations of each corrector, at
    /// most [`crate::solve::arclength::CORRECTOR_ITERATIONS`]).
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
    /// `d (parameter / |end - start|) / d s` of the unit path tangent
    /// (arclength `s` in the norm of [`BranchOptions::step`]); changes sign
    /// at a fold.
    pub dparameter: f64,
    /// `det G_x`, the determinant of the scaled multiple-shooting Jacobian
    /// at fixed parameter (exact tangents of the discrete map, from its
    /// staircase LU factors, [`crate::solve::abd::Staircase::determinant`]).
    /// Its sign changes at a simple bifurcation or a fold; its size depends
    /// on the segments and the scaling of the unknowns. NaN if unknown.
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
