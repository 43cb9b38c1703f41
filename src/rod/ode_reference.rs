//! The plain twin of the eq-25 right-hand side, written in the paper's
//! notation (world-frame matrices `a, b, c, d, e, f` of eqs 26-31, nalgebra,
//! no unrolling, a general 6x6 LU solve), and tests that the fast path
//! [`RodRhs::deriv`] agrees with it to rounding on several designs.
//!
//! Uniform bodies: `K_nu' = K_omega' = 0`, `nu*' = omega*' = 0`.
//! Sign of the `nu^ K_nu (nu - nu*)` term of eq (31): the paper prints `+`;
//! the Cosserat moment balance `m' + p' x n + l = 0` (Antman; Rucker &
//! Webster 2011, which the paper follows) gives `-`, which the code uses and
//! the analytic tests confirm (`tests/integration/analytic.rs`, e.g. the
//! shear-bending coupling of the clamped-free beam).

use nalgebra::{Matrix3, Matrix6, Quaternion, Vector3, Vector6};

use super::RodRhs;
use crate::rod::rot;

/// `v^`, the cross-product matrix.
fn hat(v: &Vector3<f64>) -> Matrix3<f64> {
    v.cross_matrix()
}

/// The world-frame system (25), `[[a, b], [c, d]] [nu'; om'] = [e; f]` with
/// blocks (26)-(31), and the elongation rates (24), for the state `y` and
/// the actuators in `active` with tensions `tau` (`F_i` in the paper).
pub(super) fn eq25_reference(
    rhs: &RodRhs<'_>,
    s: f64,
    y: &[f64],
    tau: &[f64],
    active: &[usize],
) -> (Matrix6<f64>, Vector6<f64>, Vec<f64>) {
    let body = &rhs.robot.body;
    let (k_nu, k_om) = body.stiffness();
    let r = rot(&Quaternion::new(y[3], y[4], y[5], y[6]));
    let nu = Vector3::new(y[7], y[8], y[9]);
    let om = Vector3::new(y[10], y[11], y[12]);
    let mut a = r * k_nu; // (26), first term
    let mut b = Matrix3::zeros(); // (27)
    let mut c = Matrix3::zeros(); // (28)
    let mut d = r * k_om; // (29), first term
    let mut e = r * (-hat(&om) * k_nu * (nu - body.nu_star)) - body.distributed_load(); // (30), first terms
    let mut f = r
        * (-hat(&nu) * k_nu * (nu - body.nu_star) - hat(&om) * k_om * (om - body.omega_star))
        - body.distributed_moment; // (31), first terms (sign of the nu^ term: see the module docs)
    let mut delta_dot = vec![0.0; rhs.robot.actuators.len()];
    for &i in active {
        let act = &rhs.robot.actuators[i];
        let (ri, rdi, rddi) = act.routing.eval(s);
        let pa_dot = r * (nu + hat(&om) * ri + rdi); // (19)
        let n = pa_dot.norm();
        let k = -tau[i] * hat(&pa_dot) * hat(&pa_dot) / n.powi(3); // -F_i p_a'^2 / |p_a'|^3, from (20)
        let rri = hat(&(r * ri)); // (R r_i)^
        a += k * r; // (26)
        b += k * (-r * hat(&ri)); // (27)
        c += rri * k * r; // (28)
        d += rri * k * (-r * hat(&ri)); // (29)
        let g = r * (hat(&om) * (nu + hat(&om) * ri + 2.0 * rdi) + rddi);
        e -= k * g; // (30)
        f -= rri * k * g; // (31)
        let l_i = act
            .length_ratio
            .unwrap_or_else(|| (body.nu_star + body.omega_star.cross(&ri) + rdi).norm());
        delta_dot[i] = n - l_i; // (24)
    }
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&a);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&b);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&c);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&d);
    (m, Vector6::new(e.x, e.y, e.z, f.x, f.y, f.z), delta_dot)
}

