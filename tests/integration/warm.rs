//! Warm forward solves: the first-order predictor in the inputs
//! (`tcarod::solve::predict`) and the warm run that corrects the coarse
//! grid's defect at the prediction (`tcarod::solve::predict_warm`), and
//! batch rows (`tcarod::shooting::solve_tip`). Counts are IVPs
//! (`Solution.evaluations`, coarse ones included), never times.

use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::rod::Robot;
use tcarod::shooting::{initial_guess, solve, sweep, Solution, SolveOptions};
use tcarod::solve::predict::predicted_guess;

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Tip distance [m] between a warm and a cold solution of the same
/// problem. Both stop at `max |r| <= tol = 1e-10` (scaled residual, strain
/// units), so they differ by about `tol L` (Fig. 6: ~1e-11 m; the rounding
/// floor of the steel rod, ~1e-9, gives ~1e-10 m): the bound 1e-9 m is
/// the paper fixtures' bound (tests/paper.rs), which a predictor must not
/// move results by.
fn tip_gap(a: &Solution, b: &Solution) -> f64 {
    (a.tip_position() - b.tip_position()).norm()
}

/// The two warm cases of the benchmark: Fig. 6 square warm 5 C away, steel tendon
/// robot warm after +1 % tension. (robot, old inputs, new inputs)
fn cases() -> Vec<(Robot, Vec<f64>, Vec<f64>)> {
    let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|t| t * 1.01).collect();
    vec![
        (fig6_square(true), vec![95.0, 95.0], vec![100.0, 100.0]),
        (steel_tendon_robot(), STEEL_TENDON_TENSIONS.to_vec(), up),
    ]
}

#[test]
fn the_predictor_starts_much_nearer_than_the_tension_keeping_guess() {
    let o = SolveOptions::default();
    // measured |x - x*| (max norm, scaled unknowns): Fig. 6 3.1e-2 kept,
    // 4.9e-7 predicted; steel 7.1e-3 kept (a tension input cannot be
    // kept), 2.2e-4 predicted (the base strains moved by the tension
    // change; gravity's share of the shape change is left to Newton)
    for ((robot, p0, p1), ratio) in cases().into_iter().zip([1e-4, 0.1]) {
        let warm = solve(&robot, &p0, &o, None).unwrap();
        let exact = solve(&robot, &p1, &o, None).unwrap();
        let kept = initial_guess(&robot, &p1, Some(&warm));
        let pred = predicted_guess(&robot, &p1, &warm);
        let (dk, dp) = (
            max_abs_diff(&kept, &exact.unknowns),
            max_abs_diff(&pred, &exact.unknowns),
        );
        assert!(dp < ratio * dk, "predicted {dp:.2e}, kept {dk:.2e}");
    }
}

#[test]
fn warm_solves_take_fewer_ivps_and_equal_the_cold_ones() {
    let o = SolveOptions::default();
    // a neighbour 5 C away starts Newton near the root, where the cold
    // solve has its whole path from the straight guess to go (IVP counts:
    // examples/warm_counts.rs)
    for (robot, p0, p1) in cases() {
        let warm = solve(&robot, &p0, &o, None).unwrap();
        let cold = solve(&robot, &p1, &o, None).unwrap();
        let hot = solve(&robot, &p1, &o, Some(&warm)).unwrap();
        assert!(hot.residual <= o.tol.max(hot.floor), "{}", hot.residual);
        assert!(
            hot.evaluations < cold.evaluations,
            "{} IVPs warm, {} cold",
            hot.evaluations,
            cold.evaluations
        );
        assert!(hot.iterations >= 1, "a warm solve 5 C away needs a step");
        assert!(
            tip_gap(&hot, &cold) < 1e-9,
            "{:.2e} m",
            tip_gap(&hot, &cold)
        );
        assert_eq!(hot.inputs, p1);
        assert!(
            hot.newton_jacobian.is_some(),
            "the next warm start needs it"
        );
    }
}

