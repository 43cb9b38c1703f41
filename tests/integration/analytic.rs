//! Forward kinetostatics against closed-form solutions (paper Section III).
//!
//! * a pure tip moment bends the rod into a circular arc of curvature M/(EI);
//! * a small tip load deflects it by Euler-Bernoulli plus Timoshenko shear,
//!   F L^3/(3 E I) + F L/(k G A);
//! * a large dead tip load perpendicular to the rod gives the inextensible
//!   elastica of Bisshopp & Drucker (1945), computed here independently with
//!   Carlson's elliptic integrals;
//! * a straight tendon of constant tension (the Rucker & Webster tendon model
//!   that the TCA model reduces to) gives an arc of curvature tau r/(EI) less
//!   the axial shortening tau/(EA); helical routings that degenerate to a
//!   straight path give the same answer as that path.
//!
//! Frame: base at the origin, reference tangent +z. SI units.
use crate::common;

use std::f64::consts::PI;

use common::{solve_default, tendon, weightless_body, DIAMETER, E_B, LENGTH};
use nalgebra::Vector3;
use tcarod::rod::{Body, Robot, Routing, Section};
use tcarod::roots::brent;
use tcarod::shooting::{solve, Solution, SolveOptions};

fn area() -> f64 {
    PI * DIAMETER * DIAMETER / 4.0
}
fn i_section() -> f64 {
    PI * DIAMETER.powi(4) / 64.0
}
fn ei() -> f64 {
    E_B * i_section()
}

// ------------------------------------------------------------ pure moment

#[test]
fn pure_tip_moment_gives_circular_arc() {
    // [1/m]: tip angle 0.08 and 1.0 rad; about body x and y
    for axis in [0, 1] {
        for k in [2.0, 25.0] {
            let mut body = weightless_body();
            body.tip_moment[axis] = k * ei();
            let sol = solve_default(&Robot::new(body, vec![]).unwrap(), &[]);
            let l = LENGTH;
            // A moment about world +y turns the tangent (+z) toward +x; about +x, toward -y.
            let bend = if axis == 1 {
                Vector3::x()
            } else {
                -Vector3::y()
            };
            let want = bend * (1.0 - (k * l).cos()) / k + Vector3::z() * ((k * l).sin() / k);
            // Solver tolerance 1e-10 on L * (curvature error) -> curvature error <= 2.5e-9
            // 1/m, tip error <= L^2 * 2.5e-9 ~ 4e-12 m; RK4 (100 steps) integrates an arc
            // of constant curvature to ~(kh)^5 ~ 1e-12 m. 1e-10 m leaves a margin of 10.
            let err = (sol.tip_position() - want).amax();
            assert!(err < 1e-10, "axis {axis} k {k}: {err}");
            for (w, nu) in sol.omega.iter().zip(&sol.nu) {
                // curvature along the whole body, to the solver tolerance (2.5e-9 1/m, margin 4)
                assert!((w[axis] - k).abs() < 1e-8, "axis {axis} k {k}: {w}");
                // pure moment: no internal force, so no axial or shear strain
                assert!(
                    (nu - Vector3::z()).amax() < 1e-10,
                    "axis {axis} k {k}: {nu}"
                );
            }
        }
    }
}

// ------------------------------------------------- small load, Timoshenko

#[test]
fn small_tip_load_matches_euler_bernoulli_plus_shear() {
    for shear_coefficient in [1.0, 0.5] {
        let mut body = weightless_body();
        body.shear_coefficient = shear_coefficient;
        let force = 1e-4 * ei() / (LENGTH * LENGTH); // F L^2 / EI = 1e-4: tip angle ~5e-5 rad
        body.tip_force = Vector3::new(force, 0.0, 0.0);
        let g_b = body.shear_modulus;
        let sol = solve_default(&Robot::new(body, vec![]).unwrap(), &[]);
        let bending = force * LENGTH.powi(3) / (3.0 * ei());
        let shear = force * LENGTH / (shear_coefficient * g_b * area());
        let tip = sol.tip_position();
        // Linear theory neglects terms of relative order (F L^2 / EI)^2 = 1e-8; the
        // solver tolerance contributes ~1e-9 relative. The shear term is 2-4 % of the
        // total here, so 1e-6 relative separates it from Euler-Bernoulli alone by four
        // orders of magnitude.
        let want = bending + shear;
        assert!((tip.x - want).abs() <= 1e-6 * want, "{} vs {want}", tip.x);
        assert!((tip.x - bending).abs() > 0.01 * bending);
        // the load and the rod lie in the x-z plane: y stays zero to rounding
        assert!(tip.y.abs() < 1e-15);
    }
}

