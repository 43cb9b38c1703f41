//! Elastic stability and branch following (docs/stability.md, whose
//! "Validation" table these tests produce): analytic buckling loads (Euler's
//! clamped-free column, Greenhill's self-weight column) and an independent
//! planar elastica with self-weight.

use nalgebra::Vector3;
use tcarod::branch::{follow_branch, sweep_stable, BranchOptions, EventKind, Parameter, Problem};
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve, SolveOptions};
use tcarod::stability::stability;

use crate::common::heavy_column;

/// A slender round steel-like column: L/r = 100, so shear and extension move
/// the critical loads by ~1e-4 relative (P_E/(k G A) ~ 2e-4), well inside 0.5 %.
fn column(tip_force: f64) -> Robot {
    let mut b = Body::new(0.5, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 1000.0).unwrap();
    b.tip_force = Vector3::new(0.0, 0.0, -tip_force);
    Robot::new(b, vec![]).unwrap()
}

/// Dimensionless critical load of the Euler column clamped at the base and
/// free at the tip, in units of EI / L^2.
const EULER_FREE: f64 = std::f64::consts::PI * std::f64::consts::PI / 4.0;
/// Self-weight buckling of an upright column (Greenhill): rho A g L^3 / EI.
const GREENHILL: f64 = 7.837;

/// Margin of the straight column under tip load `f` P_E.
fn column_margin(f: f64) -> (bool, f64) {
    let r = column(0.0);
    let (_, ix, _, _) = r.body.section.properties();
    let pc = EULER_FREE * r.body.youngs_modulus * ix / 0.25;
    let rob = column(f * pc);
    let sol = solve(&rob, &[], &SolveOptions::default(), None).unwrap();
    // the cold solve of the perfect column is the straight equilibrium (no
    // lateral load breaks the symmetry: the tip is on the axis to rounding)
    assert!(sol.tip_position().x.abs() < 1e-9 && sol.tip_position().y.abs() < 1e-9);
    let st = stability(&rob, &sol, &[]).unwrap();
    (st.stable, st.margin)
}

#[test]
fn euler_column_stable_below_unstable_above() {
    for f in [0.0, 0.5, 0.95, 0.995] {
        let (stable, margin) = column_margin(f);
        assert!(stable && margin > 0.0, "f = {f}: margin {margin}");
    }
    for f in [1.005, 1.05, 2.0] {
        let (stable, margin) = column_margin(f);
        assert!(!stable && margin < 0.0, "f = {f}: margin {margin}");
    }
}

#[test]
fn euler_column_critical_load_located() {
    // bisection on the verdict between 0.5 and 2 P_E
    let (mut lo, mut hi) = (0.5, 2.0);
    for _ in 0..20 {
        let mid = 0.5 * (lo + hi);
        if column_margin(mid).0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let f = 0.5 * (lo + hi);
    println!("Euler column: critical load / (pi^2 EI / 4 L^2) = {f:.6}");
    // 0.5 %: the accuracy required of the located load; shear and extension
    // shift it by ~2e-4
    assert!((f - 1.0).abs() < 5e-3, "critical load ratio {f}");
}

#[test]
fn self_weight_buckling_located() {
    let r = heavy_column();
    let pb = Problem::new(&r, Parameter::GravityScale, &[]).unwrap();
    let opts = BranchOptions {
        start: 1.0,
        end: 10.0,
        step: 0.05,
        max_step: 0.2,
        ..Default::default()
    };
    let br = follow_branch(&pb, &opts, None).unwrap();
    // the perfect column stays straight: no fold, two bifurcations, about
    // the weak axis at Greenhill's load and the strong one at (10/9)^2 times it
    assert_eq!(br.events.len(), 2);
    assert!(br.events.iter().all(|e| e.kind == EventKind::Bifurcation));
    let q = br.events[0].parameter;
    let q2 = br.events[1].parameter / (10.0f64 / 9.0).powi(2);
    println!("self-weight buckling at rho A g L^3 / EI = {q:.5}, second mode {q2:.5} (Greenhill 7.837), {} IVP-equivalents", br.evaluations);
    // 0.5 % as for Euler's load: shear and extension of the L/h = 55 column
    // shift it by ~2e-4
    assert!((q / GREENHILL - 1.0).abs() < 5e-3, "located at {q}");
    assert!(
        (q2 / GREENHILL - 1.0).abs() < 5e-3,
        "second located at {q2}"
    );
    for p in &br.points {
        assert_eq!(
            p.stability.stable,
            p.parameter < GREENHILL,
            "at {}",
            p.parameter
        );
    }
}

/// Independent planar elastica with self-weight: inextensible, unshearable,
/// `theta'' = -q (1 - s) sin(theta)` on `[0, 1]` (lengths in L, q = rho A g
/// L^3 / EI), `theta(0) = 0`, `theta'(1) = 0`, by RK4 (4000 steps) and
/// bisection on `theta'(0)`. Returns the tip (lateral, height) / L of the
/// first non-trivial (buckled) solution.
fn elastica_tip(q: f64) -> (f64, f64) {
    let shoot = |k0: f64| -> (f64, f64, f64) {
        let n = 4000;
        let h = 1.0 / n as f64;
        // y = (theta, theta', x, z)
        let f = |s: f64, y: [f64; 4]| [y[1], -q * (1.0 - s) * y[0].sin(), y[0].sin(), y[0].cos()];
        let mut y = [0.0, k0, 0.0, 0.0];
        for i in 0..n {
            let s = i as f64 * h;
            let add = |a: [f64; 4], b: [f64; 4], c: f64| {
                [
                    a[0] + c * b[0],
                    a[1] + c * b[1],
                    a[2] + c * b[2],
                    a[3] + c * b[3],
                ]
            };
            let k1 = f(s, y);
            let k2 = f(s + h / 2.0, add(y, k1, h / 2.0));
            let k3 = f(s + h / 2.0, add(y, k2, h / 2.0));
            let k4 = f(s + h, add(y, k3, h));
            for j in 0..4 {
                y[j] += h / 6.0 * (k1[j] + 2.0 * (k2[j] + k3[j]) + k4[j]);
            }
        }
        (y[1], y[2], y[3])
    };
    // scan theta'(0) upward from ~0 for the first sign change of theta'(1)
    let mut a = 1e-3;
    let mut fa = shoot(a).0;
    let mut b = a;
    loop {
        b += 0.01;
        assert!(b < 20.0, "no buckled elastica found");
        if shoot(b).0 * fa < 0.0 {
            break;
        }
        a = b;
        fa = shoot(a).0;
    }
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if shoot(m).0 * fa > 0.0 {
            a = m;
            fa = shoot(a).0;
        } else {
            b = m;
        }
    }
    let (_, x, z) = shoot(0.5 * (a + b));
    (x, z)
}

