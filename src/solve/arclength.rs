//! Pseudo-arclength continuation of `G(x, lambda) = 0`, `x` in `R^n`, through
//! folds: Keller's method (H. B. Keller, "Numerical solution of bifurcation
//! and nonlinear eigenvalue problems", 1977; Allgower & Georg, *Introduction
//! to Numerical Continuation Methods*, SIAM 2003, ch. 2). The branch is
//! parametrised by arclength in `|z|_w^2 = |x|^2 / n + w^2 lambda^2`,
//! `z = (x, lambda)` (the `1/n` makes it independent of a field's grid, as in
//! AUTO). From a point `z` with unit tangent `t` the predictor `z_p` at arc
//! length `s` (the Euler step `z + s t`, or for a homotopy the cubic Hermite
//! extrapolation of the last two points and their tangents, [`Predictor`]) is
//! corrected by Newton's method on `[G; <t, z' - z_p>_w] = 0` (its first
//! step here, the rest by [`nleq::solve`], NLEQ-ERR), whose Jacobian, `G`'s
//! bordered by `<t, .>_w`, is regular at a fold. A fold is the sign change of
//! the tangent's `lambda` component, located on the cubic Hermite interpolant
//! of `lambda(s)`. The new tangent solves `[[G_x, G_lambda], [<t, .>_w]] v =
//! [0; 1]`, which keeps the orientation `<v, t>_w > 0` (A-G sec. 2.1).
//!
//! The step is adapted from the corrector's first contraction `Theta_0`
//! (Deuflhard, *Newton Methods for Nonlinear Problems*, Springer 2004,
//! sec. 5.1), which grows as the predictor's error, `O(s^2)` for the Euler
//! step and `O(s^4)` for the Hermite one, within the bounds of Allgower &
//! Georg ch. 6. On strongly bent branches the Hermite predictor takes steps
//! several times longer for the same `Theta_0`; the tangent predictor's
//! shorter steps resolve every fold with points on both sides. A step that
//! crosses the target `lambda` is ended by a corrector at `lambda = target`
//! (bordering row `e_lambda`) from the linear interpolation of its two
//! points. A path stops where it leaves the system's domain in `lambda`
//! ([`ParametrisedSystem::domain`]).

use std::time::Instant;

mod walk;

#[cfg(test)]
use walk::hermite;
use walk::Walk;

use super::cancel;
use super::nleq::{self, NleqOptions, NonlinearSystem, DEFAULT_LAMBDA_MIN, DEFAULT_MAX_ITERATIONS};
use crate::error::{finite, positive, Error, Result, StopReason};

/// Target first contraction `Theta_0 = |dz_bar^1| / |dz^0|` (Deuflhard
/// eq. 5.24): the next step is `s sqrt(g(THETA_TARGET) / g(Theta_0))`,
/// `g(Theta) = sqrt(1 + 4 Theta) - 1`, the root as `Theta_0` grows as `s^2`.
/// Deuflhard's `1/4`: Newton's error then falls by `1e-9` in four iterations.
pub const THETA_TARGET: f64 = 0.25;

/// `Theta_0` above which a step is rejected before the corrector goes on.
/// `Theta_0 ~ h_0 / 2` for the Kantorovich quantity `h_0` (Deuflhard
/// sec. 2.1), and convergence is certain only for `h_0 < 2`: `1/2` keeps a
/// factor of two against converging to a point on another part of the branch.
pub const THETA_REJECT: f64 = 0.5;

/// Largest distance from the predictor, as a fraction of the step, at which a
/// point corrected despite `Theta_0 > THETA_REJECT` (a kink) is accepted. Half
/// the step keeps it in the cone of half-angle 27 degrees about the tangent,
/// away from other branches (A-G sec. 6.1, the distance criterion).
pub const KINK_DISTANCE: f64 = 0.5;

/// Bound on the change of the step, `[1/MAX_FACTOR, MAX_FACTOR]` (A-G
/// sec. 6.1): `Theta_0` is a small-step estimate, unreliable further out. A
/// corrector that failed halves the step.
pub const MAX_FACTOR: f64 = 2.0;

/// NLEQ iterations of a corrector after its first step: from `Theta_0 <= 1/2`
/// the error falls as `Theta_0^(2^k - 1)`, below `5e-10` of the predictor's in
/// five; the rest allow for damping and NLEQ's linearly converging chord steps.
pub const CORRECTOR_ITERATIONS: usize = 8;

