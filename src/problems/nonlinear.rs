//! Classic test problems for nonlinear equation solvers, shared by the tests
//! of [`crate::solve::nleq`], the benches and the continuation tests.
//!
//! From J. J. Moré, B. S. Garbow & K. E. Hillstrom, "Testing unconstrained
//! optimization software", ACM TOMS 7 (1981) 17-41 (MGH, problem numbers
//! below), written as square systems `F(x) = 0` (their `f_i`, not the sum of
//! squares): [`Rosenbrock`] (problem 1), [`PowellBadlyScaled`] (problem
//! 3), [`PowellSingular`] (problem 13, singular Jacobian at the root),
//! [`BrownAlmostLinear`] (problem 27) and [`BroydenTridiagonal`] (problem
//! 30). Besides: the finite-difference 1-D [`Bratu`] problem (a fold at
//! `lambda_c = 3.5138`), a piecewise-smooth penalised [`Obstacle`] problem
//! (a kink from a `max(0, .)` contact law; its Jacobian is the derivative
//! of the active piece), and [`Noisy`], which adds deterministic rounding-like noise to a
//! residual.
//!
//! Each problem implements [`TestProblem`]; [`Dense`] makes it a
//! [`NonlinearSystem`] with a dense LU factorisation (partial pivoting) and
//! counts work: a residual is 1 unit, a linearisation (residual and
//! Jacobian) 2 units.
//!
//! Rounding floors ([`TestProblem::floor`]) are the a priori bound
//! `m eps sum_j |t_j|` on the rounding error of a component computed as a sum
//! of `m` terms `t_j` (each term itself exact to a few ulps): `gamma_m
//! sum |t_j|` with `gamma_m ~ m u`, `u = eps/2` (N. J. Higham, *Accuracy and
//! Stability of Numerical Algorithms*, 2nd ed., SIAM 2002, Sec. 4.2), with a
//! factor 2 for the terms' own rounding; the max over components.

use nalgebra::{DMatrix, DVector, Dyn, LU};

use crate::error::Result;
use crate::solve::nleq::NonlinearSystem;

/// A square test system with an analytic (generalised) Jacobian.
pub trait TestProblem {
    /// Short name for tables.
    fn name(&self) -> &'static str;
    /// Number of unknowns and equations.
    fn dim(&self) -> usize;
    /// The standard starting point.
    fn start(&self) -> Vec<f64>;
    /// `F(x)` into `f`.
    fn residual(&self, x: &[f64], f: &mut [f64]);
    /// The Jacobian at `x` into `jac` (zeroed by the caller).
    fn jacobian(&self, x: &[f64], jac: &mut DMatrix<f64>);
    /// Rounding floor of `max |F|` at `x` (see the module docs).
    fn floor(&self, x: &[f64]) -> f64;
    /// A known root, if one is known in closed form.
    fn solution(&self) -> Option<Vec<f64>> {
        None
    }
}

/// `m eps sum |t_j|` for the terms `t_j` of one residual component.
fn bound(terms: &[f64]) -> f64 {
    terms.len() as f64 * f64::EPSILON * terms.iter().map(|t| t.abs()).sum::<f64>()
}

/// A [`TestProblem`] as a [`NonlinearSystem`]: dense LU with partial
/// pivoting, call counts, work = residuals + 2 linearisations.
#[derive(Debug, Clone)]
pub struct Dense<P> {
    /// The problem.
    pub problem: P,
    lu: Option<LU<f64, Dyn, Dyn>>,
    rhs: DVector<f64>,
    /// Calls of `residual`.
    pub residuals: usize,
    /// Calls of `linearise`.
    pub linearisations: usize,
    /// Calls of `solve`.
    pub solves: usize,
}

impl<P: TestProblem> Dense<P> {
    /// Wrap `problem`.
    pub fn new(problem: P) -> Self {
        let n = problem.dim();
        Dense {
            problem,
            lu: None,
            rhs: DVector::zeros(n),
            residuals: 0,
            linearisations: 0,
            solves: 0,
        }
    }
}

