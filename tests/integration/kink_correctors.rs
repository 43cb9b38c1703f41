//! A benchmark design whose direct run starts with three linear tendons at
//! their onsets (a cold start, zero tension): the slack side's Jacobian
//! gives a step that carries all three taut, and the taut model carries one
//! of them back slack. The semismooth step re-solved with that tendon slack
//! (`solve::residual::taut_step`, Katzenelson's iteration over the pieces)
//! converges without continuation.
use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{solve, SolveOptions};

/// Design 414 of the tuning seed's random family (a 17.6 mm, 568 kPa rectangular rod, three linear
/// tendons, two of them helical, and a constant-tension tendon; gravity
/// and a tip force).
const DESIGN: usize = 414;

#[test]
fn a_taut_model_landing_a_tendon_slack_converges_without_continuation() {
    let opts = SolveOptions::default();
    let d = random_design(DEFAULT_SEED, DESIGN);
    assert!(!d.past_buckling(), "{}", d.summary());
    let sol =
        solve(&d.robot, &d.inputs, &opts, None).unwrap_or_else(|e| panic!("{}: {e}", d.summary()));
    assert!(sol.residual <= opts.tol.max(sol.floor), "{}", d.summary());
    assert!(
        sol.continuation_steps.is_empty(),
        "{}: {} continuation steps",
        d.summary(),
        sol.continuation_steps.len()
    );
}
