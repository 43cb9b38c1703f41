//! A benchmark design whose path crosses a kink near `lambda = 0` (a
//! tendon's onset of tension): once the homotopy's step control
//! (`solve::continuation`), now the semismooth step across the onset
//! (`solve::system`, `Shooting::taut_step`).
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Benchmark design #153 (a 19.3 mm, 120 kPa rod, a helical linear tendon
/// and a TCA, gravity; not past self-weight buckling) converges only
/// through continuation, and its path has a kink near `lambda = 0.01`
/// (a tendon's onset of tension): correctors there fail from predictor
/// residuals as small as `4e-3` ("line search failed"), and the path gets
/// across only on some step sequences. Measured at stop 29 (main
/// 2acabf7, `benches/designs.rs`, 1,000 designs): of 35 variants of the
/// step control (predictor refusal at 10 / 15 / 20, or at 3-10 on a grown
/// or first step; steps from the predictor residual `r0` aimed at
/// 0.1-3; intermediate correctors stopped at 3-30 times their
/// tolerance and finished by an unevaluated chord step; failed steps cut
/// by `r0^(-1/3)`), 18 lost #153 (3 of them #385 too, no other design
/// not past buckling). The benchmark is the only other guard.
/// Since the semismooth step (a Newton step from a slack tendon that
/// carries it taut is recomputed with the taut slope, stop 30), the direct
/// run converges: the slack Jacobian's step overshot into tension, and
/// the line search accepted `t ~ 4e-3`.
const KINKED_START_DESIGN: usize = 153;

/// IVP bound of [`KINKED_START_DESIGN`]: 19 measured (stop 30, the coarse
/// pre-solve converging in 5 iterations); before the semismooth step 311
/// (main c41b3d0, 20 continuation steps). The bound leaves room for
/// another iteration sequence near the kink (twice the measured count) and
/// fails if the path falls back to continuation's cost.
const KINKED_START_MAX_IVPS: usize = 40;

#[test]
fn a_start_at_a_tendon_onset_converges_cold_without_continuation() {
    let opts = SolveOptions::default();
    let d = random_design(DEFAULT_SEED, KINKED_START_DESIGN);
    assert!(!d.past_buckling(), "{}", d.summary());
    let sol =
        solve(&d.robot, &d.inputs, &opts, None).unwrap_or_else(|e| panic!("{}: {e}", d.summary()));
    assert!(sol.residual <= opts.tol.max(sol.floor), "{}", d.summary());
    // the direct run converges (before the semismooth step only
    // continuation did)
    assert!(
        sol.continuation_steps.is_empty(),
        "{}: {} continuation steps",
        d.summary(),
        sol.continuation_steps.len()
    );
    assert!(
        sol.evaluations <= KINKED_START_MAX_IVPS,
        "#{KINKED_START_DESIGN}: {} IVPs (bound {KINKED_START_MAX_IVPS})",
        sol.evaluations
    );
}