/// Smallest damping factor of a corrector. Within [`THETA_REJECT`], `h_0 <= 1`
/// and Deuflhard's damping `min(1, 1/h)` (sec. 3.3) takes full steps; damping
/// below `1/4` (`h > 4`) means a predictor out of reach, replaced more cheaply
/// by a shorter step.
pub const CORRECTOR_LAMBDA_MIN: f64 = 0.25;

const SOLVER: &str = "pseudo-arclength continuation";

/// A system `G(x, lambda) = 0` with a scalar parameter, linearised in the
/// bordered form the continuation needs.
pub trait ParametrisedSystem {
    /// `n`, the dimension of `x` and of `G`.
    fn dim(&self) -> usize;
    /// `G(x, lambda)` into `f`.
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()>;
    /// `G(x, lambda)` into `f`, and `[[G_x, G_lambda], [row.0^T, row.1]]`
    /// factorised for [`solve_bordered`](Self::solve_bordered). The row is
    /// the weighted tangent, or `e_lambda` for a corrector at fixed `lambda`.
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()>;
    /// Solve the last bordered linearisation for `(b, b_last)` into
    /// `(dx, dlambda)`; `Ok(false)` if it is singular.
    fn solve_bordered(
        &mut self,
        b: &[f64],
        b_last: f64,
        dx: &mut [f64],
        dlambda: &mut f64,
    ) -> Result<bool>;
    /// Rounding floor of `max |G_i|` at `x` with residual `f` (0: unknown).
    fn floor(&self, _x: &[f64], _f: &[f64]) -> f64 {
        0.0
    }
    /// Work spent so far, in the system's own unit (e.g. IVPs).
    fn work(&self) -> f64;
    /// The interval of `lambda` on which `G` is the system's own; a path
    /// stops where an accepted point leaves it. Unbounded by default.
    fn domain(&self) -> (f64, f64) {
        (f64::NEG_INFINITY, f64::INFINITY)
    }
}

/// The direction in which the branch is followed from its start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Heading {
    /// `lambda` first moves toward the target (a homotopy, a sweep).
    #[default]
    TowardTarget,
    /// `lambda` first moves away from the target, reached after a fold.
    AwayFromTarget,
}

/// The predictor of each step ([`ArclengthOptions::predictor`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Predictor {
    /// The tangent (Euler) step `z + s t`, error `O(s^2)`: the step shrinks
    /// with the branch's curvature, so every fold is resolved by points on
    /// both sides (branch following, where the points matter).
    #[default]
    Tangent,
    /// The cubic Hermite extrapolation of the last two points and their
    /// tangents (`walk::hermite`), error `O(s^4)`: steps several times
    /// longer on strongly bent branches, which may step over a pair of folds
    /// narrower than a step (a homotopy, where only the end matters).
    Hermite,
}

/// Options of [`follow`].
#[derive(Debug, Clone)]
pub struct ArclengthOptions {
    /// Tolerance of every corrector: `max |G_i| <= tol` (or the system's floor).
    pub tol: f64,
    /// First arclength step (in the norm `|z|_w`).
    pub initial_step: f64,
    /// Smallest step: a shorter one fails the path.
    pub min_step: f64,
    /// Largest step.
    pub max_step: f64,
    /// Largest number of steps tried, rejected ones included.
    pub max_steps: usize,
    /// Largest work ([`ParametrisedSystem::work`]) of the path.
    pub max_work: f64,
    /// Wall-clock limit.
    pub deadline: Option<Instant>,
    /// Weight `w` of `lambda` in the arclength norm.
    pub lambda_weight: f64,
    /// The direction taken from the start.
    pub heading: Heading,
    /// The predictor of each step after the first (the first is the tangent's).
    pub predictor: Predictor,
    /// Iterations of each corrector (default [`CORRECTOR_ITERATIONS`]).
    pub corrector_iterations: usize,
}

impl Default for ArclengthOptions {
    fn default() -> Self {
        Self {
            tol: 1e-10,
            initial_step: 0.1,
            min_step: 1e-8,
            max_step: 1.0,
            max_steps: 1000,
            max_work: f64::INFINITY,
            predictor: Predictor::Tangent,
            deadline: None,
            lambda_weight: 1.0,
            heading: Heading::TowardTarget,
            corrector_iterations: CORRECTOR_ITERATIONS,
        }
    }
}

