//! A benchmark design whose cold start sits at a tendon's onset of
//! tension: the semismooth step (`solve::system`, `Shooting::taut_step`)
//! takes the direct run across the kink without continuation.
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Design 153 of the tuning seed's random family (a 19.3 mm, 120 kPa rod, a helical linear tendon
/// and a TCA, gravity; not past self-weight buckling). Its homotopy path
/// has a kink near `lambda = 0.01` (the tendon's onset of tension), where
/// correctors fail from predictor residuals as small as `4e-3`. The direct
/// run converges: a Newton step from the slack tendon that carries it taut
/// is recomputed with the taut slope, where the slack Jacobian's step
/// overshoots into tension.
const KINKED_START_DESIGN: usize = 153;

#[test]
fn a_start_at_a_tendon_onset_converges_cold_without_continuation() {
    let opts = SolveOptions::default();
    let d = random_design(DEFAULT_SEED, KINKED_START_DESIGN);
    assert!(!d.past_buckling(), "{}", d.summary());
    let sol =
        solve(&d.robot, &d.inputs, &opts, None).unwrap_or_else(|e| panic!("{}: {e}", d.summary()));
    assert!(sol.residual <= opts.tol.max(sol.floor), "{}", d.summary());
    // the direct run converges
    assert!(
        sol.continuation_steps.is_empty(),
        "{}: {} continuation steps",
        d.summary(),
        sol.continuation_steps.len()
    );
}