impl<P: TestProblem> NonlinearSystem for Dense<P> {
    fn dim(&self) -> usize {
        self.problem.dim()
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        self.residuals += 1;
        self.problem.residual(x, f);
        Ok(())
    }
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        self.linearisations += 1;
        self.problem.residual(x, f);
        let n = self.problem.dim();
        let mut jac = DMatrix::zeros(n, n);
        self.problem.jacobian(x, &mut jac);
        self.lu = Some(jac.lu());
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool> {
        self.solves += 1;
        let Some(lu) = &self.lu else {
            return Ok(false);
        };
        if self.rhs.len() != b.len() {
            self.rhs = DVector::zeros(b.len());
        }
        self.rhs.as_mut_slice().copy_from_slice(b);
        if !lu.solve_mut(&mut self.rhs) {
            return Ok(false);
        }
        dx.copy_from_slice(self.rhs.as_slice());
        Ok(dx.iter().all(|v| v.is_finite()))
    }
    fn floor(&self, x: &[f64], _f: &[f64]) -> f64 {
        self.problem.floor(x)
    }
    fn work(&self) -> f64 {
        self.residuals as f64 + 2.0 * self.linearisations as f64
    }
}

/// MGH problem 1, Rosenbrock's function as the system `10 (x2 - x1^2) = 0`,
/// `1 - x1 = 0`; start `(-1.2, 1)`, root `(1, 1)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rosenbrock;

impl TestProblem for Rosenbrock {
    fn name(&self) -> &'static str {
        "Rosenbrock"
    }
    fn dim(&self) -> usize {
        2
    }
    fn start(&self) -> Vec<f64> {
        vec![-1.2, 1.0]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        f[0] = 10.0 * (x[1] - x[0] * x[0]);
        f[1] = 1.0 - x[0];
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        j[(0, 0)] = -20.0 * x[0];
        j[(0, 1)] = 10.0;
        j[(1, 0)] = -1.0;
    }
    fn floor(&self, x: &[f64]) -> f64 {
        bound(&[10.0 * x[1], 10.0 * x[0] * x[0]]).max(bound(&[1.0, x[0]]))
    }
    fn solution(&self) -> Option<Vec<f64>> {
        Some(vec![1.0, 1.0])
    }
}

/// MGH problem 3, Powell's badly scaled function: `1e4 x1 x2 - 1 = 0`,
/// `exp(-x1) + exp(-x2) - 1.0001 = 0`; start `(0, 1)`, root
/// `(1.098159...e-5, 9.106146...)`: unknowns six orders apart.
#[derive(Debug, Clone, Copy, Default)]
pub struct PowellBadlyScaled;

impl PowellBadlyScaled {
    /// The root to the digits given by MGH.
    pub const ROOT: [f64; 2] = [1.098159e-5, 9.106146];
}

impl TestProblem for PowellBadlyScaled {
    fn name(&self) -> &'static str {
        "Powell badly scaled"
    }
    fn dim(&self) -> usize {
        2
    }
    fn start(&self) -> Vec<f64> {
        vec![0.0, 1.0]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        f[0] = 1e4 * x[0] * x[1] - 1.0;
        f[1] = (-x[0]).exp() + (-x[1]).exp() - 1.0001;
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        j[(0, 0)] = 1e4 * x[1];
        j[(0, 1)] = 1e4 * x[0];
        j[(1, 0)] = -(-x[0]).exp();
        j[(1, 1)] = -(-x[1]).exp();
    }
    fn floor(&self, x: &[f64]) -> f64 {
        let f0 = bound(&[1e4 * x[0] * x[1], 1.0]);
        f0.max(bound(&[(-x[0]).exp(), (-x[1]).exp(), 1.0001]))
    }
}

/// MGH problem 13, Powell's singular function: `x1 + 10 x2`, `sqrt(5) (x3 - x4)`,
/// `(x2 - 2 x3)^2`, `sqrt(10) (x1 - x4)^2`; start `(3, -1, 0, 1)`, root 0,
/// where the Jacobian is singular (rank 2): Newton converges only linearly.
#[derive(Debug, Clone, Copy, Default)]
pub struct PowellSingular;