/// A solution on the branch.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// `x`.
    pub x: Vec<f64>,
    /// `lambda`.
    pub lambda: f64,
    /// `dlambda/ds` of the unit tangent along the path; changes sign at a fold.
    pub tangent_lambda: f64,
    /// Arclength step that reached this point (0 at the start).
    pub step: f64,
}

/// Why a path ended successfully.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The last point has `lambda = target` exactly.
    ReachedTarget,
    /// Event `i` (index in [`follow_with_events`]'s slice) fired between the
    /// last two points.
    Event(usize),
}

/// A followed branch.
#[derive(Debug, Clone)]
pub struct Path {
    /// The accepted points, start to end (only the end unless kept).
    pub points: Vec<PathPoint>,
    /// Folds `(lambda, i)` between points `i - 1` and `i` of the kept path.
    pub folds: Vec<(f64, usize)>,
    /// Why the path ended.
    pub stop: Stop,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Work of the path (the system's unit).
    pub work: f64,
    /// `max |G_i|` at the last point.
    pub residual: f64,
}

/// An event: called with each pair of consecutive accepted points; `true`
/// stops the path at the second.
pub type Event<'a> = &'a mut dyn FnMut(&PathPoint, &PathPoint) -> bool;

/// Follow the branch through `(x0, lambda0)` (first corrected at fixed
/// `lambda0` if `max |G_i| > opts.tol` there) until `lambda = target` exactly,
/// with `keep_path` the points on the way.
///
/// Errors: [`Error::NotConverged`] with [`StopReason::Budget`] when
/// `max_steps`, `max_work` or the deadline runs out (saying so if the branch
/// turned back at a fold), [`StopReason::LineSearch`] when the step falls
/// below `min_step`, [`StopReason::Other`] for no solution near the start or
/// a closed branch (back at its start after two folds),
/// [`StopReason::SingularJacobian`] when `G_x` is singular at the start;
/// [`Error::Interrupted`]; the system's `InvalidParameter` and `InvalidInput`
/// (its other errors reject the step, retried shorter). The error's
/// `residual` is the best of the correctors failed since the last point, else
/// the last point's; its `evaluations` the work spent, rounded.
pub fn follow<S: ParametrisedSystem + ?Sized>(
    sys: &mut S,
    x0: &[f64],
    lambda0: f64,
    target: f64,
    opts: &ArclengthOptions,
    keep_path: bool,
) -> Result<Path> {
    follow_with_events(sys, x0, lambda0, target, opts, keep_path, &mut [])
}

/// [`follow`], stopped by the first of `events` that fires between two
/// consecutive points ([`Stop::Event`]; the last point is the one after it).
pub fn follow_with_events<S: ParametrisedSystem + ?Sized>(
    sys: &mut S,
    x0: &[f64],
    lambda0: f64,
    target: f64,
    opts: &ArclengthOptions,
    keep_path: bool,
    events: &mut [Event<'_>],
) -> Result<Path> {
    validate(sys.dim(), x0, [lambda0, target], opts)?;
    let work0 = sys.work();
    let at = start(sys, x0, (lambda0, target), opts)?;
    let path = Path {
        points: vec![point(&at, 0.0)],
        folds: Vec::new(),
        stop: Stop::ReachedTarget,
        steps: 0,
        rejected: 0,
        work: 0.0,
        residual: at.residual,
    };
    let mut walk = Walk {
        s: opts.initial_step.clamp(opts.min_step, opts.max_step),
        z0: at.z.clone(),
        metric: Metric::new(x0.len(), opts.lambda_weight),
        at,
        target,
        opts,
        keep: keep_path,
        path,
        work0,
        failed: None,
        rejected_theta: None,
        prev: None,
    };
    let mut stop = (lambda0 == target).then_some(Stop::ReachedTarget);
    while stop.is_none() {
        cancel::check()?;
        walk.check_budget(sys.work() - work0)?;
        stop = walk.step(sys, events)?;
    }
    walk.path.work = sys.work() - work0;
    walk.path.stop = stop.unwrap_or(Stop::ReachedTarget);
    if !keep_path {
        walk.path.points.drain(..walk.path.points.len() - 1);
    }
    Ok(walk.path)
}

fn validate(n: usize, x0: &[f64], lambdas: [f64; 2], o: &ArclengthOptions) -> Result<()> {
    if x0.len() != n || n == 0 {
        let why = format!("{} values for a system of dimension {n}", x0.len());
        return Err(Error::input("x0", why));
    }
    if x0.iter().any(|v| !v.is_finite()) {
        return Err(Error::input("x0", "a non-finite value"));
    }
    finite("lambda0", lambdas[0])?;
    finite("target", lambdas[1])?;
    positive("tol", o.tol)?;
    positive("initial_step", o.initial_step)?;
    positive("min_step", o.min_step)?;
    positive("lambda_weight", o.lambda_weight)?;
    if !(o.max_step.is_finite() && o.max_step >= o.min_step) {
        return Err(Error::param("max_step", o.max_step, "finite, >= min_step"));
    }
    if !(o.max_work > 0.0) {
        return Err(Error::param("max_work", o.max_work, "> 0"));
    }
    Ok(())
}

/// The arclength inner product `<a, b>_w = a_x . b_x / n + w^2 a_l b_l`.
#[derive(Debug, Clone, Copy)]
struct Metric(f64, f64);

impl Metric {
    fn new(n: usize, w: f64) -> Self {
        Metric(1.0 / n as f64, w * w)
    }
    /// The bordering row `r` with `r . v = <t, v>_w`.
    fn row(&self, t: &[f64]) -> Vec<f64> {
        let n = t.len() - 1;
        let mut r: Vec<f64> = t.iter().map(|ti| ti * self.0).collect();
        r[n] = t[n] * self.1;
        r
    }
    fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        self.row(a).iter().zip(b).map(|(p, q)| p * q).sum()
    }
    fn norm(&self, a: &[f64]) -> f64 {
        self.dot(a, a).sqrt()
    }
    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        self.norm(&a.iter().zip(b).map(|(p, q)| p - q).collect::<Vec<_>>())
    }
}

