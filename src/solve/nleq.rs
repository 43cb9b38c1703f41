//! Error-oriented damped Newton method NLEQ-ERR for square systems `F(x) = 0`
//! (P. Deuflhard, *Newton Methods for Nonlinear Problems*, Springer 2004, Sec.
//! 3.3; U. Nowak & L. Weimann, ZIB TR 91-10, 1991, code NLEQ1). Each step solves
//! `J(x) dx = -F(x)` and tries `x + lambda dx`, `lambda = min(1, 1/[h])` with the
//! prior estimate `[h] = |dxbar - dx| |dx| / (|x - x_J| |dxbar|)` from the last
//! factorisation point `x_J`. The trial passes the restricted monotonicity test if
//! the simplified correction `dxbar = -J(x)^-1 F(x + lambda dx)` has
//! `|dxbar| <= (1 - lambda/4) |dx|`; else `lambda` drops to `min(lambda/2,
//! 1/h_post)`, `h_post = 2 |dxbar - (1 - lambda) dx| / (lambda^2 |dx|)`, and halves
//! where `F` cannot be evaluated. All tests measure corrections in the unknowns
//! (scaled RMS norm), not the residual, so the iteration is invariant under
//! `F -> A F`. After a strongly contracting full step the factorisation is kept for
//! chord steps while they gain more per unit of work ([`CHORD_THETA`]). With the
//! generalised Jacobian of a piecewise-smooth `F` this is semismooth Newton, locally
//! superlinear where all generalised Jacobians are regular (L. Qi & J. Sun, Math.
//! Program. 58, 1993); the damping still models `F` as smooth and creeps across
//! stiff kinks. A solve returns the first evaluated point with `max |F| <= tol`
//! ([`Status::Converged`]), or at most the rounding floor or stalled within
//! [`FLOOR_FACTOR`] of it ([`Status::ConvergedAtFloor`]).

use std::time::Instant;

use super::cancel;
use crate::error::{Error, Result, StopReason};

/// A square system `F(x) = 0`, its residual dimensionless (order one is an
/// order-one error) and its unknowns of order one.
pub trait NonlinearSystem {
    /// Number of unknowns and of equations.
    fn dim(&self) -> usize;
    /// `F(x)` into `f`. An error other than `Interrupted`, `InvalidParameter` and
    /// `InvalidInput` (e.g. `Integration`) means `F` cannot be evaluated at `x`:
    /// the solver shortens its step.
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()>;
    /// `F(x)` into `f`, and the (generalised) Jacobian at `x` factorised for
    /// [`Self::solve`] until the next call.
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()>;
    /// `dx = J^-1 b` with the last linearisation; `Ok(false)` if `J` is singular.
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool>;
    /// Rounding floor of `max |F|` at `(x, f)`, below which `F` cannot be reduced
    /// in floating point; 0 if unknown.
    fn floor(&self, _x: &[f64], _f: &[f64]) -> f64 {
        0.0
    }
    /// Work spent so far, in the system's units (e.g. IVP-equivalents).
    fn work(&self) -> f64;
    /// For a residual that is smooth by pieces (a force law's kink): the
    /// smallest `lambda` in `(0, 1)` at which `x + lambda dx` leaves the piece
    /// of `x` for another one, if the full step does; `None` if it stays on
    /// one piece or the pieces are unknown.
    fn breakpoint(&self, _x: &[f64], _dx: &[f64]) -> Option<f64> {
        None
    }
}

/// Default smallest damping factor, NLEQ1's for highly nonlinear problems: a
/// trial at `1e-4 dx` that still fails means `[h] > 1e4`, a linear model that
/// does not describe `F` over a ten-thousandth of the Newton correction.
pub const DEFAULT_LAMBDA_MIN: f64 = 1e-4;

/// Default iteration limit, NLEQ-ERR's: quadratic convergence takes a few steps
/// once `h < 1`; at a singular root the rate is linear, 1/2 (D. W. Decker & C. T.
/// Kelley, SIAM J. Numer. Anal. 17, 1980), ~40 steps from order one to `1e-10`.
pub const DEFAULT_MAX_ITERATIONS: usize = 50;

