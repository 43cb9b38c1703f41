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

use super::abd::Staircase;
use super::arclength::ParametrisedSystem;
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
    lu: Option<Staircase>,
    /// `G_lambda`, `A^-1 G_lambda` and the border row of the last linearisation.
    g_lambda: Vec<f64>,
    a_inv_g: Vec<f64>,
    row: (Vec<f64>, f64),
    singular: bool,
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
            lu: None,
            g_lambda: Vec::new(),
            a_inv_g: Vec::new(),
            row: (Vec::new(), 0.0),
            singular: false,
            work: 0.0,
            floor: 0.0,
            hints: Vec::new(),
        }
    }

    /// `det G_x`, the determinant of the scaled multiple-shooting Jacobian
    /// at the last linearisation ([`ParametrisedSystem::linearise_bordered`]),
    /// from its staircase factors ([`Staircase::determinant`]); `None` before
    /// one, or where it was singular. Its sign changes at a simple
    /// bifurcation or a fold of the path (Allgower & Georg, *Introduction to
    /// Numerical Continuation Methods*, SIAM 2003, sec. 8.1).
    pub fn determinant(&self) -> Option<f64> {
        match self.singular {
            true => None,
            false => self.lu.as_ref().and_then(Staircase::determinant),
        }
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
            true => ms.linearise(x, f).and_then(|_| {
                let lu = match self.lu.take() {
                    Some(lu) if lu.shape().rows == ms.rows() && lu.shape().cols == ms.cols() => lu,
                    _ => ms.staircase()?,
                };
                self.singular = ms.factorise(self.lu.insert(lu));
                Ok(())
            }),
            false => ms.residual(x, f),
        };
        self.hints = ms.hints();
        self.work += ms.work;
        self.floor = ms.rounding_floor(x);
        out
    }

    /// Solve `A dx = b` in place with the last factorisation.
    fn solve_a(&self, b: &mut [f64]) -> Result<()> {
        match &self.lu {
            Some(lu) => lu.solve(b),
            None => Ok(()),
        }
    }

    /// One block elimination of the bordered system `[[A, g], [r^T,
    /// r_l]] (dx, dl) = (b, c)` (Govaerts, *Numerical Methods for
    /// Bifurcations of Dynamical Equilibria*, SIAM 2000, sec. 3.3).
    fn eliminate(&self, b: &[f64], c: f64, dx: &mut [f64]) -> Result<f64> {
        dx.copy_from_slice(b);
        self.solve_a(dx)?;
        let (r, rl) = (&self.row.0, self.row.1);
        let dot = |u: &[f64]| u.iter().zip(r).map(|(p, q)| p * q).sum::<f64>();
        let dl = (c - dot(dx)) / (rl - dot(&self.a_inv_g));
        for (d, v) in dx.iter_mut().zip(&self.a_inv_g) {
            *d -= dl * v;
        }
        Ok(dl)
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
        self.g_lambda = fh.iter().zip(f.iter()).map(|(a, b)| (a - b) / h).collect();
        self.row = (row.0.to_vec(), row.1);
        self.a_inv_g = self.g_lambda.clone();
        if !self.singular {
            let mut v = std::mem::take(&mut self.a_inv_g);
            self.solve_a(&mut v)?;
            self.a_inv_g = v;
        }
        Ok(())
    }
    /// Block elimination and one step of iterative refinement on the whole
    /// bordered system, stable also where `A` is nearly singular (a fold;
    /// Govaerts & Pryce, "Block elimination with one refinement solves
    /// bordered linear systems accurately", BIT 30, 1990).
    fn solve_bordered(
        &mut self,
        b: &[f64],
        b_last: f64,
        dx: &mut [f64],
        dlambda: &mut f64,
    ) -> Result<bool> {
        if self.singular {
            return Ok(false);
        }
        let dl = self.eliminate(b, b_last, dx)?;
        // the residual of the bordered system at (dx, dl)
        let n = dx.len();
        let mut ax = vec![0.0; n];
        if let Some(lu) = &self.lu {
            lu.mul(dx, &mut ax)?;
        }
        let rb: Vec<f64> = (0..n)
            .map(|i| b[i] - ax[i] - self.g_lambda[i] * dl)
            .collect();
        let rdot: f64 = dx.iter().zip(&self.row.0).map(|(p, q)| p * q).sum();
        let rc = b_last - rdot - self.row.1 * dl;
        let mut cx = vec![0.0; n];
        let cl = self.eliminate(&rb, rc, &mut cx)?;
        for (d, c) in dx.iter_mut().zip(&cx) {
            *d += c;
        }
        *dlambda = dl + cl;
        Ok(dx.iter().all(|v| v.is_finite()) && dlambda.is_finite())
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
