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
use tcarod::shooting::{initial_guess, solve, sweep, Loads, Shot, Solution, SolveOptions, Status};
use tcarod::solve::cancel::interruptible;
use tcarod::solve::presolve::rescale_tension_columns;
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
    // warm start after +1 % tension: a couple of iterations
    let t: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    let full_grid = SolveOptions {
        presolve: false,
        ..Default::default()
    };
    let w = solve(&robot, &t, &full_grid, Some(&d)).unwrap();
    // (chord iterations with the neighbour's Jacobian: one plain IVP each)
    assert!(
        w.iterations <= 5 && w.evaluations <= w.iterations + 2,
        "{} iterations, {} IVPs",
        w.iterations,
        w.evaluations
    );
    // with the coarse pre-solve (the default): chord iterations on the coarse
    // grid, one coarse IVP each, plus the warm defect's coarse IVP and a
    // first residual per coarse run (two full-grid IVPs among them)
    let pre = SolveOptions {
        presolve: true,
        ..Default::default()
    };
    let w = solve(&robot, &t, &pre, Some(&d)).unwrap();
    assert!(
        w.iterations <= 5 && w.evaluations <= 2 * w.iterations + 2,
        "{} iterations, {} IVPs",
        w.iterations,
        w.evaluations
    );
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
    let opts = SolveOptions {
        max_iter: 1,
        ..Default::default()
    };
    match solve(&robot, &[150.0, 150.0], &opts, None) {
        Err(Error::NotConverged {
            iterations,
            evaluations,
            residual,
            stop,
            ..
        }) => {
            assert_eq!(stop, StopReason::IterationLimit);
            assert!(iterations >= 1 && evaluations > iterations);
            assert!(residual.is_finite() && residual > 0.0);
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
    // a cold solve at 150 C needs more than 5 IVPs (it takes 8 at least)
    let opts = SolveOptions {
        max_evaluations: 5,
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
            // checked after every IVP of a line search and before every
            // iteration: at most one Newton step's IVPs past the budget
            assert!((5..=8).contains(&evaluations), "{evaluations} IVPs");
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
    // converged already: the check of the warm guess, at most one chord step
    assert!(w.iterations <= 1, "{} iterations", w.iterations);
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

/// A cold pre-solve takes its first defect from grids of two and three
/// times the coarse steps, extrapolated (`Shot::extrapolated`), in place
/// of a full-grid IVP: half its cost, and the second round's full-grid IVP
/// still converges. The extrapolation error at the solution is far below
/// the defect and the tolerance (the `n^-6` term: Fig. 6 ~1.5e-11 against
/// a defect of 1.4e-6 and tol 1e-10; steel at its rounding floor, ~9e-10).
/// (The solves' IVP counts are reported by `examples/solver_counts.rs`.)
#[test]
fn a_cold_presolve_extrapolates_its_first_defect_in_place_of_a_full_grid_ivp() {
    let o = SolveOptions::default();
    let sq = fig6_square(true);
    let steel = steel_tendon_robot();
    let cases: [(&tcarod::rod::Robot, &[f64]); 2] =
        [(&sq, &[100.0, 100.0]), (&steel, &STEEL_TENDON_TENSIONS)];
    for (robot, inputs) in cases {
        let s = solve(robot, inputs, &o, None).unwrap();
        assert!(full_grid_residual(robot, &s, o.steps) <= o.tol.max(s.floor));
        let coarse = Shot::new(robot, &s.inputs, &s.loads, o.steps / 10);
        let (r10, _, _) = coarse.residual(&s.unknowns, false).unwrap();
        let mut ivps = 0;
        let est = coarse
            .extrapolated(&s.unknowns, &r10, o.steps, &mut ivps)
            .unwrap();
        assert_eq!(ivps, 2);
        let (r100, _, _) = Shot::new(robot, &s.inputs, &s.loads, o.steps)
            .residual(&s.unknowns, false)
            .unwrap();
        let dist = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        };
        let (err, defect) = (dist(&est, &r100), dist(&r10, &r100));
        // as good as a full-grid IVP to within the attainable accuracy
        // (Fig. 6 ~1.5e-11 against tol 1e-10; steel ~4e-10, rounding, against
        // its floor 8.9e-10), and a hundredth of the defect at most (Fig. 6
        // ~1e-5 of it; steel's 1.4e-7 defect against its rounding: ~3e-3)
        assert!(err <= o.tol.max(s.floor), "error {err:e}");
        assert!(err <= 1e-2 * defect, "error {err:e}, defect {defect:e}");
    }
}

#[test]
fn a_rescaled_warm_jacobian_is_the_exact_one_at_the_new_inputs() {
    // the warm guess keeps the tensions, so the IVP at it is the warm one's
    // and the Jacobians differ only in the force laws' slopes: rescaling the
    // tension columns must give the exact Jacobian to rounding
    let sq = fig6_square(true);
    let o = SolveOptions::default();
    let loads = Loads::of(&sq);
    let w = solve(&sq, &[95.0, 95.0], &o, None).unwrap();
    let to = [100.0, 100.0];
    let x0 = initial_guess(&sq, &to, Some(&w));
    let jw = Shot::new(&sq, &w.inputs, &loads, o.steps)
        .jacobian(&w.unknowns, false)
        .unwrap()
        .1;
    let j0 = Shot::new(&sq, &to, &loads, o.steps)
        .jacobian(&x0, false)
        .unwrap()
        .1;
    let jr = rescale_tension_columns(&sq, &jw, (&w.unknowns, &w.inputs), (&x0, &to));
    let scale = j0.amax();
    // relative 1e-9: the tensions at x0 are the warm ones to the rounding of
    // the TCA law's inverse (~1e-12 relative), amplified by J's conditioning
    assert!(
        (&jr - &j0).amax() <= 1e-9 * scale,
        "{:e}",
        (&jr - &j0).amax()
    );
    // and the rescaling is not a no-op: the slopes differ by far more
    assert!(
        (&jw - &j0).amax() > 1e-4 * scale,
        "{:e}",
        (&jw - &j0).amax()
    );
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

#[test]
fn a_warm_presolve_sweep_refreshes_its_stale_coarse_jacobian() {
    // the pre-solve is the default
    assert!(SolveOptions::default().presolve);
    let opts = SolveOptions::default();
    let off = SolveOptions {
        presolve: false,
        ..opts
    };
    let sq = fig6_square(true);
    let steel = steel_tendon_robot();
    let temps: Vec<Vec<f64>> = (0..28).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect(); // 25..160 C
    let tensions: Vec<Vec<f64>> = (0..31)
        .map(|k| {
            let f = 1.0 + 0.01 * k as f64; // +0..30 % in steps of 1 %
            STEEL_TENDON_TENSIONS.iter().map(|t| t * f).collect()
        })
        .collect();
    // most IVPs (coarse ones included) of a warm step. The neighbour's
    // coarse Jacobian, handed on from step to step, goes stale: without a
    // refresh its chord steps creep at 5-15x a step (up to 22 IVPs a step on
    // the Fig. 6 sweep, 20 on the steel one). Refreshed when more than four
    // chord steps are still needed: at most 14 and 11 measured, bounds 16
    // and 14 (the paths are deterministic; the bounds leave a little room)
    for (name, robot, rows, most) in [
        ("Fig. 6", &sq, &temps, 16),
        ("steel", &steel, &tensions, 14),
    ] {
        let warm = sweep(robot, rows, &opts).unwrap();
        let full = sweep(robot, rows, &off).unwrap();
        for (k, (a, b)) in warm.iter().zip(&full).enumerate().skip(1) {
            assert!(
                a.evaluations <= most,
                "{name} step {k}: {} IVPs",
                a.evaluations
            );
            // the full-grid residual meets tol (or the floor) either way:
            // tips within 1e-9 m of the full-grid Newton's (both meet tol
            // 1e-10 in strain units)
            let r = full_grid_residual(robot, a, opts.steps);
            assert!(r <= opts.tol.max(a.floor), "{name} step {k}: {r:e}");
            let d = (a.tip_position() - b.tip_position()).norm();
            assert!(d < 1e-9, "{name} step {k}: tips {d:e} m apart");
        }
    }
}
