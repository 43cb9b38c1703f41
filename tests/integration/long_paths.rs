//! A benchmark design with a long smooth homotopy path whose coarse root
//! is out of the full-grid finish's reach: the finish hops to
//! `steps / 4` (`solve::coarse_path::HOP_GRID_DIVISOR`) and then runs
//! full-grid Newton with that grid's Jacobians (`solve::hop_finish`).
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Design 126 of the tuning seed's random family (an 84.4 mm, 11.5 mm, 16.6 kPa rod, two TCAs,
/// two constant-tension tendons, one helical; gravity and a tip force):
/// the direct run fails, the coarse path reaches `lambda = 1` in 19
/// steps, and the finish from its root fails (full-grid residual ~1.9
/// there), so the finish hops. Its tip as the benchmark records it
/// (`TCAROD_TIPS=1 benches/designs.rs`) \[m\].
const LONG_PATH_DESIGN: usize = 126;
const MAIN_TIP_M: [f64; 3] = [
    6.904_982_016_919_77e-2,
    2.850_578_959_649_629e-2,
    1.653_887_210_611_713e-2,
];

/// Tip agreement with the recorded tip \[m\]: both converge to `tol` (1e-10 scaled)
/// on the same grid, so the tips differ by Newton's last steps only
/// (measured 1e-12-scale); 1e-9 m is the project's results-unchanged rule.
const TIP_TOL_M: f64 = 1e-9;

#[test]
fn a_hop_finish_takes_the_hop_grids_jacobians() {
    let opts = SolveOptions::default();
    let d = random_design(DEFAULT_SEED, LONG_PATH_DESIGN);
    let sol =
        solve(&d.robot, &d.inputs, &opts, None).unwrap_or_else(|e| panic!("{}: {e}", d.summary()));
    assert!(sol.residual <= opts.tol.max(sol.floor), "{}", d.summary());
    // through the coarse path (its steps recorded), not the direct run
    assert!(!sol.continuation_steps.is_empty(), "{}", d.summary());
    let p = sol.tip_position();
    for (k, (a, b)) in [p.x, p.y, p.z].iter().zip(MAIN_TIP_M).enumerate() {
        assert!((a - b).abs() <= TIP_TOL_M, "tip[{k}] {a:e} against {b:e}");
    }
}