impl TestProblem for PowellSingular {
    fn name(&self) -> &'static str {
        "Powell singular"
    }
    fn dim(&self) -> usize {
        4
    }
    fn start(&self) -> Vec<f64> {
        vec![3.0, -1.0, 0.0, 1.0]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        f[0] = x[0] + 10.0 * x[1];
        f[1] = 5f64.sqrt() * (x[2] - x[3]);
        f[2] = (x[1] - 2.0 * x[2]).powi(2);
        f[3] = 10f64.sqrt() * (x[0] - x[3]).powi(2);
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        let (a, b) = (x[1] - 2.0 * x[2], x[0] - x[3]);
        j[(0, 0)] = 1.0;
        j[(0, 1)] = 10.0;
        j[(1, 2)] = 5f64.sqrt();
        j[(1, 3)] = -(5f64.sqrt());
        j[(2, 1)] = 2.0 * a;
        j[(2, 2)] = -4.0 * a;
        j[(3, 0)] = 2.0 * 10f64.sqrt() * b;
        j[(3, 3)] = -2.0 * 10f64.sqrt() * b;
    }
    fn floor(&self, x: &[f64]) -> f64 {
        let (a, b) = (x[1].abs() + 2.0 * x[2].abs(), x[0].abs() + x[3].abs());
        let rows = [
            bound(&[x[0], 10.0 * x[1]]),
            bound(&[3.0 * x[2], 3.0 * x[3]]),
            bound(&[a * a, a * a]),
            bound(&[4.0 * b * b, 4.0 * b * b]),
        ];
        rows.into_iter().fold(0.0, f64::max)
    }
    fn solution(&self) -> Option<Vec<f64>> {
        Some(vec![0.0; 4])
    }
}

/// MGH problem 30, Broyden's tridiagonal function:
/// `(3 - 2 x_i) x_i - x_{i-1} - 2 x_{i+1} + 1 = 0` with `x_0 = x_{n+1} = 0`;
/// start `x_i = -1`. The Jacobian `tridiag(-1, 3 - 4 x_i, -2)` is strictly
/// diagonally dominant near the root (`x_i` in about `[-0.7, -0.4]`).
#[derive(Debug, Clone, Copy)]
pub struct BroydenTridiagonal {
    /// Dimension (MGH: variable; 10 here by default).
    pub n: usize,
}

impl Default for BroydenTridiagonal {
    fn default() -> Self {
        BroydenTridiagonal { n: 10 }
    }
}

impl TestProblem for BroydenTridiagonal {
    fn name(&self) -> &'static str {
        "Broyden tridiagonal"
    }
    fn dim(&self) -> usize {
        self.n
    }
    fn start(&self) -> Vec<f64> {
        vec![-1.0; self.n]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            let left = if i > 0 { x[i - 1] } else { 0.0 };
            let right = if i + 1 < n { x[i + 1] } else { 0.0 };
            f[i] = (3.0 - 2.0 * x[i]) * x[i] - left - 2.0 * right + 1.0;
        }
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        for i in 0..self.n {
            j[(i, i)] = 3.0 - 4.0 * x[i];
            if i > 0 {
                j[(i, i - 1)] = -1.0;
            }
            if i + 1 < self.n {
                j[(i, i + 1)] = -2.0;
            }
        }
    }
    fn floor(&self, x: &[f64]) -> f64 {
        let at = |i: usize| x.get(i).copied().unwrap_or(0.0);
        (0..self.n)
            .map(|i| {
                let left = if i > 0 { at(i - 1) } else { 0.0 };
                bound(&[3.0 * x[i], 2.0 * x[i] * x[i], left, 2.0 * at(i + 1), 1.0])
            })
            .fold(0.0, f64::max)
    }
}

