//! Cold direct Newton runs far from any root hand over to continuation
//! without full-grid Jacobians (`shooting::DIRECT_REFINE_WITHIN`): a line
//! search that failed with the coarse grid's Jacobian failed because the
//! residual is nonlinear there, which the full grid's tangents do not cure;
//! and a direct run whose first coarse Newton run fails from the cold guess
//! hands over without retracing it on the full grid (`shooting::handed_over`).
//! Each design here converges, by the route its mechanism implies, to the
//! tip the benchmark records for it (`TCAROD_TIPS=1 benches/designs.rs`);
//! the work of each route is the benchmark's to report.
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Tip agreement with the recorded tip \[m\]: both converge to `tol` (1e-10
/// scaled) on the same grid, so the tips differ by Newton's last steps
/// only; 1e-9 m is the project's results-unchanged rule.
const TIP_TOL_M: f64 = 1e-9;

/// Designs whose direct run stays far from a root (`max |r|` 2.5-84 over
/// its iterations), of the tuning seed's random family, and their
/// recorded tips \[m\].
const CASES: [(usize, [f64; 3]); 2] = [
    (
        560,
        [
            -1.631_666_118_213_358e-3,
            8.148_029_572_981_334e-4,
            1.030_698_416_018_627e-2,
        ],
    ),
    (
        159,
        [
            2.239_673_371_211_584e-2,
            2.842_524_183_652_943e-4,
            3.280_916_852_114_718e-2,
        ],
    ),
];

#[test]
fn a_direct_run_far_from_a_root_hands_over_to_continuation() {
    for (i, tip) in CASES {
        check(i, tip, true);
    }
}

/// Solve benchmark design `i` cold with the default options and check
/// that it converges to tol (or its floor), through continuation or not
/// (`via_continuation`: its path recorded or empty), to the tip `tip`
/// \[m\] within [`TIP_TOL_M`].
fn check(i: usize, tip: [f64; 3], via_continuation: bool) {
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
}

/// Design 319 of the tuning seed's random family (not past buckling): its direct run's first
/// coarse Newton run, from the cold guess, stalls (`max |r|` 3.8 after
/// three damped steps), and the coarse grid resolves the design there
/// (full-grid residual at the guess within 1.1 % of the coarse one), so the
/// run hands over to continuation at once. Its recorded tip \[m\].
const HANDED_OVER: (usize, [f64; 3]) = (
    319,
    [
        -4.406_670_617_270_772e-3,
        1.022_343_581_405_42e-2,
        1.027_377_662_433_26e-2,
    ],
);

#[test]
fn a_failed_cold_coarse_run_hands_over_to_continuation() {
    let (i, tip) = HANDED_OVER;
    check(i, tip, true);
}

/// Design 411 of the tuning seed's random family: its cold guess has a tendon exactly at its onset
/// of tension. The taut side's Newton step fails its line search; the
/// onset is that of the current point's Jacobian, so the coarse run tries
/// the slack side's derivative, which converges: no continuation path.
#[test]
fn a_cold_guess_at_a_tendons_onset_takes_the_slack_side_on_the_coarse_grid() {
    const DESIGN: usize = 411;
    const TIP_M: [f64; 3] = [
        -1.633_205_267_178_51e-3,
        -5.004_709_455_454_196e-3,
        7.777_262_226_777_917e-3,
    ];
    check(DESIGN, TIP_M, false);
}
