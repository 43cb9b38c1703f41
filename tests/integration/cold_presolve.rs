//! The coarse first solve (`SolveOptions::presolve`) is only a guess: every
//! cold solve meets the tolerance on the full grid, checked by an
//! independent single-shooting IVP at the solution's unknowns. The work it
//! saves is the design benchmark's to report (`benches/designs.rs`).

use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, Shot, SolveOptions};

/// Cold solves of the first 100 benchmark designs all converge, each to
/// tol (or its rounding floor) on the full grid.
#[test]
fn cold_solves_meet_the_tolerance_on_the_full_grid() {
    let o = SolveOptions::default();
    let mut converged = 0;
    for i in 0..100 {
        let d = random_design(DEFAULT_SEED, i);
        let Ok(s) = solve(&d.robot, &d.inputs, &o, None) else {
            continue;
        };
        converged += 1;
        let (r, _, _) = Shot::new(&d.robot, &s.inputs, &s.loads, o.steps)
            .residual(&s.unknowns, false)
            .unwrap();
        let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // the full-grid residual Newton's test was passed on (the recomputed
        // IVP repeats it bit for bit; the 1 % keeps the check off float equality)
        assert!(norm <= 1.01 * o.tol.max(s.floor), "#{i}: residual {norm:e}");
    }
    assert_eq!(converged, 100);
}
