//! The path under way ([`Walk`]): one predictor-corrector step at a time,
//! its acceptance, the step's adaptation, folds, the target and the stops.

use std::time::Instant;

use super::*;
use crate::error::{Error, Result, StopReason};

/// The cubic Hermite interpolant of a branch through `a` and `b` (points
/// and unit tangents, `h` apart in arc length) at arc length `s` beyond
/// `b`. On a smooth branch its error is `O(s^4)` for `s ~ h`, against the
/// tangent predictor's `O(s^2)` (the interpolant reproduces the branch's
/// Taylor expansion at `b` through the cubic term up to the interpolation
/// error of `z''` over `[a, b]`; Allgower & Georg, *Introduction to
/// Numerical Continuation Methods*, SIAM 2003, ch. 6, on predictors of
/// higher order; the fold estimate of [`Walk::fold`] interpolates `lambda`
/// the same way). Both
/// points are converged solutions, so extrapolating them amplifies only
/// their tolerance-sized errors.
pub(super) fn hermite(a: (&[f64], &[f64]), b: (&[f64], &[f64]), h: f64, s: f64) -> Vec<f64> {
    let u = 1.0 + s / h;
    let (u2, u3) = (u * u, u * u * u);
    let (h00, h01) = (2.0 * u3 - 3.0 * u2 + 1.0, -2.0 * u3 + 3.0 * u2);
    let (h10, h11) = ((u3 - 2.0 * u2 + u) * h, (u3 - u2) * h);
    let ((z0, t0), (z1, t1)) = (a, b);
    (0..z1.len())
        .map(|i| h00 * z0[i] + h10 * t0[i] + h01 * z1[i] + h11 * t1[i])
        .collect()
}

/// Factor of the next step from the first contraction `theta` of a
/// predictor whose error is `O(s^order)` (Deuflhard sec. 5.1.3: `Theta_0`
/// grows as that error) within `[1/MAX_FACTOR, MAX_FACTOR]`: `MAX_FACTOR`
/// at `theta = 0` (a predictor within tolerance), `1/MAX_FACTOR` for NaN.
fn step_factor(theta: f64, order: i32) -> f64 {
    let g = |t: f64| (1.0 + 4.0 * t).sqrt() - 1.0;
    if theta.is_nan() {
        return 1.0 / MAX_FACTOR;
    }
    let factor = (g(THETA_TARGET) / g(theta)).powf(1.0 / f64::from(order));
    factor.clamp(1.0 / MAX_FACTOR, MAX_FACTOR)
}

/// The path under way: its last point `at`, the next step `s`, and the path
/// so far (all its points, or the last two for the events).
pub(super) struct Walk<'o> {
    pub(super) at: Found,
    pub(super) s: f64,
    pub(super) z0: Vec<f64>,
    pub(super) target: f64,
    pub(super) opts: &'o ArclengthOptions,
    pub(super) metric: Metric,
    pub(super) keep: bool,
    pub(super) path: Path,
    pub(super) work0: f64,
    /// Best residual of the correctors failed since the last point.
    pub(super) failed: Option<f64>,
    /// `Theta_0` of the last step rejected for it since the last point.
    pub(super) rejected_theta: Option<f64>,
    /// The point before `at`, its unit tangent and the arc length between.
    pub(super) prev: Option<(Vec<f64>, Vec<f64>, f64)>,
}

