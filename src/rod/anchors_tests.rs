//! Tests of the anchor jumps: the cached routing and before sides against
//! a per-evaluation reference, the rounding-floor exit.

use std::sync::Arc;

use super::*;
use crate::experiments::fig6_square;
use crate::rod::{Actuator, ConstantTension, Robot, Routing};

/// Fig. 6's body with a straight string ending at 0.6 L, a helix
/// passing it and a helix starting there: every kind of anchor term.
fn anchored_robot() -> Robot {
    let sq = fig6_square(true);
    let len = sq.body.length;
    let (law, x) = (Arc::new(ConstantTension), 3e-3);
    let helix = |phase| Routing::Helix {
        radius: x,
        rate: 40.0,
        phase,
    };
    let acts = vec![
        Actuator::new(Routing::Straight { x, y: 0.0 }, 0.0, 0.6 * len, law.clone()),
        Actuator::new(helix(0.2), 0.2 * len, len, law.clone()),
        Actuator::new(helix(2.0), 0.6 * len, len, law),
    ];
    Robot::new(sq.body.clone(), acts).unwrap()
}

/// An independent jump residual without the cached routing: every
/// string's routing evaluated at every call, every side from the strains.
fn reference<T: Real>(fz: &RodRhs<'_>, s: f64, w: &[T; 6], w0: &[T; 6], tau: &[T]) -> [T; 6] {
    let zero = T::cst(0.0);
    let (mut f, mut m) = ([zero; 3], [zero; 3]);
    fz.with_terms(
        s,
        false,
        |_| 0.0,
        |terms| {
            for t in terms.iter() {
                let (r, rp, _) = fz.robot.actuators[t.i].routing.eval(s);
                let u = Anchored {
                    r: r.into(),
                    rp: rp.into(),
                    ..*t
                };
                for (weight, st) in [(-t.b, w0), (t.a, w)] {
                    if weight != 0.0 {
                        let (p, rxp) = side(&u, weight, st, tau[t.i]);
                        for k in 0..3 {
                            f[k] += p[k];
                            m[k] += rxp[k];
                        }
                    }
                }
            }
        },
    );
    fz.jump_residual(w, w0, &f, &m)
}

/// A 6-vector of dual numbers seeded with the unit directions at `w`.
fn seeded(w: &[f64; 6]) -> [Dual<6>; 6] {
    std::array::from_fn(|k| {
        let mut e = [0.0; 6];
        e[k] = 1.0;
        Dual::new(w[k], e)
    })
}

fn strains(k: f64) -> [f64; 6] {
    [1e-3 * k, -2e-3, 1.0 + 0.01 * k, 3.0 * k, -2.0, 0.5 + k]
}

/// Tensions \[N\] of `anchored_robot`'s three strings in these tests.
const TENSIONS: [f64; 3] = [0.05, 0.02, 0.03];

/// `check(fz, s, terms, w, w0)` at `anchored_robot`'s anchor `s = 0.6 L`
/// under [`TENSIONS`] (all three strings at it), the before sides prepared
/// at `w0 = strains(0.3)`, for four post-jump strains `w`.
fn at_four_states(mut check: impl FnMut(&RodRhs<'_>, f64, &[Anchored], &[f64; 6], &[f64; 6])) {
    let robot = anchored_robot();
    let fz = RodRhs::new(&robot, &TENSIONS);
    let s = 0.6 * robot.body.length;
    let w0 = strains(0.3);
    for k in [0.0, 0.25, 1.0, -2.0] {
        let w = strains(0.3 + k);
        fz.with_terms(
            s,
            false,
            |i| TENSIONS[i],
            |terms| {
                assert_eq!(terms.len(), 3);
                RodRhs::prepare(terms, &w0);
                check(&fz, s, terms, &w, &w0)
            },
        );
    }
}

#[test]
fn the_cached_residual_and_jacobian_are_the_per_evaluation_ones_bit_for_bit() {
    let taud: Vec<Dual<6>> = TENSIONS.map(Dual::cst).to_vec();
    at_four_states(|fz, s, terms, w, w0| {
        // same operations in the same order: equal, not just close
        let cached = fz.after_residual(terms, w, w0);
        assert_eq!(cached, reference(fz, s, w, w0, &TENSIONS));
        let cached = fz.after_residual(terms, &seeded(w), w0);
        let old = reference(fz, s, &seeded(w), &w0.map(Dual::cst), &taud);
        assert_eq!(cached, old);
    });
}

#[test]
fn the_jump_solves_the_per_evaluation_residual_in_a_few_iterations() {
    let robot = anchored_robot();
    let fz = RodRhs::new(&robot, &TENSIONS);
    let s = 0.6 * robot.body.length;
    let w0 = strains(0.3);
    let (w, its) = fz
        .with_terms(s, false, |i| TENSIONS[i], |t| fz.jump(s, t, &w0))
        .unwrap();
    let r = reference(&fz, s, &w, &w0, &TENSIONS);
    // the loop's own test, on the independent residual
    assert!(amax(&r) < JUMP_TOL, "{r:?}");
    // a real jump (the kinks move the strains), by Newton's few steps
    assert!(amax(&std::array::from_fn(|k| w[k] - w0[k])) > 1e-3);
    assert!((1..=6).contains(&its), "{its}");
}

#[test]
fn a_jump_at_its_rounding_floor_stops_there() {
    let robot = anchored_robot();
    let fz = RodRhs::new(&robot, &TENSIONS);
    let s = 0.6 * robot.body.length;
    // curvatures of 3e4 1/m: one ulp of u L is ~4e-13, so the residual
    // cannot reach JUMP_TOL (1e-14) but reaches JUMP_FLOOR (1e-12)
    let w0 = [1e-3, -2e-3, 1.0, 3.0e4, -2.0e4, 5.0e3];
    let (w, its) = fz
        .with_terms(s, false, |i| TENSIONS[i], |t| fz.jump(s, t, &w0))
        .unwrap();
    let r = amax(&reference(&fz, s, &w, &w0, &TENSIONS));
    assert!(r >= JUMP_TOL, "not at a floor: {r:e}");
    assert!(r <= JUMP_FLOOR, "{r:e}");
    // stops at the first step that does not reduce it, not after the
    // iteration limit with every step backtracked in vain
    assert!(its <= 8, "{its}");
}

#[test]
fn the_jump_newton_matrix_is_the_dual_jacobian() {
    // `jump_matrix` assembles G_w = D (K + G) from the eq-25 blocks of each
    // string; the dual-number Jacobian of the residual is independent of
    // that derivation. Newton steps from both agree to rounding (1e-12 of
    // the step: K + G is well conditioned here, its condition ~1e2).
    at_four_states(|fz, _, terms, w, w0| {
        let r = fz.after_residual(terms, w, w0);
        let g = fz.after_residual(terms, &seeded(w), w0);
        let jac = nalgebra::Matrix6::from_fn(|i, j| g[i].eps[j]);
        let lu = jac
            .lu()
            .solve(&-nalgebra::Vector6::from_column_slice(&r))
            .unwrap();
        let step = fz.jump_matrix(terms, w).unwrap().newton_step(&r);
        let scale = amax(&step);
        assert!(scale > 1e-6, "a real step: {step:?}");
        for (a, b) in step.iter().zip(lu.iter()) {
            assert!((a - b).abs() <= 1e-12 * scale, "{step:?} vs {lu:?}");
        }
    });
}
