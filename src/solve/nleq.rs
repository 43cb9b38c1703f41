//! Error-oriented damped Newton method (NLEQ-ERR) for square systems `F(x) = 0`.
//!
//! Each iteration solves `J(x) dx = -F(x)` for the ordinary Newton correction
//! and tries `x + lambda dx` with the damping factor predicted from the
//! Kantorovich quantity of the previous step, `lambda = min(1, 1/[h])`,
//! `[h] = |dxbar - dx| |dx| / (|x - x_prev| |dxbar|)`. The trial is judged by
//! the simplified Newton correction `dxbar = -J(x)^-1 F(x + lambda dx)` (the
//! same factorisation: one residual and one solve more) with the restricted
//! monotonicity test `|dxbar| <= (1 - lambda/4) |dx|`; on failure `lambda`
//! drops to `min(lambda/2, 1/h_post)`, `h_post = 2 |dxbar - (1 - lambda) dx| /
//! (lambda^2 |dx|)`, and a trial whose residual cannot be evaluated halves
//! `lambda`. Every test measures corrections in the unknowns (scaled RMS
//! norm), never the residual, so the iteration is invariant under `F -> A F`
//! for any regular `A` (P. Deuflhard, *Newton Methods for Nonlinear
//! Problems*, Springer 2004, Sec. 3.3, algorithm NLEQ-ERR; U. Nowak & L.
//! Weimann, ZIB TR 91-10, 1991, code NLEQ1). After a full step that
//! contracted strongly the factorisation is kept for simplified Newton
//! (chord) steps while they gain more per unit of work than a new Jacobian
//! ([`CHORD_THETA`]). The Jacobian may be a generalised derivative of a
//! piecewise-smooth `F` (the derivative of the piece active at `x`): nothing
//! here assumes `F` is `C^2`; with such a Jacobian the iteration is the
//! semismooth Newton method, locally superlinear at a root whose generalised
//! Jacobians are all regular (L. Qi & J. Sun, Math. Program. 58, 1993). The
//! damping, though, models `F` as smooth: where the Jacobian jumps by much
//! (a stiff contact), steps that cross the kink fail the test and the
//! iteration creeps.
//!
//! The public contract is on the residual: the solve returns the first
//! evaluated point with `max |F| <= tol` ([`Status::Converged`]) or with
//! `max |F|` at most the system's rounding floor, or stalled within
//! [`FLOOR_FACTOR`] of it ([`Status::ConvergedAtFloor`]).

use std::time::Instant;

use super::cancel;
use crate::error::{Error, Result, StopReason};

/// A square system `F(x) = 0` as the damped Newton method sees it.
///
/// The residual is dimensionless (an order-one value is an order-one error)
/// and the unknowns of order one. `linearise` stores a factorisation of the
/// Jacobian (or of a generalised Jacobian of a piecewise-smooth `F`) that
/// `solve` reuses until the next `linearise`.
pub trait NonlinearSystem {
    /// Number of unknowns and of equations.
    fn dim(&self) -> usize;
    /// `F(x)` into `f`. An error other than `Interrupted`, `InvalidParameter`
    /// and `InvalidInput` (e.g. `Integration`) means `F` cannot be evaluated
    /// at `x`: the solver shortens its step.
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()>;
    /// `F(x)` into `f`, and the Jacobian at `x` factorised for [`Self::solve`].
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()>;
    /// `dx = J^-1 b` with the last linearisation; `Ok(false)` if `J` is singular.
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool>;
    /// Rounding floor of `max |F|` at `(x, f)`, the max-norm below which `F`
    /// cannot be reduced in floating point; 0 if unknown.
    fn floor(&self, _x: &[f64], _f: &[f64]) -> f64 {
        0.0
    }
    /// Work spent so far, in the system's units (e.g. IVP-equivalents).
    fn work(&self) -> f64;
}

/// Default smallest damping factor, NLEQ-ERR's and NLEQ1's for highly
/// nonlinear problems (Nowak & Weimann 1991): a trial at `1e-4 dx` that still
/// fails the test means `[h] > 1e4`, a linear model that does not describe
/// `F` over a ten-thousandth of the Newton correction.
pub const DEFAULT_LAMBDA_MIN: f64 = 1e-4;

/// Default iteration limit, NLEQ-ERR's: quadratic convergence takes a
/// handful of steps once `h < 1`, and at a singular root Newton converges
/// linearly with rate 1/2 (D. W. Decker & C. T. Kelley, SIAM J. Numer. Anal.
/// 17, 1980), about 40 steps from an order-one error to `1e-10`.
pub const DEFAULT_MAX_ITERATIONS: usize = 50;

/// Largest contraction `Theta = |dxbar| / |dx|` with which the factorisation
/// is kept for chord steps. At `lambda = 1` the a posteriori estimate is
/// `[h] = 2 Theta`, and the simplified Newton iteration with the Jacobian
/// fixed at `x` converges when `h = omega |dx| <= 1/2` (affine covariant
/// Kantorovich theorem, Deuflhard 2004, Sec. 2.1): `Theta <= 1/4`. Within
/// that, a chord step is taken only while it gains more digits per unit of
/// work than a Newton step (see `Run::chord_pays`).
pub const CHORD_THETA: f64 = 0.25;

/// Stall margin over the rounding floor. An iterate computed from a residual
/// with noise `e` (`|e| <= floor`) is off by `J^-1 e`, so its own residual is
/// `-e + e'` plus the rounding of the linear solve (Higham, *Accuracy and
/// Stability of Numerical Algorithms*, 2nd ed., SIAM 2002, Ch. 9): a
/// floor-limited iteration stalls at a few floors, not at one. When the
/// monotonicity test fails at `x` with `max |F(x)| <= FLOOR_FACTOR * floor`,
/// the correction is noise at that level and no decrease can be certified:
/// the solve ends with [`Status::ConvergedAtFloor`]. Ten covers the two
/// noise samples with a margin for a floor estimated from the largest terms.
pub const FLOOR_FACTOR: f64 = 10.0;

/// Options of [`solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct NleqOptions {
    /// Converged when `max |F| <= tol`; 0 asks for the floor. Default `1e-10`,
    /// four digits above the rounding of an order-one residual of a few
    /// hundred terms.
    pub tol: f64,
    /// Accepted steps (Newton and chord) before [`StopReason::IterationLimit`].
    /// Default [`DEFAULT_MAX_ITERATIONS`].
    pub max_iterations: usize,
    /// Work budget in the system's units; 0 (default) = none. Checked before
    /// each evaluation, so a solve can overrun it by one linearisation.
    pub max_work: f64,
    /// Wall-clock deadline, checked before each evaluation. Default none.
    pub deadline: Option<Instant>,
    /// Smallest damping factor tried. Default [`DEFAULT_LAMBDA_MIN`].
    pub lambda_min: f64,
    /// Chord steps ([`CHORD_THETA`]). Default `true`: they only run when
    /// they are expected to cost less than a Jacobian.
    pub chord: bool,
    /// Scales `s_i > 0` of the unknowns (corrections are measured as
    /// `dx_i / s_i`). Default none: all 1, for unknowns of order one.
    pub scale: Option<Vec<f64>>,
}

