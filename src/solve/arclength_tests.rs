//! Tests of [`super`].

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
        let (stop, residual, reason) = failure(follow(&mut sys, &[0.0], 0.0, 2.0, &opts, false));
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
    fn solve_bordered(&mut self, b: &[f64], bl: f64, dx: &mut [f64], dl: &mut f64) -> Result<bool> {
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
    let path = follow_with_events(&mut sys, &[-2.0], -6.0, 6.0, &opts, true, &mut events).unwrap();
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

/// The Hermite predictor's error on the unit circle `(cos a, sin a)`, from
/// points `h` apart extrapolated by `h`, falls as `h^4` (Taylor: the cubic
/// interpolant's extrapolation error is `z''''(xi) (u^2 (u - 1)^2 / 4!) h^4`
/// at `u = 2`); the tangent step's as `h^2`. Halving `h` divides them by
/// 16 and 4; the bounds 12 and 3.5 allow for the `O(h)` change of the
/// leading coefficient over `h = 0.2 .. 0.05`.
#[test]
fn the_hermite_predictor_is_fourth_order() {
    let on = |a: f64| (vec![a.cos(), a.sin()], vec![-a.sin(), a.cos()]);
    let errors = |h: f64| {
        let ((z0, t0), (z1, t1), (z2, _)) = (on(0.3), on(0.3 + h), on(0.3 + 2.0 * h));
        let p = hermite((&z0, &t0), (&z1, &t1), h, h);
        let e: Vec<f64> = z1.iter().zip(&t1).map(|(z, t)| z + h * t).collect();
        let dist = |a: &[f64]| {
            a.iter()
                .zip(&z2)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        (dist(&p), dist(&e))
    };
    let mut last = errors(0.2);
    for h in [0.1, 0.05] {
        let now = errors(h);
        assert!(
            last.0 / now.0 > 12.0,
            "Hermite at h = {h}: {last:?} -> {now:?}"
        );
        assert!(
            last.1 / now.1 > 3.5,
            "tangent at h = {h}: {last:?} -> {now:?}"
        );
        assert!(now.0 < 0.1 * now.1, "h = {h}: {now:?}");
        last = now;
    }
}

/// A path with the Hermite predictor ends where the tangent predictor's
/// does, on every case of [`cases`]: through the circle's fold, both folds
/// of the S-curve, Bratu's fold to its upper branch, and the Newton
/// homotopies' turning points.
#[test]
fn the_hermite_predictor_reaches_the_same_ends() {
    for mut case in cases() {
        let tangent = options(1e-12, 1.0, case.heading);
        let hermite = ArclengthOptions {
            predictor: Predictor::Hermite,
            ..tangent.clone()
        };
        let (name, target, sys) = (case.name, case.target, case.system.as_mut());
        let (x0, l0) = (&case.x0, case.lambda0);
        let a = follow(sys, x0, l0, target, &tangent, false).unwrap();
        let b = follow(sys, x0, l0, target, &hermite, false).unwrap();
        println!(
            "{name:18} steps: tangent {:3}, Hermite {:3}",
            a.steps, b.steps
        );
        let (ea, eb) = (a.points.last().unwrap(), b.points.last().unwrap());
        assert_eq!(eb.lambda, target, "{name}");
        let gap =
            ea.x.iter()
                .zip(&eb.x)
                .map(|(p, q)| (p - q).abs())
                .fold(0.0, f64::max);
        // both ends solve G to 1e-12 at the same lambda on the same branch
        assert!(gap < 1e-8, "{name}: ends {:?} and {:?}", ea.x, eb.x);
    }
}

/// [`Bordered`] `S` with `G` defined on `domain` only.
struct Within<S> {
    inner: S,
    domain: (f64, f64),
}

impl<S: ParametrisedSystem> ParametrisedSystem for Within<S> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn residual(&mut self, x: &[f64], lambda: f64, f: &mut [f64]) -> Result<()> {
        self.inner.residual(x, lambda, f)
    }
    fn linearise_bordered(
        &mut self,
        x: &[f64],
        lambda: f64,
        row: (&[f64], f64),
        f: &mut [f64],
    ) -> Result<()> {
        self.inner.linearise_bordered(x, lambda, row, f)
    }
    fn solve_bordered(&mut self, b: &[f64], c: f64, dx: &mut [f64], dl: &mut f64) -> Result<bool> {
        self.inner.solve_bordered(b, c, dx, dl)
    }
    fn work(&self) -> f64 {
        self.inner.work()
    }
    fn domain(&self) -> (f64, f64) {
        self.domain
    }
}

/// The S-curve from `lambda = -6` toward 6, on a system defined for
/// `lambda <= 0.3` only: past its first fold (0.385) the branch would turn
/// back, but the path stops at its first point beyond 0.3, with the domain
/// in its message.
#[test]
fn a_path_stops_where_it_leaves_the_systems_domain() {
    let mut sys = Within {
        inner: Bordered::new(SCurve { c: 0.0 }),
        domain: (-10.0, 0.3),
    };
    let opts = options(1e-12, 0.1, Heading::TowardTarget);
    let (stop, residual, reason) = failure(follow(&mut sys, &[-2.0], -6.0, 6.0, &opts, false));
    assert_eq!(stop, StopReason::Other, "{reason}");
    assert!(residual <= 1e-12, "{reason}");
    assert!(
        reason.contains("leaves the system's domain -10 <= lambda <= 0.3"),
        "{reason}"
    );
    let at: f64 = reason
        .split("at lambda = ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(at > 0.3 && at < 0.385, "{reason}");
}