/// `dy/ds` of eqs (22)-(25): (25) solved by LU.
pub(super) fn deriv_reference(
    rhs: &RodRhs<'_>,
    s: f64,
    y: &[f64],
    tau: &[f64],
    active: &[usize],
) -> Vec<f64> {
    let (m, b, delta_dot) = eq25_reference(rhs, s, y, tau, active);
    let x = m.lu().solve(&b).expect("(25) is regular"); // (25)
    let q = Quaternion::new(y[3], y[4], y[5], y[6]);
    let (nu, om) = (
        Vector3::new(y[7], y[8], y[9]),
        Vector3::new(y[10], y[11], y[12]),
    );
    let p_dot = rot(&q) * nu; // (22)
    let q_dot = q * Quaternion::new(0.0, om.x, om.y, om.z) * 0.5; // (23) R' = R om^ as q' = q (0, om) / 2
    let mut dy = p_dot.as_slice().to_vec();
    dy.extend_from_slice(&[q_dot.w, q_dot.i, q_dot.j, q_dot.k]);
    dy.extend_from_slice(x.as_slice());
    dy.extend_from_slice(&delta_dot); // (24)
    dy
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use nalgebra::UnitQuaternion;

    use super::*;
    use crate::experiments::{fig6_circle, fig6_square, steel_tendon_robot, table1_finger};
    use crate::rod::{Actuator, Body, ConstantTension, Robot, Routing, Section};

    /// A helix, a pre-curved body, a distributed moment and gravity: every
    /// term of eqs (26)-(31).
    fn helix_design() -> Robot {
        let mut body = Body::new(
            0.12,
            Section::Rectangle {
                width: 10e-3,
                height: 7e-3,
            },
            300e3,
            0.45,
            1100.0,
        )
        .unwrap();
        body.gravity = Vector3::new(2.0, -3.0, -9.0);
        body.distributed_moment = Vector3::new(1e-4, -2e-4, 5e-5);
        body.omega_star = Vector3::new(0.0, 2.0, 0.5);
        let acts = vec![
            Actuator::new(
                Routing::Helix {
                    radius: 3e-3,
                    rate: 30.0,
                    phase: 0.4,
                },
                0.0,
                0.12,
                Arc::new(ConstantTension),
            ),
            Actuator::new(
                Routing::Straight {
                    x: -2e-3,
                    y: 2.5e-3,
                },
                0.0,
                0.12,
                Arc::new(ConstantTension),
            ),
        ];
        Robot::new(body, acts).unwrap()
    }

    /// A deterministic pseudo-random number in [-1, 1): Knuth's MMIX
    /// linear congruential generator, its top 53 bits.
    fn rnd(k: &mut u64) -> f64 {
        *k = k
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*k >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }

    /// The five designs of these tests.
    fn designs() -> [Robot; 5] {
        [
            fig6_square(true),
            fig6_circle(true),
            table1_finger(),
            steel_tendon_robot(),
            helix_design(),
        ]
    }

    /// A random state of `robot` at which (25) is regular: a unit
    /// quaternion, strains near the reference, and tensions of either sign.
    fn random_state(robot: &Robot, seed: &mut u64) -> (Vec<f64>, Vec<f64>, f64) {
        let na = robot.actuators.len();
        let len = robot.body.length;
        let (kse, _) = robot.body.stiffness();
        let tmax = 1e-3 * kse[(0, 0)].min(50.0);
        let tau: Vec<f64> = (0..na).map(|_| tmax * rnd(seed)).collect();
        let mut y = vec![0.0; robot.n_states()];
        let axis = Vector3::new(rnd(seed), rnd(seed), rnd(seed));
        let q = UnitQuaternion::from_scaled_axis(axis * 2.0);
        y[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k]);
        let nu = Vector3::new(0.05 * rnd(seed), 0.05 * rnd(seed), 1.0 + 0.1 * rnd(seed));
        let om = Vector3::new(rnd(seed), rnd(seed), rnd(seed)) * (10.0 / len);
        y[7..10].copy_from_slice(nu.as_slice());
        y[10..13].copy_from_slice(om.as_slice());
        (y, tau, len * (0.5 + 0.5 * rnd(seed)))
    }

    /// `check(design, trial, rhs, y, s, active, seed)` on 20 random states
    /// of each design (every other actuator left out in one trial of four).
    fn for_each_state(
        mut seed: u64,
        mut check: impl FnMut(usize, usize, &RodRhs<'_>, &[f64], f64, &[usize], &mut u64),
    ) {
        for (n_design, robot) in designs().iter().enumerate() {
            let na = robot.actuators.len();
            for trial in 0..20 {
                let (y, tau, s) = random_state(robot, &mut seed);
                let rhs = RodRhs::new(robot, &tau);
                let active: Vec<usize> =
                    (0..na).filter(|&i| trial % 4 != 3 || i % 2 == 0).collect();
                check(n_design, trial, &rhs, &y, s, &active, &mut seed);
            }
        }
    }

    #[test]
    fn linearised_tangents_agree_with_dual_arithmetic_to_rounding() {
        use crate::rod::dual::Dual;
        for_each_state(11, |n_design, trial, rhs, y, s, active, seed| {
            // 8 random directions on every state and tension
            let mut dir = || -> [f64; 8] { std::array::from_fn(|_| rnd(seed)) };
            let yd: Vec<Dual<8>> = y.iter().map(|&x| Dual::new(x, dir())).collect();
            let td: Vec<Dual<8>> = rhs.tensions.iter().map(|&x| Dual::new(x, dir())).collect();
            let zero = Dual::new(0.0, [0.0; 8]);
            let (mut lin, mut dual) = (vec![zero; y.len()], vec![zero; y.len()]);
            rhs.deriv_tangent(s, &yd, &td, active, &mut lin).unwrap();
            rhs.deriv_generic(s, &yd, &td, active, &mut dual).unwrap();
            let mut plain = vec![0.0; y.len()];
            rhs.deriv(s, y, active, &mut plain).unwrap();
            for k in 0..y.len() {
                // the values are the f64 right-hand side's, bit for bit
                assert_eq!(lin[k].re, plain[k], "design {n_design} y'[{k}]");
                // the tangents: the same derivative by two formulas; (25)'s
                // solve amplifies their rounding by its condition (~1e6 for
                // the steel rod), so compare against the largest lane of the
                // row: 1e-8 is a few hundred eps times that condition
                let big = dual[k].eps.iter().fold(1e-300f64, |m, x| m.max(x.abs()));
                for d in 0..8 {
                    let err = (lin[k].eps[d] - dual[k].eps[d]).abs() / big;
                    assert!(
                        err <= 1e-8,
                        "design {n_design} trial {trial} y'[{k}] lane {d}: {} vs {} ({err:e})",
                        lin[k].eps[d],
                        dual[k].eps[d]
                    );
                }
            }
        });
    }

    #[test]
    fn fast_path_agrees_with_the_papers_notation_to_rounding() {
        for_each_state(7, |n_design, trial, rhs, y, s, active, _| {
            let tau = rhs.tensions;
            let mut fast = vec![0.0; y.len()];
            rhs.deriv_generic(s, y, tau, active, &mut fast).unwrap();
            let reference = deriv_reference(rhs, s, y, tau, active);
            // (22)-(24) involve no solve: a few roundings of O(1) terms
            for k in (0..7).chain(13..y.len()) {
                let scale = 1.0 + reference[k].abs();
                assert!(
                    (fast[k] - reference[k]).abs() <= 1e-14 * scale,
                    "design {n_design} trial {trial} y'[{k}]: {} vs {}",
                    fast[k],
                    reference[k]
                );
            }
            // (25): the strain rates, compared in the body-frame blocks by
            // the backward error of the fast solution in the reference
            // system (condition-independent: a steel rod's (25) has
            // cond ~ EA L^2 / EI ~ 1e6): |M x - b| <= 1e-13 (|M| |x| + |b|)
            let (m, b, _) = eq25_reference(rhs, s, y, tau, active);
            let x = Vector6::from_column_slice(&fast[7..13]);
            let scaled = |v: Vector6<f64>| {
                let r = rot(&Quaternion::new(y[3], y[4], y[5], y[6])).transpose();
                let (top, bot) = (r * v.fixed_rows::<3>(0), r * v.fixed_rows::<3>(3));
                Vector6::new(top.x, top.y, top.z, bot.x, bot.y, bot.z)
            };
            let res = scaled(m * x - b);
            let bound = 1e-13 * (m.abs() * x.abs() + b.abs());
            for k in 0..6 {
                assert!(
                    res[k].abs() <= bound.max(),
                    "design {n_design} trial {trial} (25) row {k}: residual {} > {}",
                    res[k],
                    bound.max()
                );
            }
            // and directly, where (25) is well conditioned enough
            let xr = Vector6::from_column_slice(&reference[7..13]);
            let rel = (x - xr).norm() / xr.norm().max(1e-300);
            assert!(
                rel <= 1e-6,
                "design {n_design} trial {trial}: rel diff {rel}"
            );
        });
    }
}