#[test]
fn post_buckled_branch_matches_elastica() {
    let r = heavy_column();
    let len = r.body.length;
    let pb = Problem::new(&r, Parameter::GravityScale, &[]).unwrap();
    let opts = BranchOptions {
        start: 1.0,
        end: 12.0,
        step: 0.05,
        max_step: 0.2,
        ..Default::default()
    };
    let sw = sweep_stable(&pb, &opts, None).unwrap();
    // one jump, at self-weight buckling (to 0.5 %, as above), onto the
    // (nearby) buckled branch
    assert_eq!(sw.jumps.len(), 1);
    assert!((sw.jumps[0].parameter / GREENHILL - 1.0).abs() < 5e-3);
    let mut checked = 0;
    for p in sw.points.iter().filter(|p| p.parameter > 8.2) {
        assert!(p.stability.stable);
        let tip = p.solution.tip_position() / len;
        let lateral = (tip.x * tip.x + tip.y * tip.y).sqrt();
        let (xe, ze) = elastica_tip(p.parameter);
        println!("q = {:.4}: tcarod tip (lateral, z)/L = ({lateral:.5}, {:.5}), elastica ({xe:.5}, {ze:.5})", p.parameter, tip.z);
        // extension and shear of the Cosserat body (q L/(E A) ~ 1e-3 at
        // these loads, (r/L)^2 = 1e-4) and the 100-step RK4 grid: 2e-3 L
        assert!(
            (lateral - xe.abs()).abs() < 2e-3 && (tip.z - ze).abs() < 2e-3,
            "q = {}",
            p.parameter
        );
        checked += 1;
    }
    assert!(checked >= 5);
}

#[test]
fn exact_tangents_match_finite_differences() {
    use tcarod::experiments::{fig6_circle, fig6_square};
    use tcarod::stability::stability_fd;
    let mut cases: Vec<(Robot, Vec<f64>)> = vec![(heavy_column(), vec![])];
    for t in [25.0, 100.0, 160.0] {
        let sq = fig6_square(true);
        let n = sq.actuators.len();
        cases.push((sq, vec![t; n]));
        let ci = fig6_circle(true);
        let n = ci.actuators.len();
        cases.push((ci, vec![t; n]));
    }
    for (r, q) in cases {
        let sol = solve(&r, &q, &SolveOptions::default(), None).unwrap();
        let a = stability(&r, &sol, &[]).unwrap();
        let b = stability_fd(&r, &sol, &[]).unwrap();
        println!(
            "inputs {:?}: exact margin {:.6e} stable {}, FD {:.6e} {}",
            q, a.margin, a.stable, b.margin, b.stable
        );
        assert_eq!(a.stable, b.stable);
        // forward differences with step sqrt(eps): ~1e-6 relative error
        assert!(
            (a.margin - b.margin).abs() < 1e-4 * (1.0 + a.margin.abs()),
            "{} vs {}",
            a.margin,
            b.margin
        );
        assert_eq!(a.evaluations, 1);
    }
}