/// Largest contraction `Theta = |dxbar| / |dx|` that keeps the factorisation for
/// chord steps: at `lambda = 1`, `[h] = 2 Theta`, and the simplified Newton
/// iteration converges for `h <= 1/2` (Deuflhard 2004, Sec. 2.1).
pub const CHORD_THETA: f64 = 0.25;

/// Stall margin over the rounding floor: a step computed from a residual with
/// noise `|e| <= floor` leaves `-e + e'` plus the linear solve's rounding (N. J.
/// Higham, *Accuracy and Stability of Numerical Algorithms*, 2002, Ch. 9); ten
/// covers both noise samples with a margin for a floor estimated from the terms.
pub const FLOOR_FACTOR: f64 = 10.0;

/// Options of [`solve`].
#[derive(Debug, Clone, PartialEq)]
pub struct NleqOptions {
    /// Converged when `max |F| <= tol`; 0 asks for the floor. Default `1e-10`, four
    /// digits above the rounding of an order-one residual of a few hundred terms.
    pub tol: f64,
    /// Accepted steps (Newton and chord) before [`StopReason::IterationLimit`].
    /// Default [`DEFAULT_MAX_ITERATIONS`].
    pub max_iterations: usize,
    /// Work budget, 0 (default) for none; checked before each evaluation, so a
    /// solve can overrun it by one linearisation.
    pub max_work: f64,
    /// Wall-clock deadline, checked before each evaluation. Default none.
    pub deadline: Option<Instant>,
    /// Smallest damping factor tried. Default [`DEFAULT_LAMBDA_MIN`].
    pub lambda_min: f64,
    /// Chord steps ([`CHORD_THETA`]), only when cheaper than a Jacobian. Default on.
    pub chord: bool,
    /// Scales `s_i > 0` of the unknowns (corrections are measured as `dx_i / s_i`).
    /// Default none: all 1.
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
    /// `max |F| > tol`, but at most the floor or stalled within [`FLOOR_FACTOR`] of it.
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
    /// Iterate and trial point (indexed by `At`), their residuals, the
    /// corrections `dx` and `dxbar`, and the last factorisation point.
    x: [Vec<f64>; 2],
    f: [Vec<f64>; 2],
    d: [Vec<f64>; 2],
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
    /// `solver_name`, with the best `max |F|` of all evaluated points (its
    /// `evaluations` is the work spent, rounded); [`Error::Interrupted`] from
    /// [`cancel::check`]; `InvalidParameter` / `InvalidInput` for bad options or
    /// from the system.
    pub fn solve<S: NonlinearSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        x0: &[f64],
        opts: &NleqOptions,
        solver_name: &'static str,
    ) -> Result<NleqResult> {
        self.run(sys, x0, None, opts, solver_name)
    }

    /// As [`Nleq::solve`], where the caller's last `sys.linearise(x0, f0)` left
    /// the factorisation at `x0` (not counted in the result).
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
        for v in self.x.iter_mut().chain(&mut self.f).chain(&mut self.d) {
            v.resize(n, 0.0);
        }
        self.xj.resize(n, 0.0);
        self.x[0].copy_from_slice(x0);
        let mut run = Run {
            work0: sys.work(),
            sys,
            opts,
            name,
            w: self,
            best: f64::INFINITY,
            iterations: 0,
            solves: 0,
            calls: [0; 2],
            cost: [0.0; 2],
            theta: 0.0,
            lambda: 1.0,
            damping: 1.0,
            ndx_j: 0.0,
        };
        let status = run.iterate(f0)?;
        Ok(NleqResult {
            x: run.w.x[0].clone(),
            residual: max_abs(&run.w.f[0]),
            status,
            iterations: run.iterations,
            linearisations: run.calls[0],
            evaluations: run.calls[1],
            solves: run.solves,
            work: run.sys.work() - run.work0,
            contraction: run.theta,
            damping: run.damping,
        })
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
        let allowed = "0 < lambda_min <= 1";
        return Err(Error::param("lambda_min", o.lambda_min, allowed));
    }
    match &o.scale {
        Some(s) if s.len() != n || s.iter().any(|v| !(v.is_finite() && *v > 0.0)) => {
            Err(Error::input("scale", format!("need {n} finite values > 0")))
        }
        _ => Ok(()),
    }
}

