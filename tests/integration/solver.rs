//! The shooting solver's contract (paper eqs 34-36; docs/choices.md, "The
//! solver"): few iterations on the tendon benchmarks of `tcarod::experiments`
//! (the soft tendon rod, the steel tendon robot), convergence to the rounding
//! floor, continuation with its path, cancellation and budgets, complete work
//! counts, the coarse-grid pre-solve, and the seeded benchmark designs that
//! exercise kinks of the force laws.
use crate::common;

use common::solve_default;
use nalgebra::Vector3;
use tcarod::experiments::{
    fig6_circle, fig6_square, soft_tendon_robot, soft_tendon_tension, steel_tendon_robot,
    STEEL_TENDON_TENSIONS,
};
use tcarod::inverse::rotation_vector;
use tcarod::shooting::{solve, sweep, Shot, Solution, SolveOptions, Status};
use tcarod::solve::cancel::interruptible;
use tcarod::{Error, StopReason};

#[test]
fn soft_tendon_bends_to_its_angle_in_a_few_iterations() {
    let robot = soft_tendon_robot();
    let opts = SolveOptions {
        steps: 50,
        ..Default::default()
    };
    for deg in [10.0f64, 30.0, 45.0, 60.0, 90.0, 120.0] {
        let th = deg.to_radians();
        let s = solve(&robot, &[soft_tendon_tension(th)], &opts, None).unwrap();
        // a straight constant-tension tendon to the tip: constant body
        // moment tau r, so omega = tau r / (E I) all along and the tip
        // rotates by exactly omega L = theta (shear and stretch change the
        // shape, not the curvature). RK4's phase error on q' = q (0, u) / 2
        // is ~(h theta / 2L)^5 / 120 per step: 50 steps at 120 deg, 3.4e-9 rad
        let angle = rotation_vector(&s.tip_rotation());
        assert!(
            (angle - Vector3::new(0.0, th, 0.0)).norm() < 1e-8,
            "{deg} deg: {angle:?}"
        );
        // the exact Jacobian (`Shot::jacobian`, a tangent IVP) makes Newton
        // quadratic from the straight guess: a few iterations, about two IVPs
        // each
        assert!(s.iterations <= 3, "{deg} deg: {} iterations", s.iterations);
        assert!(
            s.evaluations <= 2 * s.iterations + 2,
            "{deg} deg: {} IVPs",
            s.evaluations
        );
        assert!(s.continuation_steps.is_empty());
    }
}

#[test]
fn steel_tendon_converges_to_the_rounding_floor() {
    let robot = steel_tendon_robot();
    // tol far below the rounding floor (~EA eps L^2 / EI ~ 1e-10): converges
    // to the floor and says so, instead of failing
    let opts = SolveOptions {
        tol: 1e-14,
        ..Default::default()
    };
    let s = solve(&robot, &STEEL_TENDON_TENSIONS, &opts, None).unwrap();
    assert_eq!(s.status, Status::ConvergedAtFloor);
    assert!(
        s.floor > 1e-14 && s.residual <= 100.0 * s.floor,
        "residual {:e}, floor {:e}",
        s.residual,
        s.floor
    );
    // the same solution as at the default tolerance, to far below a micrometre
    // (1e-9 m: both meet the floor or 1e-10 in strain on a 0.5 m rod)
    let d = solve(
        &robot,
        &STEEL_TENDON_TENSIONS,
        &SolveOptions::default(),
        None,
    )
    .unwrap();
    assert!((s.tip_position() - d.tip_position()).norm() < 1e-9);
    // warm after +1 % tension, with and without the coarse pre-solve: the
    // cold solve's equilibrium (both meet the floor: tips within 1e-9 m)
    let t: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    let cold = solve(&robot, &t, &SolveOptions::default(), None).unwrap();
    for presolve in [false, true] {
        let o = SolveOptions {
            presolve,
            ..Default::default()
        };
        let w = solve(&robot, &t, &o, Some(&d)).unwrap();
        assert!(w.residual <= o.tol.max(w.floor));
        assert!((w.tip_position() - cold.tip_position()).norm() < 1e-9);
    }
}

#[test]
fn continuation_records_its_path_and_counts_all_work() {
    let robot = fig6_square(true);
    // two iterations are too few from the cold guess at 140 C: the direct
    // solve fails and continuation in inputs and loads takes over (at 150 C
    // two suffice: the cold pre-solve's first coarse run stops at 1e-5)
    let opts = SolveOptions {
        max_iter: 2,
        ..Default::default()
    };
    let s = solve(&robot, &[140.0, 140.0], &opts, None).unwrap();
    assert!(!s.continuation_steps.is_empty());
    assert_eq!(*s.continuation_steps.last().unwrap(), 1.0);
    assert!(s.continuation_steps.windows(2).all(|w| w[0] < w[1]));
    // the failed direct attempt's iterations and IVPs are counted too
    assert!(s.iterations > 2 && s.evaluations > s.iterations);
    let reference = solve(&robot, &[140.0, 140.0], &SolveOptions::default(), None).unwrap();
    // the same root: both meet tol 1e-10 in strain, tips ~1e-12 m apart
    assert!((s.tip_position() - reference.tip_position()).norm() < 1e-9);
}

