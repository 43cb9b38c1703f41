//! The warm sweeps' outcomes and statistics, and the counts per orientation
//! of gravity, for the designs benchmark's report.
use serde::Serialize;

use super::json::{json, Json};
use super::{quantile_text, quantiles, share, sorted, Outcome};

/// One converged warm step of a sweep.
pub(crate) struct Step {
    /// IVPs of the step's solve (`Solution.evaluations`, the solver's own
    /// count).
    pub(crate) ivps: usize,
    /// The step's CPU time over one plain IVP's at its solution.
    pub(crate) ivp_equivalents: f64,
}

/// The sweep's end against the cold solve's end (both converged).
pub(crate) struct End {
    /// `max(|p_sweep - p_cold| / L, |R_sweep - R_cold|_F)` at the tip.
    pub(crate) distance: f64,
    /// Whether `distance` is above the tolerance of one equilibrium.
    pub(crate) apart: bool,
    /// Stability verdicts (cold, sweep) of two apart ends (`None`: a
    /// verdict failed).
    pub(crate) verdicts: Option<(Option<bool>, Option<bool>)>,
}

/// A warm sweep: a cold solve at the reference inputs (the start), then
/// `K` solves in equal steps to the design's inputs, each warm from the
/// previous solution.
pub(crate) struct SweepOutcome {
    /// The converged warm steps, in order (the start excluded).
    pub(crate) steps: Vec<Step>,
    /// IVPs of the start, if it converged.
    pub(crate) start_ivps: Option<usize>,
    /// The step that failed (0: the start) and why; `None`: all converged.
    pub(crate) failed: Option<(usize, String)>,
    /// The end against the cold solve's (`None`: either failed).
    pub(crate) end: Option<End>,
}

/// Per orientation of gravity (`none`: no gravity): designs, converged cold,
/// sweeps converged; printed and as JSON.
pub(crate) fn orientations(out: &[Outcome]) -> Json {
    let mut pairs = serde_json::Map::new();
    for name in ["hanging", "upright", "horizontal", "none"] {
        let of: Vec<&Outcome> = out.iter().filter(|o| o.orientation == name).collect();
        if of.is_empty() {
            continue;
        }
        let ok = of.iter().filter(|o| o.result.is_ok()).count();
        let swept = of.iter().filter(|o| sweep_converged(o)).count();
        let has_sweeps = of.iter().any(|o| o.sweep.is_some());
        println!(
            "  {name:>10}: {:4} designs, converged cold {}{}",
            of.len(),
            share(ok, of.len()),
            if has_sweeps {
                format!(", sweeps converged {}", share(swept, of.len()))
            } else {
                String::new()
            }
        );
        pairs.insert(
            name.to_string(),
            json!({"n": of.len(), "converged": ok, "sweeps_converged": swept}),
        );
    }
    Json::Object(pairs)
}

fn sweep_converged(o: &Outcome) -> bool {
    o.sweep.as_ref().is_some_and(|s| s.failed.is_none())
}