// ------------------------------------------------ large load, the elastica

/// Carlson's symmetric elliptic integral R_F(x, y, z) (Carlson 1995, duplication
/// to a relative 1e-16: the series' error falls by 4^6 per halving).
fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    for _ in 0..60 {
        let l = (x * y).sqrt() + (y * z).sqrt() + (z * x).sqrt();
        (x, y, z) = ((x + l) / 4.0, (y + l) / 4.0, (z + l) / 4.0);
        let a = (x + y + z) / 3.0;
        if (x - a).abs().max((y - a).abs()).max((z - a).abs()) < 1e-4 * a {
            let (dx, dy, dz) = (1.0 - x / a, 1.0 - y / a, 1.0 - z / a);
            let (e2, e3) = (dx * dy - dz * dz, dx * dy * dz);
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / a.sqrt();
        }
    }
    unreachable!("R_F duplication converges in ~20 steps")
}

/// Carlson's R_D(x, y, z) (Carlson 1995).
fn carlson_rd(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    let (mut sum, mut fac) = (0.0, 1.0);
    for _ in 0..60 {
        let l = (x * y).sqrt() + (y * z).sqrt() + (z * x).sqrt();
        sum += fac / (z.sqrt() * (z + l));
        fac /= 4.0;
        (x, y, z) = ((x + l) / 4.0, (y + l) / 4.0, (z + l) / 4.0);
        let a = (x + y + 3.0 * z) / 5.0;
        if (x - a).abs().max((y - a).abs()).max((z - a).abs()) < 1e-4 * a {
            let (dx, dy, dz) = (1.0 - x / a, 1.0 - y / a, 1.0 - z / a);
            let ea = dx * dy;
            let eb = dz * dz;
            let (ec, ed) = (ea - eb, ea - 6.0 * eb);
            let ee = ed + ec + ec;
            let s = 1.0
                + ed * (-3.0 / 14.0 + 9.0 / 88.0 * ed - 9.0 / 52.0 * dz * ee)
                + dz * (ee / 6.0 + dz * (-9.0 / 22.0 * ec + dz * 3.0 / 26.0 * ea));
            return 3.0 * sum + fac * s / (a * a.sqrt());
        }
    }
    unreachable!("R_D duplication converges in ~20 steps")
}

/// Incomplete elliptic integrals of the first and second kind, `(F(phi, k), E(phi, k))`.
fn elliptic_fe(phi: f64, k: f64) -> (f64, f64) {
    let (s, c) = phi.sin_cos();
    let y = 1.0 - k * k * s * s;
    let f = s * carlson_rf(c * c, y, 1.0);
    (f, f - k * k * s.powi(3) * carlson_rd(c * c, y, 1.0) / 3.0)
}

/// Bisshopp & Drucker (1945): inextensible cantilever of length L under a dead end
/// load P perpendicular to its straight shape, `alpha = P L^2 / EI`.
///
/// Returns `(theta0 [rad], x/L, y/L)`: tip slope, tip coordinate along the original
/// axis, tip deflection along the load. With `k^2 = (1 + sin theta0) / 2` and
/// `sin phi1 = 1 / (sqrt(2) k)`: `sqrt(alpha) = K(k) - F(phi1, k)`,
/// `y/L = 1 - 2 (E(k) - E(phi1, k)) / sqrt(alpha)` and
/// `x/L = sqrt(2 sin(theta0) / alpha)` (from `EI theta'^2 / 2 = P (sin theta0 - sin theta)`).
fn elastica(alpha: f64) -> (f64, f64, f64) {
    let parts = |k: f64| {
        let phi1 = (1.0 / (2f64.sqrt() * k)).asin();
        let (kk, ek) = elliptic_fe(PI / 2.0, k);
        let (f1, e1) = elliptic_fe(phi1, k);
        (kk - f1, ek - e1)
    };
    let k = brent(
        |k| parts(k).0 - alpha.sqrt(),
        1.0 / 2f64.sqrt() + 1e-15,
        1.0 - 1e-15,
        1e-15,
    )
    .expect("bracketed");
    let theta0 = (2.0 * k * k - 1.0).asin();
    let y = 1.0 - 2.0 / alpha.sqrt() * parts(k).1;
    let x = (2.0 * theta0.sin() / alpha).sqrt();
    (theta0, x, y)
}

