//! Stability over the design set: every converged solution of the seeded
//! random designs of `tcarod::problems` carries a stability verdict, and warm
//! sweeps that end elsewhere than cold solves are explained by it
//! (`cargo bench --bench stability_designs`).
//!
//! For each design: a cold solve at its inputs (from the reference guess,
//! the solver's fallback included) and a warm sweep from the reference
//! inputs to its inputs in 8 equal steps, both under the default policy
//! `Policy::Report` (`stability::solve_checked`, `stability::sweep_checked`:
//! the verdict is part of every solve). Where the two tips differ by more
//! than 1 % of the body length, the pair is classified by the verdicts, and
//! both are solved again under `Policy::Continue` (an unstable one moves to
//! a stable equilibrium at the same inputs); the pairs that still differ are
//! two coexisting stable shapes. Environment: `TCAROD_DESIGNS` (default
//! 1000), `TCAROD_SEED` (default `problems::DEFAULT_SEED`),
//! `TCAROD_VERBOSE=1` lists each differing pair.
//!
//! Verdict cost, per cold solution: thread-CPU time of the verdict
//! (`stability::stability`, which integrates one tangent IVP) over that of
//! one tangent IVP at the solution without recorded nodes
//! (`shooting::Shot::jacobian` on the full grid: the exact Newton Jacobian),
//! each the median of 3, interleaved; and the same over one plain IVP.
//! Prints the counts and one `JSON ` line with the same numbers.
use std::time::Instant;

use tcarod::problems::{random_design, Design, DEFAULT_SEED};
use tcarod::shooting::{Loads, Shot, Solution, SolveOptions};
use tcarod::stability::{solve_checked, stability, sweep_checked, Checked, Policy};

#[path = "clock/mod.rs"]
mod clock;

/// Thread CPU time [s], else wall time since `t0`.
fn cpu(t0: Instant) -> f64 {
    clock::thread_cpu().unwrap_or_else(|| t0.elapsed().as_secs_f64())
}

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Counts over the designs.
#[derive(Default)]
struct Tally {
    cold_ok: usize,
    warm_ok: usize,
    /// Converged solutions (cold, and every sweep point) and those with a verdict.
    solutions: usize,
    with_verdict: usize,
    stable_cold: usize,
    stable_warm: usize,
    differ: usize,
    one_unstable: usize,
    cold_unstable_warm_stable: usize,
    both_stable: usize,
    both_unstable: usize,
    /// Differing pairs still apart after both are solved with `Continue`.
    differ_continued: usize,
    /// Verdict time over one tangent IVP, and over one plain IVP.
    per_tangent: Vec<f64>,
    per_ivp: Vec<f64>,
}

/// Thread-CPU time of the verdict and of one tangent and one plain IVP at `s`.
fn cost(d: &Design, s: &Solution, t0: Instant, tally: &mut Tally) {
    let r = &d.robot;
    let (mut v, mut t, mut p) = (vec![], vec![], vec![]);
    for _ in 0..3 {
        let a = cpu(t0);
        let _ = std::hint::black_box(stability(r, s, &[]));
        let b = cpu(t0);
        let _ = std::hint::black_box(
            Shot::new(r, &s.inputs, &s.loads, s.steps).jacobian(&s.unknowns, false),
        );
        let c = cpu(t0);
        let _ = std::hint::black_box(
            Shot::new(r, &s.inputs, &s.loads, s.steps).residual(&s.unknowns, false),
        );
        let e = cpu(t0);
        v.push(b - a);
        t.push(c - b);
        p.push(e - c);
    }
    let (v, t, p) = (median(v), median(t), median(p));
    tally.per_tangent.push(v / t);
    tally.per_ivp.push(v / p);
}

fn stable(c: &Checked) -> bool {
    c.stability.as_ref().is_some_and(|s| s.stable)
}