/// Scaled RMS norm of `a u + b v`, the largest term factored out against
/// overflow and underflow.
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

/// `Err(e)` for errors passed to the caller, `Ok(message)` for an evaluation
/// that failed at this point.
fn evaluation_failure(e: Error) -> Result<String> {
    match e {
        Error::Interrupted | Error::InvalidParameter { .. } | Error::InvalidInput { .. } => Err(e),
        other => Ok(other.to_string()),
    }
}

/// The current iterate or the trial point.
#[derive(Clone, Copy)]
enum At {
    Current = 0,
    Trial = 1,
}

/// One solve in progress.
struct Run<'a, S: ?Sized> {
    sys: &'a mut S,
    opts: &'a NleqOptions,
    name: &'static str,
    w: &'a mut Nleq,
    /// Work at the start, smallest `max |F|` of all evaluated points, accepted
    /// steps, calls of `solve`, and calls of `linearise` and `residual` (indexed by
    /// [`At`]) with the work of the last of each.
    work0: f64,
    best: f64,
    iterations: usize,
    solves: usize,
    calls: [usize; 2],
    cost: [f64; 2],
    /// Contraction and damping factor of the last accepted step, the smallest
    /// damping factor accepted, and `|dx|` at the factorisation point.
    theta: f64,
    lambda: f64,
    damping: f64,
    ndx_j: f64,
}

