//! The forward problem along a path of inputs and loads, for the
//! continuation ([`super::arclength`]): `G(x, lambda)` is the
//! multiple-shooting residual ([`super::ms`]) of the robot at the inputs
//! `a + lambda (b - a)` under the loads `L_a + lambda (L_b - L_a)` (the
//! distributed loads, gravity included, and the tip loads). From the
//! reference configuration (reference inputs, no load: the unloaded body
//! at rest, an exact solution) to the requested inputs and loads this is
//! the homotopy of a cold solve; from a neighbouring solution's inputs
//! and loads, a warm solve's; between the problem at the two ends of a
//! parameter's interval, a followed branch's ([`crate::branch`]).

use nalgebra::{Quaternion, Vector3};

use super::arclength::ParametrisedSystem;
use super::bordered::Bordered;
use super::ms::MultipleShooting;
use super::residual::Loads;
use crate::error::Result;
use crate::rod::Robot;

/// Inputs and loads at one end of a path.
#[derive(Debug, Clone)]
pub struct Endpoint {
    /// Actuator inputs.
    pub inputs: Vec<f64>,
    /// Tip loads.
    pub loads: Loads,
    /// Distributed force \[N/m\] (world frame, gravity's `psi A g` included).
    pub distributed_force: Vector3<f64>,
    /// Distributed moment \[N m/m\].
    pub distributed_moment: Vector3<f64>,
}

impl Endpoint {
    /// The robot's own loads at `inputs`.
    pub fn loaded(robot: &Robot, inputs: &[f64], loads: Loads) -> Self {
        Endpoint {
            inputs: inputs.to_vec(),
            loads,
            distributed_force: robot.body.distributed_load(),
            distributed_moment: robot.body.distributed_moment,
        }
    }
    /// The reference inputs and no load.
    pub fn unloaded(robot: &Robot) -> Self {
        Endpoint {
            inputs: robot.reference_inputs(),
            loads: Loads {
                tip_force: Vector3::zeros(),
                tip_moment: Vector3::zeros(),
            },
            distributed_force: Vector3::zeros(),
            distributed_moment: Vector3::zeros(),
        }
    }
}

/// `G(x, lambda)` along the straight path between two [`Endpoint`]s.
pub struct LoadPath<'a> {
    robot: &'a Robot,
    from: Endpoint,
    to: Endpoint,
    steps: usize,
    starts: Vec<usize>,
    charts: Vec<Quaternion<f64>>,
    /// The robot at the `lambda` of the last evaluation.
    at: Robot,
    /// `G_x` of the last linearisation with its border.
    lin: Bordered,
    work: f64,
    /// The rounding floor of the last evaluation's residual
    /// ([`MultipleShooting`]'s, as the forward solve's Newton uses).
    floor: f64,
    /// Where the next evaluation's law coordinates start their inversion
    /// ([`MultipleShooting::hints`]): the last evaluation's elongations.
    hints: Vec<f64>,
}

impl<'a> LoadPath<'a> {
    /// The path of `robot` from `from` to `to` on `steps` RK4 steps, with
    /// the segments starting at `starts` and rotation charts `charts` (as
    /// [`MultipleShooting::new`]).
    pub fn new(
        robot: &'a Robot,
        (from, to): (Endpoint, Endpoint),
        steps: usize,
        starts: Vec<usize>,
        charts: Vec<Quaternion<f64>>,
    ) -> Self {
        LoadPath {
            robot,
            from,
            to,
            steps,
            starts,
            charts,
            at: robot.clone(),
            lin: Bordered::default(),
            work: 0.0,
            floor: 0.0,
            hints: Vec::new(),
        }
    }

    /// `det G_x`, the determinant of the scaled multiple-shooting Jacobian
    /// at the last linearisation ([`ParametrisedSystem::linearise_bordered`]),
    /// from its staircase factors ([`Bordered::determinant`]); `None` before
    /// one, or where it was singular. Its sign changes at a simple
    /// bifurcation or a fold of the path (Allgower & Georg, *Introduction to
    /// Numerical Continuation Methods*, SIAM 2003, sec. 8.1).
    pub fn determinant(&self) -> Option<f64> {
        self.lin.determinant()
    }