fn one(i: usize, d: &Design, opts: &SolveOptions, t0: Instant, verbose: bool, tally: &mut Tally) {
    let r = &d.robot;
    let len = r.body.length;
    let loads = Loads::of(r);
    let reference = r.reference_inputs();
    let path: Vec<Vec<f64>> = (1..=8)
        .map(|k| {
            let f = k as f64 / 8.0;
            reference
                .iter()
                .zip(&d.inputs)
                .map(|(a, b)| a + (b - a) * f)
                .collect()
        })
        .collect();
    let cold = solve_checked(r, &d.inputs, &loads, opts, None, Policy::Report).ok();
    let warm = sweep_checked(r, &path, opts, Policy::Report).ok();
    for c in cold.iter().chain(warm.iter().flatten()) {
        tally.solutions += 1;
        tally.with_verdict += c.stability.is_some() as usize;
    }
    let warm = warm.and_then(|v| v.into_iter().last());
    if let Some(c) = &cold {
        tally.cold_ok += 1;
        tally.stable_cold += stable(c) as usize;
        cost(d, &c.solution, t0, tally);
    }
    if let Some(w) = &warm {
        tally.warm_ok += 1;
        tally.stable_warm += stable(w) as usize;
    }
    let (Some(c), Some(w)) = (&cold, &warm) else {
        return;
    };
    let dist = (c.solution.tip_position() - w.solution.tip_position()).norm() / len;
    if dist <= 0.01 {
        return;
    }
    tally.differ += 1;
    match (stable(c), stable(w)) {
        (true, true) => tally.both_stable += 1,
        (false, false) => tally.both_unstable += 1,
        (false, true) => {
            tally.one_unstable += 1;
            tally.cold_unstable_warm_stable += 1
        }
        (true, false) => tally.one_unstable += 1,
    }
    // both again under `Continue`: the cold solve from scratch, the sweep's
    // last point from its own warm start
    let cc = solve_checked(r, &d.inputs, &loads, opts, None, Policy::Continue).ok();
    let wc = sweep_checked(r, &path, opts, Policy::Continue)
        .ok()
        .and_then(|v| v.into_iter().last());
    let still = match (&cc, &wc) {
        (Some(a), Some(b)) => {
            (a.solution.tip_position() - b.solution.tip_position()).norm() / len > 0.01
        }
        _ => true,
    };
    tally.differ_continued += still as usize;
    if verbose {
        let m = |c: &Checked| c.stability.as_ref().map_or(f64::NAN, |s| s.margin);
        println!(
            "design {i}: tips differ by {dist:.3} L; cold stable {} (margin {:.3e}), warm stable {} (margin {:.3e}); column ratio {:.2}; after 'continue': {}",
            stable(c),
            m(c),
            stable(w),
            m(w),
            d.column_ratio(),
            if still { "still apart (two stable shapes)" } else { "the same shape" }
        );
    }
}

fn main() {
    let n = env("TCAROD_DESIGNS", 1000) as usize;
    let seed = env("TCAROD_SEED", DEFAULT_SEED);
    let verbose = std::env::var("TCAROD_VERBOSE").is_ok();
    let opts = SolveOptions::default();
    let mut t = Tally::default();
    let t0 = Instant::now();
    for i in 0..n {
        one(i, &random_design(seed, i), &opts, t0, verbose, &mut t);
    }
    let samples = t.per_tangent.len();
    println!(
        "designs {n}, seed {seed}, {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    println!(
        "converged: cold {}, warm sweep {}; solutions {} of which with a verdict {}; stable: cold {}, warm {}",
        t.cold_ok, t.warm_ok, t.solutions, t.with_verdict, t.stable_cold, t.stable_warm
    );
    println!(
        "cold and warm tips differ by > 1 % L: {} (one of the pair unstable: {}, of which cold unstable / warm stable: {}; both stable: {}; both unstable: {}); still apart after both continue to stable: {}",
        t.differ, t.one_unstable, t.cold_unstable_warm_stable, t.both_stable, t.both_unstable, t.differ_continued
    );
    let (per_tangent, per_ivp) = (median(t.per_tangent), median(t.per_ivp));
    println!(
        "verdict cost: median {per_tangent:.3} tangent IVPs (full grid, no recording), {per_ivp:.2} plain IVPs (thread-CPU ratios, median of 3 each, {samples} solutions)"
    );
    println!(
        "JSON {{\"bench\":\"stability_designs\",\"n\":{n},\"seed\":{seed},\"cold_converged\":{},\"warm_converged\":{},\"solutions\":{},\"with_verdict\":{},\"stable_cold\":{},\"stable_warm\":{},\
\"differ\":{},\"one_unstable\":{},\"cold_unstable_warm_stable\":{},\"both_stable\":{},\"both_unstable\":{},\"differ_after_continue\":{},\
\"verdict_per_tangent_ivp\":{},\"verdict_per_plain_ivp\":{},\"cost_samples\":{samples}}}",
        t.cold_ok,
        t.warm_ok,
        t.solutions,
        t.with_verdict,
        t.stable_cold,
        t.stable_warm,
        t.differ,
        t.one_unstable,
        t.cold_unstable_warm_stable,
        t.both_stable,
        t.both_unstable,
        t.differ_continued,
        jnum(per_tangent),
        jnum(per_ivp)
    );
}

/// `x` with four decimals as a JSON number, or `null` if it is not finite
/// (the median of no samples).
fn jnum(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.4}")
    } else {
        "null".to_string()
    }
}