impl Default for NleqOptions {
    fn default() -> Self {
        NleqOptions {
            tol: 1e-10,
            max_iterations: DEFAULT_MAX_ITERATIONS,
            max_work: 0.0,
            deadline: None,
            lambda_min: DEFAULT_LAMBDA_MIN,
            chord: true,
            scale: None,
        }
    }
}

/// How a solve ended successfully.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// `max |F| <= tol`.
    Converged,
    /// `max |F| > tol` but at most the rounding floor, or stalled within
    /// [`FLOOR_FACTOR`] of it.
    ConvergedAtFloor,
}

/// A converged solve.
#[derive(Debug, Clone, PartialEq)]
pub struct NleqResult {
    /// The solution, a point whose residual was evaluated.
    pub x: Vec<f64>,
    /// `max |F(x)|`.
    pub residual: f64,
    /// How it converged.
    pub status: Status,
    /// Accepted steps (Newton and chord).
    pub iterations: usize,
    /// Calls of [`NonlinearSystem::linearise`].
    pub linearisations: usize,
    /// Calls of [`NonlinearSystem::residual`].
    pub evaluations: usize,
    /// Calls of [`NonlinearSystem::solve`].
    pub solves: usize,
    /// Work spent by this solve, in the system's units.
    pub work: f64,
    /// Contraction `|dxbar| / |dx|` of the last accepted step (0 if none).
    pub contraction: f64,
    /// Smallest damping factor accepted (1 if no step was damped).
    pub damping: f64,
}

/// Workspace: repeated solves of one dimension allocate only the returned `x`.
#[derive(Debug, Clone, Default)]
pub struct Nleq {
    x: Vec<f64>,
    f: Vec<f64>,
    xt: Vec<f64>,
    ft: Vec<f64>,
    dx: Vec<f64>,
    dxbar: Vec<f64>,
    xj: Vec<f64>,
}

/// Solve `F(x) = 0` from `x0` with a fresh workspace ([`Nleq::solve`]).
pub fn solve<S: NonlinearSystem + ?Sized>(
    sys: &mut S,
    x0: &[f64],
    opts: &NleqOptions,
    solver_name: &'static str,
) -> Result<NleqResult> {
    Nleq::default().solve(sys, x0, opts, solver_name)
}

impl Nleq {
    /// Solve `F(x) = 0` from `x0`. Errors: [`Error::NotConverged`] naming
    /// `solver_name`, with the best `max |F|` over all evaluated points (the
    /// `evaluations` field is the work spent, rounded); [`Error::Interrupted`]
    /// from [`cancel::check`]; `InvalidParameter` / `InvalidInput` for bad
    /// options or from the system.
    pub fn solve<S: NonlinearSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        x0: &[f64],
        opts: &NleqOptions,
        solver_name: &'static str,
    ) -> Result<NleqResult> {
        self.run(sys, x0, None, opts, solver_name)
    }

    /// As [`Nleq::solve`], where the caller's last `sys.linearise(x0, f0)`
    /// left the factorisation at `x0` (not counted in the result).
    pub fn solve_linearised<S: NonlinearSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        x0: &[f64],
        f0: &[f64],
        opts: &NleqOptions,
        solver_name: &'static str,
    ) -> Result<NleqResult> {
        self.run(sys, x0, Some(f0), opts, solver_name)
    }

    fn run<S: NonlinearSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        x0: &[f64],
        f0: Option<&[f64]>,
        opts: &NleqOptions,
        name: &'static str,
    ) -> Result<NleqResult> {
        let n = sys.dim();
        validate(n, x0, f0, opts)?;
        let w = &mut *self;
        for v in [
            &mut w.x,
            &mut w.f,
            &mut w.xt,
            &mut w.ft,
            &mut w.dx,
            &mut w.dxbar,
            &mut w.xj,
        ] {
            v.resize(n, 0.0);
        }
        self.x.copy_from_slice(x0);
        let work0 = sys.work();
        let run = Run {
            sys,
            opts,
            name,
            w: self,
            work0,
            iterations: 0,
            evaluations: 0,
            linearisations: 0,
            solves: 0,
            best: f64::INFINITY,
            theta: 0.0,
            lambda: 1.0,
            damping: 1.0,
            ndx_j: 0.0,
            cost_f: 0.0,
            cost_l: 0.0,
        };
        run.iterate(f0)
    }
}

fn validate(n: usize, x0: &[f64], f0: Option<&[f64]>, o: &NleqOptions) -> Result<()> {
    if x0.len() != n || f0.is_some_and(|f| f.len() != n) {
        return Err(Error::input("x0", format!("length != dimension {n}")));
    }
    if x0.iter().any(|v| !v.is_finite()) {
        return Err(Error::input("x0", "contains a non-finite value"));
    }
    crate::error::non_negative("tol", o.tol)?;
    crate::error::non_negative("max_work", o.max_work)?;
    if !(o.lambda_min > 0.0 && o.lambda_min <= 1.0) {
        return Err(Error::param(
            "lambda_min",
            o.lambda_min,
            "0 < lambda_min <= 1",
        ));
    }
    match &o.scale {
        Some(s) if s.len() != n || s.iter().any(|v| !(v.is_finite() && *v > 0.0)) => {
            Err(Error::input("scale", format!("need {n} finite values > 0")))
        }
        _ => Ok(()),
    }
}

/// Scaled RMS norm of `a u + b v`, with the largest term factored out so
/// that it neither overflows nor underflows.
fn norm(scale: Option<&[f64]>, a: f64, u: &[f64], b: f64, v: &[f64]) -> f64 {
    let term = |i: usize| (a * u[i] + b * v[i]) / scale.map_or(1.0, |s| s[i]);
    let big = (0..u.len()).fold(0.0_f64, |m, i| m.max(term(i).abs()));
    if big == 0.0 || !big.is_finite() {
        return big;
    }
    let sum: f64 = (0..u.len()).map(|i| (term(i) / big).powi(2)).sum();
    big * (sum / u.len() as f64).sqrt()
}

