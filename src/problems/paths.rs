//! Parametrised test problems of the pseudo-arclength continuation
//! ([`crate::solve::arclength`]), shared by its tests and the benches.
//!
//! Each problem is a [`Model`] (the residual `G(x, lambda)` with its exact
//! derivatives `G_x`, `G_lambda`) wrapped in [`Bordered`], which implements
//! [`ParametrisedSystem`] by a dense LU factorisation (partial pivoting,
//! nalgebra) of the bordered matrix `[[G_x, G_lambda], [row]]`:
//!
//! - [`Circle`]: `x^2 + lambda^2 - 1 = 0`, folds at `lambda = -1, 1`; a
//!   closed branch.
//! - [`SCurve`]: `x^3 - x - lambda + c = 0`, folds at
//!   `lambda = c -+ 2 / (3 sqrt 3)` (`x = -+1/sqrt 3`).
//! - [`Bratu`]: `u'' + lambda e^u = 0` on `(0, 1)`, `u(0) = u(1) = 0`, by
//!   central differences on `n` interior nodes ([`nonlinear::Bratu`] with
//!   `lambda` free); one fold (`lambda* = 3.513830719` for the differential
//!   equation), two solutions below it.
//! - [`NewtonHomotopy`]: `F(x) - (1 - lambda) F(x0)` for a [`TestProblem`]
//!   `F` of [`nonlinear`] (Moré-Garbow-Hillstrom) or [`FreudensteinRoth`]:
//!   `x0` solves it at `lambda = 0`, a root of `F` at `lambda = 1`.
//!
//! [`cases`] lists paths through them (starts and targets) for the benches.
//!
//! Work ([`ParametrisedSystem::work`]) counts a residual as 1 and a
//! linearisation as `1 + n`, the residual and a forward-difference
//! Jacobian, as a rod problem counts IVPs (so a Jacobian is as dear here as
//! there; [`nonlinear::Dense`] counts an analytic one as 2).

use nalgebra::{DMatrix, DVector, Dyn, LU};

use super::nonlinear::{self, PowellBadlyScaled, TestProblem};
use crate::error::Result;
use crate::solve::arclength::{Heading, ParametrisedSystem};

/// A smooth parametrised residual with exact derivatives.
pub trait Model {
    /// `n`.
    fn dim(&self) -> usize;
    /// `G(x, lambda)` into `f`.
    fn eval(&self, x: &[f64], lambda: f64, f: &mut [f64]);
    /// `G_x` into `gx` (`n x n`, zeroed) and `G_lambda` into `gl`.
    fn jacobian(&self, x: &[f64], lambda: f64, gx: &mut DMatrix<f64>, gl: &mut [f64]);
    /// Rounding floor of `max |G_i(x, lambda)|` (0: none known).
    fn floor(&self, _x: &[f64], _lambda: f64) -> f64 {
        0.0
    }
}

/// A [`Model`] as a [`ParametrisedSystem`]: dense LU of the bordered matrix.
#[derive(Debug, Clone)]
pub struct Bordered<M> {
    /// The problem.
    pub model: M,
    /// Residual evaluations, those of the linearisations included.
    pub evaluations: usize,
    /// Linearisations (factorised bordered Jacobians).
    pub linearisations: usize,
    lu: Option<LU<f64, Dyn, Dyn>>,
    /// `lambda` of the last linearisation, for the floor.
    lambda: f64,
}

/// Pivots of the LU factorisation below this times the largest are taken
/// as zero: the bordered matrix is singular to working precision (a pivot
/// that small carries no correct digit after the `O(n eps)` backward error
/// of partial pivoting, `n <= 51` here; Higham 2002, ch. 9).
pub const SINGULAR_PIVOT: f64 = 1e3 * f64::EPSILON;

impl<M: Model> Bordered<M> {
    /// `model` with zero counts.
    pub fn new(model: M) -> Self {
        Self {
            model,
            evaluations: 0,
            linearisations: 0,
            lu: None,
            lambda: 0.0,
        }
    }