/// MGH problem 27, Brown's almost-linear function: `x_i + sum_j x_j - (n + 1) = 0`
/// for `i < n`, `prod_j x_j - 1 = 0`; start `x_i = 1/2`. Roots
/// `(a, ..., a, a^(1-n))` with `n a^n - (n + 1) a^(n-1) + 1 = 0`, among them
/// `a = 1`. From the standard start the Newton path runs into singular
/// Jacobians before any root, so affine covariant damped Newton methods
/// (NLEQ1, NLEQ-ERR, NLEQ-RES in ZIB's test set) stop there; a start at
/// `x_i = 1.02` converges.
#[derive(Debug, Clone, Copy)]
pub struct BrownAlmostLinear {
    /// Dimension (10 by default).
    pub n: usize,
}

impl Default for BrownAlmostLinear {
    fn default() -> Self {
        BrownAlmostLinear { n: 10 }
    }
}

impl TestProblem for BrownAlmostLinear {
    fn name(&self) -> &'static str {
        "Brown almost-linear"
    }
    fn dim(&self) -> usize {
        self.n
    }
    fn start(&self) -> Vec<f64> {
        vec![0.5; self.n]
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        let n = self.n;
        let sum: f64 = x.iter().sum();
        for i in 0..n - 1 {
            f[i] = x[i] + sum - (n as f64 + 1.0);
        }
        f[n - 1] = x.iter().product::<f64>() - 1.0;
    }
    fn jacobian(&self, x: &[f64], j: &mut DMatrix<f64>) {
        let n = self.n;
        for i in 0..n - 1 {
            for k in 0..n {
                j[(i, k)] = if i == k { 2.0 } else { 1.0 };
            }
        }
        // d(prod)/dx_k = product of the others, without dividing by x_k.
        let mut left = 1.0;
        for k in 0..n {
            let right: f64 = x[k + 1..].iter().product();
            j[(n - 1, k)] = left * right;
            left *= x[k];
        }
    }
    fn solution(&self) -> Option<Vec<f64>> {
        Some(vec![1.0; self.n])
    }
    fn floor(&self, x: &[f64]) -> f64 {
        let n = self.n;
        let sum_abs: f64 = x.iter().map(|v| v.abs()).sum();
        let linear = (n + 2) as f64 * f64::EPSILON * (2.0 * sum_abs + n as f64 + 1.0);
        let prod = x.iter().map(|v| v.abs()).product::<f64>();
        linear.max(bound(&[n as f64 * prod, 1.0]))
    }
}

/// The 1-D Bratu (Liouville-Gelfand) problem `u'' + lambda e^u = 0`,
/// `u(0) = u(1) = 0`, by central differences on `n` interior nodes
/// (`h = 1/(n + 1)`): `(u_{i-1} - 2 u_i + u_{i+1}) / h^2 + lambda e^(u_i) = 0`.
/// Start `u = 0`. Solutions exist for `lambda <= lambda_c = 3.51383`; the
/// lower branch is `u(t) = -2 ln(cosh((t - 1/2) theta/2) / cosh(theta/4))`
/// with the smaller root of `theta = sqrt(2 lambda) cosh(theta/4)`
/// ([`Bratu::exact`]; the finite-difference solution differs by `O(h^2)`).
/// (Also scipy's `solve_bvp` example; J. Jacobsen & K. Schmitt, J. Differential
/// Equations 184 (2002) 283-298.)
#[derive(Debug, Clone, Copy)]
pub struct Bratu {
    /// Interior nodes.
    pub n: usize,
    /// The load parameter `lambda`.
    pub lambda: f64,
}

/// `theta_c / 4`, the root of `s tanh(s) = 1`: the fold of the Bratu problem,
/// `lambda_c = 8 s^2 / cosh(s)^2 = 3.513830719`.
const BRATU_FOLD_S: f64 = 1.199_678_640_257_734;

impl Bratu {
    /// `n = 50` nodes at `lambda`.
    pub fn new(lambda: f64) -> Self {
        Bratu { n: 50, lambda }
    }

