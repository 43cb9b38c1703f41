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

/// A scalar system `f(x)` with its exact derivative, `(f, df/dx) =
/// f(n, x)` at the `n`-th evaluation, and a known rounding floor.
struct Scalar<F: FnMut(usize, f64) -> (f64, f64)> {
    f: F,
    floor: f64,
    n: usize,
}

impl<F: FnMut(usize, f64) -> (f64, f64)> System for Scalar<F> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        Ok(self.residual_and_jacobian(x)?.0)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.n += 1;
        let (v, d) = (self.f)(self.n, x[0]);
        Ok((vec![v], DMatrix::from_element(1, 1, d)))
    }
    fn floor(&self, _x: &[f64], _r: &[f64]) -> f64 {
        self.floor
    }
    fn evaluations(&self) -> usize {
        self.n
    }
}

/// A residual with rounding noise of 1e-9: tol 1e-12 converges to the
/// floor (reported), instead of failing.
#[test]
fn tol_below_the_floor_converges_to_the_floor() {
    let noisy = |n: usize, x: f64| {
        let noise = 1e-9 * ((n as f64 * 12.9898).sin() * 43758.5453).fract();
        (x - 2.0 + noise, 1.0)
    };
    let mut sys = Scalar {
        f: noisy,
        floor: 1e-9,
        n: 0,
    };
    let o = NewtonOptions::new(1e-12, 20, 1e-6);
    let r = newton(&mut sys, &[10.0], &o, "test").unwrap();
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
    let kink = |_: usize, x: f64| {
        let k = if x >= 0.0 { 1.0 } else { 1000.0 };
        (k * x + 1.0, k)
    };
    let mut sys = Scalar {
        f: kink,
        floor: 0.0,
        n: 0,
    };
    let o = NewtonOptions::new(1e-12, 20, 1e-10);
    let r = newton(&mut sys, &[1.0], &o, "test").unwrap();
    // the root to rounding: |f| <= 1e-12 means |x + 1e-3| <= 1e-15
    assert!((r.x[0] + 1e-3).abs() < 1e-15, "{}", r.x[0]);
    assert_eq!(r.iterations, 2);
}