/// Print the sweeps' statistics (`k` steps each) and return them as JSON.
pub(crate) fn report(out: &[Outcome], k: usize) -> Json {
    let sw: Vec<(&Outcome, &SweepOutcome)> = out
        .iter()
        .filter_map(|o| o.sweep.as_ref().map(|s| (o, s)))
        .collect();
    let n = sw.len();
    let converged = sw.iter().filter(|(_, s)| s.failed.is_none()).count();
    let start_failed = sw
        .iter()
        .filter(|(_, s)| matches!(s.failed, Some((0, _))))
        .count();
    let rescued = sw
        .iter()
        .filter(|(o, s)| s.failed.is_none() && o.result.is_err())
        .count();
    let ends: Vec<&End> = sw.iter().filter_map(|(_, s)| s.end.as_ref()).collect();
    let apart: Vec<&&End> = ends.iter().filter(|e| e.apart).collect();
    let far = apart.iter().filter(|e| e.distance > 0.01).count();
    let steps: Vec<&Step> = sw.iter().flat_map(|(_, s)| &s.steps).collect();
    let step_ivp = sorted(steps.iter().map(|s| s.ivps as f64).collect());
    let step_ive = sorted(steps.iter().map(|s| s.ivp_equivalents).collect());
    let total = sorted(
        sw.iter()
            .filter(|(_, s)| s.failed.is_none())
            .map(|(_, s)| {
                (s.start_ivps.unwrap_or(0) + s.steps.iter().map(|t| t.ivps).sum::<usize>()) as f64
            })
            .collect(),
    );
    println!(
        "warm sweeps ({k} steps from the reference inputs): converged {}; the start (reference inputs, cold) failed {start_failed}, a warm step {}; converged where the cold solve failed: {rescued}",
        share(converged, n),
        n - converged - start_failed
    );
    let verdicts = verdict_counts(&apart);
    println!(
        "  ends compared with the cold solve's: {}; on another equilibrium: {} ({far} more than 1 % of L apart); verdicts cold/sweep: {verdicts}",
        ends.len(),
        apart.len()
    );
    println!(
        "  IVPs per warm step (own count): {}",
        quantile_text(&step_ivp, 0)
    );
    println!(
        "  IVP-equivalents per warm step: {}",
        quantile_text(&step_ive, 1)
    );
    println!(
        "  IVPs per converged sweep (own count, start included): {}",
        quantile_text(&total, 0)
    );
    list(&sw, k);
    json!({
        "steps": k,
        "n": n,
        "converged": converged,
        "start_failed": start_failed,
        "step_failed": n - converged - start_failed,
        "converged_where_cold_failed": rescued,
        "compared": ends.len(),
        "other_equilibrium": apart.len(),
        "other_far": far,
        "other_verdicts": verdicts,
        "step_ivp": quantiles(&step_ivp, 0),
        "step_ivp_equivalents": quantiles(&step_ive, 2),
        "ivp_total": quantiles(&total, 0),
    })
}

/// Each failed sweep (the step and why) and each sweep ending on another
/// equilibrium than the cold solve's (distance, verdicts).
fn list(sw: &[(&Outcome, &SweepOutcome)], k: usize) {
    for (o, s) in sw {
        if let Some((j, r)) = &s.failed {
            println!("  SWEEP FAIL #{} at step {j} of {k}: {r}", o.index);
        }
        if let Some(e) = s.end.as_ref().filter(|e| e.apart) {
            let word = |v: Option<bool>| match v {
                Some(true) => "stable",
                Some(false) => "unstable",
                None => "no verdict",
            };
            let (cold, end) = e.verdicts.unwrap_or((None, None));
            println!(
                "  SWEEP OTHER #{} distance {:.2e}: cold {}, sweep {}",
                o.index,
                e.distance,
                word(cold),
                word(end)
            );
        }
    }
}

/// Stability verdicts of the pairs of ends on different equilibria (as
/// JSON: an object of the counts, in this order).
#[derive(Default, Serialize)]
struct Verdicts {
    cold_stable_sweep_unstable: usize,
    cold_unstable_sweep_stable: usize,
    both_stable: usize,
    both_unstable: usize,
    no_verdict: usize,
}

impl std::fmt::Display for Verdicts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "stable/unstable {}, unstable/stable {}, both stable {}, both unstable {}, no verdict {}",
            self.cold_stable_sweep_unstable,
            self.cold_unstable_sweep_stable,
            self.both_stable,
            self.both_unstable,
            self.no_verdict
        )
    }
}

fn verdict_counts(apart: &[&&End]) -> Verdicts {
    let mut v = Verdicts::default();
    for e in apart {
        match e.verdicts {
            Some((Some(true), Some(false))) => v.cold_stable_sweep_unstable += 1,
            Some((Some(false), Some(true))) => v.cold_unstable_sweep_stable += 1,
            Some((Some(true), Some(true))) => v.both_stable += 1,
            Some((Some(false), Some(false))) => v.both_unstable += 1,
            _ => v.no_verdict += 1,
        }
    }
    v
}