    /// The lower-branch solution of the differential equation at `t` in
    /// `[0, 1]`; `None` for `lambda` outside `(0, lambda_c]`.
    pub fn exact(lambda: f64, t: f64) -> Option<f64> {
        let g = |theta: f64| (2.0 * lambda).sqrt() * (theta / 4.0).cosh() - theta;
        let (mut lo, mut hi) = (0.0, 4.0 * BRATU_FOLD_S);
        if !(lambda > 0.0 && g(hi) <= 0.0) {
            return None;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let theta = 0.5 * (lo + hi);
        Some(-2.0 * (((t - 0.5) * theta / 2.0).cosh() / (theta / 4.0).cosh()).ln())
    }

    fn h(&self) -> f64 {
        1.0 / (self.n as f64 + 1.0)
    }
}

impl TestProblem for Bratu {
    fn name(&self) -> &'static str {
        "Bratu"
    }
    fn dim(&self) -> usize {
        self.n
    }
    fn start(&self) -> Vec<f64> {
        vec![0.0; self.n]
    }
    fn residual(&self, u: &[f64], f: &mut [f64]) {
        let (n, h2) = (self.n, self.h() * self.h());
        for i in 0..n {
            let left = if i > 0 { u[i - 1] } else { 0.0 };
            let right = if i + 1 < n { u[i + 1] } else { 0.0 };
            f[i] = (left - 2.0 * u[i] + right) / h2 + self.lambda * u[i].exp();
        }
    }
    fn jacobian(&self, u: &[f64], j: &mut DMatrix<f64>) {
        let (n, h2) = (self.n, self.h() * self.h());
        for i in 0..n {
            j[(i, i)] = -2.0 / h2 + self.lambda * u[i].exp();
            if i > 0 {
                j[(i, i - 1)] = 1.0 / h2;
            }
            if i + 1 < n {
                j[(i, i + 1)] = 1.0 / h2;
            }
        }
    }
    fn floor(&self, u: &[f64]) -> f64 {
        let h2 = self.h() * self.h();
        let at = |i: usize| u.get(i).copied().unwrap_or(0.0);
        (0..self.n)
            .map(|i| {
                let left = if i > 0 { at(i - 1) } else { 0.0 };
                let lap = [left / h2, 2.0 * u[i] / h2, at(i + 1) / h2];
                bound(&[lap[0], lap[1], lap[2], self.lambda * u[i].exp()])
            })
            .fold(0.0, f64::max)
    }
}

/// A piecewise-smooth problem: a string on a cubic elastic foundation pushed
/// by a uniform load `p` against a stiff unilateral support (penalty `k` on
/// the penetration `max(0, u - g)`), by central differences on `n` interior
/// nodes: `-(u_{i-1} - 2 u_i + u_{i+1}) / h^2 + u_i^3 + k max(0, u_i - g) - p
/// = 0`. `F` is Lipschitz and semismooth but not differentiable where
/// `u_i = g`; the Jacobian is the derivative of the active piece (`k` where
/// `u_i > g`, else 0), an element of Clarke's generalised Jacobian, so
/// Newton's method is the semismooth Newton method (L. Qi & J. Sun, Math.
/// Program. 58, 1993; the primal-dual active set method of M. Hintermüller,
/// K. Ito & K. Kunisch, SIAM J. Optim. 13, 2002). Start `u = 0` (no contact);
/// at the root a middle band of nodes is in contact. The error-oriented
/// damping models `F` as smooth; with a support much stiffer than the
/// string's lowest mode (`pi^2`), steps across the kink fail its test and the
/// iteration creeps (`k = 1e3`: 77 steps, past the default limit, against 8
/// at `k = 30`).
#[derive(Debug, Clone, Copy)]
pub struct Obstacle {
    /// Interior nodes.
    pub n: usize,
    /// Support stiffness (penalty).
    pub k: f64,
    /// Gap to the support.
    pub g: f64,
    /// Load.
    pub p: f64,
}

impl Default for Obstacle {
    /// `n = 20`, `k = 30`, `g = 1`, `p = 20`: without the support the peak
    /// deflection would be about `p/8 = 2.5 > g`.
    fn default() -> Self {
        Obstacle {
            n: 20,
            k: 30.0,
            g: 1.0,
            p: 20.0,
        }
    }
}