    /// The inputs and tip loads at `lambda`; the robot's distributed loads
    /// set to theirs.
    fn set(&mut self, lambda: f64) -> (Vec<f64>, Loads) {
        let (a, b) = (&self.from, &self.to);
        let mix = |p: f64, q: f64| p + lambda * (q - p);
        let mix3 = |p: &Vector3<f64>, q: &Vector3<f64>| p + (q - p) * lambda;
        let body = &mut self.at.body;
        // the distributed force is carried whole by `distributed_force`
        body.gravity = Vector3::zeros();
        body.distributed_force = mix3(&a.distributed_force, &b.distributed_force);
        body.distributed_moment = mix3(&a.distributed_moment, &b.distributed_moment);
        // a corrector may look past an end of the path, where an input can
        // leave its law's range: the inputs are held at the range's edge
        let inputs =
            (a.inputs.iter().zip(&b.inputs).zip(&self.robot.actuators)).map(|((&p, &q), act)| {
                let (lo, hi) = act.law.input_bounds();
                mix(p, q).clamp(lo, hi)
            });
        let loads = Loads {
            tip_force: mix3(&a.loads.tip_force, &b.loads.tip_force),
            tip_moment: mix3(&a.loads.tip_moment, &b.loads.tip_moment),
        };
        (inputs.collect(), loads)
    }

    /// `G(x, lambda)` into `f`, and with `jacobian` the Jacobian `G_x`
    /// factorised into `self.lu` (`self.singular` says if it is singular).
    fn eval(&mut self, x: &[f64], lambda: f64, f: &mut [f64], jacobian: bool) -> Result<()> {
        let (inputs, loads) = self.set(lambda);
        let charts = self.charts.clone();
        let mut ms =
            MultipleShooting::new(&self.at, &inputs, loads, self.steps, &self.starts, charts)?;
        ms.set_hints(&self.hints);
        let out = match jacobian {
            true => ms.linearise(x, f).and_then(|_| self.lin.factorise(&ms)),
            false => ms.residual(x, f),
        };
        self.hints = ms.hints();
        self.work += ms.work;
        self.floor = ms.rounding_floor(x);
        out
    }
}

impl ParametrisedSystem for LoadPath<'_> {
    fn dim(&self) -> usize {
        super::ms::unknowns(self.robot.actuators.len(), self.starts.len())
    }
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
        super::cancel::check()?;
        self.eval(x, lambda, f, false)
    }
    /// The Jacobian `A = G_x` factorised as a staircase; `G_lambda` by a
    /// one-sided difference of step `sqrt(eps)` toward the inside of the
    /// path (error `~sqrt(eps)` relative, which leaves the corrector's
    /// convergence quadratic to that level; one residual more per
    /// linearisation).
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()> {
        super::cancel::check()?;
        self.eval(x, lambda, f, true)?;
        let h = f64::EPSILON.sqrt() * if lambda > 0.5 { -1.0 } else { 1.0 };
        let mut fh = vec![0.0; f.len()];
        self.eval(x, lambda + h, &mut fh, false)?;
        let g_lambda = fh.iter().zip(f.iter()).map(|(a, b)| (a - b) / h).collect();
        self.lin.border(g_lambda, row)
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
    /// The rounding floor of `max |G_i|` at the last evaluation, which the
    /// continuation asks for at the point it has just evaluated: `4 eps`
    /// times the largest term of any row (the forward solve's,
    /// [`MultipleShooting`]). A heavy body's terms reach `1e-10` relative
    /// to the residual's scale, where a corrector at a fixed `1e-10` would
    /// stall.
    fn floor(&self, _x: &[f64], _f: &[f64]) -> f64 {
        self.floor
    }
    fn work(&self) -> f64 {
        self.work
    }
    /// Where every input `a + lambda (b - a)` lies within its law's range:
    /// beyond, the inputs are held at the range's edge and `G` no longer
    /// depends on `lambda` through them.
    fn domain(&self) -> (f64, f64) {
        let ends = self.from.inputs.iter().zip(&self.to.inputs);
        let laws = ends.zip(&self.robot.actuators).filter(|((a, b), _)| a != b);
        laws.fold(
            (f64::NEG_INFINITY, f64::INFINITY),
            |(lo, hi), ((&a, &b), act)| {
                let (min, max) = act.law.input_bounds();
                let (p, q) = ((min - a) / (b - a), (max - a) / (b - a));
                (lo.max(p.min(q)), hi.min(p.max(q)))
            },
        )
    }
}

/// `robot` with no load: the path's start for a cold solve, whose
/// reference configuration (the reference strains, zero tensions at the
/// reference inputs) is its exact solution.
pub fn unloaded(robot: &Robot) -> Robot {
    let mut r = robot.clone();
    r.body.gravity = Vector3::zeros();
    r.body.distributed_force = Vector3::zeros();
    r.body.distributed_moment = Vector3::zeros();
    r.body.tip_force = Vector3::zeros();
    r.body.tip_moment = Vector3::zeros();
    r
}