    /// Plain Newton at fixed `lambda` from `x` (full steps, `G_x` by LU):
    /// the solution once `max |G_i| <= tol`, `None` after 50 iterations or
    /// at a singular `G_x`. A reference independent of the continuation,
    /// from a start close to the solution wanted.
    pub fn newton(&self, x: &[f64], lambda: f64, tol: f64) -> Option<Vec<f64>> {
        let n = self.model.dim();
        let mut x = DVector::from_column_slice(x);
        let (mut f, mut gl) = (vec![0.0; n], vec![0.0; n]);
        for _ in 0..50 {
            self.model.eval(x.as_slice(), lambda, &mut f);
            if f.iter().all(|v| v.abs() <= tol) {
                return Some(x.as_slice().to_vec());
            }
            let mut gx = DMatrix::zeros(n, n);
            self.model.jacobian(x.as_slice(), lambda, &mut gx, &mut gl);
            x -= gx.lu().solve(&DVector::from_column_slice(&f))?;
        }
        None
    }
}

impl<M: Model> ParametrisedSystem for Bordered<M> {
    fn dim(&self) -> usize {
        self.model.dim()
    }

    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
        self.evaluations += 1;
        self.lambda = lambda;
        self.model.eval(x, lambda, f);
        Ok(())
    }

    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        (row, last): (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()> {
        let n = self.model.dim();
        self.residual(x, lambda, f)?;
        self.linearisations += 1;
        let mut gx = DMatrix::zeros(n, n);
        let mut gl = vec![0.0; n];
        self.model.jacobian(x, lambda, &mut gx, &mut gl);
        let mut a = DMatrix::zeros(n + 1, n + 1);
        a.view_mut((0, 0), (n, n)).copy_from(&gx);
        for i in 0..n {
            a[(i, n)] = gl[i];
            a[(n, i)] = row[i];
        }
        a[(n, n)] = last;
        self.lu = Some(a.lu());
        Ok(())
    }

    fn solve_bordered(
        &mut self,
        b: &[f64],
        b_last: f64,
        dx: &mut [f64],
        dlambda: &mut f64,
    ) -> Result<bool> {
        let Some(lu) = &self.lu else { return Ok(false) };
        let pivots = lu.u().diagonal().abs();
        if !(pivots.min() > SINGULAR_PIVOT * pivots.max()) {
            return Ok(false);
        }
        let rhs = DVector::from_iterator(b.len() + 1, b.iter().copied().chain([b_last]));
        let Some(sol) = lu.solve(&rhs) else {
            return Ok(false);
        };
        let n = b.len();
        dx.copy_from_slice(&sol.as_slice()[..n]);
        *dlambda = sol[n];
        Ok(sol.iter().all(|v| v.is_finite()))
    }

    /// The model's floor at the `lambda` last evaluated (the corrector asks
    /// right after evaluating there).
    fn floor(&self, x: &[f64], _f: &[f64]) -> f64 {
        self.model.floor(x, self.lambda)
    }

    fn work(&self) -> f64 {
        (self.evaluations + self.linearisations * self.model.dim()) as f64
    }
}

/// `x^2 + lambda^2 - 1 = 0`: the unit circle, folds at `lambda = +-1`
/// (`x = 0`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Circle;

impl Model for Circle {
    fn dim(&self) -> usize {
        1
    }
    fn eval(&self, x: &[f64], lambda: f64, f: &mut [f64]) {
        f[0] = x[0] * x[0] + lambda * lambda - 1.0;
    }
    fn jacobian(&self, x: &[f64], lambda: f64, gx: &mut DMatrix<f64>, gl: &mut [f64]) {
        gx[(0, 0)] = 2.0 * x[0];
        gl[0] = 2.0 * lambda;
    }
}

/// `x^3 - x - lambda + c = 0`: `lambda = x^3 - x + c`, an S with folds at
/// `x = -+1/sqrt(3)`, `lambda = c +- 2 / (3 sqrt 3)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct SCurve {
    /// The shift `c` of the S in `lambda`.
    pub c: f64,
}

impl SCurve {
    /// The folds' `lambda`, in the order a path from `x = -inf` meets them.
    pub fn folds(&self) -> [f64; 2] {
        let d = 2.0 / (3.0 * 3f64.sqrt());
        [self.c + d, self.c - d]
    }
}

impl Model for SCurve {
    fn dim(&self) -> usize {
        1
    }
    fn eval(&self, x: &[f64], lambda: f64, f: &mut [f64]) {
        f[0] = x[0].powi(3) - x[0] - lambda + self.c;
    }
    fn jacobian(&self, x: &[f64], _lambda: f64, gx: &mut DMatrix<f64>, gl: &mut [f64]) {
        gx[(0, 0)] = 3.0 * x[0] * x[0] - 1.0;
        gl[0] = -1.0;
    }
}

