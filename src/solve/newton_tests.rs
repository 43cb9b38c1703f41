//! Unit tests of [`super::newton`].
use super::*;

/// Rosenbrock's function as a system: f = (10 (y - x^2), 1 - x), root (1, 1).
#[test]
fn solves_rosenbrock_from_afar_and_reports_failures() {
    let mut sys = FnSystem::new(|x: &[f64]| Ok(vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]]));
    let o = NewtonOptions::new(1e-12, 50, 1e-10);
    let r = newton(&mut sys, &[-1.2, 1.0], &o, "test").unwrap();
    assert!((r.x[0] - 1.0).abs() < 1e-10 && (r.x[1] - 1.0).abs() < 1e-10);
    assert_eq!(r.status, Status::Converged);
    // x^2 + 1 = 0 has no real root: the merit's minimum is at 0 with f = 1
    let mut sys = FnSystem::new(|x: &[f64]| Ok(vec![x[0] * x[0] + 1.0]));
    match newton(&mut sys, &[0.7], &o, "test") {
        Err(Error::NotConverged {
            residual,
            evaluations,
            stop,
            ..
        }) => {
            assert!((residual - 1.0).abs() < 1e-6, "best residual {residual}");
            assert!(evaluations > 2);
            assert!(matches!(
                stop,
                StopReason::LineSearch | StopReason::SingularJacobian | StopReason::IterationLimit
            ));
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

/// A residual with rounding noise of 1e-9: tol 1e-12 converges to the
/// floor (reported), instead of failing.
#[test]
fn tol_below_the_floor_converges_to_the_floor() {
    struct Noisy(usize);
    impl System for Noisy {
        fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
            self.0 += 1;
            let noise = 1e-9 * ((self.0 as f64 * 12.9898).sin() * 43758.5453).fract();
            Ok(vec![x[0] - 2.0 + noise])
        }
        fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
            Ok((self.residual(x)?, DMatrix::from_element(1, 1, 1.0)))
        }
        fn floor(&self, _x: &[f64], _r: &[f64]) -> f64 {
            1e-9
        }
        fn evaluations(&self) -> usize {
            self.0
        }
    }
    let o = NewtonOptions::new(1e-12, 20, 1e-6);
    let r = newton(&mut Noisy(0), &[10.0], &o, "test").unwrap();
    assert_eq!(r.status, Status::ConvergedAtFloor);
    assert!((r.x[0] - 2.0).abs() <= 2e-9);
    assert_eq!(r.floor, 1e-9);
}

/// A force law's kink: `f(x) = x + 1` (slack side, `x >= 0`), `1000 x + 1`
/// (stiff side, root `x = -1e-3`), with its exact Jacobian. From `x = 1` the
/// Newton step lands at `x = -1` on the stiff side and fails the Armijo
/// test; the watchdog's second step, with the stiff side's Jacobian, lands
/// on the root, so two iterations suffice. (Backtracking alone needs three:
/// `t = 1/2` to the kink, `t = 2^-9` along the next step, then the stiff
/// Newton step.)
#[test]
fn a_watchdog_step_crosses_a_kink() {
    struct Kink(usize);
    impl System for Kink {
        fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
            self.0 += 1;
            let k = if x[0] >= 0.0 { 1.0 } else { 1000.0 };
            Ok(vec![k * x[0] + 1.0])
        }
        fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
            let k = if x[0] >= 0.0 { 1.0 } else { 1000.0 };
            Ok((self.residual(x)?, DMatrix::from_element(1, 1, k)))
        }
        fn evaluations(&self) -> usize {
            self.0
        }
    }
    let o = NewtonOptions::new(1e-12, 20, 1e-10);
    let r = newton(&mut Kink(0), &[1.0], &o, "test").unwrap();
    // the root to rounding: |f| <= 1e-12 means |x + 1e-3| <= 1e-15
    assert!((r.x[0] + 1e-3).abs() < 1e-15, "{}", r.x[0]);
    assert_eq!(r.iterations, 2);
}
