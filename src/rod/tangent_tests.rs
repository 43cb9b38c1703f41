//! Tests of the tangent pass: the linearised right-hand side against the
//! reference pass in dual arithmetic throughout, and the values against the
//! plain IVP (the finite-difference oracles are in
//! `tests/integration/tangent.rs`).

use std::sync::Arc;

use super::*;
use crate::experiments::{fig6_square, steel_tendon_robot};
use crate::rod::{integrate, Actuator, ConstantTension, Robot, Routing};

/// The pass with the linearised right-hand side against the reference
/// pass in dual arithmetic throughout, and its values against the plain IVP.
fn compare(robot: &Robot, tensions: &[f64], v0: Vector3<f64>, u0: Vector3<f64>) {
    let na = robot.actuators.len();
    let k = 6 + na;
    let mut seeds = TangentSeeds::zeros(na, k);
    for j in 0..k {
        match j {
            0..=2 => seeds.nu0[(j, j)] = 1.0,
            3..=5 => seeds.omega0[(j - 3, j)] = 1.0,
            _ => seeds.tensions[(j - 6, j)] = 1.0,
        }
    }
    let body = &robot.body;
    let spec = IvpSpec {
        robot,
        tensions,
        tip_force: body.tip_force,
        tip_moment: body.tip_moment,
        steps: 60,
    };
    let new = integrate_tangent(&spec, &v0, &u0, &seeds, false).unwrap();
    let reference = with_dual_rhs(|| integrate_tangent(&spec, &v0, &u0, &seeds, false));
    let reference = reference.unwrap();
    // the values are the plain IVP's, bit for bit
    let plain = integrate(&spec, &v0, &u0, false).unwrap();
    assert_eq!(new.ivp.tip, plain.tip);
    assert_eq!(new.ivp.elongation, plain.elongation);
    // the tangents: one derivative by two formulas, their rounding
    // carried through 60 steps and amplified by (25)'s condition (~1e6
    // for the steel rod): 1e-8 of each row's largest entry
    for (a, b) in [
        (&new.tip, &reference.tip),
        (&new.elongation, &reference.elongation),
    ] {
        for r in 0..a.nrows() {
            let big = b.row(r).amax().max(1e-300);
            let err = (a.row(r) - b.row(r)).amax() / big;
            assert!(err <= 1e-8, "row {r}: {err:e}\n{a:.6e}\n{b:.6e}");
        }
    }
}

#[test]
fn linearised_pass_agrees_with_the_dual_pass_and_the_plain_ivp() {
    let sq = fig6_square(true);
    let (v0, u0) = (
        Vector3::new(0.001, -0.002, 1.01),
        Vector3::new(3.0, -2.0, 0.5),
    );
    compare(&sq, &[-0.05, 0.02], v0, u0);
    // an interior anchor (strain jump) and a helix
    let len = sq.body.length;
    let (law, x) = (Arc::new(ConstantTension), 3e-3);
    let helix = Routing::Helix {
        radius: x,
        rate: 40.0,
        phase: 0.2,
    };
    let acts = vec![
        Actuator::new(Routing::Straight { x, y: 0.0 }, 0.0, 0.6 * len, law.clone()),
        Actuator::new(helix, 0.2 * len, len, law),
    ];
    let mixed = Robot::new(sq.body.clone(), acts).unwrap();
    compare(&mixed, &[-0.05, 0.02], v0, u0);
    // no distributed force but a distributed moment, and intervals with no
    // string at all (an actuator anchored at 0.3 L and 0.7 L only)
    let mut body = sq.body.clone();
    body.gravity = Vector3::zeros();
    body.distributed_moment = Vector3::new(2e-3, -1e-3, 5e-4);
    let law = Arc::new(ConstantTension);
    let inner = Actuator::new(Routing::Straight { x, y: -x }, 0.3 * len, 0.7 * len, law);
    let inner = Robot::new(body, vec![inner]).unwrap();
    compare(&inner, &[-0.03], v0, u0);
    let steel = steel_tendon_robot();
    let u0 = Vector3::new(0.0, 0.3, 0.0);
    compare(
        &steel,
        &[15.0, 0.0, 0.0, 0.0],
        Vector3::new(0.0, 0.0, 1.0),
        u0,
    );
}