#[test]
fn a_warm_fig6_sweep_matches_cold_solves_and_stays_cheap() {
    let robot = fig6_square(true);
    let o = SolveOptions::default();
    let inputs: Vec<Vec<f64>> = (0..=15).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let path = sweep(&robot, &inputs, &o).unwrap();
    let (mut warm_ivps, mut cold_ivps) = (0, 0);
    for (sol, p) in path.iter().zip(&inputs).skip(1) {
        let cold = solve(&robot, p, &o, None).unwrap();
        assert!(
            tip_gap(sol, &cold) < 1e-9,
            "{p:?}: {:.2e} m",
            tip_gap(sol, &cold)
        );
        warm_ivps += sol.evaluations;
        cold_ivps += cold.evaluations;
    }
    // each step starts from its neighbour 5 C away (IVP counts of the
    // chord policy: examples/warm_counts.rs --batch)
    assert!(
        warm_ivps < cold_ivps,
        "{warm_ivps} IVPs for 15 warm steps, {cold_ivps} cold"
    );
}

#[test]
fn a_checked_sweep_runs_its_rows_as_the_plain_sweep() {
    // `sweep_checked` (Python's `Robot.sweep`, verdict on each row) takes
    // the same chord policy as `sweep`: the same IVPs a row (the verdict's
    // pass replaces a plain IVP, counted once), the same tips (both to
    // tol), and each row's verdict is that of a single checked solve
    use tcarod::shooting::Loads;
    use tcarod::stability::{solve_checked, sweep_checked, Policy};
    let robot = fig6_square(true);
    let o = SolveOptions::default();
    let rows: Vec<Vec<f64>> = (0..=15).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let plain = sweep(&robot, &rows, &o).unwrap();
    let checked = sweep_checked(&robot, &rows, &o, Policy::Report).unwrap();
    let ivps = |e: &mut dyn Iterator<Item = usize>| e.skip(1).sum::<usize>();
    let (p, c) = (
        ivps(&mut plain.iter().map(|s| s.evaluations)),
        ivps(&mut checked.iter().map(|c| c.solution.evaluations)),
    );
    assert_eq!(p, c, "plain sweep {p} IVPs, checked {c}");
    let loads = Loads::of(&robot);
    for ((q, s), c) in rows.iter().zip(&plain).zip(&checked) {
        assert!(tip_gap(s, &c.solution) < 1e-9, "{q:?}");
        let single = solve_checked(&robot, q, &loads, &o, None, Policy::Report).unwrap();
        let (a, b) = (c.stability.as_ref().unwrap(), single.stability.unwrap());
        assert_eq!(a.stable, b.stable, "{q:?}");
        // the margins of two solutions ~1e-11 m apart: relative 1e-6 is
        // far above that and far below any change of verdict
        assert!(
            (a.margin - b.margin).abs() <= 1e-6 * b.margin.abs(),
            "{q:?}: {} against {}",
            a.margin,
            b.margin
        );
    }
}

#[test]
fn a_warm_start_in_the_opposite_direction_and_at_rest_works() {
    let robot = fig6_square(true);
    let o = SolveOptions::default();
    let hot = solve(&robot, &[100.0, 100.0], &o, None).unwrap();
    // cooling (the predictor's sign) and no change at all (the warm
    // solution itself, at its own residual: Newton takes no step)
    let down = solve(&robot, &[90.0, 90.0], &o, Some(&hot)).unwrap();
    let cold = solve(&robot, &[90.0, 90.0], &o, None).unwrap();
    assert!(tip_gap(&down, &cold) < 1e-9);
    assert!(
        down.evaluations < cold.evaluations,
        "{} IVPs 10 C down, {} cold",
        down.evaluations,
        cold.evaluations
    );
    let same = solve(&robot, &[100.0, 100.0], &o, Some(&hot)).unwrap();
    assert!(tip_gap(&same, &hot) < 1e-9);
    assert_eq!(same.iterations, 0, "a step at the warm point");
}

/// IVPs of a one-thread batch (no verdicts) along `rows`, per row, the
/// IVPs of cold single solves of the same rows, and the largest tip
/// distance [m, per coordinate] between the two.
fn batch_ivps_and_gap(robot: &Robot, rows: &[Vec<f64>]) -> (Vec<u32>, usize, f64) {
    use tcarod::batch::{solve_batch, BatchOptions};
    let opts = BatchOptions {
        threads: 1,
        stability: false,
        ..BatchOptions::default()
    };
    let o = SolveOptions::default();
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    let out = solve_batch(robot, &flat, None, &opts).unwrap();
    assert!(out.converged.iter().all(|c| *c));
    let (mut gap, mut cold_ivps) = (0.0f64, 0);
    for (q, tip) in rows.iter().zip(&out.tip_positions) {
        let cold = solve(robot, q, &o, None).unwrap();
        cold_ivps += cold.evaluations;
        let t = cold.tip_position();
        gap = (0..3).fold(gap, |m, k| m.max((tip[k] - t[k]).abs()));
    }
    (out.evaluations, cold_ivps, gap)
}

