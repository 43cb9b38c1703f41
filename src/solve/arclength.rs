//! Pseudo-arclength continuation of a parametrised system `G(x, lambda) = 0`,
//! `x` in `R^n`, through folds.
//!
//! Keller's method (H. B. Keller, "Numerical solution of bifurcation and
//! nonlinear eigenvalue problems", 1977; Allgower & Georg, *Introduction to
//! Numerical Continuation Methods*, SIAM 2003, ch. 2): the branch is
//! parametrised by its arclength `s` in the norm
//! `|z|_w^2 = |x|^2 / n + w^2 lambda^2` of `z = (x, lambda)` (`w` is
//! [`ArclengthOptions::lambda_weight`]; the `1/n` makes the norm of a
//! discretised field independent of its grid, as in AUTO). From a solution
//! `z` with unit tangent `t`, the Euler predictor `z + s t` is corrected by
//! Newton's method on the augmented system
//! `[G(x, lambda); <t, z' - z - s t>_w] = 0` (its first step here, to
//! measure the contraction the step rule needs, the rest by [`nleq::solve`],
//! NLEQ-ERR), whose Jacobian, `G`'s bordered by the row `<t, .>_w`, is
//! regular at a fold: a fold is passed like any other point, and recognised
//! afterwards by the sign change of the tangent's `lambda` component
//! (located by the cubic Hermite interpolant of `lambda(s)`). The new tangent
//! solves `[[G_x, G_lambda], [<t, .>_w]] v = [0; 1]` (normalised; the `1`
//! keeps `<v, t>_w > 0`, the orientation of the path, Allgower-Georg
//! sec. 2.1). The step is adapted from the corrector's first contraction
//! `Theta_0` as in Deuflhard, *Newton Methods for Nonlinear Problems*
//! (Springer 2004), sec. 5.1.3, within Allgower-Georg's bounds of sec. 6.1
//! (see [`THETA_TARGET`], [`THETA_REJECT`], [`KINK_DISTANCE`],
//! [`MAX_FACTOR`]). When a step
//! crosses the target `lambda`, the last point is corrected at
//! `lambda = target` exactly (bordering row `e_lambda`) from the linear
//! interpolation of the two points about the crossing.

use std::time::Instant;

use super::cancel;
use super::nleq::{self, NleqOptions, NonlinearSystem, DEFAULT_LAMBDA_MIN, DEFAULT_MAX_ITERATIONS};
use crate::error::{finite, positive, Error, Result, StopReason};

/// The corrector's target first contraction `Theta_0 = |dz_bar^1| / |dz^0|`
/// (Deuflhard sec. 5.1.3, eq. 5.24): the next step is
/// `s sqrt(g(THETA_TARGET) / g(Theta_0))`, `g(Theta) = sqrt(1 + 4 Theta) - 1`,
/// the square root because the Euler predictor's error, and with it
/// `Theta_0`, grows as `s^2`. `1/4` (`g = sqrt(2) - 1`) is Deuflhard's
/// choice: Newton's error then falls as `4^-(2^k - 1)`, by `1e-9` in four
/// iterations.
pub const THETA_TARGET: f64 = 0.25;

/// First contraction above which the step is rejected, before the
/// corrector goes on, and retried with the same rule, shorter.
/// `Theta_0 ~ h_0 / 2` for the
/// Kantorovich quantity `h_0 = omega |dz^0|` (Deuflhard sec. 2.1), and
/// Newton is guaranteed to converge only for `h_0 < 2`; `1/2` keeps a factor
/// of two from that limit, as `Theta_0` is only an estimate and a corrector
/// near its limit may converge to a solution other than the nearest (on
/// another part of the branch, or another branch).
pub const THETA_REJECT: f64 = 0.5;

/// Largest distance from the predictor, as a fraction of the step, at
/// which a corrected point whose first contraction exceeded
/// [`THETA_REJECT`] is accepted. The predictor's error is `O(s^2)` on a
/// smooth branch and `O(s |dt|)` across a kink, where the tangent jumps by
/// `dt` (at most 2 for unit tangents); half the step keeps the corrected
/// point inside the cone of half-angle 27 degrees about the tangent, away
/// from other branches, which meet the path at finite distance
/// (Allgower & Georg sec. 6.1, the distance criterion of step control).
pub const KINK_DISTANCE: f64 = 0.5;

/// Bound on the change of the step: at most doubled after an accepted step
/// and at least halved after it; halved after a corrector that failed.
/// Allgower & Georg sec. 6.1 bound their deceleration factor to `[1/2, 2]`:
/// `Theta_0` is an asymptotic (small-step) estimate, unreliable for
/// factors further out.
pub const MAX_FACTOR: f64 = 2.0;

/// NLEQ iterations of a corrector after its first Newton step. From
/// `Theta_0 <= 1/2` Newton's error falls as `Theta_0^(2^k - 1)` (Deuflhard
/// sec. 2.1), below `2^-31 = 5e-10` of the predictor's error after five
/// iterations; the rest allow for damping and for NLEQ's chord steps, which
/// converge linearly.
pub const CORRECTOR_ITERATIONS: usize = 8;

/// Smallest damping factor of a corrector's Newton step. A predictor
/// within [`THETA_REJECT`] has `h_0 ~ 2 Theta_0 <= 1`, for which
/// Deuflhard's damping `min(1, 1/h)` (sec. 3.3) takes full steps; one that
/// needs damping below `1/4` (`h > 4`, `Theta_0 ~ 2`) started far outside
/// the corrector's reach and is replaced by a shorter step more cheaply.
pub const CORRECTOR_LAMBDA_MIN: f64 = 0.25;

/// Name of the continuation in its errors.
const SOLVER: &str = "pseudo-arclength continuation";

/// A system `G(x, lambda) = 0` with a scalar parameter, linearised in the
/// bordered form the continuation needs.
pub trait ParametrisedSystem {
    /// `n`, the dimension of `x` and of `G`.
    fn dim(&self) -> usize;
    /// `G(x, lambda)` into `f`.
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()>;
    /// `G(x, lambda)` into `f`, and the bordered Jacobian
    /// `[[G_x, G_lambda], [row.0^T, row.1]]` factorised for
    /// [`solve_bordered`](Self::solve_bordered). The row is the weighted
    /// tangent, or `e_lambda` for a corrector at fixed `lambda`.
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()>;
    /// Solve the last bordered linearisation for the right-hand side
    /// `(b, b_last)` into `(dx, dlambda)`; `Ok(false)` if it is singular.
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
}

/// The direction in which the branch is followed from its start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Heading {
    /// `lambda` first moves toward the target (a homotopy, a sweep).
    #[default]
    TowardTarget,
    /// `lambda` first moves away from the target: the target is reached
    /// after a fold (the upper branch of a problem with two solutions).
    AwayFromTarget,
}

