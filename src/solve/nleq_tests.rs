//! Tests of [`super`].

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
    let r =
        solve(&mut sys, &p.start(), o, "nleq test").unwrap_or_else(|e| panic!("{}: {e}", p.name()));
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
    let (stop, best, _, _) = not_converged(solve(&mut Faulty::new(true), &[-1.2, 1.0], &o, "t"));
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
    let (stop, _, iterations, _) = not_converged(solve(&mut Dense::new(p), &p.start(), &o, "t"));
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

/// `F(x) = g(x) + c` for a spring law `g` that stiffens from slope 1 to
/// slope `K` below zero over the interval `[-eps, 0]` (`g' = 1 - (K - 1) x
/// / eps` there: C1, the shape of a TCA's coil contact,
/// `crate::tca::TcaAt::tension`), with its breakpoints reported or not.
struct Stiffening {
    k: f64,
    eps: f64,
    c: f64,
    report: bool,
    lu: f64,
    xs: Vec<f64>,
}

impl Stiffening {
    fn g(&self, x: f64) -> (f64, f64) {
        let (k, e) = (self.k, self.eps);
        if x >= 0.0 {
            (x, 1.0)
        } else if x >= -e {
            (x - (k - 1.0) * x * x / (2.0 * e), 1.0 - (k - 1.0) * x / e)
        } else {
            (-e - (k - 1.0) * e / 2.0 + k * (x + e), k)
        }
    }
}

impl NonlinearSystem for Stiffening {
    fn dim(&self) -> usize {
        1
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        f[0] = self.g(x[0]).0 + self.c;
        Ok(())
    }
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        self.xs.push(x[0]);
        let (g, dg) = self.g(x[0]);
        (f[0], self.lu) = (g + self.c, dg);
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool> {
        dx[0] = b[0] / self.lu;
        Ok(true)
    }
    fn work(&self) -> f64 {
        self.xs.len() as f64
    }
    fn breakpoint(&self, x: &[f64], dx: &[f64]) -> Option<f64> {
        let (x, end, a) = (x[0], x[0] + dx[0], -self.eps);
        (self.report && x >= 0.0 && end < a).then(|| (a - x) / dx[0])
    }
}

/// A step over a kink of a piecewise smooth residual: Newton from the
/// soft side predicts a root deep in the stiff side, where the residual
/// is `K` times larger than predicted. Stepping to the breakpoint puts the
/// next linearisation on the stiff piece, which is linear here, so that
/// Newton's next step is exact: the linearisation points are the start,
/// the breakpoint `-eps` and the root. Without the breakpoint each damped
/// step stays on the soft piece, where the error-oriented damping, fed by
/// trials on the stiff side, creeps toward the kink.
#[test]
fn a_step_over_a_kink_stops_at_the_breakpoint() {
    let sys = |report| Stiffening {
        k: 400.0,
        eps: 1e-3,
        c: 4.0,
        report,
        lu: 0.0,
        xs: Vec::new(),
    };
    let mut kinked = sys(true);
    let r = solve(&mut kinked, &[1.0], &opts(1e-12, false), "kink").unwrap();
    let root = r.x[0];
    assert!((kinked.g(root).0 + 4.0).abs() <= 1e-12);
    assert!(root < -1e-3, "the root is on the stiff piece: {root}");
    // (the start, the breakpoint to rounding, then the stiff piece's exact
    // Newton step lands at the root: at most one more evaluation confirms)
    assert!(kinked.xs.len() <= 4, "{:?}", kinked.xs);
    assert!((kinked.xs[1] + 1e-3).abs() < 1e-15, "{:?}", kinked.xs);
    // (without the breakpoint: not converged within three times the
    // linearisations, or not at all within the iteration limit)
    let mut plain = sys(false);
    let p = solve(&mut plain, &[1.0], &opts(1e-12, false), "kink");
    assert!(
        p.is_err() || plain.xs.len() > 3 * kinked.xs.len(),
        "{:?}",
        plain.xs
    );
}
