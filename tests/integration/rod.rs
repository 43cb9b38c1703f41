//! Analytic and physical checks of the rod model (paper Section III) and the
//! shooting solver on the core's fixtures: arcs under a tip moment and a
//! straight tendon, the quaternion's orthogonality, the sign of a heated
//! extension TCA, the reference configuration, the base wrench.
use std::sync::Arc;

use nalgebra::Vector3;
use tcarod::experiments::{fig6_circle, fig6_square};
use tcarod::rod::{Actuator, Body, ConstantTension, Robot, Routing, Section};
use tcarod::shooting::{solve, SolveOptions};

fn weightless_rod(len: f64) -> Body {
    Body::new(len, Section::Circle { diameter: 8e-3 }, 37.8e3, 0.5, 1040.0).unwrap()
}

#[test]
fn pure_tip_moment_gives_circular_arc() {
    let mut body = weightless_rod(0.04);
    let (_, ix, ..) = body.section.properties();
    let ei = body.youngs_modulus * ix;
    let m = 2.0 * ei; // curvature 2 1/m, tip angle 0.08 rad
    body.tip_moment = Vector3::new(0.0, m, 0.0);
    let robot = Robot::new(body, vec![]).unwrap();
    let sol = solve(&robot, &[], &SolveOptions::default(), None).unwrap();
    let k = m / ei;
    let l = 0.04;
    let want = Vector3::new((1.0 - (k * l).cos()) / k, 0.0, (k * l).sin() / k);
    // RK4 with 100 steps integrates an arc to ~1e-12 m; solver tol 1e-10 in strain
    assert!(
        (sol.tip_position() - want).norm() < 1e-11,
        "{}",
        sol.tip_position() - want
    );
    // curvature along the body to the solver tolerance (1e-10 / L = 2.5e-9 1/m)
    for w in &sol.omega {
        assert!((w.y - k).abs() < 1e-8);
    }
}

#[test]
fn straight_tendon_gives_arc_less_axial_shortening() {
    let body = weightless_rod(0.04);
    let (a, ix, ..) = body.section.properties();
    let (ei, ea) = (body.youngs_modulus * ix, body.youngs_modulus * a);
    let r = 3e-3;
    let tau = 0.05;
    let act = Actuator::new(
        Routing::Straight { x: r, y: 0.0 },
        0.0,
        0.04,
        Arc::new(ConstantTension),
    );
    let robot = Robot::new(body, vec![act]).unwrap();
    let sol = solve(&robot, &[tau], &SolveOptions::default(), None).unwrap();
    let k = tau * r / ei; // tendon moment / EI, bends toward the tendon (+x)
    let vz = 1.0 - tau / ea;
    let l = 0.04;
    let want = Vector3::new(vz * (1.0 - (k * l).cos()) / k, 0.0, vz * (k * l).sin() / k);
    // exact arc under this model (Rucker & Webster 2011): RK4 and the solver
    // tolerance leave ~1e-12 m
    assert!(
        (sol.tip_position() - want).norm() < 1e-11,
        "{:?} vs {:?}",
        sol.tip_position(),
        want
    );
    assert!(sol.tip_position().x > 0.0);
}

#[test]
fn quaternion_keeps_rotation_orthogonal() {
    let mut body = weightless_rod(0.04);
    body.tip_moment = Vector3::new(3e-6, 5e-5, 1e-6);
    body.tip_force = Vector3::new(1e-3, -2e-3, 0.0);
    let robot = Robot::new(body, vec![]).unwrap();
    let opts = SolveOptions {
        steps: 20_000,
        ..Default::default()
    };
    let sol = solve(&robot, &[], &opts, None).unwrap();
    let worst = sol
        .rotations
        .iter()
        .map(|r| (r.transpose() * r - nalgebra::Matrix3::identity()).norm())
        .fold(0.0, f64::max);
    // unit quaternion renormalised every step: orthogonal to rounding
    assert!(worst < 1e-14, "drift {worst}");
}

#[test]
fn heated_extension_tca_at_plus_x_bends_toward_minus_x() {
    let robot = fig6_square(false);
    let sol = solve(&robot, &[100.0, 100.0], &SolveOptions::default(), None).unwrap();
    assert!(sol.tip_position().x < -1e-3, "{}", sol.tip_position());
    assert!(
        sol.tensions.iter().all(|&t| t < 0.0),
        "a heated extension TCA pushes"
    );
    assert!(sol.elongations.iter().all(|&d| d > 0.0));
}

#[test]
fn reference_temperature_is_the_reference_configuration() {
    for robot in [fig6_square(false), fig6_circle(false)] {
        let ref_in = robot.reference_inputs();
        let sol = solve(&robot, &ref_in, &SolveOptions::default(), None).unwrap();
        // the reference guess is the exact solution: rounding only
        for (w, s) in sol.omega.iter().zip(&sol.s) {
            assert!((w - robot.body.omega_star).norm() < 1e-12, "at s = {s}");
        }
        assert!(sol.tensions.iter().all(|t| t.abs() < 1e-12));
        assert!(sol.elongations.iter().all(|d| d.abs() < 1e-15));
    }
}

#[test]
fn base_wrench_balances_external_loads() {
    let mut robot = fig6_square(true);
    robot.body.tip_force = Vector3::new(2e-3, 1e-3, -1e-3);
    robot.body.tip_moment = Vector3::new(0.0, 1e-5, 0.0);
    let sol = solve(&robot, &[120.0, 90.0], &SolveOptions::default(), None).unwrap();
    let fe = robot.body.distributed_load();
    let want_f = robot.body.tip_force + fe * robot.body.length;
    // the solver's tip-force tolerance (1e-10 EI/L^2, 2e-12 N here) and
    // rounding: 1e-11 N
    assert!(
        (sol.base_force - want_f).norm() < 1e-12 * 10.0,
        "{} vs {}",
        sol.base_force,
        want_f
    );
    println!(
        "iterations {} evaluations {}",
        sol.iterations, sol.evaluations
    );
}