/// Bisshopp & Drucker's table, to the 4 digits it is usually quoted with
/// (alpha = P L^2 / EI: x/L, y/L), e.g. alpha = 1: horizontal shortening
/// (L - x)/L = 0.0564, vertical deflection 0.3017.
const PUBLISHED: [(f64, f64, f64); 3] = [
    (1.0, 0.9436, 0.3017),
    (2.0, 0.8394, 0.4935),
    (10.0, 0.4450, 0.8106),
];

#[test]
fn elliptic_reference_reproduces_published_table() {
    // the integrals themselves against known values: K(1/sqrt 2) = 1.8540746773013719,
    // E(1/sqrt 2) = 1.3506438810476755 (Abramowitz & Stegun table 17.1, m = 1/2)
    let (kk, ek) = elliptic_fe(PI / 2.0, 0.5f64.sqrt());
    assert!((kk - 1.854_074_677_301_371_9).abs() < 1e-14, "{kk}");
    assert!((ek - 1.350_643_881_047_675_5).abs() < 1e-14, "{ek}");
    for (alpha, x_pub, y_pub) in PUBLISHED {
        let (_, x, y) = elastica(alpha);
        // 4 published digits: rounding leaves at most 5e-5
        assert!((x - x_pub).abs() <= 5e-5, "alpha {alpha}: x {x}");
        assert!((y - y_pub).abs() <= 5e-5, "alpha {alpha}: y {y}");
    }
}

fn custom_section(area_factor: f64) -> Section {
    let i = i_section();
    Section::Custom {
        area: area() * area_factor,
        ix: i,
        iy: i,
        j: 2.0 * i,
    }
}

fn loaded_body(area_factor: f64, alpha: f64) -> Body {
    let mut body = Body::new(LENGTH, custom_section(area_factor), E_B, 0.5, 0.0).unwrap();
    body.tip_force = Vector3::new(alpha * ei() / (LENGTH * LENGTH), 0.0, 0.0);
    body
}

/// Tip positions / L of a rod with `area_factor` times the area (same I, hence
/// same EI, but EA and GA scaled) under dead tip loads `alpha EI/L^2` along +x,
/// reached by load continuation (each solve warm-started from the previous load).
fn loaded_tips(area_factor: f64, alphas: &[f64]) -> Vec<Vector3<f64>> {
    let mut previous: Option<Solution> = None;
    let mut tips = Vec::new();
    for &alpha in alphas {
        let robot = Robot::new(loaded_body(area_factor, alpha), vec![]).unwrap();
        let sol = solve(&robot, &[], &SolveOptions::default(), previous.as_ref()).unwrap();
        tips.push(sol.tip_position() / LENGTH);
        previous = Some(sol);
    }
    tips
}

