//! Issue-16 benchmark: a stability verdict for every converged solution of
//! the seeded random designs of `tcarod::problems`, and warm sweeps against
//! cold solves (`cargo bench --bench stability_designs`).
//!
//! For each design: a cold solve at its inputs (from the reference guess,
//! the solver's fallback included) and a warm sweep from the reference
//! inputs to its inputs in 8 equal steps (`shooting::sweep`), each with its
//! verdict (`stability::stability`, one tangent IVP). Where the two tips
//! differ by more than 1 % of the body length, the pair is classified by
//! the verdicts. Environment: `TCAROD_DESIGNS` (default 1000), `TCAROD_SEED`
//! (default `problems::DEFAULT_SEED`), `TCAROD_VERBOSE=1` lists each
//! differing pair. Verdict cost: thread-CPU time of the verdict over that of
//! one plain IVP at the solution (mean of 5), the "IVP-equivalents", beside
//! that of one tangent IVP (the solver's Jacobian) without recorded nodes.
use std::time::Instant;

use tcarod::problems::{random_design, DEFAULT_SEED};
use tcarod::shooting::{shoot, shoot_jacobian, solve, sweep, SolveOptions};
use tcarod::stability::stability;

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    // POSIX, in the C library every Rust program on Linux links already
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}

/// Thread CPU time [s] (`CLOCK_THREAD_CPUTIME_ID` = 3 on Linux), else wall time.
fn cpu(t0: Instant) -> f64 {
    if cfg!(target_os = "linux") && cfg!(target_pointer_width = "64") {
        let mut ts = Timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `ts` is a valid, writable timespec (64-bit Linux layout).
        if unsafe { clock_gettime(3, &mut ts) } == 0 {
            return ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9;
        }
    }
    t0.elapsed().as_secs_f64()
}

fn env(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let n = env("TCAROD_DESIGNS", 1000) as usize;
    let seed = env("TCAROD_SEED", DEFAULT_SEED);
    let verbose = std::env::var("TCAROD_VERBOSE").is_ok();
    let opts = SolveOptions::default();
    let (mut cold_ok, mut warm_ok, mut stable_cold, mut stable_warm) = (0, 0, 0, 0);
    let (mut differ, mut one_unstable, mut both_stable, mut both_unstable) = (0, 0, 0, 0);
    let mut cold_unstable_warm_stable = 0;
    let mut ratios: Vec<f64> = vec![];
    let mut tangent_ratios: Vec<f64> = vec![];
    let t0 = Instant::now();
    for i in 0..n {
        let d = random_design(seed, i);
        let r = &d.robot;
        let len = r.body.length;
        let cold = solve(r, &d.inputs, &opts, None).ok();
        let reference = r.reference_inputs();
        let path: Vec<Vec<f64>> = (1..=8)
            .map(|k| {
                reference
                    .iter()
                    .zip(&d.inputs)
                    .map(|(a, b)| a + (b - a) * k as f64 / 8.0)
                    .collect()
            })
            .collect();
        let warm = sweep(r, &path, &opts)
            .ok()
            .and_then(|v| v.into_iter().last());
        let vc = cold.as_ref().and_then(|s| {
            let a = cpu(t0);
            let v = stability(r, s, &[]).ok()?;
            let b = cpu(t0);
            for _ in 0..5 {
                let _ = std::hint::black_box(shoot(
                    r,
                    &s.inputs,
                    &s.loads,
                    &s.unknowns,
                    s.steps,
                    false,
                ));
            }
            let c = cpu(t0);
            let _ = std::hint::black_box(shoot_jacobian(
                r,
                &s.inputs,
                &s.loads,
                &s.unknowns,
                s.steps,
                false,
            ));
            let d = cpu(t0);
            let ivp = (c - b) / 5.0;
            ratios.push((b - a) / ivp);
            tangent_ratios.push((d - c) / ivp);
            Some(v)
        });
        let vw = warm.as_ref().and_then(|s| stability(r, s, &[]).ok());
        cold_ok += cold.is_some() as usize;
        warm_ok += warm.is_some() as usize;
        stable_cold += vc.as_ref().map_or(0, |v| v.stable as usize);
        stable_warm += vw.as_ref().map_or(0, |v| v.stable as usize);
        if let (Some(c), Some(w), Some(vc), Some(vw)) = (&cold, &warm, &vc, &vw) {
            let dist = (c.tip_position() - w.tip_position()).norm() / len;
            if dist > 0.01 {
                differ += 1;
                match (vc.stable, vw.stable) {
                    (true, true) => both_stable += 1,
                    (false, false) => both_unstable += 1,
                    (false, true) => {
                        one_unstable += 1;
                        cold_unstable_warm_stable += 1
                    }
                    (true, false) => one_unstable += 1,
                }
                if verbose {
                    println!(
                        "design {i}: tips differ by {dist:.3} L; cold stable {} (margin {:.3e}), warm stable {} (margin {:.3e}); column ratio {:.2}",
                        vc.stable,
                        vc.margin,
                        vw.stable,
                        vw.margin,
                        d.column_ratio()
                    );
                }
            }
        }
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        if v.is_empty() {
            f64::NAN
        } else {
            v[v.len() / 2]
        }
    };
    let nr = ratios.len();
    let med = median(ratios);
    let med_t = median(tangent_ratios);
    println!(
        "designs {n}, seed {seed}, {:.1} s",
        t0.elapsed().as_secs_f64()
    );
    println!("converged: cold {cold_ok}, warm sweep {warm_ok}; stable: cold {stable_cold}, warm {stable_warm}");
    println!(
        "cold and warm tips differ by > 1 % L: {differ} (one of the pair unstable: {one_unstable}, of which cold unstable / warm stable: {cold_unstable_warm_stable}; both stable: {both_stable}; both unstable: {both_unstable})"
    );
    println!("verdict cost: median {med:.2} plain-IVP equivalents; one tangent IVP without recording: {med_t:.2} (thread-CPU ratios, {nr} samples)");
}