impl Obstacle {
    fn h2(&self) -> f64 {
        (1.0 / (self.n as f64 + 1.0)).powi(2)
    }

    /// Nodes in contact (`u_i > g`).
    pub fn contacts(&self, u: &[f64]) -> usize {
        u.iter().filter(|&&v| v > self.g).count()
    }
}

impl TestProblem for Obstacle {
    fn name(&self) -> &'static str {
        "Obstacle (kink)"
    }
    fn dim(&self) -> usize {
        self.n
    }
    fn start(&self) -> Vec<f64> {
        vec![0.0; self.n]
    }
    fn residual(&self, u: &[f64], f: &mut [f64]) {
        let (n, h2) = (self.n, self.h2());
        for i in 0..n {
            let left = if i > 0 { u[i - 1] } else { 0.0 };
            let right = if i + 1 < n { u[i + 1] } else { 0.0 };
            let contact = self.k * (u[i] - self.g).max(0.0);
            f[i] = -(left - 2.0 * u[i] + right) / h2 + u[i].powi(3) + contact - self.p;
        }
    }
    fn jacobian(&self, u: &[f64], j: &mut DMatrix<f64>) {
        let (n, h2) = (self.n, self.h2());
        for i in 0..n {
            let active = if u[i] > self.g { self.k } else { 0.0 };
            j[(i, i)] = 2.0 / h2 + 3.0 * u[i] * u[i] + active;
            if i > 0 {
                j[(i, i - 1)] = -1.0 / h2;
            }
            if i + 1 < n {
                j[(i, i + 1)] = -1.0 / h2;
            }
        }
    }
    fn floor(&self, u: &[f64]) -> f64 {
        let h2 = self.h2();
        let at = |i: usize| u.get(i).copied().unwrap_or(0.0);
        (0..self.n)
            .map(|i| {
                let left = if i > 0 { at(i - 1) } else { 0.0 };
                let contact = self.k * (u[i].abs() + self.g);
                let cubic = u[i].powi(3);
                bound(&[
                    left / h2,
                    2.0 * u[i] / h2,
                    at(i + 1) / h2,
                    cubic,
                    contact,
                    self.p,
                ])
            })
            .fold(0.0, f64::max)
    }
}

/// A problem with deterministic pseudo-noise of amplitude `noise` added to
/// every residual component (a hash of the bits of `x`, so `F` stays a
/// function of `x`), reporting the rounding floor `floor`. The Jacobian is
/// the inner problem's.
#[derive(Debug, Clone, Copy)]
pub struct Noisy<P> {
    /// The smooth problem.
    pub inner: P,
    /// Noise amplitude: each component is perturbed by at most this.
    pub noise: f64,
    /// The floor reported.
    pub floor: f64,
}

impl<P: TestProblem> TestProblem for Noisy<P> {
    fn name(&self) -> &'static str {
        "noisy"
    }
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn start(&self) -> Vec<f64> {
        self.inner.start()
    }
    fn residual(&self, x: &[f64], f: &mut [f64]) {
        self.inner.residual(x, f);
        let seed = x.iter().fold(0x9e37_79b9_7f4a_7c15_u64, |h, v| {
            splitmix64(h ^ v.to_bits())
        });
        for (i, fi) in f.iter_mut().enumerate() {
            let r = splitmix64(seed.wrapping_add(i as u64));
            // Uniform in [-1, 1) from the top 53 bits.
            let u = (r >> 11) as f64 / (1u64 << 52) as f64 - 1.0;
            *fi += self.noise * u;
        }
    }
    fn jacobian(&self, x: &[f64], jac: &mut DMatrix<f64>) {
        self.inner.jacobian(x, jac);
    }
    fn floor(&self, _x: &[f64]) -> f64 {
        self.floor
    }
}

/// SplitMix64 (S. Vigna's reference mixer): a bijective 64-bit hash.
pub fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