#[test]
fn failures_report_best_residual_work_and_reason() {
    let robot = fig6_square(true);
    // Newton on the full grid from the cold guess at 150 C takes more than
    // four IVPs: stopped by the budget after its second iteration
    let opts = SolveOptions {
        max_evaluations: 4,
        presolve: false,
        ..Default::default()
    };
    match solve(&robot, &[150.0, 150.0], &opts, None) {
        Err(Error::NotConverged {
            iterations,
            evaluations,
            residual,
            stop,
            reason,
            ..
        }) => {
            assert_eq!(stop, StopReason::Budget);
            assert!(iterations >= 1 && evaluations >= 4);
            // the best residual evaluated, below the cold guess's (order one)
            assert!(residual.is_finite() && residual > 0.0 && residual < 1.0);
            assert!(!reason.is_empty());
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

#[test]
fn a_cancel_check_interrupts_a_sweep() {
    let robot = fig6_square(true);
    let rows: Vec<Vec<f64>> = (0..100_000)
        .map(|k| vec![40.0 + 1e-3 * k as f64; 2])
        .collect();
    let start = std::time::Instant::now();
    let stop_after = std::time::Duration::from_millis(100);
    let check = || start.elapsed() > stop_after;
    let r = interruptible(&check, || sweep(&robot, &rows, &SolveOptions::default()));
    assert!(
        matches!(r, Err(Error::Interrupted)),
        "{:?}",
        r.map(|v| v.len())
    );
    // polled every 20 ms of work at most (plus one solve): far below the sweep's minutes
    assert!(start.elapsed() < std::time::Duration::from_secs(5));
}

#[test]
fn a_budget_bounds_every_solve() {
    let robot = fig6_square(true);
    // a cold solve at 150 C on the full grid needs more than 5 IVPs
    let opts = SolveOptions {
        max_evaluations: 5,
        presolve: false,
        ..Default::default()
    };
    match solve(&robot, &[150.0, 150.0], &opts, None) {
        Err(Error::NotConverged {
            stop,
            evaluations,
            residual,
            ..
        }) => {
            assert_eq!(stop, StopReason::Budget);
            // checked before every evaluation: at most one linearisation
            // (a tangent IVP of 8 directions, counted as 2 IVPs) past it
            assert!((5..=7).contains(&evaluations), "{evaluations} IVPs");
            assert!(residual.is_finite() && residual > 0.0);
        }
        other => panic!("expected a budget error, got {other:?}"),
    }
    let opts = SolveOptions {
        time_limit: Some(std::time::Duration::from_nanos(1)),
        ..Default::default()
    };
    assert!(matches!(
        solve(&robot, &[150.0, 150.0], &opts, None),
        Err(Error::NotConverged {
            stop: StopReason::Budget,
            ..
        })
    ));
    // zero budgets are rejected as input errors
    for bad in [
        SolveOptions {
            max_evaluations: 0,
            ..Default::default()
        },
        SolveOptions {
            time_limit: Some(std::time::Duration::ZERO),
            ..Default::default()
        },
    ] {
        assert!(matches!(
            solve(&robot, &[100.0, 100.0], &bad, None),
            Err(Error::InvalidParameter { .. })
        ));
    }
}

/// Two seeded benchmark designs (`tcarod::problems::random_design`) start a
/// cold solve with a linear tendon exactly at its onset of tension (zero
/// tension), where the residual has a kink: with the one-sided derivative of
/// the wrong side the Newton direction does not descend (the merit grows like
/// t^2 from t = 0) and the solve fails, continuation included. The generalised
/// derivative (taut side, then slack side after a failed line search)
/// converges.
#[test]
fn a_linear_tendon_at_its_onset_of_tension_converges_cold() {
    use tcarod::problems::{equilibrium, random_design, DEFAULT_SEED};
    for i in [532, 719] {
        let d = random_design(DEFAULT_SEED, i);
        let s = solve(&d.robot, &d.inputs, &SolveOptions::default(), None)
            .unwrap_or_else(|e| panic!("#{i}: {e}"));
        assert!(s.residual <= 1e-10, "#{i}: {}", s.residual);
        // the equilibrium check of the benchmark (1e-8 relative at 100 steps
        // for these two mildly bent designs; measured 1e-9..1e-10)
        let eq = equilibrium(&d.robot, &s);
        assert!(eq.relative < 1e-8, "#{i}: {eq:?}");
    }
}

/// A warm start from a converged solution at the same inputs is that
/// solution. The seeded design drawn here has a TCA pressed 0.49 um into coil
/// contact; the warm guess re-derives each TCA's elongation from its tension
/// through the law's inverse, which must follow the C1-smoothed contact onset
/// (`TcaAt::tension`, 0.1 um wide): a linear contact branch would miss it by
/// half its width (0.05 um, a tension error of ~400 k_s x 0.05 um, with k_s
/// the coil spring's stiffness) and the warm solve would fail outright.
#[test]
fn a_warm_start_from_a_solution_in_coil_contact_stays_there() {
    use tcarod::problems::{random_design, DEFAULT_SEED};
    let d = random_design(DEFAULT_SEED, 817);
    let o = SolveOptions::default();
    let s = solve(&d.robot, &d.inputs, &o, None).unwrap();
    assert!(s.tensions.iter().any(|&t| t < 0.0), "a TCA in coil contact");
    let w = solve(&d.robot, &d.inputs, &o, Some(&s)).unwrap();
    assert!(w.tensions.iter().any(|&t| t < 0.0), "still in coil contact");
    // the same root: the tips agree to the Newton tolerance (1e-10 of the length)
    assert!((w.tip_position() - s.tip_position()).norm() < 1e-10 * d.robot.body.length);
}

/// Max-norm of the full-grid residual at a solution's unknowns, from an
/// independent IVP.
fn full_grid_residual(robot: &tcarod::rod::Robot, s: &Solution, steps: usize) -> f64 {
    let (r, _, _) = Shot::new(robot, &s.inputs, &s.loads, steps)
        .residual(&s.unknowns, false)
        .unwrap();
    r.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

#[test]
fn the_coarse_presolve_converges_on_the_full_grid_to_the_same_tips() {
    let o = SolveOptions {
        presolve: true,
        ..Default::default()
    };
    let off = SolveOptions {
        presolve: false,
        ..o
    };
    let sq = fig6_square(true);
    let steel = steel_tendon_robot();
    let s95 = solve(&sq, &[95.0, 95.0], &o, None).unwrap();
    let s0 = solve(&steel, &STEEL_TENDON_TENSIONS, &o, None).unwrap();
    let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    let cases: [(&tcarod::rod::Robot, &[f64], Option<&Solution>); 4] = [
        (&sq, &[100.0, 100.0], None),
        (&sq, &[100.0, 100.0], Some(&s95)),
        (&steel, &STEEL_TENDON_TENSIONS, None),
        (&steel, &up, Some(&s0)),
    ];
    for (k, (robot, inputs, warm)) in cases.into_iter().enumerate() {
        let a = solve(robot, inputs, &o, warm).unwrap();
        let b = solve(robot, inputs, &off, warm).unwrap();
        // a coarse solution is only a guess: the solution meets the
        // tolerance (or the floor) on the full grid, re-integrated here
        let r = full_grid_residual(robot, &a, o.steps);
        assert!(
            r <= o.tol.max(a.floor),
            "case {k}: full-grid residual {r:e}"
        );
        assert!(a.residual <= o.tol.max(a.floor));
        // the pre-solve moves the fixtures' tips by < 1e-9 m (both meet tol
        // 1e-10 in strain units: tips agree to ~1e-12 m)
        let d = (a.tip_position() - b.tip_position()).norm();
        assert!(d < 1e-9, "case {k}: tips {d:e} m apart");
        // every IVP counted: at least the two full-grid ones of a
        // defect-corrected round and the coarse ones before them
        assert!(a.evaluations >= 3, "case {k}: {} IVPs", a.evaluations);
    }
}

#[test]
fn fig6_sweeps_converge_cold_and_warm() {
    let temps: Vec<f64> = (0..28).map(|k| 25.0 + 5.0 * k as f64).collect(); // 25..160 C
    let opts = SolveOptions::default();
    for gravity in [true, false] {
        for robot in [fig6_circle(gravity), fig6_square(gravity)] {
            let n = robot.actuators.len();
            let rows: Vec<Vec<f64>> = temps.iter().map(|&t| vec![t; n]).collect();
            let warm = sweep(&robot, &rows, &opts).unwrap();
            // every temperature from the reference guess
            let cold: Vec<_> = rows.iter().map(|r| solve_default(&robot, r)).collect();
            for (w, c) in warm.iter().zip(&cold) {
                assert!(w.residual <= 1e-10 && c.residual <= 1e-10);
                // incl. the fallback continuation of a cold solve
                assert!(w.iterations <= 50 && c.iterations <= 50 * 11);
                // the same solution from both starts (tolerance 1e-10 in strain -> ~1e-11 m)
                assert!(common::max_diff(&w.positions, &c.positions) <= 1e-9);
            }
            // the warm start pays off over the sweep in IVPs (its chord iterations are
            // one plain IVP each; a cold iteration needs a tangent IVP)
            let ivps = |s: &[Solution]| s.iter().map(|x| x.evaluations).sum::<usize>();
            // (counted on full-grid Newton: the coarse pre-solve's IVPs cost a
            // tenth each, so its counts do not measure this)
            let off = SolveOptions {
                presolve: false,
                ..opts
            };
            let warm = sweep(&robot, &rows, &off).unwrap();
            let cold: Vec<_> = rows
                .iter()
                .map(|r| solve(&robot, r, &off, None).unwrap())
                .collect();
            assert!(ivps(&warm) < ivps(&cold), "gravity {gravity}");
        }
    }
}
