//! The exact shooting Jacobian (tangent IVP, `src/rod/tangent.rs`) against
//! central finite differences of the residual (paper eqs 32-33, scaled as in
//! docs/choices.md, "Shooting unknowns and residuals"), on designs that
//! exercise every path: TCA law (with coil contact), constant and linear
//! tendons, helices, interior anchors (strain jumps), pre-curvature, gravity
//! and tip loads.
use std::sync::Arc;

use nalgebra::{DMatrix, Vector3};
use tcarod::experiments::{
    fig6_circle, fig6_square, manipulator_tca, soft_tendon_robot, steel_tendon_robot,
    MANIPULATOR_TURNS,
};
use tcarod::rod::{Actuator, Body, ConstantTension, LinearTendon, Robot, Routing, Section, TcaLaw};
use tcarod::shooting::{initial_guess, solve, Loads, Shot, SolveOptions};

/// A soft helix-and-interior-anchor design: a constant-tension helix from
/// 0.2 L to the tip, a linear tendon anchored at 0.3 L .. 0.7 L, a straight
/// TCA over the first half (anchored inside), gravity sideways, a tip load.
fn mixed() -> Robot {
    let len = 0.1;
    let mut body = Body::new(
        len,
        Section::Rectangle {
            width: 12e-3,
            height: 9e-3,
        },
        200e3,
        0.45,
        1100.0,
    )
    .unwrap();
    body.gravity = Vector3::new(3.0, -2.0, -9.0);
    body.tip_force = Vector3::new(0.001, 0.002, -0.001);
    body.tip_moment = Vector3::new(0.0, 1e-5, 2e-5);
    body.omega_star = Vector3::new(0.5, 0.0, 1.0);
    let acts = vec![
        Actuator::new(
            Routing::Helix {
                radius: 3e-3,
                rate: 20.0,
                phase: 0.3,
            },
            0.2 * len,
            len,
            Arc::new(ConstantTension),
        ),
        Actuator::new(
            Routing::Straight { x: -3e-3, y: 2e-3 },
            0.3 * len,
            0.7 * len,
            Arc::new(LinearTendon { stiffness: 500.0 }),
        ),
        Actuator::new(
            Routing::Straight { x: 0.0, y: -3.5e-3 },
            0.0,
            0.5 * len,
            Arc::new(TcaLaw(manipulator_tca(0.5 * len, MANIPULATOR_TURNS))),
        ),
    ];
    Robot::new(body, acts).unwrap()
}

/// Central differences of the scaled residual, step `h_j` per unknown.
fn fd_jacobian(robot: &Robot, inputs: &[f64], x: &[f64], steps: usize) -> DMatrix<f64> {
    let loads = Loads::of(robot);
    let n = x.len();
    let mut j = DMatrix::zeros(n, n);
    for c in 0..n {
        // h = 1e-9 on every (scaled, O(1e-3..1)) unknown: the steel rod's
        // residual is so nonlinear in shear strain that h = 1e-6 has a 25 %
        // truncation error in its shear columns, 1e-8 still 2e-5
        let h = 1e-9;
        let mut xp = x.to_vec();
        xp[c] += h;
        let rp = Shot::new(robot, inputs, &loads, steps)
            .residual(&xp, false)
            .unwrap()
            .0;
        xp[c] = x[c] - h;
        let rm = Shot::new(robot, inputs, &loads, steps)
            .residual(&xp, false)
            .unwrap()
            .0;
        for r in 0..n {
            j[(r, c)] = (rp[r] - rm[r]) / (2.0 * h);
        }
    }
    j
}

fn check(name: &str, robot: &Robot, inputs: &[f64], x: &[f64], steps: usize) {
    let loads = Loads::of(robot);
    let (r, jac, _, _) = Shot::new(robot, inputs, &loads, steps)
        .jacobian(x, false)
        .unwrap();
    let (r0, _, _) = Shot::new(robot, inputs, &loads, steps)
        .residual(x, false)
        .unwrap();
    // the generic (dual) twin of the RHS and the f64 fast path compute the
    // same map: residuals agree to rounding of O(1) strains over the grid
    for (a, b) in r.iter().zip(&r0) {
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
            "{name}: residual {a:e} vs {b:e}"
        );
    }
    let fd = fd_jacobian(robot, inputs, x, steps);
    let scale = fd.amax().max(1.0);
    let err = (&jac - &fd).amax() / scale;
    // central differences: truncation ~h^2 r''' and rounding ~eps |r| / h;
    // with h = 1e-9 both are below ~1e-6 of the largest entry; an error in a
    // tangent term is O(1) of its entries
    assert!(err < 1e-5, "{name}: exact vs FD Jacobian, max error {err:e} of {scale:e}\nexact {jac:.4e}\nfd {fd:.4e}");
    println!("{name}: max |J - J_fd| / max|J| = {err:.2e}");
}

#[test]
fn tangent_jacobian_matches_differences() {
    let opts = SolveOptions::default();
    // TCA square with gravity: at a solution and away from it
    let sq = fig6_square(true);
    let s = solve(&sq, &[100.0, 100.0], &opts, None).unwrap();
    check("square at solution", &sq, &[100.0, 100.0], &s.unknowns, 100);
    let mut x = s.unknowns.clone();
    x[3] += 0.3;
    x[1] -= 0.01;
    check("square off solution", &sq, &[100.0, 100.0], &x, 100);
    // coil contact: one leg hot, the other passive and pressed (elongation < 0)
    let mut opp = sq.clone();
    opp.actuators[1].routing = Routing::Straight { x: -3e-3, y: 0.0 };
    let s2 = solve(&opp, &[130.0, 25.0], &opts, None).unwrap();
    assert!(
        s2.elongations[1] < 0.0,
        "the passive TCA is pressed: {:?}",
        s2.elongations
    );
    check(
        "opposed TCAs, coil contact",
        &opp,
        &[130.0, 25.0],
        &s2.unknowns,
        100,
    );
    // pre-curved circle
    let c = fig6_circle(true);
    let sc = solve(&c, &[90.0], &opts, None).unwrap();
    check("circle", &c, &[90.0], &sc.unknowns, 60);
    // steel tendons, three at zero tension
    let st = steel_tendon_robot();
    let x0 = initial_guess(&st, &[15.0, 0.0, 0.0, 0.0], None);
    check(
        "steel tendon cold guess",
        &st,
        &[15.0, 0.0, 0.0, 0.0],
        &x0,
        100,
    );
    // soft tendon at a large angle
    let so = soft_tendon_robot();
    let mut x = initial_guess(&so, &[2.0], None);
    x[4] = 1.2;
    check("soft tendon", &so, &[2.0], &x, 50);
    // helix, interior anchors, linear tendon, TCA anchored inside, loads
    let m = mixed();
    let inputs = [0.3, 2e-4, 80.0];
    let mut x = initial_guess(&m, &inputs, None);
    x[3] = 0.2;
    x[4] = -0.4;
    x[5] = 0.1;
    x[7] += 1e-3; // the linear tendon taut (its law has a kink at zero tension)
    check("mixed at a guess", &m, &inputs, &x, 80);
    let sm = solve(&m, &inputs, &opts, None).unwrap();
    check("mixed at solution", &m, &inputs, &sm.unknowns, 80);
}