/// The rod made inextensible and unshearable by `Section::Custom` with a larger area
/// (same I) converges, as the area grows, to the elastica.
///
/// Directly with a very large area (x1000) the shooting solver does not converge
/// (see `stiff_section_large_load_converges_from_straight`), so the inextensible
/// limit is reached by Richardson extrapolation in the axial/shear compliance
/// 1/area_factor: the tip's deviation from the elastica is a smooth function
/// c1/f + c2/f^2 + ... of 1/f (f = area factor), and three areas f = 2, 4, 8
/// eliminate c1 and c2.
#[test]
fn large_tip_load_matches_bisshopp_drucker_elastica() {
    let alphas: Vec<f64> = (1..=40).map(|j| 0.25 * j as f64).collect(); // 0.25 .. 10
    let runs: Vec<_> = [2.0, 4.0, 8.0]
        .iter()
        .map(|&f| loaded_tips(f, &alphas))
        .collect();
    for alpha in [1.0, 2.0, 5.0, 10.0] {
        let j = alphas.iter().position(|&a| a == alpha).unwrap();
        let (_, x, y) = elastica(alpha);
        let (t2, t4, t8) = (runs[0][j], runs[1][j], runs[2][j]);
        // compliance matters at f = 2: the tip differs from the elastica by 0.3-2 % of L
        assert!((t2.x - y).abs() > 1e-3, "alpha {alpha}");
        // eliminate c1, then c2
        let (r24, r48) = (2.0 * t4 - t2, 2.0 * t8 - t4);
        let limit = (4.0 * r48 - r24) / 3.0;

        // 4 digits: |error| < 5e-5 L. The c3/f^3 remainder is ~(2 %)^3 / 64 ~ 1e-7,
        // RK4 (100 steps) and the solver tolerance ~1e-9.
        assert!(
            (limit.x - y).abs() < 5e-5,
            "alpha {alpha}: {limit} vs y {y}"
        );
        assert!(
            (limit.z - x).abs() < 5e-5,
            "alpha {alpha}: {limit} vs x {x}"
        );
        // planar problem: no deflection out of the x-z plane beyond rounding
        assert!(limit.y.abs() < 1e-12);
    }
}

/// The tip force residual is scaled by L^2/EI (`residual_scales`), so the line
/// search sees force errors of axially stiff sections.
#[test]
fn stiff_section_large_load_converges_from_straight() {
    for (area_factor, alpha) in [(1.0, 10.0), (100.0, 1.0)] {
        let robot = Robot::new(loaded_body(area_factor, alpha), vec![]).unwrap();
        let sol = solve_default(&robot, &[]);
        let (_, _, y) = elastica(alpha);
        // Shear and axial compliance only add deflection along the load, and by at
        // most the largest shear plus axial strain, P/(k G A) + P/(E A), integrated
        // over the length (|d(p - p_inextensible)/ds| <= those strains).
        let p_load = alpha * ei() / (LENGTH * LENGTH);
        let a = area() * area_factor;
        let bound = p_load / (E_B / 3.0 * a) + p_load / (E_B * a);
        // Below: the numerical floor (solver tolerance 1e-10 in strain, RK4 on
        // 100 steps, the reference elastica to 1e-15) keeps any shortfall far
        // below 1e-6 L.
        let excess = sol.tip_position().x / LENGTH - y;
        assert!(
            -1e-6 < excess && excess < bound,
            "f {area_factor}: {excess} {bound}"
        );
    }
}

// ------------------------------------------------ tendon of constant tension

#[test]
fn straight_tendon_gives_arc_less_axial_shortening() {
    let tau = 0.05; // [N]
    for (x, y) in [(3e-3, 0.0), (0.0, -2e-3), (1.5e-3, 2e-3)] {
        let routing = Routing::Straight { x, y };
        let robot = Robot::new(weightless_body(), vec![tendon(routing, 0.0, LENGTH)]).unwrap();
        let sol = solve_default(&robot, &[tau]);
        let ea = E_B * area();
        let radius = x.hypot(y);
        let k = tau * radius / ei(); // the tendon's moment / EI; bends the body toward it
        let stretch = 1.0 - tau / ea; // compressed by the tension
        let toward = Vector3::new(x, y, 0.0) / radius;
        let l = LENGTH;
        let want = toward * (stretch * (1.0 - (k * l).cos()) / k)
            + Vector3::z() * (stretch * (k * l).sin() / k);
        // exact arc under this model (Rucker & Webster 2011); RK4 + solver tolerance ~1e-12 m
        let err = (sol.tip_position() - want).amax();
        assert!(err < 1e-11, "({x}, {y}): {err}");
        assert_eq!(sol.tensions[0], tau);
        // the tendon path is the centre line offset by R r: shorter than the body
        assert!(sol.elongations[0] < 0.0);
    }
}

