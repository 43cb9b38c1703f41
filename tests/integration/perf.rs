//! Checks of the fast paths: batch solves equal single solves, exact wrench
//! columns equal differenced ones, and the accuracy of coarse RK4 grids.
use nalgebra::Vector3;
use tcarod::batch::{solve_batch, BatchOptions};
use tcarod::experiments::{fig6_circle, fig6_square};
use tcarod::inverse::{sensitivities, sensitivities_fast, Groups, Scheme};
use tcarod::shooting::{solve, solve_loaded, Loads, SolveOptions};

fn temps(n: usize) -> Vec<f64> {
    // a sweep with a jump back: a warm-started chain that must restart far away
    (0..n)
        .flat_map(|k| {
            let t = if k == n / 2 {
                30.0
            } else {
                40.0 + 100.0 * k as f64 / n as f64
            };
            [t, t + 3.0]
        })
        .collect()
}

#[test]
fn batch_equals_individual_solves() {
    let robot = fig6_square(true);
    let n = 23;
    let inputs = temps(n);
    let opts = SolveOptions::default();
    for (threads, chunk) in [(1, 5), (2, 5), (2, 100)] {
        let b = solve_batch(
            &robot,
            &inputs,
            None,
            &BatchOptions {
                solve: opts,
                chunk_size: chunk,
                threads,
                warm: true,
                ..Default::default()
            },
        )
        .unwrap();
        for k in 0..n {
            let s = solve(&robot, &inputs[2 * k..2 * k + 2], &opts, None).unwrap();
            assert!(b.converged[k]);
            let p = s.tip_position();
            let d = (Vector3::from(b.tip_positions[k]) - p).norm();
            // both converged to the residual tolerance 1e-10 (strain): ~1e-12 m
            assert!(d < 1e-9, "row {k}: {d:e}");
            // rotation entries (order 1) to the same tolerance as the tip [m]
            let r = s.tip_rotation();
            for a in 0..3 {
                for c in 0..3 {
                    assert!((b.tip_rotations[k][3 * a + c] - r[(a, c)]).abs() < 1e-9);
                }
            }
            // tensions [N] (~0.07 N at most here) differ by ~1e-12 N between
            // the warm batch and the cold single solve: 1e-11 N bounds it
            for (i, t) in s.tensions.iter().enumerate() {
                let d = (b.tensions[2 * k + i] - t).abs();
                assert!(d < 1e-11, "row {k} actuator {i}: {d:e} N");
            }
        }
    }
}

#[test]
fn batch_is_independent_of_thread_count() {
    let robot = fig6_square(true);
    let inputs = temps(17);
    let run = |threads| {
        solve_batch(
            &robot,
            &inputs,
            None,
            &BatchOptions {
                chunk_size: 4,
                threads,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.tip_positions, b.tip_positions);
    assert_eq!(a.tensions, b.tensions);
    assert_eq!(a.iterations, b.iterations);
}

#[test]
fn batch_with_wrenches_equals_loaded_solves() {
    let robot = fig6_square(true);
    let inputs = vec![80.0, 80.0, 90.0, 90.0];
    let w = vec![
        1e-3, 0.0, 0.0, 0.0, 1e-5, 0.0, 0.0, 2e-3, -1e-3, 0.0, 0.0, 0.0,
    ];
    let b = solve_batch(&robot, &inputs, Some(&w), &BatchOptions::default()).unwrap();
    for k in 0..2 {
        let l = Loads {
            tip_force: Vector3::new(w[6 * k], w[6 * k + 1], w[6 * k + 2]),
            tip_moment: Vector3::new(w[6 * k + 3], w[6 * k + 4], w[6 * k + 5]),
        };
        let s = solve_loaded(
            &robot,
            &inputs[2 * k..2 * k + 2],
            &l,
            &SolveOptions::default(),
            None,
        )
        .unwrap();
        // both converged to the residual tolerance 1e-10 (strain): ~1e-12 m
        assert!((Vector3::from(b.tip_positions[k]) - s.tip_position()).norm() < 1e-9);
    }
}

#[test]
fn batch_rejects_invalid_rows_by_index() {
    let robot = fig6_square(true);
    let e = solve_batch(
        &robot,
        &[50.0, 50.0, 50.0, 500.0],
        None,
        &BatchOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("row 1"), "{e}");
}

#[test]
fn exact_wrench_columns_match_differenced_ones() {
    for (robot, inputs, groups) in [
        (fig6_square(true), vec![100.0, 100.0], Groups(vec![0, 0])),
        (fig6_circle(true), vec![120.0], Groups(vec![0])),
    ] {
        let mut loads = Loads::of(&robot);
        loads.tip_force = Vector3::new(1e-3, -5e-4, 2e-3);
        let sol = solve_loaded(
            &robot,
            &inputs,
            &loads,
            &SolveOptions {
                tol: 1e-12,
                ..Default::default()
            },
            None,
        )
        .unwrap();
        let slow =
            sensitivities(&robot, &sol, &loads, &groups, sol.steps, Scheme::Central).unwrap();
        let fast =
            sensitivities_fast(&robot, &sol, &loads, &groups, sol.steps, Scheme::Central).unwrap();
        let ec = (&fast.compliance - &slow.compliance).norm() / slow.compliance.norm();
        let ej = (&fast.jacobian - &slow.jacobian).norm() / slow.jacobian.norm();
        // C: exact wrench columns against central differences (~1e-8 relative
        // truncation, amplified by B_u^-1); J: the same differenced input
        // columns in both (12 IVPs fewer is the wrench columns alone), so
        // rounding only
        assert!(ec < 1e-6, "C {ec:e}");
        assert!(ej < 1e-12, "J {ej:e}");
        assert_eq!(fast.evaluations + 12, slow.evaluations);
    }
}

/// The step count of the "cold solve within 1 um of a 5,000-step reference"
/// bench row: measured, not assumed.
#[test]
fn ten_rk4_steps_are_within_one_micrometre_of_5000() {
    let robot = fig6_square(true);
    for t in [40.0, 80.0, 120.0, 160.0] {
        let reference = solve(
            &robot,
            &[t, t],
            &SolveOptions {
                steps: 5000,
                ..Default::default()
            },
            None,
        )
        .unwrap();
        let coarse = solve(
            &robot,
            &[t, t],
            &SolveOptions {
                steps: 10,
                ..Default::default()
            },
            None,
        )
        .unwrap();
        let err = (coarse.tip_position() - reference.tip_position()).norm();
        println!("T = {t} C: 10-step tip error {err:.3e} m");
        // 1 um: the accuracy the bench row states for 10 steps
        assert!(err < 1e-6, "T = {t}: {err:e}");
    }
}