/// `max |v_i|` (NaN if any component is NaN).
fn max_abs(v: &[f64]) -> f64 {
    match v.iter().any(|a| a.is_nan()) {
        true => f64::NAN,
        false => v.iter().fold(0.0, |m, a| m.max(a.abs())),
    }
}

/// `r`, with an error after which a step is retried shorter (all but a
/// cancellation and invalid arguments, as in NLEQ) replaced by `fallback`.
fn soft<T>(r: Result<T>, fallback: T) -> Result<T> {
    match r {
        Err(Error::Interrupted | Error::InvalidParameter { .. } | Error::InvalidInput { .. }) => r,
        Err(_) => Ok(fallback),
        ok => ok,
    }
}

/// The corrector's system `[G(x, lambda); row . (z - at)] = 0`. With `fix`
/// (`row = e_lambda`) the `lambda` correction is set to its exact value, the
/// last right-hand side, so `lambda` keeps `at`'s to the last bit.
struct Augmented<'a, S: ?Sized> {
    sys: &'a mut S,
    row: Vec<f64>,
    at: Vec<f64>,
    fix: bool,
}

impl<'a, S: ParametrisedSystem + ?Sized> Augmented<'a, S> {
    /// The corrector at the fixed `lambda` of `z`.
    fn at_lambda(sys: &'a mut S, z: &[f64]) -> Self {
        let n = z.len() - 1;
        let (mut row, at, fix) = (vec![0.0; n + 1], z.to_vec(), true);
        row[n] = 1.0;
        Augmented { sys, row, at, fix }
    }
    fn last(&self, z: &[f64]) -> f64 {
        let d = z.iter().zip(&self.at).map(|(a, b)| a - b);
        self.row.iter().zip(d).map(|(r, d)| r * d).sum()
    }
}

impl<S: ParametrisedSystem + ?Sized> NonlinearSystem for Augmented<'_, S> {
    fn dim(&self) -> usize {
        self.row.len()
    }
    fn residual(&mut self, z: &[f64], f: &mut [f64]) -> Result<()> {
        let n = z.len() - 1;
        self.sys.residual(&z[..n], z[n], &mut f[..n])?;
        f[n] = self.last(z);
        Ok(())
    }
    fn linearise(&mut self, z: &[f64], f: &mut [f64]) -> Result<()> {
        let (n, r) = (z.len() - 1, &self.row);
        let (x, row) = (&z[..n], (&r[..n], r[n]));
        self.sys.linearise_bordered(x, z[n], row, &mut f[..n])?;
        f[n] = self.last(z);
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dz: &mut [f64]) -> Result<bool> {
        let n = b.len() - 1;
        let (dx, dl) = dz.split_at_mut(n);
        let ok = self.sys.solve_bordered(&b[..n], b[n], dx, &mut dl[0])?;
        if self.fix {
            dl[0] = b[n];
        }
        Ok(ok)
    }
    fn floor(&self, z: &[f64], f: &[f64]) -> f64 {
        let n = z.len() - 1;
        self.sys.floor(&z[..n], &f[..n])
    }
    fn work(&self) -> f64 {
        self.sys.work()
    }
}