impl Walk<'_> {
    /// One step from the last point; `Some` when the path ends.
    pub(super) fn step<S>(&mut self, sys: &mut S, events: &mut [Event<'_>]) -> Result<Option<Stop>>
    where
        S: ParametrisedSystem + ?Sized,
    {
        let Some((next, factor)) = self.trial(sys)? else {
            return Ok(None);
        };
        let fold = self.fold(&next);
        let (l0, l1) = (self.at.lambda(), next.lambda());
        let (d0, d1) = (self.at.t[self.at.t.len() - 1], next.t[next.t.len() - 1]);
        if d0 * d1 > 0.0 && (l1 - l0) * d0 < 0.0 {
            // `lambda` moved against the tangents at both ends, which agree:
            // no fold lies between, so the corrector's hyperplane met the
            // branch behind the last point, across a sharp bend (a heavy
            // body's path bends so near its start). Shorter steps follow
            // the bend.
            return self.reject(1.0 / MAX_FACTOR);
        }
        let (lp, ln) = (l0 - self.target, l1 - self.target);
        let excursion = fold.map_or(0.0, |lf| lf - l0);
        if fold.is_some() && lp * excursion <= 0.0 && lp.abs() <= 2.0 * excursion.abs() {
            // The target lies between the point and the fold passed, or beyond
            // it by less than the fold estimate's likely error: the path may
            // cross it twice in the step. Shorter steps resolve the fold.
            return self.reject(1.0 / MAX_FACTOR);
        }
        if lp * ln > 0.0 {
            self.accept(next, fold);
            self.s = (self.s * factor).clamp(self.opts.min_step, self.opts.max_step);
            let (lo, hi) = sys.domain();
            if !(lo..=hi).contains(&l1) {
                let why = format!("it leaves the system's domain {lo} <= lambda <= {hi}");
                return Err(self.error(StopReason::Other, &why));
            }
            return match self.fire(events) {
                None => self.check_closed(),
                stop => Ok(stop),
            };
        }
        let Some(end) = self.at_target(sys, &next)? else {
            return self.reject(1.0 / MAX_FACTOR);
        };
        self.accept(end, fold);
        Ok(Some(self.fire(events).unwrap_or(Stop::ReachedTarget)))
    }

    /// The predictor ([`Self::predictor`]) corrected on the hyperplane
    /// `<t, z' - z_p>_w = 0` through it, with its tangent and the factor of
    /// the next step; `None` if the step was rejected.
    fn trial<S>(&mut self, sys: &mut S) -> Result<Option<(Found, f64)>>
    where
        S: ParametrisedSystem + ?Sized,
    {
        let (t, tol, iterations) = (&self.at.t, self.opts.tol, self.opts.corrector_iterations);
        let corrector = (iterations, CORRECTOR_LAMBDA_MIN);
        let pred = self.predictor();
        let (row, at, fix) = (self.metric.row(t), pred.clone(), false);
        let mut aug = Augmented { sys, row, at, fix };
        let Some((z1, theta, r1, d1)) = first_step(&mut aug, &pred, tol, self.metric)? else {
            return self.reject(1.0 / MAX_FACTOR);
        };
        // Past `THETA_REJECT` the step is retried shorter, which on a smooth
        // branch divides `Theta_0` by four at least (`2^p` for a predictor
        // whose error is `O(s^p)`). If halving the step did not halve
        // it, a kink of a piecewise-smooth `G` lies ahead (the predictor's
        // error is `O(s)` there, and the wrong piece's Jacobian keeps
        // `Theta_0` large): the corrector goes on, and its point is taken
        // within `KINK_DISTANCE` of the predictor.
        let shrinking = self.rejected_theta.map_or(true, |prev| theta <= 0.5 * prev);
        if theta.is_nan() || (theta > THETA_REJECT && shrinking) {
            return self.reject_theta(theta, r1);
        }
        let chord = match r1 <= tol {
            true => Some(z1.clone()),
            false => simplified(&mut aug, (z1.clone(), d1), (tol, iterations), self.metric)?,
        };
        let x = if let Some(x) = chord {
            x
        } else {
            // Newton with a Jacobian at each iterate where the chord stalls
            let spent = aug.work() - self.work0;
            match correct(&mut aug, &z1, self.opts, spent, corrector)? {
                Ok(x) => x,
                Err(best) => {
                    self.note(best.or(Some(r1)));
                    return self.reject(step_factor(theta, self.order()).min(1.0 / MAX_FACTOR));
                }
            }
        };
        if theta > THETA_REJECT && self.metric.distance(&x, &pred) > KINK_DISTANCE * self.s {
            return self.reject_theta(theta, r1);
        }
        match tangent(aug.sys, x, &aug.row, self.metric)? {
            Some(next) => Ok(Some((next, step_factor(theta, self.order())))),
            None => self.reject(1.0 / MAX_FACTOR),
        }
    }

    /// The predictor's error order `p` (error `O(s^p)`): 4 for the cubic
    /// Hermite extrapolation once there is a previous point, 2 for the
    /// tangent (Euler) predictor.
    fn order(&self) -> i32 {
        match (self.opts.predictor, &self.prev) {
            (Predictor::Hermite, Some(_)) => 4,
            _ => 2,
        }
    }

    /// The predictor at arc length `s` beyond the last point: with
    /// [`Predictor::Hermite`] after the first step, the cubic Hermite
    /// interpolant of the last two points and their tangents, extrapolated
    /// ([`hermite`]); else `z + s t`.
    fn predictor(&self) -> Vec<f64> {
        let (z, t, s) = (&self.at.z, &self.at.t, self.s);
        match (self.order(), &self.prev) {
            (4, Some((z0, t0, h))) => hermite((z0, t0), (z, t), *h, s),
            _ => z.iter().zip(t).map(|(z, t)| z + s * t).collect(),
        }
    }

    /// The solution at `lambda = target` between the last point and `next`,
    /// corrected from their linear interpolation, with its tangent oriented
    /// by `next`'s.
    fn at_target<S>(&mut self, sys: &mut S, next: &Found) -> Result<Option<Found>>
    where
        S: ParametrisedSystem + ?Sized,
    {
        let (l0, l1, t) = (self.at.lambda(), next.lambda(), self.target);
        let u = if l1 == l0 { 1.0 } else { (t - l0) / (l1 - l0) };
        let (a, b) = (&self.at.z, &next.z);
        let mut z: Vec<f64> = a.iter().zip(b).map(|(a, b)| a + u * (b - a)).collect();
        z[b.len() - 1] = t;
        let spent = sys.work() - self.work0;
        let corrector = (self.opts.corrector_iterations, CORRECTOR_LAMBDA_MIN);
        let mut aug = Augmented::at_lambda(sys, &z);
        match correct(&mut aug, &z, self.opts, spent, corrector)? {
            Ok(x) => tangent(sys, x, &self.metric.row(&next.t), self.metric),
            Err(best) => {
                self.note(best);
                Ok(None)
            }
        }
    }

    /// The fold's `lambda` if `dlambda/ds` changes sign between the last point
    /// and `next`: the extremum of the cubic Hermite interpolant of
    /// `lambda(s)` over the step, by bisection on its derivative.
    fn fold(&self, next: &Found) -> Option<f64> {
        let n = next.z.len() - 1;
        let (l0, l1, d0, d1) = (self.at.z[n], next.z[n], self.at.t[n], next.t[n]);
        if !(d0 * d1 < 0.0) {
            return None;
        }
        let h = self.arc_length(next);
        let (m0, m1) = (h * d0, h * d1);
        let slope = |u: f64| {
            6.0 * u * (u - 1.0) * (l0 - l1)
                + (3.0 * u - 1.0) * (u - 1.0) * m0
                + u * (3.0 * u - 2.0) * m1
        };
        let (mut a, mut b) = (0.0, 1.0);
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            let right = slope(m) * slope(a) > 0.0;
            (a, b) = if right { (m, b) } else { (a, m) };
        }
        let u = 0.5 * (a + b);
        let h00 = (1.0 + 2.0 * u) * (1.0 - u) * (1.0 - u);
        Some(h00 * l0 + u * (1.0 - u) * (1.0 - u) * m0 + (1.0 - h00) * l1 + u * u * (u - 1.0) * m1)
    }

    /// The arc length from the last point to `next`: an arc whose tangents
    /// turn by `phi` is `phi / (2 sin(phi / 2))` times its chord.
    fn arc_length(&self, next: &Found) -> f64 {
        let phi = self.metric.dot(&self.at.t, &next.t).clamp(-1.0, 1.0).acos();
        let half = 0.5 * phi;
        let arc = if phi > 1e-8 { half / half.sin() } else { 1.0 };
        arc * self.metric.distance(&next.z, &self.at.z)
    }

    fn accept(&mut self, next: Found, fold: Option<f64>) {
        let step = self.metric.distance(&next.z, &self.at.z);
        let path = &mut self.path;
        path.points.push(point(&next, step));
        if !self.keep && path.points.len() > 2 {
            path.points.remove(0);
        }
        path.steps += 1;
        path.residual = next.residual;
        path.folds.extend(fold.map(|lf| (lf, path.steps)));
        let arc = self.arc_length(&next);
        let old = std::mem::replace(&mut self.at, next);
        self.prev = Some((old.z, old.t, arc));
        (self.failed, self.rejected_theta) = (None, None);
    }

    /// Records the best residual of a failed corrector.
    fn note(&mut self, best: Option<f64>) {
        self.failed = best.into_iter().chain(self.failed).reduce(f64::min);
    }

    /// A step rejected for its first contraction `theta` (kept unless NaN),
    /// with the residual `r1` after the first Newton step.
    fn reject_theta<T>(&mut self, theta: f64, r1: f64) -> Result<Option<T>> {
        if !theta.is_nan() {
            self.rejected_theta = Some(theta);
        }
        self.note(Some(r1));
        self.reject(step_factor(theta, self.order()))
    }

    /// A rejected step: retried `factor` times as long, unless below `min_step`.
    fn reject<T>(&mut self, factor: f64) -> Result<Option<T>> {
        self.path.rejected += 1;
        self.s *= factor;
        if self.s >= self.opts.min_step {
            return Ok(None);
        }
        let why = format!("the step fell below min_step = {:.3e}", self.opts.min_step);
        Err(self.error(StopReason::LineSearch, &why))
    }

    pub(super) fn check_budget(&mut self, work: f64) -> Result<()> {
        self.path.work = work;
        let (o, tried) = (self.opts, self.path.steps + self.path.rejected);
        let why = if tried >= o.max_steps {
            format!("max_steps = {} steps tried", o.max_steps)
        } else if work >= o.max_work {
            format!("work {work:.4e} reached max_work = {:.4e}", o.max_work)
        } else if o.deadline.is_some_and(|d| Instant::now() >= d) {
            "the deadline passed".to_string()
        } else {
            return Ok(());
        };
        Err(self.error(StopReason::Budget, &why))
    }

    /// An error if the branch came back to its start after two folds (a closed
    /// branch): the start lies within the last step of the new point.
    fn check_closed(&self) -> Result<Option<Stop>> {
        let last_step = self.path.points.last().map_or(0.0, |p| p.step);
        if self.path.folds.len() < 2 || self.metric.distance(&self.at.z, &self.z0) > last_step {
            return Ok(None);
        }
        let folds = self.path.folds.iter().map(|f| format!("{:.6}", f.0));
        let why = format!(
            "the branch is closed: it comes back to its start after folds at lambda = {} \
             and never reaches the target",
            folds.collect::<Vec<_>>().join(", ")
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