fn max_abs(f: &[f64]) -> f64 {
    f.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// `Err(e)` for errors passed to the caller, `Ok(message)` for an
/// evaluation that failed at this point.
fn evaluation_failure(e: Error) -> Result<String> {
    match e {
        Error::Interrupted | Error::InvalidParameter { .. } | Error::InvalidInput { .. } => Err(e),
        other => Ok(other.to_string()),
    }
}

/// The next damping factor `target`, but not below `lambda_min` before
/// `lambda_min` itself has been tried (NLEQ-ERR).
fn reduce(lambda: f64, target: f64, lambda_min: f64) -> f64 {
    if lambda > lambda_min {
        target.max(lambda_min)
    } else {
        target
    }
}

/// One solve in progress: system, options, workspace and counts.
struct Run<'a, S: ?Sized> {
    sys: &'a mut S,
    opts: &'a NleqOptions,
    name: &'static str,
    w: &'a mut Nleq,
    work0: f64,
    iterations: usize,
    evaluations: usize,
    linearisations: usize,
    solves: usize,
    /// Smallest `max |F|` over every evaluated point.
    best: f64,
    /// Contraction and damping factor of the last accepted step, and the
    /// smallest damping factor accepted.
    theta: f64,
    lambda: f64,
    damping: f64,
    /// `|dx|` at the factorisation point.
    ndx_j: f64,
    /// Work of the last residual and of the last linearisation.
    cost_f: f64,
    cost_l: f64,
}

/// The current iterate (`x`, `f`; correction `dx`) or the trial point
/// (`xt`, `ft`; correction `dxbar`).
#[derive(Clone, Copy)]
enum At {
    Current,
    Trial,
}