/// NLEQ-ERR from `z` with the path's tolerance and deadline, the work left
/// after `spent` (NLEQ reads 0 as none) and `(max_iterations, lambda_min)`:
/// the solution, or the best finite residual of a failed solve.
fn correct<S: ParametrisedSystem + ?Sized>(
    aug: &mut Augmented<'_, S>,
    z: &[f64],
    opts: &ArclengthOptions,
    spent: f64,
    (max_iterations, lambda_min): (usize, f64),
) -> Result<std::result::Result<Vec<f64>, Option<f64>>> {
    let left = opts.max_work - spent;
    let nopts = NleqOptions {
        tol: opts.tol,
        max_iterations,
        max_work: if left.is_finite() {
            left.max(f64::MIN_POSITIVE)
        } else {
            0.0
        },
        deadline: opts.deadline,
        lambda_min,
        ..NleqOptions::default()
    };
    match nleq::solve(aug, z, &nopts, SOLVER) {
        Ok(r) => Ok(Ok(r.x)),
        Err(Error::NotConverged { residual: r, .. }) => Ok(Err(Some(r).filter(|r| r.is_finite()))),
        Err(e) => soft(Err(e), Err(None)),
    }
}

/// The corrector's first Newton step from the predictor `z`, taken here for
/// `Theta_0 = |dz_bar^1|_w / |dz^0|_w` (simplified Newton correction at `z1`
/// over the Newton correction, Deuflhard sec. 5.1.3), which NLEQ does not
/// report: `(z1, Theta_0, max |F(z1)|, dz_bar^1)`, `(z, 0, max |F(z)|, 0)`
/// if `z` meets `tol`; `None` if `F` fails or is not finite, or the matrix
/// is singular. The factorisation at `z` stays for [`simplified`].
fn first_step<S: ParametrisedSystem + ?Sized>(
    aug: &mut Augmented<'_, S>,
    z: &[f64],
    tol: f64,
    metric: Metric,
) -> Result<Option<FirstStep>> {
    let m = z.len();
    let (mut f, mut dz, mut dzbar) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let evaluated = |r: Result<()>, f: &[f64]| soft(r.map(|_| max_abs(f).is_finite()), false);
    if !evaluated(aug.linearise(z, &mut f), &f)? {
        return Ok(None);
    }
    if max_abs(&f) <= tol.max(aug.floor(z, &f)) {
        return Ok(Some((z.to_vec(), 0.0, max_abs(&f), dzbar)));
    }
    if !soft(aug.solve(&f, &mut dz), false)? {
        return Ok(None);
    }
    let z1: Vec<f64> = z.iter().zip(&dz).map(|(a, d)| a - d).collect();
    if !evaluated(aug.residual(&z1, &mut f), &f)? || !soft(aug.solve(&f, &mut dzbar), false)? {
        return Ok(None);
    }
    let theta = metric.norm(&dzbar) / metric.norm(&dz);
    Ok(Some((z1, theta, max_abs(&f), dzbar)))
}

/// The corrector's first iterate `z1`, `Theta_0`, `max |F(z1)|` and the
/// simplified correction at `z1`.
type FirstStep = (Vec<f64>, f64, f64, Vec<f64>);

/// The simplified Newton corrector (Deuflhard sec. 5.1.3) from the first
/// iterate `z` and its simplified correction `d`, with the factorisation
/// at the predictor: each iteration one residual and one solve, no new
/// Jacobian. The solution, or `None` where a correction fails to contract
/// by [`THETA_REJECT`] over the last (the linear convergence of the chord
/// iteration is then too slow to pay) or after `iterations`.
fn simplified<S: ParametrisedSystem + ?Sized>(
    aug: &mut Augmented<'_, S>,
    (mut z, mut d): (Vec<f64>, Vec<f64>),
    (tol, iterations): (f64, usize),
    metric: Metric,
) -> Result<Option<Vec<f64>>> {
    let mut f = vec![0.0; z.len()];
    let mut last = metric.norm(&d);
    for _ in 0..iterations {
        z.iter_mut().zip(&d).for_each(|(a, b)| *a -= b);
        let ok = soft(aug.residual(&z, &mut f).map(|_| true), false)?;
        if !ok || !max_abs(&f).is_finite() {
            return Ok(None);
        }
        if max_abs(&f) <= tol.max(aug.floor(&z, &f)) {
            return Ok(Some(z));
        }
        if !soft(aug.solve(&f, &mut d), false)? {
            return Ok(None);
        }
        let norm = metric.norm(&d);
        if !(norm <= THETA_REJECT * last) {
            return Ok(None);
        }
        last = norm;
    }
    Ok(None)
}

