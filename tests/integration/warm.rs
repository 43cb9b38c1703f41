//! Warm forward solves: from a neighbouring solution, single solves,
//! sweeps and batch rows converge to the cold solves' equilibria with less
//! work. Counts are IVPs (`Solution.evaluations`, coarse ones in units of
//! full-grid IVPs), never times.
use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::rod::Robot;
use tcarod::shooting::{solve, sweep, Solution, SolveOptions};

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
fn warm_solves_equal_the_cold_ones() {
    let o = SolveOptions::default();
    // from a neighbour 5 C away, the cold solve's equilibrium
    for (robot, p0, p1) in cases() {
        let warm = solve(&robot, &p0, &o, None).unwrap();
        let cold = solve(&robot, &p1, &o, None).unwrap();
        let hot = solve(&robot, &p1, &o, Some(&warm)).unwrap();
        assert!(hot.residual <= o.tol.max(hot.floor), "{}", hot.residual);
        assert!(hot.iterations >= 1, "a warm solve 5 C away needs a step");
        assert!(
            tip_gap(&hot, &cold) < 1e-9,
            "{:.2e} m",
            tip_gap(&hot, &cold)
        );
        assert_eq!(hot.inputs, p1);
    }
}

#[test]
fn a_warm_fig6_sweep_matches_cold_solves() {
    let robot = fig6_square(true);
    let o = SolveOptions::default();
    let inputs: Vec<Vec<f64>> = (0..=15).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let path = sweep(&robot, &inputs, &o).unwrap();
    for (sol, p) in path.iter().zip(&inputs).skip(1) {
        let cold = solve(&robot, p, &o, None).unwrap();
        assert!(
            tip_gap(sol, &cold) < 1e-9,
            "{p:?}: {:.2e} m",
            tip_gap(sol, &cold)
        );
    }
}

#[test]
fn a_checked_sweep_runs_its_rows_as_the_plain_sweep() {
    // `sweep_checked` (Python's `Robot.sweep`, verdict on each row) solves
    // its rows as `sweep` does: the same IVPs a row plus the verdict's
    // tangent pass, the same tips (both to tol), and each row's verdict is
    // that of a single checked solve
    use tcarod::shooting::Loads;
    use tcarod::stability::{solve_checked, sweep_checked, Policy};
    let robot = fig6_square(true);
    let o = SolveOptions::default();
    let rows: Vec<Vec<f64>> = (0..=15).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let plain = sweep(&robot, &rows, &o).unwrap();
    let checked = sweep_checked(&robot, &rows, &o, Policy::Report).unwrap();
    for (s, c) in plain.iter().zip(&checked) {
        let verdict = c.stability.as_ref().unwrap().evaluations;
        assert_eq!(c.solution.evaluations, s.evaluations + verdict);
    }
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
    // cooling and no change at all (the warm
    // solution itself, at its own residual: Newton takes no step)
    let down = solve(&robot, &[90.0, 90.0], &o, Some(&hot)).unwrap();
    let cold = solve(&robot, &[90.0, 90.0], &o, None).unwrap();
    assert!(tip_gap(&down, &cold) < 1e-9);
    let same = solve(&robot, &[100.0, 100.0], &o, Some(&hot)).unwrap();
    assert!(tip_gap(&same, &hot) < 1e-9);
}

/// The largest tip distance [m, per coordinate] between the rows of a
/// one-thread batch (no verdicts) along `rows` and cold single solves of
/// the same rows.
fn batch_gap(robot: &Robot, rows: &[Vec<f64>]) -> f64 {
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
    let mut gap = 0.0f64;
    for (q, tip) in rows.iter().zip(&out.tip_positions) {
        let cold = solve(robot, q, &o, None).unwrap();
        let t = cold.tip_position();
        gap = (0..3).fold(gap, |m, k| m.max((tip[k] - t[k]).abs()));
    }
    gap
}

#[test]
fn batch_rows_start_from_their_neighbours() {
    // Fig. 6 every 5 C from 25 to 160 C, the steel robot every 1 % from 15 N
    // to 22.5 N: each row starts from its neighbour's solution and ends on
    // the cold solve's equilibrium
    let fig6: Vec<Vec<f64>> = (0..28).map(|k| vec![25.0 + 5.0 * k as f64; 2]).collect();
    let steel: Vec<Vec<f64>> = (0..=50)
        .map(|k| {
            let f = 1.0 + 0.01 * k as f64;
            STEEL_TENDON_TENSIONS.iter().map(|t| t * f).collect()
        })
        .collect();
    for (robot, rows) in [(fig6_square(true), fig6), (steel_tendon_robot(), steel)] {
        let gap = batch_gap(&robot, &rows);
        // the same bound as `tip_gap`'s, per coordinate
        assert!(gap < 1e-9, "{gap:.2e} m");
    }
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
    // designs 385 and 25 of the tuning seed's random family (25 past
    // self-weight buckling), both solved through continuation: a cold
    // batch row takes the single solve's route, so the same IVPs and tip
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