/// Options of [`follow`].
#[derive(Debug, Clone)]
pub struct ArclengthOptions {
    /// Tolerance of every corrector: `max |G_i| <= tol` (or the system's floor).
    pub tol: f64,
    /// First arclength step (in the norm `|z|_w`).
    pub initial_step: f64,
    /// Smallest step: a step that would be shorter fails the path.
    pub min_step: f64,
    /// Largest step.
    pub max_step: f64,
    /// Largest number of steps tried, rejected ones included.
    pub max_steps: usize,
    /// Largest work (the system's [`ParametrisedSystem::work`]) of the path.
    pub max_work: f64,
    /// Wall-clock limit.
    pub deadline: Option<Instant>,
    /// Weight `w` of `lambda` in the arclength norm `|x|^2 / n + w^2 lambda^2`.
    pub lambda_weight: f64,
    /// The direction taken from the start.
    pub heading: Heading,
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
            deadline: None,
            lambda_weight: 1.0,
            heading: Heading::TowardTarget,
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
    /// `dlambda/ds`, the `lambda` component of the unit tangent (oriented
    /// along the path); its sign changes at a fold.
    pub tangent_lambda: f64,
    /// Arclength step that reached this point (0 at the start).
    pub step: f64,
}

/// Why a path ended successfully.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The last point has `lambda = target` exactly.
    ReachedTarget,
    /// Event `i` (its index in the slice given to [`follow_with_events`])
    /// fired between the last two points.
    Event(usize),
}

/// A followed branch.
#[derive(Debug, Clone)]
pub struct Path {
    /// The accepted points from the start to the end (only the end point
    /// unless the path was kept).
    pub points: Vec<PathPoint>,
    /// Folds: `(lambda, i)`, the fold's `lambda` (from the cubic Hermite
    /// interpolant of `lambda(s)` through the two points) between points
    /// `i - 1` and `i` (indices of the kept path).
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

/// Follow the branch through `(x0, lambda0)` (a solution: if `max |G_i|`
/// exceeds `opts.tol` there it is first corrected at fixed `lambda0`) until
/// `lambda = target` exactly, with `keep_path` the points on the way.
///
/// Errors: [`Error::NotConverged`] with [`StopReason::Budget`] when
/// `max_steps`, `max_work` or the deadline runs out (the message says so
/// when the branch turned back at a fold and moves away from the target),
/// [`StopReason::LineSearch`] when the step falls below `min_step`,
/// [`StopReason::Other`] when the branch is closed (it comes back to its
/// start after two folds), [`StopReason::SingularJacobian`] when `G_x` is
/// singular at the start; [`Error::Interrupted`]; the system's
/// `InvalidParameter` and `InvalidInput` (any other error of the system,
/// such as [`Error::Integration`], rejects the step, which is retried
/// shorter). The error's `residual` is the best of the correctors that
/// failed since the last point, else the last point's; its `evaluations`
/// the work spent, rounded.
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

/// [`follow`], stopped early by the first of `events` that fires between
/// two consecutive points ([`Stop::Event`]; the last point is the one after
/// the event, which can be the point at the target).
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
    let first = start(sys, x0, (lambda0, target), opts)?;
    let mut walk = Walk::new(first, target, opts, keep_path, work0);
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

/// The arclength inner product `<a, b>_w = a_x . b_x / n + w^2 a_l b_l` of
/// `z = (x, lambda)` vectors.
#[derive(Debug, Clone, Copy)]
struct Metric(f64, f64);

impl Metric {
    fn new(n: usize, weight: f64) -> Self {
        Metric(1.0 / n as f64, weight * weight)
    }

    /// The bordering row `r` with `r . v = <t, v>_w`.
    fn row(&self, t: &[f64]) -> Vec<f64> {
        let n = t.len() - 1;
        (0..=n)
            .map(|i| t[i] * if i < n { self.0 } else { self.1 })
            .collect()
    }

    fn dot(&self, a: &[f64], b: &[f64]) -> f64 {
        self.row(a).iter().zip(b).map(|(p, q)| p * q).sum()
    }

    fn norm(&self, a: &[f64]) -> f64 {
        self.dot(a, a).sqrt()
    }

    fn distance(&self, a: &[f64], b: &[f64]) -> f64 {
        let d: Vec<f64> = a.iter().zip(b).map(|(p, q)| p - q).collect();
        self.dot(&d, &d).sqrt()
    }
}

/// `max |v_i|` (NaN if any component is NaN).
fn max_abs(v: &[f64]) -> f64 {
    match v.iter().any(|a| a.is_nan()) {
        true => f64::NAN,
        false => v.iter().fold(0.0, |m, a| m.max(a.abs())),
    }
}

fn e_lambda(n: usize) -> Vec<f64> {
    (0..=n).map(|i| if i < n { 0.0 } else { 1.0 }).collect()
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
    let positive_ones = [
        ("tol", o.tol),
        ("initial_step", o.initial_step),
        ("min_step", o.min_step),
        ("lambda_weight", o.lambda_weight),
    ];
    for (name, value) in positive_ones {
        positive(name, value)?;
    }
    if !(o.max_step.is_finite() && o.max_step >= o.min_step) {
        return Err(Error::param("max_step", o.max_step, "finite, >= min_step"));
    }
    match o.max_work > 0.0 {
        true => Ok(()),
        false => Err(Error::param("max_work", o.max_work, "> 0")),
    }
}

/// The corrector's system: `[G(x, lambda); row . (z - anchor)] = 0` for
/// `z = (x, lambda)`, with `G`'s Jacobian bordered by `row`. With
/// `fixed` (`row = e_lambda`) the `lambda` correction is set to the last
/// right-hand side, its exact value, so `lambda` stays at the anchor's to
/// the last bit.
struct Augmented<'a, S: ?Sized> {
    sys: &'a mut S,
    row: Vec<f64>,
    anchor: Vec<f64>,
    fixed: bool,
}