#[test]
fn helix_of_zero_radius_is_a_centred_tendon() {
    // r = 0 whatever the rate: the tendon runs on the centre line and only
    // compresses the straight rod by tau/(EA).
    let tau = 0.2;
    let routing = Routing::Helix {
        radius: 0.0,
        rate: 300.0,
        phase: 0.7,
    };
    let robot = Robot::new(weightless_body(), vec![tendon(routing, 0.0, LENGTH)]).unwrap();
    let sol = solve_default(&robot, &[tau]);
    let ea = E_B * area();
    let tip = sol.tip_position();
    // x, y exactly zero (nothing bends it); z to the solver tolerance 1e-10 on the
    // axial strain: L * 1e-10 = 4e-12 m (margin 5)
    assert_eq!((tip.x, tip.y), (0.0, 0.0));
    assert!((tip.z - LENGTH * (1.0 - tau / ea)).abs() < 2e-11, "{tip}");
    // tau / EA = 0.1: strain tolerance 1e-10 is 1e-9 relative (margin 10)
    let want = -LENGTH * tau / ea;
    assert!((sol.elongations[0] - want).abs() <= 1e-8 * want.abs());
}

#[test]
fn helix_of_zero_rate_equals_straight_routing() {
    // rate 0: r = radius (cos phase, sin phase, 0) for all s, r' = r'' = 0, the same
    // path as a straight routing at that offset -- through the helix code path.
    let (radius, phase, tau) = (2.5e-3, 2.0f64, 0.03);
    let helix = Routing::Helix {
        radius,
        rate: 0.0,
        phase,
    };
    let straight = Routing::Straight {
        x: radius * phase.cos(),
        y: radius * phase.sin(),
    };
    let run = |r| {
        let robot = Robot::new(weightless_body(), vec![tendon(r, 0.0, LENGTH)]).unwrap();
        solve_default(&robot, &[tau])
    };
    let (a, b) = (run(helix), run(straight));
    // identical arithmetic up to the sin/cos rounding of the offset
    assert!(common::max_diff(&a.positions, &b.positions) < 1e-14);
}

/// A helical tendon `r = a (cos(w s), sin(w s), 0)` with `w = 2 pi turns / L` under a
/// small tension. Cutting the body at `s`, the tendon's force `tau t_a` with
/// `t_a = (e3 + r') / sqrt(1 + (a w)^2)` acts at `r`, so to first order in `tau` the
/// body carries the moment `-r x tau t_a`: a bending curvature `tau a / (EI c)` toward
/// the tendon (`c = sqrt(1 + (a w)^2)`) and a twist `u_z = -tau a^2 w / (GJ c)`. The
/// bending direction turns with the tendon, so the tip moves sideways by
/// `int_0^L (L - s) kappa (cos(w s), sin(w s)) ds = (0, kappa L^2 / (2 pi turns))`.
/// This checks the helix's `r'` terms (tangent, twisting moment) independently.
#[test]
fn helical_tendon_small_tension_matches_linear_theory() {
    let (a, tau) = (3e-3, 1e-4); // [m], [N]: kappa L ~ 2e-3, twist over L ~ 1e-3 rad
    for turns in [1.0, -1.0, 2.0] {
        let w = 2.0 * PI * turns / LENGTH;
        let routing = Routing::Helix {
            radius: a,
            rate: w,
            phase: 0.0,
        };
        let body = weightless_body();
        let gj = body.shear_modulus * 2.0 * i_section(); // J = 2 I for a circle
        let robot = Robot::new(body, vec![tendon(routing, 0.0, LENGTH)]).unwrap();
        let sol = solve_default(&robot, &[tau]);
        let c = (1.0 + (a * w).powi(2)).sqrt();
        let kappa = tau * a / (ei() * c);
        let y_lin = kappa * LENGTH * LENGTH / (2.0 * PI * turns);
        let tip = sol.tip_position();
        // neglected terms are of relative order kappa L and (twist angle): ~2e-3;
        // 5e-3 leaves margin 2.5
        assert!(
            (tip.y - y_lin).abs() <= 5e-3 * y_lin.abs(),
            "turns {turns}: {tip}"
        );
        assert!(tip.x.abs() < 5e-3 * y_lin.abs(), "turns {turns}: {tip}");
        let twist = -tau * a * a * w / (gj * c);
        for om in &sol.omega {
            assert!(
                (om.z - twist).abs() <= 5e-3 * twist.abs(),
                "turns {turns}: {om}"
            );
        }
    }
}