/// The finite-difference 1-D Bratu problem of [`nonlinear::Bratu`] with
/// `lambda` the parameter: `G_i = (u_{i-1} - 2 u_i + u_{i+1}) / h^2 +
/// lambda e^{u_i}` on `n` interior nodes, `h = 1 / (n + 1)`.
#[derive(Debug, Clone, Copy)]
pub struct Bratu {
    /// Interior nodes.
    pub n: usize,
}

/// Fold of the differential equation: `lambda* = theta^2 / (2 cosh^2(theta/4))`
/// at its maximum over `theta` (`theta = 4.798714561`).
pub const BRATU_FOLD: f64 = 3.513_830_719_125_16;

/// `max u` of the differential equation's two solutions at `lambda = 1`,
/// `2 ln cosh(theta / 4)` for the roots [`BRATU_THETA_AT_1`].
pub const BRATU_MAX_U_AT_1: [f64; 2] = [0.140_539_214_400_480, 4.091_467_246_189_26];

/// The roots `theta` of `theta = sqrt(2) cosh(theta / 4)`: the lower and
/// upper solutions at `lambda = 1`.
pub const BRATU_THETA_AT_1: [f64; 2] = [1.517_164_599_050_803, 10.938_702_772_122_106];

impl Bratu {
    fn at(&self, lambda: f64) -> nonlinear::Bratu {
        nonlinear::Bratu { n: self.n, lambda }
    }

    /// The differential equation's solution on the nodes for a root
    /// `theta` of `theta = sqrt(2 lambda) cosh(theta / 4)` (either branch):
    /// `u(s) = -2 ln(cosh((s - 1/2) theta / 2) / cosh(theta / 4))`.
    pub fn exact(&self, theta: f64) -> Vec<f64> {
        let h = 1.0 / (self.n + 1) as f64;
        let u = |s: f64| -2.0 * (((s - 0.5) * theta / 2.0).cosh() / (theta / 4.0).cosh()).ln();
        (1..=self.n).map(|i| u(i as f64 * h)).collect()
    }
}

impl Model for Bratu {
    fn dim(&self) -> usize {
        self.n
    }
    fn eval(&self, u: &[f64], lambda: f64, f: &mut [f64]) {
        self.at(lambda).residual(u, f);
    }
    fn jacobian(&self, u: &[f64], lambda: f64, gx: &mut DMatrix<f64>, gl: &mut [f64]) {
        self.at(lambda).jacobian(u, gx);
        gl.iter_mut().zip(u).for_each(|(g, ui)| *g = ui.exp());
    }
    fn floor(&self, u: &[f64], lambda: f64) -> f64 {
        self.at(lambda).floor(u)
    }
}

/// Freudenstein and Roth's function (MGH problem 2):
/// `F = (-13 + x1 + ((5 - x2) x2 - 2) x2, -29 + x1 + ((x2 + 1) x2 - 14) x2)`,
/// start `(0.5, -2)`, root `(5, 4)`; `|F|^2` has a local minimiser at
/// `(11.41, -0.8968)` (value 48.98) that draws descent methods from the start.
#[derive(Debug, Clone, Copy, Default)]
pub struct FreudensteinRoth;

impl TestProblem for FreudensteinRoth {
    fn name(&self) -> &'static str {
        "Freudenstein-Roth"
    }
    fn dim(&self) -> usize {
        2
    }
    fn start(&self) -> Vec<f64> {
        vec![0.5, -2.0]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        f[0] = -13.0 + x[0] + ((5.0 - x[1]) * x[1] - 2.0) * x[1];
        f[1] = -29.0 + x[0] + ((x[1] + 1.0) * x[1] - 14.0) * x[1];
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        j[(0, 0)] = 1.0;
        j[(0, 1)] = 10.0 * x[1] - 3.0 * x[1] * x[1] - 2.0;
        j[(1, 0)] = 1.0;
        j[(1, 1)] = 3.0 * x[1] * x[1] + 2.0 * x[1] - 14.0;
    }
    /// `m eps sum |t_j|` over the terms of the cubic (as [`nonlinear`]).
    fn floor(&self, x: &[f64]) -> f64 {
        let y = x[1].abs();
        let terms = 29.0 + x[0].abs() + y * y * y + 5.0 * y * y + 14.0 * y;
        5.0 * f64::EPSILON * terms
    }
    fn solution(&self) -> Option<Vec<f64>> {
        Some(vec![5.0, 4.0])
    }
}

