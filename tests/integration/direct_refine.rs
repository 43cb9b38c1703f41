//! A cold direct Newton run far from any root hands over to continuation
//! without full-grid Jacobians (`shooting::DIRECT_REFINE_WITHIN`): its
//! line search failed with the coarse grid's Jacobian because the residual
//! is nonlinear there, which the full grid's tangents (several IVP times
//! each) do not cure; and a direct run whose first coarse Newton run fails
//! from the cold guess hands over without retracing it on the full grid
//! (`shooting::handed_over`).
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Tip agreement with main 4994354 \[m\]: both converge to `tol` (1e-10
/// scaled) on the same grid by the same continuation, so the tips differ
/// by Newton's last steps only (measured: bit for bit the same); 1e-9 m is
/// the project's results-unchanged rule.
const TIP_TOL_M: f64 = 1e-9;

/// Design index, IVP bound and its tip on main 4994354
/// (`TCAROD_TIPS=1 benches/designs.rs`) \[m\]. #560 (direct run on main:
/// 22 full-grid IVPs and 9 full-grid Jacobians while `max |r|` stayed at
/// 2.5-15, then continuation): 100 IVPs measured, 127 on main; the bound
/// 110 leaves 10 and fails if the direct run's 27 come back. #159 (its
/// direct run's 3 full-grid Jacobians at `max |r|` 12-84): 86 measured,
/// 100 on main; bound 92 (the 14 saved, less 8).
const CASES: [(usize, usize, [f64; 3]); 2] = [
    (
        560,
        110,
        [
            -1.631_666_118_213_358e-3,
            8.148_029_572_981_334e-4,
            1.030_698_416_018_627e-2,
        ],
    ),
    (
        159,
        92,
        [
            2.239_673_371_211_584e-2,
            2.842_524_183_652_943e-4,
            3.280_916_852_114_718e-2,
        ],
    ),
];

#[test]
fn a_direct_run_far_from_a_root_hands_over_without_full_grid_jacobians() {
    for (i, max_ivps, tip) in CASES {
        check(i, max_ivps, tip, true);
    }
}

/// Solve benchmark design `i` cold with the default options and check
/// that it converges to tol (or its floor), through continuation or not
/// (`via_continuation`: its path recorded or empty), to the tip `tip`
/// \[m\] within [`TIP_TOL_M`], in at most `max_ivps` IVPs.
fn check(i: usize, max_ivps: usize, tip: [f64; 3], via_continuation: bool) {
    let opts = SolveOptions::default();
    let d = random_design(DEFAULT_SEED, i);
    let sol = solve(&d.robot, &d.inputs, &opts, None)
        .unwrap_or_else(|e| panic!("#{i} {}: {e}", d.summary()));
    assert!(sol.residual <= opts.tol.max(sol.floor), "#{i}");
    assert_eq!(
        !sol.continuation_steps.is_empty(),
        via_continuation,
        "#{i}: path {:?}",
        sol.continuation_steps
    );
    let p = sol.tip_position();
    for (k, (a, b)) in [p.x, p.y, p.z].iter().zip(tip).enumerate() {
        assert!(
            (a - b).abs() <= TIP_TOL_M,
            "#{i} tip[{k}] {a:e} against {b:e}"
        );
    }
    assert!(
        sol.evaluations <= max_ivps,
        "#{i}: {} IVPs (bound {max_ivps})",
        sol.evaluations
    );
}

/// Benchmark design #319 (not past buckling): its direct run's first
/// coarse Newton run, from the cold guess, stalls (`max |r|` 3.8 after
/// three damped steps), and the coarse grid resolves the design there
/// (full-grid residual at the guess within 1.1 % of the coarse one).
/// Main c233d58 then ran full-grid Newton from the guess, which retraced
/// the coarse iterates with the coarse, the full and the slack-side
/// Jacobians and failed alike (29 IVPs, 53 % of its solve time), before
/// continuation; now the run hands over at once (`shooting::handed_over`).
/// 130 IVPs measured, 159 on main; the bound 140 fails if the retrace
/// comes back. Its tip on main c233d58 (`TCAROD_TIPS=1
/// benches/designs.rs`) \[m\]: the same continuation, so bit for bit the
/// same (measured).
const HANDED_OVER: (usize, usize, [f64; 3]) = (
    319,
    140,
    [
        -4.406_670_617_270_772e-3,
        1.022_343_581_405_42e-2,
        1.027_377_662_433_26e-2,
    ],
);

#[test]
fn a_failed_cold_coarse_run_hands_over_without_a_full_grid_retrace() {
    let (i, max_ivps, tip) = HANDED_OVER;
    check(i, max_ivps, tip, true);
}

/// Benchmark design #411: its cold guess has a tendon exactly at its onset
/// of tension. The taut side's Newton step fails its line search, and so
/// did the watchdog's step from its trial point; the watchdog's Jacobian
/// there (no onset) hid the guess's onset from `System::refine`, so the
/// coarse run gave up without trying the slack side's derivative, which
/// converges. Main c233d58 found it only on the full grid, after retracing
/// the failure twice (30 IVPs); with the hand-over
/// (`shooting::handed_over`) it would go to continuation. The onset is now
/// that of the current point's Jacobian: the direct run converges on the
/// coarse grid's slack side, 20 IVPs measured; bound 24. Tip on main \[m\]:
/// the same root (measured within 6.5e-14 m).
#[test]
fn a_cold_guess_at_a_tendons_onset_takes_the_slack_side_on_the_coarse_grid() {
    const DESIGN: usize = 411;
    const MAX_IVPS: usize = 24;
    const MAIN_TIP_M: [f64; 3] = [
        -1.633_205_267_178_51e-3,
        -5.004_709_455_454_196e-3,
        7.777_262_226_777_917e-3,
    ];
    // the direct run converges: no continuation path
    check(DESIGN, MAX_IVPS, MAIN_TIP_M, false);
}
