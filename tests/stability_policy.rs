//! The stability policy of a solve (issue 16): `solve_checked` never hands
//! back an unstable equilibrium without saying so, and `Continue` moves to a
//! stable one at the same inputs.

use nalgebra::Vector3;
use tcarod::error::Error;
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve_loaded, Loads, SolveOptions};
use tcarod::stability::{solve_checked, Policy};

/// A slender round column (L/r = 100) under a dead compressive tip load of
/// `ratio` times the Euler load `pi^2 EI / (4 L^2)`; weightless, so the
/// elastica below is exact up to shear and extension (~2e-4 relative).
fn column(ratio: f64) -> Robot {
    let len = 0.5;
    let mut b = Body::new(len, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 1000.0).unwrap();
    b.gravity = Vector3::zeros();
    let (_, ix, _, _) = b.section.properties();
    let pc = std::f64::consts::PI.powi(2) * b.youngs_modulus * ix / (4.0 * len * len);
    b.tip_force = Vector3::new(0.0, 0.0, -ratio * pc);
    Robot::new(b, vec![]).unwrap()
}

/// Complete elliptic integral of the first kind K(k) by the AGM.
fn ellip_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Lateral tip deflection / L of the clamped-free inextensible elastica under
/// a dead axial tip load `ratio` P_E (first mode): `lambda L = K(k)` with
/// `lambda = sqrt(P / EI)`, deflection `2 k / lambda`.
fn elastica_deflection(ratio: f64) -> f64 {
    let target = std::f64::consts::FRAC_PI_2 * ratio.sqrt();
    let (mut lo, mut hi) = (0.0, 0.999_999);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ellip_k(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let k = 0.5 * (lo + hi);
    2.0 * k / ellip_k(k)
}

fn lateral(p: Vector3<f64>) -> f64 {
    (p.x * p.x + p.y * p.y).sqrt()
}

#[test]
fn report_carries_the_verdict_at_one_tangent_ivp() {
    let opts = SolveOptions::default();
    for (ratio, stable) in [(0.5, true), (1.5, false)] {
        let r = column(ratio);
        let loads = Loads::of(&r);
        let plain = solve_loaded(&r, &[], &loads, &opts, None).unwrap();
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Report).unwrap();
        let st = c.stability.expect("Report always carries a verdict");
        assert_eq!(st.stable, stable, "ratio {ratio}: margin {}", st.margin);
        assert_eq!(st.stable, st.margin > 0.0);
        // the same equilibrium (the cold solve of the perfect column is straight)
        assert_eq!(c.solution.unknowns, plain.unknowns);
        assert!(lateral(c.solution.tip_position()) < 1e-9);
        // cost: exactly one integration (a tangent IVP) more than the solve
        assert_eq!(st.evaluations, 1);
        assert_eq!(c.solution.evaluations, plain.evaluations + 1);
        assert!(c.continued.is_none());
    }
}

#[test]
fn off_skips_and_require_refuses() {
    let opts = SolveOptions::default();
    let r = column(1.5);
    let loads = Loads::of(&r);
    let plain = solve_loaded(&r, &[], &loads, &opts, None).unwrap();
    let off = solve_checked(&r, &[], &loads, &opts, None, Policy::Off).unwrap();
    assert!(off.stability.is_none());
    assert_eq!(off.solution.evaluations, plain.evaluations);
    match solve_checked(&r, &[], &loads, &opts, None, Policy::Require) {
        Err(Error::NoSolution { reason }) => {
            assert!(
                reason.contains("unstable") && reason.contains("margin"),
                "{reason}"
            )
        }
        other => panic!("expected NoSolution, got {other:?}"),
    }
    // a stable equilibrium passes `Require` unchanged
    let r = column(0.5);
    let c = solve_checked(&r, &[], &Loads::of(&r), &opts, None, Policy::Require).unwrap();
    assert!(c.stability.unwrap().stable);
}

#[test]
fn policy_names_parse_and_bad_ones_name_the_argument() {
    for (s, p) in [
        ("report", Policy::Report),
        ("require", Policy::Require),
        ("continue", Policy::Continue),
        ("off", Policy::Off),
    ] {
        assert_eq!(s.parse::<Policy>().unwrap(), p);
    }
    assert_eq!(Policy::default(), Policy::Report);
    let e = "stable".parse::<Policy>().unwrap_err().to_string();
    assert!(e.contains("stability") && e.contains("'continue'"), "{e}");
}

#[test]
fn continue_lands_on_the_post_buckled_elastica() {
    let opts = SolveOptions::default();
    for ratio in [1.2, 1.5, 2.0] {
        let r = column(ratio);
        let loads = Loads::of(&r);
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Continue).unwrap();
        let st = c.stability.expect("verdict");
        assert!(st.stable, "ratio {ratio}: margin {}", st.margin);
        let cont = c.continued.expect("the straight column was unstable");
        assert!(!cont.from_stability.stable && lateral(cont.from.tip_position()) < 1e-9);
        // the route is recorded (imperfection homotopy, or a perturbed Newton start)
        assert!(!cont.route.to_string().is_empty() && cont.candidates >= 1);
        assert!(cont.evaluations > 0 && c.solution.evaluations > cont.evaluations);
        // the same problem: inputs and loads unchanged, an equilibrium to tol
        assert_eq!(c.solution.loads, loads);
        assert!(c.solution.residual <= opts.tol);
        let d = lateral(c.solution.tip_position()) / 0.5;
        let e = elastica_deflection(ratio);
        println!(
            "P/P_E = {ratio}: continued tip deflection {d:.5} L, elastica {e:.5} L ({})",
            cont.route
        );
        // 1e-3 L: shear and extension of an L/r = 100 column (~2e-4) and RK4
        assert!((d - e).abs() < 1e-3, "ratio {ratio}: {d} vs elastica {e}");
    }
}