/// The Newton homotopy `H(x, lambda) = F(x) - (1 - lambda) F(x0)`: `x0`
/// solves it at `lambda = 0`, a root of `F` at `lambda = 1`, where `H = F`
/// exactly.
#[derive(Debug, Clone)]
pub struct NewtonHomotopy<P> {
    /// `F`.
    pub problem: P,
    /// `F(x0)` at the start.
    pub f0: Vec<f64>,
}

impl<P: TestProblem> NewtonHomotopy<P> {
    /// The homotopy from `F`'s standard start, with that start.
    pub fn new(problem: P) -> (Self, Vec<f64>) {
        let x0 = problem.start();
        let mut f0 = vec![0.0; problem.dim()];
        problem.residual(&x0, &mut f0);
        (Self { problem, f0 }, x0)
    }
}

impl<P: TestProblem> Model for NewtonHomotopy<P> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn eval(&self, x: &[f64], lambda: f64, f: &mut [f64]) {
        self.problem.residual(x, f);
        f.iter_mut()
            .zip(&self.f0)
            .for_each(|(fi, f0)| *fi -= (1.0 - lambda) * f0);
    }
    fn jacobian(&self, x: &[f64], _lambda: f64, gx: &mut DMatrix<f64>, gl: &mut [f64]) {
        self.problem.jacobian(x, gx);
        gl.copy_from_slice(&self.f0);
    }
    /// `F`'s floor and the rounding of the `F(x0)` term.
    fn floor(&self, x: &[f64], _lambda: f64) -> f64 {
        let f0 = self.f0.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        self.problem.floor(x) + 2.0 * f64::EPSILON * f0
    }
}

/// A path to follow: a system, its start and target.
pub struct Case {
    /// Short name.
    pub name: &'static str,
    /// The system.
    pub system: Box<dyn ParametrisedSystem>,
    /// `x` at the start (a solution at `lambda0`).
    pub x0: Vec<f64>,
    /// `lambda` at the start.
    pub lambda0: f64,
    /// The target `lambda`.
    pub target: f64,
    /// The direction taken from the start.
    pub heading: Heading,
}

/// The paths of the tests and benches: the circle from `(-1, 0)` down
/// through its fold at `lambda = -1` to `lambda = 0.5` on `x > 0`; the S
/// (`c = 0`) from `(-2, -6)` through both folds to `lambda = 6`; Bratu
/// (`n = 50`) from the lower branch at `lambda = 2` up around its fold and
/// down the upper branch to `lambda = 1`; the Newton homotopies (`lambda`
/// from 0 to 1) of Powell's badly scaled function and of Freudenstein-Roth's
/// (through two folds).
pub fn cases() -> Vec<Case> {
    let bratu = Bordered::new(Bratu { n: 50 });
    let lower = bratu
        .newton(&[0.0; 50], 2.0, 1e-9)
        .expect("Newton from u = 0 at lambda = 2");
    let case = |name, (system, x0), lambda0, target, heading| Case {
        name,
        system,
        x0,
        lambda0,
        target,
        heading,
    };
    let (away, toward) = (Heading::AwayFromTarget, Heading::TowardTarget);
    let circle: Box<dyn ParametrisedSystem> = Box::new(Bordered::new(Circle));
    let s: Box<dyn ParametrisedSystem> = Box::new(Bordered::new(SCurve { c: 0.0 }));
    vec![
        case("circle", (circle, vec![-1.0]), 0.0, 0.5, away),
        case("s-curve", (s, vec![-2.0]), -6.0, 6.0, toward),
        case("bratu", (Box::new(bratu), lower), 2.0, 1.0, away),
        case("powell", boxed(PowellBadlyScaled), 0.0, 1.0, toward),
        case(
            "freudenstein-roth",
            boxed(FreudensteinRoth),
            0.0,
            1.0,
            toward,
        ),
    ]
}

/// The Newton homotopy of `p` as a boxed system, with its start.
fn boxed<P: TestProblem + 'static>(p: P) -> (Box<dyn ParametrisedSystem>, Vec<f64>) {
    let (h, x0) = NewtonHomotopy::new(p);
    (Box::new(Bordered::new(h)), x0)
}