impl<S: ParametrisedSystem + ?Sized> Augmented<'_, S> {
    fn last(&self, z: &[f64]) -> f64 {
        let d = z.iter().zip(&self.anchor).map(|(a, b)| a - b);
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
        let n = z.len() - 1;
        let row = (&self.row[..n], self.row[n]);
        self.sys
            .linearise_bordered(&z[..n], z[n], row, &mut f[..n])?;
        f[n] = self.last(z);
        Ok(())
    }

    fn solve(&mut self, b: &[f64], dz: &mut [f64]) -> Result<bool> {
        let n = b.len() - 1;
        let (dx, dl) = dz.split_at_mut(n);
        let ok = self.sys.solve_bordered(&b[..n], b[n], dx, &mut dl[0])?;
        if self.fixed {
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

/// Errors after which a step is retried shorter: all but a cancellation
/// and invalid arguments (a corrector that did not converge, a system that
/// cannot be evaluated at a trial point), as NLEQ treats its system's.
fn recoverable(e: &Error) -> bool {
    !matches!(
        e,
        Error::Interrupted | Error::InvalidParameter { .. } | Error::InvalidInput { .. }
    )
}

/// `r`, with a recoverable error replaced by `fallback`.
fn soft<T>(r: Result<T>, fallback: T) -> Result<T> {
    match r {
        Err(e) if recoverable(&e) => Ok(fallback),
        other => other,
    }
}

/// Iteration limit and smallest damping factor of a corrector from a
/// predictor; the start, which may be further off, gets NLEQ's defaults.
const CORRECTOR: (usize, f64) = (CORRECTOR_ITERATIONS, CORRECTOR_LAMBDA_MIN);

/// Options of a corrector: the path's tolerance and deadline, what is left
/// of its work budget after `spent` (NLEQ reads 0 as none), and
/// `(max_iterations, lambda_min)`.
fn nleq_options(opts: &ArclengthOptions, spent: f64, limits: (usize, f64)) -> NleqOptions {
    let left = opts.max_work - spent;
    NleqOptions {
        tol: opts.tol,
        max_iterations: limits.0,
        max_work: if left.is_finite() {
            left.max(f64::MIN_POSITIVE)
        } else {
            0.0
        },
        deadline: opts.deadline,
        lambda_min: limits.1,
        ..NleqOptions::default()
    }
}

/// NLEQ-ERR from `z` on the augmented system: the solution, or the best
/// residual of a failed solve (`None` if it failed before computing one).
fn correct<S: ParametrisedSystem + ?Sized>(
    aug: &mut Augmented<'_, S>,
    z: &[f64],
    nopts: &NleqOptions,
) -> Result<std::result::Result<Vec<f64>, Option<f64>>> {
    match nleq::solve(aug, z, nopts, SOLVER) {
        Ok(r) => Ok(Ok(r.x)),
        Err(Error::NotConverged { residual, .. }) => {
            Ok(Err(Some(residual).filter(|r| r.is_finite())))
        }
        Err(e) if recoverable(&e) => Ok(Err(None)),
        Err(e) => Err(e),
    }
}

/// The corrector's first Newton step from the predictor `z`, taken here to
/// measure its contraction `Theta_0 = |dz_bar^1|_w / |dz^0|_w` (the
/// simplified Newton correction at the new point over the Newton correction,
/// Deuflhard sec. 5.1.3), which the step rule needs and NLEQ does not
/// report. `Some((z1, Theta_0, max |F(z1)|))`, with `z1 = z` and
/// `Theta_0 = 0` if `z` already meets `tol`; `None` if `F` cannot be
/// evaluated or is not finite, or the bordered matrix is singular.
fn first_step<S: ParametrisedSystem + ?Sized>(
    aug: &mut Augmented<'_, S>,
    z: &[f64],
    tol: f64,
    metric: Metric,
) -> Result<Option<(Vec<f64>, f64, f64)>> {
    let m = z.len();
    let (mut f, mut dz, mut dzbar) = (vec![0.0; m], vec![0.0; m], vec![0.0; m]);
    let evaluated = |r: Result<()>, f: &[f64]| soft(r.map(|_| max_abs(f).is_finite()), false);
    if !evaluated(aug.linearise(z, &mut f), &f)? {
        return Ok(None);
    }
    if max_abs(&f) <= tol.max(aug.floor(z, &f)) {
        return Ok(Some((z.to_vec(), 0.0, max_abs(&f))));
    }
    if !soft(aug.solve(&f, &mut dz), false)? {
        return Ok(None);
    }
    let z1: Vec<f64> = z.iter().zip(&dz).map(|(a, d)| a - d).collect();
    if !evaluated(aug.residual(&z1, &mut f), &f)? || !soft(aug.solve(&f, &mut dzbar), false)? {
        return Ok(None);
    }
    let theta = metric.norm(&dzbar) / metric.norm(&dz);
    Ok(Some((z1, theta, max_abs(&f))))
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

/// The solution `z` with its unit tangent: `[[G_x, G_lambda], [row]] v =
/// [0; 1]`, `v / |v|_w`; `None` if the bordered matrix is singular or the
/// system fails or is not finite there.
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

/// The start, corrected at fixed `lambda0` if needed, with its tangent
/// from the row `e_lambda`, oriented by the heading.
fn start<S: ParametrisedSystem + ?Sized>(
    sys: &mut S,
    x0: &[f64],
    (lambda0, target): (f64, f64),
    opts: &ArclengthOptions,
) -> Result<Found> {
    let (n, metric) = (x0.len(), Metric::new(x0.len(), opts.lambda_weight));
    let e = e_lambda(n);
    let z: Vec<f64> = x0.iter().copied().chain([lambda0]).collect();
    let why = format!("G_x is singular at the start, lambda = {lambda0} (a fold or a bifurcation)");
    let fail = |stop, residual, reason| Error::NotConverged {
        solver: SOLVER,
        iterations: 0,
        evaluations: 0,
        residual,
        stop,
        reason,
    };
    let singular = || fail(StopReason::SingularJacobian, f64::INFINITY, why.clone());
    let mut first = tangent(sys, z.clone(), &e, metric)?.ok_or_else(singular)?;
    if first.residual > opts.tol.max(first.floor) {
        let why = format!(
            "no solution near the start: max |G| = {:.3e}",
            first.residual
        );
        let nopts = nleq_options(opts, 0.0, (DEFAULT_MAX_ITERATIONS, DEFAULT_LAMBDA_MIN));
        let (row, anchor) = (e.clone(), z.clone());
        let mut aug = Augmented {
            sys,
            row,
            anchor,
            fixed: true,
        };
        let x = correct(&mut aug, &z, &nopts)?
            .map_err(|best| fail(StopReason::Other, best.unwrap_or(first.residual), why))?;
        first = tangent(aug.sys, x, &e, metric)?.ok_or_else(singular)?;
    }
    let toward = if target >= lambda0 { 1.0 } else { -1.0 };
    let sign = match opts.heading {
        Heading::TowardTarget => toward,
        Heading::AwayFromTarget => -toward,
    };
    if first.t[n] * sign < 0.0 {
        first.t.iter_mut().for_each(|ti| *ti = -*ti);
    }
    Ok(first)
}

/// Factor of the next step from the corrector's first contraction `theta`
/// (Deuflhard sec. 5.1.3): `sqrt(g(THETA_TARGET) / g(theta))`, within
/// `[1/MAX_FACTOR, MAX_FACTOR]` (`MAX_FACTOR` at `theta = 0`, a predictor
/// that met the tolerance; `1/MAX_FACTOR` for NaN).
fn step_factor(theta: f64) -> f64 {
    let g = |t: f64| (1.0 + 4.0 * t).sqrt() - 1.0;
    match theta.is_nan() {
        true => 1.0 / MAX_FACTOR,
        false => (g(THETA_TARGET) / g(theta))
            .sqrt()
            .clamp(1.0 / MAX_FACTOR, MAX_FACTOR),
    }
}

/// Hermite cubic `lambda(s)` on `[0, h]` with end values `l0`, `l1` and
/// slopes `d0`, `d1` of opposite signs: its value at its extremum (a fold),
/// located by bisection on its derivative.
fn fold_lambda(l0: f64, l1: f64, d0: f64, d1: f64, h: f64) -> f64 {
    let (m0, m1) = (h * d0, h * d1);
    let slope = |u: f64| {
        6.0 * u * (u - 1.0) * (l0 - l1)
            + (3.0 * u - 1.0) * (u - 1.0) * m0
            + u * (3.0 * u - 2.0) * m1
    };
    let (mut a, mut b) = (0.0, 1.0);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        (a, b) = if slope(m) * slope(a) > 0.0 {
            (m, b)
        } else {
            (a, m)
        };
    }
    let u = 0.5 * (a + b);
    let h00 = (1.0 + 2.0 * u) * (1.0 - u) * (1.0 - u);
    h00 * l0 + u * (1.0 - u) * (1.0 - u) * m0 + (1.0 - h00) * l1 + u * u * (u - 1.0) * m1
}

/// The outcome of a predictor-corrector step.
enum Trial {
    /// Retry with the step multiplied by the factor.
    Rejected(f64),
    /// The new point, and the factor of the next step.
    Accepted(Found, f64),
}

/// The path under way: its last point, the next step `s`, and the path so
/// far (all its points, or the last two for the events).
struct Walk<'o> {
    at: Found,
    s: f64,
    z0: Vec<f64>,
    target: f64,
    opts: &'o ArclengthOptions,
    metric: Metric,
    keep: bool,
    path: Path,
    attempts: usize,
    /// The system's work at the start.
    work0: f64,
    /// Best residual of the correctors that failed since the last point.
    failed: Option<f64>,
    /// `Theta_0` of the last step rejected for it since the last point.
    rejected_theta: Option<f64>,
}

impl<'o> Walk<'o> {
    fn new(at: Found, target: f64, opts: &'o ArclengthOptions, keep: bool, work0: f64) -> Self {
        let path = Path {
            points: vec![point(&at, 0.0)],
            folds: Vec::new(),
            stop: Stop::ReachedTarget,
            steps: 0,
            rejected: 0,
            work: 0.0,
            residual: at.residual,
        };
        Walk {
            s: opts.initial_step.clamp(opts.min_step, opts.max_step),
            z0: at.z.clone(),
            metric: Metric::new(at.z.len() - 1, opts.lambda_weight),
            at,
            target,
            opts,
            keep,
            path,
            attempts: 0,
            work0,
            failed: None,
            rejected_theta: None,
        }
    }

    /// One step from the last point; `Some` when the path ends.
    fn step<S>(&mut self, sys: &mut S, events: &mut [Event<'_>]) -> Result<Option<Stop>>
    where
        S: ParametrisedSystem + ?Sized,
    {
        self.attempts += 1;
        let (next, factor) = match self.trial(sys)? {
            Trial::Accepted(next, factor) => (next, factor),
            Trial::Rejected(factor) => return self.reject(factor).map(|_| None),
        };
        let fold = self.fold(&next);
        let (lp, ln) = (self.at.lambda() - self.target, next.lambda() - self.target);
        let excursion = fold.map_or(0.0, |lf| lf - self.at.lambda());
        if fold.is_some() && lp * excursion <= 0.0 && lp.abs() <= 2.0 * excursion.abs() {
            // The step passed a fold, and the target lies between the last
            // point and the fold, or beyond the fold by less than the fold
            // estimate's likely error: the path may cross the target twice
            // within the step. Shorter steps resolve the fold until the
            // target lies unambiguously on one side of it.
            return self.reject(1.0 / MAX_FACTOR).map(|_| None);
        }
        if lp * ln > 0.0 {
            self.accept(next, fold);
            self.s = (self.s * factor).clamp(self.opts.min_step, self.opts.max_step);
            return match self.fire(events) {
                None => self.check_closed().map(|_| None),
                stop => Ok(stop),
            };
        }
        match self.at_target(sys, &next)? {
            Some(end) => {
                self.accept(end, fold);
                Ok(Some(self.fire(events).unwrap_or(Stop::ReachedTarget)))
            }
            None => self.reject(1.0 / MAX_FACTOR).map(|_| None),
        }
    }

    /// The Euler predictor `z + s t`, corrected on the hyperplane
    /// `<t, z' - z - s t>_w = 0`: the first Newton step here (for
    /// `Theta_0`), the rest by NLEQ-ERR; with its tangent.
    fn trial<S: ParametrisedSystem + ?Sized>(&mut self, sys: &mut S) -> Result<Trial> {
        let (z, t) = (&self.at.z, &self.at.t);
        let pred: Vec<f64> = z.iter().zip(t).map(|(z, t)| z + self.s * t).collect();
        let row = self.metric.row(t);
        let (anchor, tol) = (pred.clone(), self.opts.tol);
        let mut aug = Augmented {
            sys,
            row: row.clone(),
            anchor,
            fixed: false,
        };
        let Some((z1, theta, r1)) = first_step(&mut aug, &pred, tol, self.metric)? else {
            return Ok(Trial::Rejected(1.0 / MAX_FACTOR));
        };
        if theta.is_nan() {
            self.note(Some(r1));
            return Ok(Trial::Rejected(step_factor(theta)));
        }
        if theta > THETA_REJECT && self.rejected_theta.map_or(true, |prev| theta <= 0.5 * prev) {
            self.rejected_theta = Some(theta);
            self.note(Some(r1));
            return Ok(Trial::Rejected(step_factor(theta)));
        }
        let x = if r1 <= tol {
            z1
        } else {
            let nopts = nleq_options(self.opts, aug.work() - self.work0, CORRECTOR);
            match correct(&mut aug, &z1, &nopts)? {
                Ok(x) => x,
                Err(best) => {
                    self.note(best.or(Some(r1)));
                    return Ok(Trial::Rejected(step_factor(theta).min(1.0 / MAX_FACTOR)));
                }
            }
        };
        // Past `THETA_REJECT` the step is retried shorter, which on a smooth
        // branch divides `Theta_0` by four (the predictor's error is `O(s^2)`);
        // if halving the step did not halve it, a kink of a piecewise-smooth
        // `G` lies between the point and the predictor (the error is `O(s)`
        // there, and the Jacobian of the wrong piece keeps `Theta_0` large):
        // the corrected point is taken if it lies within `KINK_DISTANCE` of
        // the step from the predictor.
        if theta > THETA_REJECT {
            let off = self.metric.distance(&x, &pred);
            if off > KINK_DISTANCE * self.s {
                self.rejected_theta = Some(theta);
                self.note(Some(r1));
                return Ok(Trial::Rejected(step_factor(theta)));
            }
        }
        Ok(match tangent(aug.sys, x, &row, self.metric)? {
            Some(next) => Trial::Accepted(next, step_factor(theta)),
            None => Trial::Rejected(1.0 / MAX_FACTOR),
        })
    }

    /// The solution at `lambda = target` between the last point and `next`
    /// (on either side of it): corrected at fixed `lambda` from their
    /// linear interpolation, with its tangent oriented along `next`'s.
    fn at_target<S>(&mut self, sys: &mut S, next: &Found) -> Result<Option<Found>>
    where
        S: ParametrisedSystem + ?Sized,
    {
        let n = next.z.len() - 1;
        let (lp, ln) = (self.at.lambda(), next.lambda());
        let u = if ln == lp {
            1.0
        } else {
            (self.target - lp) / (ln - lp)
        };
        let mut z: Vec<f64> = self
            .at
            .z
            .iter()
            .zip(&next.z)
            .map(|(a, b)| a + u * (b - a))
            .collect();
        z[n] = self.target;
        let mut aug = Augmented {
            sys,
            row: e_lambda(n),
            anchor: z.clone(),
            fixed: true,
        };
        let nopts = nleq_options(self.opts, aug.work() - self.work0, CORRECTOR);
        match correct(&mut aug, &z, &nopts)? {
            Ok(x) => tangent(aug.sys, x, &self.metric.row(&next.t), self.metric),
            Err(best) => {
                self.note(best);
                Ok(None)
            }
        }
    }

    /// Records the best residual of a failed corrector.
    fn note(&mut self, best: Option<f64>) {
        self.failed = best.into_iter().chain(self.failed).reduce(f64::min);
    }

    /// The fold's `lambda` if `dlambda/ds` changes sign between the last
    /// point and `next`.
    fn fold(&self, next: &Found) -> Option<f64> {
        let n = next.z.len() - 1;
        let (d0, d1) = (self.at.t[n], next.t[n]);
        // The arclength between the points: a circular arc whose tangents
        // turn by phi is phi / (2 sin(phi / 2)) times its chord.
        let phi = self.metric.dot(&self.at.t, &next.t).clamp(-1.0, 1.0).acos();
        let arc = if phi > 1e-8 {
            0.5 * phi / (0.5 * phi).sin()
        } else {
            1.0
        };
        let h = arc * self.metric.distance(&next.z, &self.at.z);
        (d0 * d1 < 0.0).then(|| fold_lambda(self.at.lambda(), next.lambda(), d0, d1, h))
    }

    fn accept(&mut self, next: Found, fold: Option<f64>) {
        let path = &mut self.path;
        path.points
            .push(point(&next, self.metric.distance(&next.z, &self.at.z)));
        if !self.keep && path.points.len() > 2 {
            path.points.remove(0);
        }
        path.steps += 1;
        path.residual = next.residual;
        path.folds.extend(fold.map(|lf| (lf, path.steps)));
        (self.at, self.failed, self.rejected_theta) = (next, None, None);
    }

    /// A rejected step: retried `factor` times as long, unless below `min_step`.
    fn reject(&mut self, factor: f64) -> Result<()> {
        self.path.rejected += 1;
        self.s *= factor;
        if self.s >= self.opts.min_step {
            return Ok(());
        }
        let why = format!("the step fell below min_step = {:.3e}", self.opts.min_step);
        Err(self.error(StopReason::LineSearch, &why))
    }

    fn check_budget(&mut self, work: f64) -> Result<()> {
        self.path.work = work;
        let why = if self.attempts >= self.opts.max_steps {
            format!("max_steps = {} steps tried", self.opts.max_steps)
        } else if work >= self.opts.max_work {
            format!(
                "work {work:.4e} reached max_work = {:.4e}",
                self.opts.max_work
            )
        } else if self.opts.deadline.is_some_and(|d| Instant::now() >= d) {
            "the deadline passed".to_string()
        } else {
            return Ok(());
        };
        Err(self.error(StopReason::Budget, &why))
    }

    /// An error if the branch came back to its start after two folds (a
    /// closed branch): the start lies within the last step of the new point.
    fn check_closed(&self) -> Result<()> {
        let last_step = self.path.points.last().map_or(0.0, |p| p.step);
        if self.path.folds.len() < 2 || self.metric.distance(&self.at.z, &self.z0) > last_step {
            return Ok(());
        }
        let folds: Vec<String> = self
            .path
            .folds
            .iter()
            .map(|f| format!("{:.6}", f.0))
            .collect();
        let why = format!(
            "the branch is closed: it comes back to its start after folds at lambda = {} \
             and never reaches the target",
            folds.join(", ")
        );
        Err(self.error(StopReason::Other, &why))
    }

    /// The first of `events` that fires between the last two points.
    fn fire(&self, events: &mut [Event<'_>]) -> Option<Stop> {
        let [.., a, b] = &self.path.points[..] else {
            return None;
        };
        events.iter_mut().position(|e| e(a, b)).map(Stop::Event)
    }

    fn error(&self, stop: StopReason, why: &str) -> Error {
        let (lambda, target) = (self.at.lambda(), self.target);
        let away = self.at.t[self.at.z.len() - 1] * (target - lambda) < 0.0;
        let turned = match self.path.folds.last() {
            Some((lf, _)) if away => format!(
                "the branch turns back at lambda = {lf:.6} (a fold) and does not reach the \
                 target {target}; "
            ),
            _ => String::new(),
        };
        let (steps, rejected) = (self.path.steps, self.path.rejected);
        Error::NotConverged {
            solver: SOLVER,
            iterations: steps,
            evaluations: self.path.work.round() as usize,
            residual: self.failed.unwrap_or(self.at.residual),
            stop,
            reason: format!(
                "{turned}{why}; at lambda = {lambda:.6} after {steps} steps ({rejected} \
                 rejected), target {target}"
            ),
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problems::nonlinear::PowellBadlyScaled;
    use crate::problems::paths::{
        cases, Bordered, Bratu, Circle, FreudensteinRoth, NewtonHomotopy, SCurve, BRATU_FOLD,
        BRATU_MAX_U_AT_1, BRATU_THETA_AT_1,
    };

    /// Default options with `tol` and the largest step.
    fn options(tol: f64, max_step: f64, heading: Heading) -> ArclengthOptions {
        ArclengthOptions {
            tol,
            max_step,
            heading,
            ..Default::default()
        }
    }

    fn assert_finite(path: &Path) {
        for p in &path.points {
            assert!(p.x.iter().all(|v| v.is_finite()), "{p:?}");
            assert!(p.lambda.is_finite() && p.tangent_lambda.is_finite() && p.step.is_finite());
        }
        assert!(path.work.is_finite() && path.residual.is_finite());
        assert!(path.folds.iter().all(|f| f.0.is_finite()));
    }

    fn max_u(u: &[f64]) -> f64 {
        u.iter().copied().fold(f64::MIN, f64::max)
    }

    /// The path's error: panics on success.
    fn failure(r: Result<Path>) -> (StopReason, f64, String) {
        match r {
            Err(Error::NotConverged {
                stop,
                residual,
                reason,
                ..
            }) => (stop, residual, reason),
            other => panic!("expected NotConverged, got {other:?}"),
        }
    }

    /// Every case of the problems module ends exactly at its target with a
    /// residual within `tol`, re-evaluated independently of the path.
    #[test]
    fn every_case_reaches_its_target_exactly() {
        for mut case in cases() {
            let opts = options(1e-9, 1.0, case.heading);
            let sys = case.system.as_mut();
            let path = follow(sys, &case.x0, case.lambda0, case.target, &opts, true).unwrap();
            assert_finite(&path);
            assert_eq!(path.stop, Stop::ReachedTarget);
            let last = path.points.last().unwrap();
            assert_eq!(last.lambda, case.target, "{}", case.name);
            let mut f = vec![0.0; last.x.len()];
            sys.residual(&last.x, last.lambda, &mut f).unwrap();
            assert!(max_abs(&f) <= opts.tol, "{}: {f:?}", case.name);
            assert_eq!(path.residual, max_abs(&f));
            println!(
                "{:18} steps {:3} rejected {:2} work {:6} folds {:?}",
                case.name, path.steps, path.rejected, path.work, path.folds
            );
        }
    }
    /// The circle from `(-1, 0)`, heading down, reaches `lambda = 0.5` only
    /// through its fold at `lambda = -1`: on the other half, `x = +sqrt(3)/2`.
    /// The fold's `lambda` comes from the Hermite cubic of `lambda(s)`
    /// (`lambda = -cos s`), error below `h^4 max |lambda^(4)| / 384 = 1.6e-8`
    /// at `h = 0.05`; asserted to `1e-7`.
    #[test]
    fn circle_passes_its_fold() {
        let opts = options(1e-12, 0.05, Heading::AwayFromTarget);
        let path = follow(&mut Bordered::new(Circle), &[-1.0], 0.0, 0.5, &opts, true).unwrap();
        assert_finite(&path);
        let last = path.points.last().unwrap();
        assert_eq!(last.lambda, 0.5);
        assert!((last.x[0] - 0.75f64.sqrt()).abs() <= 1e-12, "{last:?}");
        assert_eq!(path.folds.len(), 1);
        let (lf, i) = path.folds[0];
        assert!((lf + 1.0).abs() <= 1e-7, "fold at {lf}");
        let (a, b) = (&path.points[i - 1], &path.points[i]);
        assert!(a.tangent_lambda < 0.0 && b.tangent_lambda > 0.0 && a.x[0] * b.x[0] <= 0.0);
    }

    /// The S-curve from `x = -2` to `lambda = 6` passes both folds; their
    /// `lambda` (`+-2/(3 sqrt 3)`) from the Hermite cubic at `h <= 0.05`:
    /// error below `h^4 max |lambda^(4)| / 384 = 3.3e-6` (`|lambda^(4)(s)|
    /// <= 200` on `lambda = x^3 - x`), measured 7e-8 and 2.7e-6; asserted
    /// to `5e-6`.
    #[test]
    fn s_curve_passes_both_folds() {
        let s = SCurve { c: 0.0 };
        let opts = options(1e-12, 0.05, Heading::TowardTarget);
        let path = follow(&mut Bordered::new(s), &[-2.0], -6.0, 6.0, &opts, false).unwrap();
        assert_finite(&path);
        assert_eq!(path.points.len(), 1);
        let last = &path.points[0];
        assert_eq!(last.lambda, 6.0);
        assert!((last.x[0] - 2.0).abs() <= 1e-12);
        let found: Vec<f64> = path.folds.iter().map(|f| f.0).collect();
        assert_eq!(found.len(), 2, "{found:?}");
        for (f, exact) in found.iter().zip(s.folds()) {
            assert!((f - exact).abs() <= 5e-6, "fold {f} vs {exact}");
        }
    }

    /// A target just below the S's first fold is crossed twice within a
    /// long step over the fold; the path stops at the first crossing, on
    /// the branch before the fold (`x < -1/sqrt 3`), not on a later branch.
    #[test]
    fn target_next_to_a_fold_is_met_at_its_first_crossing() {
        let opts = options(1e-12, 1.0, Heading::TowardTarget);
        let path = follow(
            &mut Bordered::new(SCurve { c: 0.0 }),
            &[-2.0],
            -6.0,
            0.383,
            &opts,
            true,
        )
        .unwrap();
        let last = path.points.last().unwrap();
        assert_eq!(last.lambda, 0.383);
        assert!(last.x[0] < -1.0 / 3f64.sqrt(), "{last:?}");
        assert!(path.folds.is_empty());
    }

    /// The FD Bratu problem's fold, by an independent route: `lambda` on the
    /// branch parametrised by the peak value `mu = u_m` (regular at the
    /// fold), maximised by golden section.
    fn bratu_fd_fold(n: usize) -> f64 {
        let mut sys = Bordered::new(Bratu { n });
        let m = n / 2 - 1;
        let mut row = vec![0.0; n];
        row[m] = 1.0;
        let mut lambda_at = |mu: f64| {
            let theta = 4.0 * (mu / 2.0).exp().acosh();
            let mut lambda = theta * theta / (2.0 * (theta / 4.0).cosh().powi(2));
            let mut u = sys.model.exact(theta);
            let (mut f, mut du, mut dl) = (vec![0.0; n], vec![0.0; n], 0.0);
            for _ in 0..30 {
                sys.linearise_bordered(&u, lambda, (&row, 0.0), &mut f)
                    .unwrap();
                if max_abs(&f) <= 1e-10 && (u[m] - mu).abs() <= 1e-14 {
                    return lambda;
                }
                assert!(sys.solve_bordered(&f, u[m] - mu, &mut du, &mut dl).unwrap());
                u.iter_mut().zip(&du).for_each(|(a, d)| *a -= d);
                lambda -= dl;
            }
            panic!("no FD Bratu solution with u_m = {mu}");
        };
        let g = (5f64.sqrt() - 1.0) / 2.0;
        let (mut a, mut b) = (0.8, 1.6);
        for _ in 0..60 {
            let (c, d) = (b - g * (b - a), a + g * (b - a));
            if lambda_at(c) > lambda_at(d) {
                b = d;
            } else {
                a = c;
            }
        }
        lambda_at(0.5 * (a + b))
    }

    /// Bratu (`n = 50`) from the lower branch at `lambda = 2` over its fold
    /// and down the upper branch to `lambda = 1`. The fold agrees with the
    /// FD problem's own (measured difference 4e-7 at `h <= 0.05`, asserted
    /// `2e-6`), which is within the discretisation error `O(h^2)` of the
    /// continuous `3.51383` (difference 7e-4, asserted `2e-3`). At
    /// `lambda = 1` the solution is the FD upper one, from a Newton solve
    /// started at the continuous solution (both to `max |G| <= 1e-9`;
    /// asserted `1e-8`), with `max u` within the discretisation error of
    /// the continuous `4.0915` (3e-3, asserted `1e-2`); its lower-branch
    /// counterpart, the same way, near `0.14054`.
    #[test]
    fn bratu_around_its_fold_to_the_upper_branch() {
        let mut sys = Bordered::new(Bratu { n: 50 });
        let lower = sys.newton(&[0.0; 50], 2.0, 1e-9).unwrap();
        let opts = options(1e-9, 0.05, Heading::AwayFromTarget);
        let path = follow(&mut sys, &lower, 2.0, 1.0, &opts, true).unwrap();
        assert_finite(&path);
        let last = path.points.last().unwrap();
        assert_eq!(last.lambda, 1.0);
        assert_eq!(path.folds.len(), 1);
        let fd = bratu_fd_fold(50);
        assert!(
            (path.folds[0].0 - fd).abs() <= 2e-6,
            "fold {} vs FD {fd}",
            path.folds[0].0
        );
        assert!((fd - BRATU_FOLD).abs() <= 2e-3, "FD fold {fd}");
        let [low, high] = BRATU_THETA_AT_1.map(|theta| {
            let start = sys.model.exact(theta);
            sys.newton(&start, 1.0, 1e-9).unwrap()
        });
        let err = last
            .x
            .iter()
            .zip(&high)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err <= 1e-8, "upper branch off by {err}");
        assert!((max_u(&high) - BRATU_MAX_U_AT_1[1]).abs() <= 1e-2);
        assert!((max_u(&low) - BRATU_MAX_U_AT_1[0]).abs() <= 1e-3);
        println!(
            "FD fold {fd}, path fold {}, max u {} {}",
            path.folds[0].0,
            max_u(&low),
            max_u(&high)
        );
    }

    /// Newton homotopies from the MGH starts reach the roots: Powell's badly
    /// scaled function (to the 7 digits MGH print) and Freudenstein-Roth's,
    /// through two folds of the homotopy, to `(5, 4)`.
    #[test]
    fn newton_homotopies_reach_the_roots() {
        let opts = options(1e-12, 1.0, Heading::TowardTarget);
        let (h, x0) = NewtonHomotopy::new(PowellBadlyScaled);
        let path = follow(&mut Bordered::new(h), &x0, 0.0, 1.0, &opts, false).unwrap();
        assert_finite(&path);
        let x = &path.points[0].x;
        for (xi, root) in x.iter().zip(PowellBadlyScaled::ROOT) {
            assert!((xi / root - 1.0).abs() <= 1e-6, "{x:?}");
        }
        assert!(path.residual <= 1e-12);

        let (h, x0) = NewtonHomotopy::new(FreudensteinRoth);
        let path = follow(&mut Bordered::new(h), &x0, 0.0, 1.0, &opts, false).unwrap();
        assert_finite(&path);
        let x = &path.points[0].x;
        assert!(
            (x[0] - 5.0).abs() <= 1e-10 && (x[1] - 4.0).abs() <= 1e-10,
            "{x:?}"
        );
        assert_eq!(path.folds.len(), 2);
    }

    /// The step grows where the branch is straight and shrinks where it
    /// bends: on the S from `x = -3` to 3, the curvature of `lambda = x^3 - x`
    /// is below 0.01 for `|x| > 2` and 3.5 at the folds, and the contraction
    /// rule keeps `Theta_0 ~ kappa s^2` constant, so the steps should differ
    /// by about `sqrt(350) = 19`; asserted: a factor 10. From a tiny first
    /// step, the first steps double ([`MAX_FACTOR`]).
    #[test]
    fn step_grows_on_straight_stretches_and_shrinks_at_folds() {
        let opts = ArclengthOptions {
            tol: 1e-12,
            initial_step: 0.01,
            max_step: 100.0,
            ..Default::default()
        };
        let path = follow(
            &mut Bordered::new(SCurve { c: 0.0 }),
            &[-3.0],
            -24.0,
            24.0,
            &opts,
            true,
        )
        .unwrap();
        assert_finite(&path);
        // Steps with both ends in a stretch.
        let steps = |keep: &dyn Fn(f64) -> bool| -> Vec<f64> {
            let both = |w: &&[PathPoint]| keep(w[0].x[0]) && keep(w[1].x[0]);
            path.points
                .windows(2)
                .filter(both)
                .map(|w| w[1].step)
                .collect()
        };
        let (outer, inner) = (
            steps(&|x: f64| x.abs() > 2.0),
            steps(&|x: f64| x.abs() < 1.0),
        );
        let big = outer.iter().copied().fold(0.0, f64::max);
        let worst_inner = inner.iter().copied().fold(0.0, f64::max);
        assert!(
            !inner.is_empty() && big >= 10.0 * worst_inner,
            "outer {outer:?} inner {inner:?}"
        );
        for w in path.points[1..5].windows(2) {
            assert!((w[1].step / w[0].step - MAX_FACTOR).abs() < 1e-3, "{w:?}");
        }
    }

    /// `x = lambda`, which cannot be evaluated past `lambda = 1` (as a rod
    /// whose IVP fails): an `Integration` error there, or with `nan` a NaN
    /// residual.
    struct Wall {
        row: (f64, f64),
        evaluations: usize,
        nan: bool,
    }

    impl ParametrisedSystem for Wall {
        fn dim(&self) -> usize {
            1
        }
        fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
            self.evaluations += 1;
            f[0] = if lambda > 1.0 {
                f64::NAN
            } else {
                x[0] - lambda
            };
            match lambda > 1.0 && !self.nan {
                true => Err(Error::Integration {
                    s: lambda,
                    reason: "past the wall".into(),
                }),
                false => Ok(()),
            }
        }
        fn linearise_bordered(
            &mut self,
            x: &[f64],
            lambda: f64,
            row: (&[f64], f64),
            f: &mut [f64],
        ) -> Result<()> {
            self.row = (row.0[0], row.1);
            self.residual(x, lambda, f)
        }
        fn solve_bordered(
            &mut self,
            b: &[f64],
            b_last: f64,
            dx: &mut [f64],
            dl: &mut f64,
        ) -> Result<bool> {
            // [[1, -1], [r0, r1]] (dx, dl) = (b, b_last).
            let det = self.row.0 + self.row.1;
            *dl = (b_last - self.row.0 * b[0]) / det;
            dx[0] = b[0] + *dl;
            Ok(det != 0.0)
        }
        fn work(&self) -> f64 {
            self.evaluations as f64
        }
    }

    /// Steps that fail (the system cannot be evaluated, or gives NaN) are
    /// halved; below `min_step` the path fails with `LineSearch`, a finite
    /// best residual (the last point's, within `tol`: no failed corrector
    /// produced a finite one) and a message naming `min_step`; the last
    /// point is within `2 min_step` of the wall (a step's `lambda` share is
    /// `1/sqrt 2` of it), reached after about `log2(0.25 / 1e-3) = 8`
    /// halvings at least.
    #[test]
    fn steps_halve_down_to_min_step_then_fail() {
        let opts = ArclengthOptions {
            tol: 1e-12,
            initial_step: 0.25,
            max_step: 0.25,
            min_step: 1e-3,
            ..Default::default()
        };
        for nan in [false, true] {
            let mut sys = Wall {
                row: (0.0, 1.0),
                evaluations: 0,
                nan,
            };
            let (stop, residual, reason) =
                failure(follow(&mut sys, &[0.0], 0.0, 2.0, &opts, false));
            assert_eq!(stop, StopReason::LineSearch, "{reason}");
            assert!(residual.is_finite() && residual <= opts.tol, "{residual}");
            assert!(reason.contains("min_step"), "{reason}");
            let number = |after: &str| -> f64 {
                let tail = reason.split(after).nth(1).unwrap();
                tail.split([' ', ')']).next().unwrap().parse().unwrap()
            };
            let lambda = number("at lambda = ");
            assert!(lambda <= 1.0 && lambda > 1.0 - 2e-3, "{reason}");
            assert!(number("steps (") >= 8.0, "{reason}");
        }
    }

    /// `max_steps`, `max_work` and a past deadline stop the path with
    /// `Budget` and the last point's residual (within `tol`).
    #[test]
    fn budgets_give_structured_errors() {
        let mut sys = Bordered::new(Bratu { n: 50 });
        let lower = sys.newton(&[0.0; 50], 2.0, 1e-9).unwrap();
        let base = options(1e-9, 0.1, Heading::AwayFromTarget);
        let budgets = [
            ArclengthOptions {
                max_steps: 3,
                ..base.clone()
            },
            ArclengthOptions {
                max_work: 500.0,
                ..base.clone()
            },
            ArclengthOptions {
                deadline: Some(Instant::now()),
                ..base.clone()
            },
        ];
        for opts in &budgets {
            let (stop, residual, reason) = failure(follow(&mut sys, &lower, 2.0, 1.0, opts, true));
            assert_eq!(stop, StopReason::Budget, "{reason}");
            assert!(
                residual.is_finite() && residual <= opts.tol,
                "{residual} {reason}"
            );
        }
    }

    /// Bratu has no solution above its fold: from the lower branch toward
    /// `lambda = 5` the path turns back at the fold and moves away from the
    /// target until its budget runs out, and the error says so, with the
    /// fold (to 0.01: steps up to 0.5 here).
    #[test]
    fn a_branch_that_turns_back_is_reported_in_plain_terms() {
        let mut sys = Bordered::new(Bratu { n: 50 });
        let lower = sys.newton(&[0.0; 50], 2.0, 1e-9).unwrap();
        let opts = ArclengthOptions {
            max_steps: 40,
            ..options(1e-9, 0.5, Heading::TowardTarget)
        };
        let (stop, residual, reason) = failure(follow(&mut sys, &lower, 2.0, 5.0, &opts, false));
        assert_eq!(stop, StopReason::Budget, "{reason}");
        assert!(residual.is_finite());
        let tail = reason
            .split("the branch turns back at lambda = ")
            .nth(1)
            .unwrap();
        let fold: f64 = tail.split(' ').next().unwrap().parse().unwrap();
        assert!((fold - BRATU_FOLD).abs() < 0.01, "{reason}");
        assert!(
            reason.contains("(a fold) and does not reach the target 5"),
            "{reason}"
        );
    }

    /// The circle never reaches `lambda = 2`: the path comes back to its
    /// start after its two folds and stops there.
    #[test]
    fn a_closed_branch_stops_after_one_turn() {
        let opts = options(1e-12, 0.2, Heading::TowardTarget);
        let (stop, residual, reason) = failure(follow(
            &mut Bordered::new(Circle),
            &[-1.0],
            0.0,
            2.0,
            &opts,
            false,
        ));
        assert_eq!(stop, StopReason::Other, "{reason}");
        assert!(residual <= 1e-12);
        assert!(
            reason.contains("the branch is closed") && reason.contains("never reaches the target"),
            "{reason}"
        );
    }

    /// A system that takes 1 ms per linearisation: a path of more than
    /// 20 linearisations outlasts the cancel check's poll interval.
    struct Slow<S>(S);

    impl<S: ParametrisedSystem> ParametrisedSystem for Slow<S> {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn residual(&mut self, x: &[f64], l: f64, f: &mut [f64]) -> Result<()> {
            self.0.residual(x, l, f)
        }
        fn linearise_bordered(
            &mut self,
            x: &[f64],
            l: f64,
            row: (&[f64], f64),
            f: &mut [f64],
        ) -> Result<()> {
            std::thread::sleep(std::time::Duration::from_millis(1));
            self.0.linearise_bordered(x, l, row, f)
        }
        fn solve_bordered(
            &mut self,
            b: &[f64],
            bl: f64,
            dx: &mut [f64],
            dl: &mut f64,
        ) -> Result<bool> {
            self.0.solve_bordered(b, bl, dx, dl)
        }
        fn work(&self) -> f64 {
            self.0.work()
        }
    }

    #[test]
    fn a_cancel_check_interrupts_the_path() {
        let opts = options(1e-12, 0.01, Heading::TowardTarget);
        let mut sys = Slow(Bordered::new(Circle));
        let r = cancel::interruptible(&|| true, || {
            follow(&mut sys, &[-1.0], 0.0, 2.0, &opts, false)
        });
        assert_eq!(r.unwrap_err(), Error::Interrupted);
    }

    /// Events see consecutive points; the first that fires stops the path
    /// and is named by its index. A fold event (sign change of
    /// `dlambda/ds`) stops the S just past its first fold.
    #[test]
    fn events_stop_the_path() {
        let mut never = |_: &PathPoint, _: &PathPoint| false;
        let mut fold = |a: &PathPoint, b: &PathPoint| a.tangent_lambda * b.tangent_lambda < 0.0;
        let mut events: [Event<'_>; 2] = [&mut never, &mut fold];
        let opts = options(1e-12, 0.1, Heading::TowardTarget);
        let mut sys = Bordered::new(SCurve { c: 0.0 });
        let path =
            follow_with_events(&mut sys, &[-2.0], -6.0, 6.0, &opts, true, &mut events).unwrap();
        assert_eq!(path.stop, Stop::Event(1));
        assert_eq!(path.folds.len(), 1);
        let [.., a, b] = &path.points[..] else {
            panic!()
        };
        assert!(a.tangent_lambda > 0.0 && b.tangent_lambda < 0.0);
        assert!(
            (b.lambda - SCurve { c: 0.0 }.folds()[0]).abs() < 0.01,
            "{b:?}"
        );
    }

    /// Keeping the path changes nothing but the points returned.
    #[test]
    fn keeping_the_path_only_keeps_points() {
        let opts = options(1e-12, 0.3, Heading::TowardTarget);
        let run = |keep| {
            follow(
                &mut Bordered::new(SCurve { c: 0.5 }),
                &[-2.0],
                -5.5,
                6.5,
                &opts,
                keep,
            )
            .unwrap()
        };
        let (kept, last) = (run(true), run(false));
        assert_eq!(kept.points.len(), kept.steps + 1);
        assert_eq!(last.points.len(), 1);
        assert_eq!(kept.points.last(), last.points.last());
        assert_eq!(
            (kept.steps, kept.rejected, kept.work),
            (last.steps, last.rejected, last.work)
        );
        assert_eq!(kept.folds, last.folds);
    }

    /// A start off the branch is corrected at its `lambda` first; a start
    /// at the target is the path; a start at a fold, bad options and a
    /// wrong dimension are errors.
    #[test]
    fn starts_and_arguments() {
        let opts = options(1e-12, 0.3, Heading::AwayFromTarget);
        let path = follow(&mut Bordered::new(Circle), &[-1.01], 0.0, 0.5, &opts, true).unwrap();
        assert!((path.points[0].x[0] + 1.0).abs() <= 1e-12);
        assert_eq!(path.points.last().unwrap().lambda, 0.5);

        let path = follow(&mut Bordered::new(Circle), &[-1.0], 0.0, 0.0, &opts, true).unwrap();
        assert_eq!(
            (path.steps, path.points.len(), path.stop),
            (0, 1, Stop::ReachedTarget)
        );

        let (stop, _, reason) = failure(follow(
            &mut Bordered::new(Circle),
            &[0.0],
            1.0,
            0.0,
            &opts,
            true,
        ));
        assert_eq!(stop, StopReason::SingularJacobian, "{reason}");

        let bad = ArclengthOptions {
            tol: 0.0,
            ..opts.clone()
        };
        let r = follow(&mut Bordered::new(Circle), &[-1.0], 0.0, 0.5, &bad, true);
        assert!(matches!(r, Err(Error::InvalidParameter { .. })), "{r:?}");
        let r = follow(
            &mut Bordered::new(Circle),
            &[-1.0, 0.0],
            0.0,
            0.5,
            &opts,
            true,
        );
        assert!(matches!(r, Err(Error::InvalidInput { .. })), "{r:?}");
    }
}