impl<S: NonlinearSystem + ?Sized> Run<'_, S> {
    fn iterate(&mut self, f0: Option<&[f64]>) -> Result<Status> {
        match f0 {
            Some(f) if f.iter().all(|v| v.is_finite()) => self.w.f[0].copy_from_slice(f),
            Some(_) => return Err(self.fail(StopReason::NonFinite, "F(x0) not finite".into())),
            None => self.linearise("the starting point")?,
        }
        self.w.xj.copy_from_slice(&self.w.x[0]);
        if let Some(status) = self.status(At::Current) {
            return Ok(status);
        }
        let mut distance = None; // |x - x_J|, for the prior estimate
        loop {
            self.limits()?;
            let status = match self.newton_step(distance)? {
                None => self.chord()?,
                done => done,
            };
            if let Some(status) = status {
                return Ok(status);
            }
            distance = Some(self.norm(&self.w.x[0], -1.0, &self.w.xj));
            self.linearise("an accepted iterate")?;
            self.w.xj.copy_from_slice(&self.w.x[0]);
        }
    }

    /// One damped Newton step from `x`, factorised there, where `dxbar` holds the
    /// previous factorisation's correction, at `distance`. `Some` if converged.
    fn newton_step(&mut self, distance: Option<f64>) -> Result<Option<Status>> {
        self.correction(At::Current)?;
        let lmin = self.opts.lambda_min;
        let [dx, dxbar] = &self.w.d;
        let ndx = self.norm(dx, 0.0, dx);
        let den = self.norm(dxbar, -1.0, dx) * ndx;
        self.ndx_j = ndx;
        // The prior estimate, raised to lambda_min so that it is tried (NLEQ1).
        let prior = |d: f64| (d * self.norm(dxbar, 0.0, dxbar) / den).min(1.0);
        let mut lambda = distance.filter(|_| den > 0.0).map_or(1.0, prior).max(lmin);
        // Below lambda_min only once lambda_min itself has been tried (NLEQ-ERR).
        let reduce = |l: f64, to: f64| if l > lmin { to.max(lmin) } else { to };
        let (mut reduced, mut evaluated, mut theta) = (false, false, f64::NAN);
        let mut last_error = String::new();
        loop {
            if lambda < lmin {
                return Err(self.damping_failure(evaluated, theta, &last_error));
            }
            if !self.move_trial(lambda, 0) {
                return self.at_rounding_level(lambda, ndx).map(Some);
            }
            if let Some(message) = self.evaluate(At::Trial)? {
                (last_error, lambda, reduced) = (message, reduce(lambda, 0.5 * lambda), true);
                continue;
            }
            evaluated = true;
            if let Some(status) = self.status(At::Trial) {
                self.accept(lambda, self.theta);
                return Ok(Some(status));
            }
            self.correction(At::Trial)?;
            let [dx, dxbar] = &self.w.d;
            theta = self.norm(dxbar, 0.0, dxbar) / ndx;
            // 1/h_post; f64::min ignores a NaN from 0/0.
            let mu = 0.5 * ndx * lambda * lambda / self.norm(dxbar, lambda - 1.0, dx);
            if !(theta <= 1.0 - 0.25 * lambda) {
                if self.stagnant() {
                    return Ok(Some(Status::ConvergedAtFloor));
                }
                // A trial past a breakpoint of a piecewise smooth residual
                // measures the other piece, not the curvature of this one:
                // the next trial is the breakpoint, where the next Jacobian
                // is the other piece's (Kojima & Shindo, J. Oper. Res. Soc.
                // Japan 29, 1986)
                let kink = self.sys.breakpoint(&self.w.x[0], &self.w.d[0]);
                let next = match kink.filter(|&b| b < lambda) {
                    Some(b) => b,
                    None => f64::min(mu, 0.5 * lambda),
                };
                (lambda, reduced) = (reduce(lambda, next), true);
            } else if !reduced && lambda < 1.0 && f64::min(1.0, mu) >= 4.0 * lambda {
                lambda = f64::min(1.0, mu); // a posteriori factor 4x larger: retry (NLEQ-ERR)
            } else {
                self.accept(lambda, theta);
                return Ok(None);
            }
        }
    }

    /// Chord steps `x <- x + dxbar` while [`Self::chord_pays`]; a step that fails
    /// the test at `lambda = 1` (`Theta > 3/4`) or cannot be evaluated is dropped.
    fn chord(&mut self) -> Result<Option<Status>> {
        while self.chord_pays() {
            self.limits()?;
            if !self.move_trial(1.0, 1) || self.evaluate(At::Trial)?.is_some() {
                return Ok(None);
            }
            if let Some(status) = self.status(At::Trial) {
                self.accept(1.0, self.theta);
                return Ok(Some(status));
            }
            self.w.d.swap(0, 1); // the step taken becomes `dx`
            self.correction(At::Trial)?;
            let [dx, dxbar] = &self.w.d;
            let theta = self.norm(dxbar, 0.0, dxbar) / self.norm(dx, 0.0, dx);
            if !(theta <= 0.75) {
                self.w.d.swap(0, 1);
                return Ok(None);
            }
            self.accept(1.0, theta);
        }
        Ok(None)
    }

    /// After a full step, whether a chord step gains more digits per unit of work
    /// than a Newton step. With errors `e_J` at the factorisation point and `e` now,
    /// a chord step contracts by `Theta_c ~ omega e_J` (the last contraction), a
    /// Newton step by `omega e / 2 = Theta_c Pi / 2`, `Pi = |dxbar| / |dx_J| ~ e /
    /// e_J` (Deuflhard 2004, Sec. 2.1), at measured costs `c_F` and `c_L + c_F`;
    /// unknown costs leave only `Theta_c <= CHORD_THETA`.
    fn chord_pays(&self) -> bool {
        if !(self.opts.chord && self.lambda == 1.0 && self.theta <= CHORD_THETA) {
            return false;
        }
        let pi = self.norm(&self.w.d[1], 0.0, &self.w.d[1]) / self.ndx_j;
        let ([cl, cf], theta_newton) = (self.cost, 0.5 * self.theta * pi);
        !(cf > 0.0 && cl > 0.0)
            || (cl + cf) * (1.0 / self.theta).ln() >= cf * (1.0 / theta_newton).ln()
    }

    /// `xt = x + lambda d` with `d = dx` (0) or `dxbar` (1); false if `xt == x`.
    fn move_trial(&mut self, lambda: f64, d: usize) -> bool {
        let [x, xt] = &mut self.w.x;
        for ((t, x), d) in xt.iter_mut().zip(&*x).zip(&self.w.d[d]) {
            *t = x + lambda * d;
        }
        xt != x
    }

    /// `x + lambda dx == x`: at the floor if [`Self::stagnant`] (the test would fail
    /// with `Theta = 1`), else no damping can make progress.
    fn at_rounding_level(&mut self, lambda: f64, ndx: f64) -> Result<Status> {
        if self.stagnant() {
            return Ok(Status::ConvergedAtFloor);
        }
        let (r, tol) = (max_abs(&self.w.f[0]), self.opts.tol);
        let floor = self.floor(At::Current);
        let reason = format!(
            "lambda dx (lambda = {lambda:.1e}, |dx| = {ndx:.1e}) is below the rounding level of \
             x, while max|F| = {r:.2e} exceeds tol = {tol:.1e} and {FLOOR_FACTOR} times the \
             rounding floor {floor:.1e}"
        );
        Err(self.fail(StopReason::LineSearch, reason))
    }

    /// Within [`FLOOR_FACTOR`] of the floor at `x`, where a failed test is noise.
    fn stagnant(&self) -> bool {
        max_abs(&self.w.f[0]) <= FLOOR_FACTOR * self.floor(At::Current)
    }

    fn floor(&self, at: At) -> f64 {
        let (x, f) = (&self.w.x[at as usize], &self.w.f[at as usize]);
        let v = self.sys.floor(x, f);
        if v.is_finite() {
            v.max(0.0)
        } else {
            0.0
        }
    }

    /// Convergence test at an evaluated point; records the best residual.
    fn status(&mut self, at: At) -> Option<Status> {
        let r = max_abs(&self.w.f[at as usize]);
        self.best = self.best.min(r);
        if r <= self.opts.tol {
            Some(Status::Converged)
        } else {
            (r <= self.floor(at)).then_some(Status::ConvergedAtFloor)
        }
    }

    fn accept(&mut self, lambda: f64, theta: f64) {
        self.w.x.swap(0, 1);
        self.w.f.swap(0, 1);
        self.iterations += 1;
        (self.lambda, self.theta) = (lambda, theta);
        self.damping = self.damping.min(lambda);
    }

    fn norm(&self, u: &[f64], b: f64, v: &[f64]) -> f64 {
        norm(self.opts.scale.as_deref(), 1.0, u, b, v)
    }

    /// `F` and the Jacobian at `x` (`Current`) or `F` at `xt` (`Trial`);
    /// `Ok(Some(message))` if not evaluable or not finite.
    fn evaluate(&mut self, at: At) -> Result<Option<String>> {
        self.budget()?;
        let (i, w, before) = (at as usize, &mut *self.w, self.sys.work());
        self.calls[i] += 1;
        let result = match at {
            At::Current => self.sys.linearise(&w.x[0], &mut w.f[0]),
            At::Trial => self.sys.residual(&w.x[1], &mut w.f[1]),
        };
        self.cost[i] = self.sys.work() - before;
        match result {
            Err(e) => evaluation_failure(e).map(Some),
            Ok(()) if w.f[i].iter().any(|v| !v.is_finite()) => Ok(Some("F not finite".into())),
            Ok(()) => Ok(None),
        }
    }

    fn linearise(&mut self, what: &str) -> Result<()> {
        let Some(message) = self.evaluate(At::Current)? else {
            return Ok(());
        };
        let reason = format!("F and its Jacobian at {what} cannot be evaluated: {message}");
        Err(self.fail(StopReason::NonFinite, reason))
    }

    /// `dx = -J^-1 F(x)` or `dxbar = -J^-1 F(xt)`.
    fn correction(&mut self, at: At) -> Result<()> {
        self.solves += 1;
        let (w, i) = (&mut *self.w, at as usize);
        let regular = match self.sys.solve(&w.f[i], &mut w.d[i]) {
            Ok(regular) => regular,
            Err(e) => evaluation_failure(e).map(|_| false)?,
        };
        w.d[i].iter_mut().for_each(|v| *v = -*v);
        if regular && w.d[i].iter().all(|v| v.is_finite()) {
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
    fn limits(&self) -> Result<()> {
        cancel::check()?;
        let (k, tol, theta) = (self.iterations, self.opts.tol, self.theta);
        if k >= self.opts.max_iterations {
            let r = max_abs(&self.w.f[0]);
            let reason = format!(
                "{k} steps without max|F| <= {tol:.1e} (now {r:.2e}; last contraction {theta:.2}: \
                 near 1 is slow linear convergence, as at a singular root)"
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
}

#[cfg(test)]
#[path = "nleq_tests.rs"]
mod tests;