impl<S: NonlinearSystem + ?Sized> Run<'_, S> {
    fn iterate(mut self, f0: Option<&[f64]>) -> Result<NleqResult> {
        match f0 {
            Some(f) if f.iter().all(|v| v.is_finite()) => self.w.f.copy_from_slice(f),
            Some(_) => return Err(self.fail(StopReason::NonFinite, "F(x0) not finite".into())),
            None => self.linearise("the starting point")?,
        }
        self.w.xj.copy_from_slice(&self.w.x);
        if let Some(status) = self.status(At::Current) {
            return Ok(self.finish(status));
        }
        // |x - x_J| to the previous factorisation, for the prior estimate.
        let mut distance = None;
        loop {
            self.limits()?;
            if let Some(status) = self.newton_step(distance)? {
                return Ok(self.finish(status));
            }
            if self.opts.chord && self.lambda == 1.0 {
                if let Some(status) = self.chord()? {
                    return Ok(self.finish(status));
                }
            }
            let scale = self.opts.scale.as_deref();
            distance = Some(norm(scale, 1.0, &self.w.x, -1.0, &self.w.xj));
            self.linearise("an accepted iterate")?;
            self.w.xj.copy_from_slice(&self.w.x);
        }
    }

    /// One damped Newton step from `x` (factorised there); `dxbar` holds the
    /// previous factorisation's correction at `x`, `distance` its distance.
    /// `Ok(Some)` if an evaluated point converged, `Ok(None)` after a step.
    fn newton_step(&mut self, distance: Option<f64>) -> Result<Option<Status>> {
        self.correction(At::Current)?;
        let scale = self.opts.scale.as_deref();
        let (dx, dxbar) = (&self.w.dx, &self.w.dxbar);
        let ndx = norm(scale, 1.0, dx, 0.0, dx);
        self.ndx_j = ndx;
        let lmin = self.opts.lambda_min;
        // Prior estimate (Deuflhard 2004, Sec. 3.3), clamped to lambda_min so
        // that the smallest step is tried before failing (as NLEQ1).
        let mut lambda = distance.map_or(1.0, |d| {
            let den = norm(scale, 1.0, dxbar, -1.0, dx) * ndx;
            let mu = d * norm(scale, 1.0, dxbar, 0.0, dxbar) / den;
            if den > 0.0 {
                mu.min(1.0)
            } else {
                1.0
            }
        });
        lambda = lambda.max(lmin);
        let (mut reduced, mut evaluated, mut theta) = (false, false, f64::NAN);
        let mut last_error = String::new();
        loop {
            if lambda < lmin {
                return Err(self.damping_failure(evaluated, theta, &last_error));
            }
            let w = &mut *self.w;
            for i in 0..w.x.len() {
                w.xt[i] = w.x[i] + lambda * w.dx[i];
            }
            if w.xt == w.x {
                return self.at_rounding_level(lambda, ndx).map(Some);
            }
            if let Some(message) = self.trial()? {
                last_error = message;
                (lambda, reduced) = (reduce(lambda, 0.5 * lambda, lmin), true);
                continue;
            }
            evaluated = true;
            if let Some(status) = self.status(At::Trial) {
                self.accept(lambda, self.theta);
                return Ok(Some(status));
            }
            self.correction(At::Trial)?;
            let (dx, dxbar) = (&self.w.dx, &self.w.dxbar);
            theta = norm(scale, 1.0, dxbar, 0.0, dxbar) / ndx;
            // 1/h_post; f64::min below ignores a NaN from 0/0.
            let mu = 0.5 * ndx * lambda * lambda / norm(scale, 1.0, dxbar, lambda - 1.0, dx);
            if !(theta <= 1.0 - 0.25 * lambda) {
                if self.stagnant() {
                    return Ok(Some(Status::ConvergedAtFloor));
                }
                (lambda, reduced) = (reduce(lambda, f64::min(mu, 0.5 * lambda), lmin), true);
                continue;
            }
            // NLEQ-ERR: retry with the a posteriori factor if it is at least
            // four times larger and no reduction has been made.
            let lambda_post = f64::min(1.0, mu);
            if !reduced && lambda < 1.0 && lambda_post >= 4.0 * lambda {
                lambda = lambda_post;
                continue;
            }
            self.accept(lambda, theta);
            return Ok(None);
        }
    }

    /// Chord steps `x <- x + dxbar` with the factorisation kept, while
    /// [`Self::chord_pays`]. A step that fails the restricted test at
    /// `lambda = 1` (`Theta > 3/4`) or cannot be evaluated is discarded.
    fn chord(&mut self) -> Result<Option<Status>> {
        let scale = self.opts.scale.as_deref();
        while self.chord_pays() {
            self.limits()?;
            let w = &mut *self.w;
            for i in 0..w.x.len() {
                w.xt[i] = w.x[i] + w.dxbar[i];
            }
            if w.xt == w.x || self.trial()?.is_some() {
                return Ok(None);
            }
            if let Some(status) = self.status(At::Trial) {
                self.accept(1.0, self.theta);
                return Ok(Some(status));
            }
            // The step taken moves to `dx`, the new correction into `dxbar`.
            std::mem::swap(&mut self.w.dx, &mut self.w.dxbar);
            self.correction(At::Trial)?;
            let (dx, dxbar) = (&self.w.dx, &self.w.dxbar);
            let theta = norm(scale, 1.0, dxbar, 0.0, dxbar) / norm(scale, 1.0, dx, 0.0, dx);
            if !(theta <= 0.75) {
                std::mem::swap(&mut self.w.dx, &mut self.w.dxbar);
                return Ok(None);
            }
            self.accept(1.0, theta);
        }
        Ok(None)
    }

    /// Whether a chord step gains more digits per unit of work than a Newton
    /// step. With the error `e_J` at the factorisation point and `e` now, a
    /// chord step contracts by `Theta_c ~ omega e_J` (the last contraction
    /// seen), a Newton step by `omega e / 2 = Theta_c Pi / 2` with
    /// `Pi = |dxbar| / |dx_J| ~ e / e_J` (Deuflhard 2004, Sec. 2.1). Costs: a
    /// residual `c_F` against a linearisation and a residual (measured);
    /// unknown costs leave only `Theta_c <= CHORD_THETA`.
    fn chord_pays(&self) -> bool {
        if !(self.theta <= CHORD_THETA) {
            return false;
        }
        let scale = self.opts.scale.as_deref();
        let pi = norm(scale, 1.0, &self.w.dxbar, 0.0, &self.w.dxbar) / self.ndx_j;
        let theta_newton = 0.5 * self.theta * pi;
        let (cf, cl) = (self.cost_f, self.cost_l);
        !(cf > 0.0 && cl > 0.0)
            || (cl + cf) * (1.0 / self.theta).ln() >= cf * (1.0 / theta_newton).ln()
    }

    /// `x + lambda dx == x` in floating point: at the floor if `F(x)` is
    /// within [`FLOOR_FACTOR`] of it (the test would fail with `Theta = 1`),
    /// else no damping can make progress.
    fn at_rounding_level(&mut self, lambda: f64, ndx: f64) -> Result<Status> {
        if self.stagnant() {
            return Ok(Status::ConvergedAtFloor);
        }
        let (r, floor, tol) = (max_abs(&self.w.f), self.floor(At::Current), self.opts.tol);
        let reason = format!(
            "lambda dx (lambda = {lambda:.1e}, |dx| = {ndx:.1e}) is below the rounding level of \
             x, while max|F| = {r:.2e} exceeds tol = {tol:.1e} and {FLOOR_FACTOR} times the \
             rounding floor {floor:.1e}"
        );
        Err(self.fail(StopReason::LineSearch, reason))
    }

    /// `max |F(x)| <= FLOOR_FACTOR * floor(x, F)` at the current iterate.
    fn stagnant(&self) -> bool {
        max_abs(&self.w.f) <= FLOOR_FACTOR * self.floor(At::Current)
    }

    fn floor(&self, at: At) -> f64 {
        let floor = match at {
            At::Current => self.sys.floor(&self.w.x, &self.w.f),
            At::Trial => self.sys.floor(&self.w.xt, &self.w.ft),
        };
        if floor.is_finite() {
            floor.max(0.0)
        } else {
            0.0
        }
    }

    /// Convergence test at an evaluated point; records the best residual.
    fn status(&mut self, at: At) -> Option<Status> {
        let r = max_abs(match at {
            At::Current => &self.w.f,
            At::Trial => &self.w.ft,
        });
        self.best = self.best.min(r);
        if r <= self.opts.tol {
            Some(Status::Converged)
        } else if r <= self.floor(at) {
            Some(Status::ConvergedAtFloor)
        } else {
            None
        }
    }

    fn accept(&mut self, lambda: f64, theta: f64) {
        std::mem::swap(&mut self.w.x, &mut self.w.xt);
        std::mem::swap(&mut self.w.f, &mut self.w.ft);
        self.iterations += 1;
        (self.lambda, self.theta) = (lambda, theta);
        self.damping = self.damping.min(lambda);
    }

    /// `F(xt)` into `ft`; `Ok(Some(message))` if not evaluable or not finite.
    fn trial(&mut self) -> Result<Option<String>> {
        self.budget()?;
        self.evaluations += 1;
        let (w, before) = (&mut *self.w, self.sys.work());
        let result = self.sys.residual(&w.xt, &mut w.ft);
        self.cost_f = self.sys.work() - before;
        match result {
            Err(e) => evaluation_failure(e).map(Some),
            Ok(()) if w.ft.iter().any(|v| !v.is_finite()) => Ok(Some("F not finite".into())),
            Ok(()) => Ok(None),
        }
    }

    /// `F(x)` and the factorised Jacobian at the current iterate.
    fn linearise(&mut self, what: &str) -> Result<()> {
        self.budget()?;
        self.linearisations += 1;
        let (w, before) = (&mut *self.w, self.sys.work());
        let result = self.sys.linearise(&w.x, &mut w.f);
        self.cost_l = self.sys.work() - before;
        let message = match result {
            Err(e) => evaluation_failure(e)?,
            Ok(()) if w.f.iter().any(|v| !v.is_finite()) => "F not finite".to_string(),
            Ok(()) => return Ok(()),
        };
        let reason = format!("F and its Jacobian at {what} cannot be evaluated: {message}");
        Err(self.fail(StopReason::NonFinite, reason))
    }

    /// `dx = -J^-1 F(x)` or `dxbar = -J^-1 F(xt)`.
    fn correction(&mut self, at: At) -> Result<()> {
        self.solves += 1;
        let w = &mut *self.w;
        let (rhs, out) = match at {
            At::Current => (&w.f, &mut w.dx),
            At::Trial => (&w.ft, &mut w.dxbar),
        };
        let regular = match self.sys.solve(rhs, out) {
            Ok(regular) => regular,
            Err(e) => evaluation_failure(e).map(|_| false)?,
        };
        out.iter_mut().for_each(|v| *v = -*v);
        if regular && out.iter().all(|v| v.is_finite()) {
            return Ok(());
        }
        let reason = format!(
            "the Jacobian after {} steps is singular (J dx = -F has no unique finite solution): \
             a fold or singular point of the equations, or a redundant unknown",
            self.iterations
        );
        Err(self.fail(StopReason::SingularJacobian, reason))
    }

    /// Cancel check, iteration limit and budget, once per step.
    fn limits(&mut self) -> Result<()> {
        cancel::check()?;
        if self.iterations >= self.opts.max_iterations {
            let reason = format!(
                "{} steps without max|F| <= {:.1e} (now {:.2e}; last contraction {:.2}: near 1 \
                 is slow linear convergence, as at a singular root)",
                self.iterations,
                self.opts.tol,
                max_abs(&self.w.f),
                self.theta
            );
            return Err(self.fail(StopReason::IterationLimit, reason));
        }
        self.budget()
    }

    /// The work budget and the deadline, before each evaluation.
    fn budget(&self) -> Result<()> {
        let (spent, max) = (self.sys.work() - self.work0, self.opts.max_work);
        if max > 0.0 && spent >= max {
            return Err(self.fail(StopReason::Budget, format!("work {spent} of {max} spent")));
        }
        if self.opts.deadline.is_some_and(|d| Instant::now() >= d) {
            return Err(self.fail(StopReason::Budget, "deadline passed".into()));
        }
        Ok(())
    }

    fn damping_failure(&self, evaluated: bool, theta: f64, last_error: &str) -> Error {
        let lmin = self.opts.lambda_min;
        let (stop, mut reason) = if evaluated {
            let reason = format!(
                "damping factor below lambda_min = {lmin:.1e}: the simplified Newton correction \
                 did not contract (last |dxbar|/|dx| = {theta:.3} > 1 - lambda/4), so F is too \
                 nonlinear along the Newton direction or inconsistent with its Jacobian"
            );
            (StopReason::LineSearch, reason)
        } else {
            let reason =
                format!("F cannot be evaluated at any x + lambda dx, lambda >= {lmin:.1e}");
            (StopReason::NonFinite, reason)
        };
        if !last_error.is_empty() {
            reason = format!("{reason}; last failed evaluation: {last_error}");
        }
        self.fail(stop, reason)
    }

    fn fail(&self, stop: StopReason, reason: String) -> Error {
        let spent = (self.sys.work() - self.work0).max(0.0);
        Error::NotConverged {
            solver: self.name,
            iterations: self.iterations,
            evaluations: spent.round() as usize,
            residual: self.best,
            stop,
            reason,
        }
    }

    fn finish(&self, status: Status) -> NleqResult {
        NleqResult {
            x: self.w.x.clone(),
            residual: max_abs(&self.w.f),
            status,
            iterations: self.iterations,
            linearisations: self.linearisations,
            evaluations: self.evaluations,
            solves: self.solves,
            work: self.sys.work() - self.work0,
            contraction: self.theta,
            damping: self.damping,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::problems::nonlinear::{
        splitmix64, Bratu, BrownAlmostLinear, BroydenTridiagonal, Dense, Noisy, Obstacle,
        PowellBadlyScaled, PowellSingular, Rosenbrock, TestProblem,
    };

    fn max_norm(f: &[f64]) -> f64 {
        f.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
    }

    fn opts(tol: f64, chord: bool) -> NleqOptions {
        NleqOptions {
            tol,
            chord,
            ..Default::default()
        }
    }

    /// Solve `p` from its start; check the result's own claims: the residual
    /// is `max |F(x)|` re-evaluated, within `tol`, the counts agree with the
    /// problem's, and nothing is NaN.
    fn solved<P: TestProblem + Clone>(p: &P, o: &NleqOptions) -> NleqResult {
        let mut sys = Dense::new(p.clone());
        let r = solve(&mut sys, &p.start(), o, "nleq test")
            .unwrap_or_else(|e| panic!("{}: {e}", p.name()));
        check_result(p, &sys, &r, o.tol);
        r
    }

    fn check_result<P: TestProblem>(p: &P, sys: &Dense<P>, r: &NleqResult, tol: f64) {
        let mut f = vec![0.0; p.dim()];
        p.residual(&r.x, &mut f);
        assert_eq!(max_norm(&f), r.residual, "{}", p.name());
        match r.status {
            Status::Converged => assert!(r.residual <= tol, "{}", p.name()),
            Status::ConvergedAtFloor => {
                assert!(r.residual <= FLOOR_FACTOR * p.floor(&r.x), "{}", p.name())
            }
        }
        assert!(r.x.iter().all(|v| v.is_finite()));
        assert!(r.contraction.is_finite() && r.damping > 0.0 && r.damping <= 1.0);
        assert_eq!(r.evaluations, sys.residuals);
        assert_eq!(r.linearisations, sys.linearisations);
        assert_eq!(r.solves, sys.solves);
        assert_eq!(r.work, (r.evaluations + 2 * r.linearisations) as f64);
    }

    /// The MGH problems from their standard starts, with and without chord
    /// steps. Solutions: Rosenbrock's root (1, 1), where `|J^-1|_inf = 2.1`,
    /// so `|x - x*| <= 2.1 tol` to first order; Powell badly scaled against the
    /// seven digits MGH print; Powell singular's root 0 is singular, where
    /// `|x1 - x4| <= (tol/sqrt(10))^(1/2)`, `|x2 - 2 x3| <= tol^(1/2)` and the
    /// two linear equations give `|x| <= 2e-4`.
    #[test]
    fn mgh_problems_converge() {
        for chord in [false, true] {
            let o = opts(1e-10, chord);
            let r = solved(&Rosenbrock, &o);
            assert!(r.x.iter().all(|v| (v - 1.0).abs() <= 2.2e-10));
            let r = solved(&PowellBadlyScaled, &o);
            for (x, x_mgh) in r.x.iter().zip(PowellBadlyScaled::ROOT) {
                assert!((x / x_mgh - 1.0).abs() < 1e-6, "{x} vs {x_mgh}");
            }
            let r = solved(&PowellSingular, &o);
            assert!(max_norm(&r.x) <= 2e-4, "{:?}", r.x);
            let r = solved(&BroydenTridiagonal::default(), &o);
            assert_eq!(r.status, Status::Converged);
        }
    }

    /// Brown's almost-linear function from MGH's start 1/2: the Newton path
    /// (Deuflhard 2004, Sec. 3.1), which every affine covariant damped Newton
    /// method follows, ends on the manifold of singular Jacobians (for the
    /// symmetric iterates `x_i = a`, `x_n = b`, `det J ~ a^(n-2) (n a - (n-1) b)`)
    /// before any root, so the solve must fail cleanly (NLEQ1, NLEQ-ERR and
    /// NLEQ-RES fail here too; NLEQ2's rank reduction passes). From 1.02,
    /// inside the root's basin, it converges to the root `a = 0.979430...`.
    #[test]
    fn brown_almost_linear() {
        let p = BrownAlmostLinear::default();
        let f0 = 5.5; // max |F(1/2, ..., 1/2)| = |1/2 + 5 - 11|
        match solve(
            &mut Dense::new(p),
            &p.start(),
            &NleqOptions::default(),
            "brown",
        ) {
            Err(Error::NotConverged { stop, residual, .. }) => {
                assert!(matches!(
                    stop,
                    StopReason::LineSearch | StopReason::SingularJacobian
                ));
                assert!(residual <= f0, "{residual}");
            }
            other => panic!("{other:?}"),
        }
        let mut sys = Dense::new(p);
        let r = solve(&mut sys, &[1.02; 10], &NleqOptions::default(), "brown").unwrap();
        check_result(&p, &sys, &r, 1e-10);
        let a = r.x[0];
        assert!(r.x[..9].iter().all(|v| (v - a).abs() < 1e-9));
        assert!((10.0 * a.powi(10) - 11.0 * a.powi(9) + 1.0).abs() < 1e-9);
    }

    /// A system recording `(x, max |F|)` at each linearisation.
    struct Traced<P> {
        inner: Dense<P>,
        points: Vec<(Vec<f64>, f64)>,
    }

    impl<P: TestProblem> NonlinearSystem for Traced<P> {
        fn dim(&self) -> usize {
            self.inner.dim()
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
            self.inner.residual(x, f)
        }
        fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
            self.inner.linearise(x, f)?;
            self.points.push((x.to_vec(), max_norm(f)));
            Ok(())
        }
        fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool> {
            self.inner.solve(b, dx)
        }
        fn floor(&self, x: &[f64], f: &[f64]) -> f64 {
            self.inner.floor(x, f)
        }
        fn work(&self) -> f64 {
            self.inner.work()
        }
    }

    /// Quadratic convergence on Broyden's tridiagonal function. `F` is
    /// quadratic, so after a full step exactly `F_i(x + dx) = -2 dx_i^2`,
    /// and `|dx| <= |J^-1| |F|` with Varah's bound `|J^-1| <= 1 / min_i
    /// (|3 - 4 x_i| - 3)` for the diagonally dominant `J`: hence
    /// `r_(k+1) <= 2 v^2 r_k^2`, plus rounding (a few floors).
    #[test]
    fn quadratic_convergence_broyden() {
        let p = BroydenTridiagonal::default();
        let mut sys = Traced {
            inner: Dense::new(p),
            points: Vec::new(),
        };
        let r = solve(&mut sys, &p.start(), &opts(1e-14, false), "broyden").unwrap();
        let mut seq = sys.points.clone();
        seq.push((r.x.clone(), r.residual));
        let mut checked = 0;
        for pair in seq.windows(2) {
            let ((x, rk), (_, rk1)) = (&pair[0], &pair[1]);
            let margin = x
                .iter()
                .map(|v| (3.0 - 4.0 * v).abs() - 3.0)
                .fold(f64::INFINITY, f64::min);
            if *rk > 1e-2 || margin <= 0.0 {
                continue;
            }
            let v = 1.0 / margin;
            assert!(
                *rk1 <= 2.0 * v * v * rk * rk + 4.0 * p.floor(x),
                "{rk} -> {rk1}"
            );
            checked += 1;
        }
        assert!(checked >= 2, "{seq:?}");
    }

    /// Rosenbrock from (-1.2, 1): the exact trace. `F` is quadratic with
    /// `dxbar(lambda) = (1 - lambda) dx + lambda^2 (0, dx_1^2)`. Step 1:
    /// `dx = (2.2, -4.84)`, the full step gives `Theta = 0.910 > 3/4`, so
    /// `lambda = min(1/2, 1/h_post) = min(1/2, 1/1.82) = 1/2`, where
    /// `Theta = 0.307 <= 7/8` passes: `x = (-0.1, -1.42)`. Step 2: the prior
    /// estimate gives `1/h = 1.10`, so `lambda = 1` (`Theta = 0.740 <= 3/4`)
    /// and `x1 = 1` exactly (`F_2 = 1 - x1` is linear). Step 3: `F` is now
    /// linear in `x2`, and the full step lands on the root. So exactly three
    /// iterations, one of them damped by 1/2, and one rejected trial.
    #[test]
    fn damping_on_rosenbrock() {
        let r = solved(&Rosenbrock, &opts(1e-10, false));
        assert_eq!(r.damping, 0.5);
        assert_eq!((r.iterations, r.linearisations, r.evaluations), (3, 3, 4));
        assert_eq!(r.x, vec![1.0, 1.0]);
    }

    /// Rosenbrock with its equations mixed, `G = A F`: an affine covariant
    /// iteration takes the same steps (Deuflhard 2004, Sec. 3.3).
    #[derive(Clone, Copy)]
    struct Mixed;

    impl Mixed {
        const A: [[f64; 2]; 2] = [[3.0, -1.0], [50.0, 2.0]];
    }

    impl TestProblem for Mixed {
        fn name(&self) -> &'static str {
            "mixed Rosenbrock"
        }
        fn dim(&self) -> usize {
            2
        }
        fn start(&self) -> Vec<f64> {
            Rosenbrock.start()
        }
        fn residual(&self, x: &[f64], g: &mut [f64]) {
            let mut f = [0.0; 2];
            Rosenbrock.residual(x, &mut f);
            for (i, row) in Self::A.iter().enumerate() {
                g[i] = row[0] * f[0] + row[1] * f[1];
            }
        }
        fn jacobian(&self, x: &[f64], jac: &mut nalgebra::DMatrix<f64>) {
            let mut j = nalgebra::DMatrix::zeros(2, 2);
            Rosenbrock.jacobian(x, &mut j);
            let [[a, b], [c, d]] = Self::A;
            let a = nalgebra::Matrix2::new(a, b, c, d);
            jac.copy_from(&(a * j));
        }
        fn floor(&self, x: &[f64]) -> f64 {
            52.0 * Rosenbrock.floor(x)
        }
    }

    /// Affine covariance: mixing the equations changes nothing but rounding;
    /// a uniform scale of the unknowns' norm changes nothing either, and a
    /// per-component scale is accepted.
    #[test]
    fn invariances_and_scaling() {
        let plain = solved(&Rosenbrock, &opts(1e-10, false));
        let mixed = solved(&Mixed, &opts(1e-10, false));
        assert_eq!(
            (mixed.iterations, mixed.linearisations, mixed.evaluations),
            (plain.iterations, plain.linearisations, plain.evaluations)
        );
        assert_eq!(mixed.damping, 0.5);
        let scaled = |scale: Vec<f64>| NleqOptions {
            scale: Some(scale),
            ..Default::default()
        };
        let p = PowellBadlyScaled;
        let a = solved(&p, &NleqOptions::default());
        let b = solved(&p, &scaled(vec![1e5, 1e5]));
        assert_eq!(
            (a.iterations, a.linearisations),
            (b.iterations, b.linearisations)
        );
        solved(&p, &scaled(vec![1e-5, 10.0]));
        let r = solve(&mut Dense::new(p), &p.start(), &scaled(vec![1.0, 0.0]), "t");
        assert!(matches!(r, Err(Error::InvalidInput { .. })));
    }

    /// Chord steps on the mildly nonlinear Bratu problem (lambda = 1) save
    /// linearisations and work. Both answers have `max |F| <= tol`, and
    /// `|J^-1| <= (1/8) / (1 - e^0.15 / 8) < 0.15` (the discrete Laplacian's
    /// inverse has norm <= 1/8), so they differ by at most `0.3 tol`.
    #[test]
    fn chord_saves_linearisations() {
        let p = Bratu::new(1.0);
        let newton = solved(&p, &opts(1e-10, false));
        let chord = solved(&p, &opts(1e-10, true));
        assert!(chord.linearisations < newton.linearisations);
        assert!(chord.work < newton.work);
        let diff = chord.x.iter().zip(&newton.x).map(|(a, b)| (a - b).abs());
        assert!(diff.fold(0.0, f64::max) <= 1e-10);
    }

    /// Bratu against the exact solution of the differential equation. At
    /// lambda = 1 the error obeys `|e| <= |J^-1| |tau|` with the truncation
    /// `tau = h^2/12 u''''`, `|u''''| = lambda e^u |u'^2 - lambda e^u| <= 1.67`
    /// and `|J^-1| <= 0.146`: `|e| <= 7.8e-6`. At 3.5, next to the fold, the
    /// check is second-order convergence: halving `h` divides the error by 4
    /// (within 25 %).
    #[test]
    fn bratu_matches_exact_solution() {
        let error = |n: usize, lambda: f64| {
            let r = solved(&Bratu { n, lambda }, &NleqOptions::default());
            let h = 1.0 / (n as f64 + 1.0);
            let e =
                r.x.iter()
                    .enumerate()
                    .map(|(i, u)| (u - Bratu::exact(lambda, (i + 1) as f64 * h).unwrap()).abs());
            e.fold(0.0, f64::max)
        };
        assert!(error(50, 1.0) <= 7.8e-6);
        let ratio = error(25, 3.5) / error(51, 3.5);
        assert!((3.0..=5.0).contains(&ratio), "{ratio}");
    }

    /// The piecewise-smooth obstacle problem: the first full step pushes the
    /// string far into the support, the damping takes it across the kink, and
    /// once the contact set is right the semismooth Newton steps converge
    /// superlinearly: the residual ratios of the last two steps above the
    /// rounding (100 floors) decrease.
    #[test]
    fn kink_converges() {
        let p = Obstacle::default();
        let mut sys = Traced {
            inner: Dense::new(p),
            points: Vec::new(),
        };
        let r = solve(&mut sys, &p.start(), &opts(1e-10, false), "obstacle").unwrap();
        check_result(&p, &sys.inner, &r, 1e-10);
        assert!(r.damping < 1.0 && r.iterations <= 12);
        assert!((1..p.n).contains(&p.contacts(&r.x)));
        let mut seq = sys.points.clone();
        seq.push((r.x.clone(), r.residual));
        let res: Vec<f64> = seq
            .iter()
            .filter(|(x, f)| *f > 100.0 * p.floor(x))
            .map(|(_, f)| *f)
            .collect();
        let k = res.len();
        assert!(k >= 4, "{res:?}");
        assert!(res[k - 1] / res[k - 2] < res[k - 2] / res[k - 3], "{res:?}");
        assert!(res[k - 2] / res[k - 3] < res[k - 3] / res[k - 4], "{res:?}");
    }

    /// A system whose evaluations fail (`residual` always; `linearise` too
    /// when `all`), or that sleeps in `linearise`, or returns invalid input.
    struct Faulty {
        inner: Dense<Rosenbrock>,
        all: bool,
        sleep: Option<Duration>,
        invalid: bool,
    }

    impl Faulty {
        fn new(all: bool) -> Self {
            Faulty {
                inner: Dense::new(Rosenbrock),
                all,
                sleep: None,
                invalid: false,
            }
        }
    }

    impl NonlinearSystem for Faulty {
        fn dim(&self) -> usize {
            2
        }
        fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
            self.inner.residual(x, f)?;
            if self.invalid {
                return Err(Error::input("x", "outside the model"));
            }
            Err(Error::Integration {
                s: 0.1,
                reason: "stiffness singular".into(),
            })
        }
        fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
            if let Some(d) = self.sleep {
                std::thread::sleep(d);
            }
            self.inner.linearise(x, f)?;
            if self.all {
                return Err(Error::Integration {
                    s: 0.0,
                    reason: "no".into(),
                });
            }
            Ok(())
        }
        fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool> {
            self.inner.solve(b, dx)
        }
        fn work(&self) -> f64 {
            self.inner.work()
        }
    }

    fn not_converged(r: Result<NleqResult>) -> (StopReason, f64, usize, usize) {
        match r {
            Err(Error::NotConverged {
                stop,
                residual,
                iterations,
                evaluations,
                reason,
                ..
            }) => {
                assert!(!residual.is_nan() && !reason.is_empty());
                (stop, residual, iterations, evaluations)
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn failed_evaluations() {
        // Trials never evaluate: lambda halves to lambda_min (15 trials) and
        // the best residual is the start's, max |F(-1.2, 1)| = 4.4.
        let o = NleqOptions::default();
        let (stop, best, iterations, work) =
            not_converged(solve(&mut Faulty::new(false), &[-1.2, 1.0], &o, "t"));
        assert_eq!(stop, StopReason::NonFinite);
        assert!((best - 4.4).abs() < 1e-12 && iterations == 0);
        assert_eq!(work, 2 + 15);
        // Nothing evaluates: no residual seen at all.
        let (stop, best, _, _) =
            not_converged(solve(&mut Faulty::new(true), &[-1.2, 1.0], &o, "t"));
        assert_eq!((stop, best), (StopReason::NonFinite, f64::INFINITY));
        // Invalid input from the system is passed through.
        let mut sys = Faulty::new(false);
        sys.invalid = true;
        let r = solve(&mut sys, &[-1.2, 1.0], &o, "t");
        assert!(matches!(r, Err(Error::InvalidInput { .. })));
    }

    #[test]
    fn budgets_and_limits() {
        let x0 = Rosenbrock.start();
        let o = NleqOptions {
            max_work: 5.0,
            ..Default::default()
        };
        let (stop, _, _, work) = not_converged(solve(&mut Dense::new(Rosenbrock), &x0, &o, "t"));
        assert_eq!(stop, StopReason::Budget);
        assert!((5..=7).contains(&work)); // overrun by at most one linearisation
        let o = NleqOptions {
            deadline: Some(Instant::now()),
            ..Default::default()
        };
        let (stop, ..) = not_converged(solve(&mut Dense::new(Rosenbrock), &x0, &o, "t"));
        assert_eq!(stop, StopReason::Budget);
        let o = NleqOptions {
            max_iterations: 3,
            ..Default::default()
        };
        let p = PowellSingular;
        let (stop, _, iterations, _) =
            not_converged(solve(&mut Dense::new(p), &p.start(), &o, "t"));
        assert_eq!((stop, iterations), (StopReason::IterationLimit, 3));
    }

    /// `F(x) = x^2 - 1` at `x = 0`: `J = 0`.
    #[derive(Clone, Copy)]
    struct SquareMinusOne;

    impl TestProblem for SquareMinusOne {
        fn name(&self) -> &'static str {
            "x^2 - 1"
        }
        fn dim(&self) -> usize {
            1
        }
        fn start(&self) -> Vec<f64> {
            vec![0.0]
        }
        fn residual(&self, x: &[f64], f: &mut [f64]) {
            f[0] = x[0] * x[0] - 1.0;
        }
        fn jacobian(&self, x: &[f64], j: &mut nalgebra::DMatrix<f64>) {
            j[(0, 0)] = 2.0 * x[0];
        }
        fn floor(&self, _x: &[f64]) -> f64 {
            0.0
        }
    }

    #[test]
    fn singular_jacobian_and_bad_input() {
        let o = NleqOptions::default();
        let r = solve(&mut Dense::new(SquareMinusOne), &[0.0], &o, "t");
        assert_eq!(not_converged(r).0, StopReason::SingularJacobian);
        let r = solve(&mut Dense::new(SquareMinusOne), &[0.0, 1.0], &o, "t");
        assert!(matches!(r, Err(Error::InvalidInput { .. })));
        let bad = NleqOptions {
            lambda_min: 0.0,
            ..Default::default()
        };
        let r = solve(&mut Dense::new(SquareMinusOne), &[0.5], &bad, "t");
        assert!(matches!(r, Err(Error::InvalidParameter { .. })));
    }

    /// The cancel check is polled at most every 20 ms; a linearisation that
    /// takes 25 ms makes the first iteration's poll see it.
    #[test]
    fn interrupt_passes_through() {
        let mut sys = Faulty::new(false);
        sys.sleep = Some(Duration::from_millis(25));
        let r = cancel::interruptible(&|| true, || {
            solve(&mut sys, &[-1.2, 1.0], &NleqOptions::default(), "t")
        });
        assert_eq!(r, Err(Error::Interrupted));
    }

    /// Deterministic noise of 1e-12 on Broyden's residual. With the true
    /// floor (1e-12) a tolerance of 1e-14 ends at the floor and 1e-10
    /// converges. With a floor of half the noise the iteration stagnates
    /// within `FLOOR_FACTOR` of it (the residual after a noise-limited step
    /// is up to twice the noise); with a floor a thousand times too small it
    /// must not claim convergence.
    #[test]
    fn converged_at_floor() {
        let noisy = |floor| Noisy {
            inner: BroydenTridiagonal::default(),
            noise: 1e-12,
            floor,
        };
        let r = solved(&noisy(1e-12), &opts(1e-14, false));
        assert_eq!(r.status, Status::ConvergedAtFloor);
        let r = solved(&noisy(1e-12), &opts(1e-10, false));
        assert_eq!(r.status, Status::Converged);
        let r = solved(&noisy(5e-13), &opts(1e-14, false));
        assert_eq!(r.status, Status::ConvergedAtFloor);
        let p = noisy(1e-15);
        let (stop, best, ..) = not_converged(solve(
            &mut Dense::new(p),
            &p.start(),
            &opts(1e-14, false),
            "t",
        ));
        assert!(matches!(
            stop,
            StopReason::LineSearch | StopReason::IterationLimit
        ));
        assert!(best > 1e-14);
    }

    /// A supplied first linearisation saves one; a reused workspace gives
    /// the same answer as a fresh one.
    #[test]
    fn linearised_start_and_workspace_reuse() {
        let p = BroydenTridiagonal::default();
        let o = NleqOptions::default();
        let fresh = solved(&p, &o);
        let mut sys = Dense::new(p);
        let mut f0 = vec![0.0; p.n];
        sys.linearise(&p.start(), &mut f0).unwrap();
        let mut nleq = Nleq::default();
        let r = nleq
            .solve_linearised(&mut sys, &p.start(), &f0, &o, "t")
            .unwrap();
        assert_eq!(r.x, fresh.x);
        assert_eq!(r.linearisations + 1, fresh.linearisations);
        let again = nleq.solve(&mut Dense::new(p), &p.start(), &o, "t").unwrap();
        assert_eq!(again, fresh);
    }

    /// Seeded random starts (SplitMix64): every answer honours the contract
    /// (see `check_result`), every failure is a `NotConverged` with a finite
    /// best residual no larger than the start's. In the boxes where the
    /// Newton paths reach a root all starts converge; Broyden's box
    /// [-2, 2]^10 crosses `x_i = 3/4`, where its Jacobian degenerates, and
    /// most starts fail there (as undamped Newton does).
    #[test]
    fn random_starts() {
        let mut state = 0x5eed_u64;
        let mut uniform = |lo: f64, hi: f64| {
            state = splitmix64(state);
            lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)
        };
        let mut outcomes = [0usize; 2];
        for k in 0..240 {
            let (ok, f0) = match k % 4 {
                0 => run_from(Rosenbrock, &mut uniform, (-3.0, 3.0)),
                1 => run_from(BroydenTridiagonal::default(), &mut uniform, (-2.0, 0.0)),
                2 => run_from(Obstacle::default(), &mut uniform, (-1.0, 3.0)),
                _ => run_from(BroydenTridiagonal::default(), &mut uniform, (-2.0, 2.0)),
            };
            assert!(ok || k % 4 == 3, "start {k}: max|F0| = {f0}");
            outcomes[usize::from(ok)] += 1;
        }
        assert!(outcomes[0] > 0, "no failure path exercised");
    }

    fn run_from<P: TestProblem + Clone>(
        p: P,
        uniform: &mut impl FnMut(f64, f64) -> f64,
        (lo, hi): (f64, f64),
    ) -> (bool, f64) {
        let x0: Vec<f64> = (0..p.dim()).map(|_| uniform(lo, hi)).collect();
        let mut f = vec![0.0; p.dim()];
        p.residual(&x0, &mut f);
        let f0 = max_norm(&f);
        let mut sys = Dense::new(p.clone());
        let o = NleqOptions::default();
        match solve(&mut sys, &x0, &o, "random") {
            Ok(r) => {
                check_result(&p, &sys, &r, o.tol);
                (true, f0)
            }
            r => {
                let (_, best, iterations, _) = not_converged(r);
                assert!(best.is_finite() && best <= f0 && iterations <= o.max_iterations);
                (false, f0)
            }
        }
    }

    /// Prints iteration and work counts on every test problem:
    /// `cargo test --lib nleq::tests::table -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn table() {
        fn row<P: TestProblem + Clone>(p: P, label: &str) {
            for chord in [false, true] {
                let mut sys = Dense::new(p.clone());
                match solve(&mut sys, &p.start(), &opts(1e-10, chord), "table") {
                    Ok(r) => println!(
                        "| {label} | {chord} | {:?} | {} | {} | {} | {} | {} | {:.1e} | {} |",
                        r.status,
                        r.iterations,
                        r.linearisations,
                        r.evaluations,
                        r.solves,
                        r.work,
                        r.residual,
                        r.damping
                    ),
                    Err(e) => println!("| {label} | {chord} | {e} |"),
                }
            }
        }
        println!("| problem | chord | status | iterations | linearisations | residuals | solves | work | max abs F | min lambda |");
        row(Rosenbrock, "Rosenbrock");
        row(PowellBadlyScaled, "Powell badly scaled");
        row(PowellSingular, "Powell singular");
        row(BroydenTridiagonal::default(), "Broyden tridiagonal n=10");
        row(BrownAlmostLinear::default(), "Brown almost-linear n=10");
        row(Bratu::new(1.0), "Bratu n=50 lambda=1");
        row(Bratu::new(3.5), "Bratu n=50 lambda=3.5");
        row(Obstacle::default(), "Obstacle n=20 k=30");
    }
}