#[test]
fn batch_rows_start_from_the_prediction() {
    // Fig. 6 every 5 C from 25 to 160 C, the steel robot every 1 % from 15 N
    // to 22.5 N: each row starts from the prediction of its neighbours, so
    // the batch takes fewer IVPs than cold solves of its rows and ends on
    // their equilibria (IVP counts of the chord policies:
    // examples/warm_counts.rs --batch)
    let fig6: Vec<Vec<f64>> = (0..28).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let steel: Vec<Vec<f64>> = (0..=50)
        .map(|k| {
            let f = 1.0 + 0.01 * k as f64;
            STEEL_TENDON_TENSIONS.iter().map(|t| t * f).collect()
        })
        .collect();
    for (robot, rows) in [(fig6_square(true), fig6), (steel_tendon_robot(), steel)] {
        let (ivps, cold, gap) = batch_ivps_and_gap(&robot, &rows);
        let warm: u32 = ivps.iter().sum();
        assert!(
            (warm as usize) < cold,
            "{warm} IVPs for {} rows in a batch, {cold} cold",
            rows.len()
        );
        // the same bound as `tip_gap`'s, per coordinate
        assert!(gap < 1e-9, "{gap:.2e} m");
    }
}

#[test]
fn a_batch_sweep_refreshes_its_aging_jacobian() {
    // Fig. 6 every 1 C from 25 to 160 C: each row hands its Jacobian to the
    // next. Handed on unchanged while its chord steps kept converging, it
    // aged: rows took 4-5 IVPs after a refresh, then one more every 8-10
    // rows, up to 13 (7.82 a row). Refreshed once two chord steps have not
    // converged, no row takes more than 7 (2 full-grid IVPs, the coarse one
    // at the prediction, 2 chord steps, the coarse tangent, 1 chord step)
    let rows: Vec<Vec<f64>> = (0..=135).map(|k| vec![25.0 + k as f64; 2]).collect();
    let (ivps, _, gap) = batch_ivps_and_gap(&fig6_square(true), &rows);
    let most = ivps.iter().skip(1).max().unwrap();
    assert!(*most <= 7, "a row took {most} IVPs: {ivps:?}");
    assert!(gap < 1e-9, "{gap:.2e} m");
}

#[test]
fn a_cold_batch_row_is_a_single_cold_solve() {
    use tcarod::batch::{solve_batch, BatchOptions};
    use tcarod::problems::{random_design, DEFAULT_SEED};
    let opts = BatchOptions {
        threads: 1,
        stability: false,
        ..BatchOptions::default()
    };
    // designs 385 and 25 of the tuning seed's random family: 385's direct
    // run is cut at `shooting::DIRECT_MIN_STEP` and continuation (the
    // coarse homotopy path) takes over; 25 is past buckling, its cut run
    // and its continuation fail (the coarse path stalls at a fold, and the
    // full grid from there) and the repeat with the options' full damping
    // converges. A cold batch row takes the single solve's route, so the
    // same IVPs and tip
    for i in [385, 25] {
        let d = random_design(DEFAULT_SEED, i);
        let single = solve(&d.robot, &d.inputs, &SolveOptions::default(), None).unwrap();
        let row = solve_batch(&d.robot, &d.inputs, None, &opts).unwrap();
        assert_eq!(row.evaluations[0] as usize, single.evaluations, "#{i}");
        let t = single.tip_position();
        let gap = (0..3).fold(0.0f64, |m, k| m.max((row.tip_positions[0][k] - t[k]).abs()));
        // the same IVPs on the same path: equal but for the assembly's
        // rounding (measured 0)
        assert!(gap < 1e-12, "#{i}: {gap:.2e} m");
    }
}