/// A solution `z = (x, lambda)` with its unit tangent `t`, `max |G_i|` and
/// the system's floor of it.
#[derive(Debug, Clone)]
struct Found {
    z: Vec<f64>,
    t: Vec<f64>,
    residual: f64,
    floor: f64,
}

impl Found {
    fn lambda(&self) -> f64 {
        self.z[self.z.len() - 1]
    }
}

fn point(at: &Found, step: f64) -> PathPoint {
    let n = at.z.len() - 1;
    PathPoint {
        x: at.z[..n].to_vec(),
        lambda: at.z[n],
        tangent_lambda: at.t[n],
        step,
    }
}

/// `z` with its unit tangent `v / |v|_w`, `[[G_x, G_lambda], [row]] v = [0; 1]`;
/// `None` if the matrix is singular or the system fails or is not finite.
fn tangent<S>(sys: &mut S, z: Vec<f64>, row: &[f64], metric: Metric) -> Result<Option<Found>>
where
    S: ParametrisedSystem + ?Sized,
{
    let n = z.len() - 1;
    let (mut f, mut t) = (vec![0.0; n], vec![0.0; n + 1]);
    let (tx, tl) = t.split_at_mut(n);
    let solved = sys
        .linearise_bordered(&z[..n], z[n], (&row[..n], row[n]), &mut f)
        .and_then(|_| sys.solve_bordered(&vec![0.0; n], 1.0, tx, &mut tl[0]));
    let norm = metric.norm(&t);
    if !(soft(solved, false)? && norm.is_finite() && norm > 0.0 && max_abs(&f).is_finite()) {
        return Ok(None);
    }
    t.iter_mut().for_each(|ti| *ti /= norm);
    let (residual, floor) = (max_abs(&f), sys.floor(&z[..n], &f));
    Ok(Some(Found {
        z,
        t,
        residual,
        floor,
    }))
}

/// The start, corrected at fixed `lambda0` if needed (with NLEQ's default
/// limits, as it may be further off than a predictor), with its tangent from
/// the row `e_lambda`, oriented by the heading.
fn start<S: ParametrisedSystem + ?Sized>(
    sys: &mut S,
    x0: &[f64],
    (lambda0, target): (f64, f64),
    opts: &ArclengthOptions,
) -> Result<Found> {
    let z: Vec<f64> = x0.iter().copied().chain([lambda0]).collect();
    let (n, metric) = (x0.len(), Metric::new(x0.len(), opts.lambda_weight));
    let fail = |stop, residual, reason| Error::NotConverged {
        solver: SOLVER,
        iterations: 0,
        evaluations: 0,
        residual,
        stop,
        reason,
    };
    let singular = || {
        let why =
            format!("G_x is singular at the start, lambda = {lambda0} (a fold or a bifurcation)");
        fail(StopReason::SingularJacobian, f64::INFINITY, why)
    };
    let mut aug = Augmented::at_lambda(sys, &z);
    let mut first = tangent(aug.sys, z.clone(), &aug.row, metric)?.ok_or_else(singular)?;
    if first.residual > opts.tol.max(first.floor) {
        let limits = (DEFAULT_MAX_ITERATIONS, DEFAULT_LAMBDA_MIN);
        let r0 = first.residual;
        let x = correct(&mut aug, &z, opts, 0.0, limits)?.map_err(|best| {
            let why = format!("no solution near the start: max |G| = {r0:.3e}");
            fail(StopReason::Other, best.unwrap_or(r0), why)
        })?;
        first = tangent(aug.sys, x, &aug.row, metric)?.ok_or_else(singular)?;
    }
    let (toward, away) = (target >= lambda0, opts.heading == Heading::AwayFromTarget);
    let sign = if toward != away { 1.0 } else { -1.0 };
    if first.t[n] * sign < 0.0 {
        first.t.iter_mut().for_each(|ti| *ti = -*ti);
    }
    Ok(first)
}

#[cfg(test)]
#[path = "arclength_tests.rs"]
mod tests;
