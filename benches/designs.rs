//! The solver's design benchmark: cold solves of the seeded random designs
//! of `tcarod::problems` (`cargo bench --bench designs`).
//!
//! Environment: `TCAROD_DESIGNS` (default 1000) designs, `TCAROD_SEED`
//! (default `problems::DEFAULT_SEED`), `TCAROD_VERBOSE=1` lists each failure
//! and each equilibrium residual above the target; diagnostics:
//! `TCAROD_ONLY=3,17` solves only these designs, `TCAROD_STEPS` sets the RK4 steps,
//! `TCAROD_TIPS=1` prints every converged design's tip position,
//! `TCAROD_LIST=1` lists every converged design (index, IVP-equivalents,
//! IVPs, iterations, homotopy steps, `past` if past buckling), `TCAROD_REPEAT`
//! (default 3) sets the timed repeats. `TCAROD_EQUILIBRIUM_TOL=1e-8` solves
//! every design with that `SolveOptions::equilibrium_tol` (the grid refined
//! until the global equilibrium check holds: the accuracy target),
//! so that the statistics are those of the controlled solve (IVP-equivalents
//! stay in units of one plain IVP on the `TCAROD_STEPS` grid).
//!
//! Each design is solved once from the reference (straight) guess with the
//! default `SolveOptions` (100 RK4 steps, tol 1e-10, max_iter 50 per Newton
//! run), the solver's own fallback (homotopy continuation) included; the
//! count of converged solves that needed it is printed. IVPs are
//! `Solution.evaluations` (a tangent IVP, which carries the Jacobian, counts
//! as one); IVP-equivalents are the solve's CPU time over the CPU time of one
//! plain IVP of the same design at its solution (mean of 5), the median of
//! `TCAROD_REPEAT` (default 3) such pairs, solve then IVPs, interleaved (on a
//! shared machine a single pair can swing by 30 %). Times are thread-CPU
//! times from `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` (`clock/mod.rs`), or
//! wall time from `Instant` where that is unavailable. Prints a table and one
//! `JSON ` line.
use std::time::Instant;

use tcarod::problems::{equilibrium, random_design, Design, DEFAULT_SEED, EQUILIBRIUM_TOL};
use tcarod::shooting::{solve, Loads, Shot, SolveOptions};
use tcarod::Error;

#[path = "clock/mod.rs"]
mod clock;
use clock::thread_cpu;
#[path = "designs_report/mod.rs"]
mod designs_report;
use designs_report::{quantile, report, sorted, Converged, Outcome};

fn reason(e: &Error) -> String {
    match e {
        Error::NotConverged { reason, .. } => reason.clone(),
        Error::Integration { reason, .. } => format!(
            "integration: {}",
            reason.split(':').next().unwrap_or(reason)
        ),
        other => format!("{other}"),
    }
}

fn main() {
    let n: usize = std::env::var("TCAROD_DESIGNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    let seed: u64 = std::env::var("TCAROD_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_SEED);
    let verbose = std::env::var("TCAROD_VERBOSE").is_ok_and(|v| v == "1");
    let repeat: usize = std::env::var("TCAROD_REPEAT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3)
        .max(1);
    let mut opts = SolveOptions::default();
    if let Some(steps) = std::env::var("TCAROD_STEPS")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        opts.steps = steps;
    }
    if let Some(tol) = std::env::var("TCAROD_EQUILIBRIUM_TOL")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        opts.equilibrium_tol = Some(tol);
    }
    // TCAROD_ONLY=i,j,...: just these designs (diagnostics)
    let only: Option<Vec<usize>> = std::env::var("TCAROD_ONLY")
        .ok()
        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect());
    let clock = if thread_cpu().is_some() {
        "thread-cpu (clock_gettime)"
    } else {
        "wall (Instant)"
    };
    let wall = Instant::now();
    let now = || thread_cpu().unwrap_or_else(|| wall.elapsed().as_secs_f64());
    let mut out = Vec::with_capacity(n);
    let indices: Vec<usize> = only.clone().unwrap_or_else(|| (0..n).collect());
    let n = indices.len();
    for &i in &indices {
        let d = random_design(seed, i);
        out.push(solve_one(
            &d,
            &opts,
            (verbose, only.is_some()),
            repeat,
            &now,
        ));
    }
    let wall = wall.elapsed().as_secs_f64();
    report(&out, n, seed, clock, wall);
}

/// Solve design `d` cold, time it (`repeat` times), check its equilibrium
/// (and, above the target, solve it again with the grid refined until the
/// check holds); `verbose`, `diagnose` print more.
fn solve_one(
    d: &Design,
    opts: &SolveOptions,
    (verbose, diagnose): (bool, bool),
    repeat: usize,
    now: &dyn Fn() -> f64,
) -> Outcome {
    let i = d.index;
    let opts = *opts;
    let t0 = now();
    let r = solve(&d.robot, &d.inputs, &opts, None);
    let cpu = now() - t0;
    let result = match r {
        Ok(sol) => {
            let eq = equilibrium(&d.robot, &sol);
            print_tip(i, &sol);
            if diagnose {
                eprintln!(
                    "#{i} steps {} residual {:.2e}: {eq:?}\n  {}\n  tensions {:?}",
                    opts.steps,
                    sol.residual,
                    d.summary(),
                    sol.tensions
                );
            }
            let ivp = plain_ivp_cpu(d, &opts, &sol.unknowns, now);
            let ive = ivp_equivalents(d, &opts, (cpu, ivp), repeat, &sol.unknowns, now);
            let fine = (eq.relative > EQUILIBRIUM_TOL)
                .then(|| controlled(d, &opts, now))
                .flatten()
                .map(|(e, cpu)| (e, cpu / ivp));
            Ok((
                Converged {
                    ivps: sol.evaluations,
                    iterations: sol.iterations,
                    equilibrium: eq.relative,
                    ivp_equivalents: ive,
                    continuation_steps: sol.continuation_steps.len(),
                },
                fine,
            ))
        }
        Err(e) => {
            if verbose {
                eprintln!("FAIL {}: {e}", d.summary());
            }
            Err(reason(&e))
        }
    };
    if verbose {
        if let Ok((c, _)) = &result {
            if c.equilibrium > EQUILIBRIUM_TOL {
                eprintln!("EQUILIBRIUM {:.2e} {}", c.equilibrium, d.summary());
            }
        }
    }
    let (result, fine) = match result {
        Ok((c, fine)) => (Ok(c), fine),
        Err(e) => (Err(e), None),
    };
    if let (true, Some((f, _))) = (verbose, fine) {
        eprintln!("EQUILIBRIUM with equilibrium_tol #{i} {f:.2e}");
    }
    Outcome {
        index: i,
        past: d.past_buckling(),
        cpu,
        result,
        fine,
    }
}

/// CPU time \[s\] of one plain IVP of design `d` at `unknowns` (mean of 5).
fn plain_ivp_cpu(d: &Design, opts: &SolveOptions, unknowns: &[f64], now: &dyn Fn() -> f64) -> f64 {
    let loads = Loads::of(&d.robot);
    let shot = Shot::new(&d.robot, &d.inputs, &loads, opts.steps);
    let t1 = now();
    for _ in 0..5 {
        let _ = std::hint::black_box(shot.residual(unknowns, false));
    }
    (now() - t1) / 5.0
}

/// The median over `repeat` (solve CPU / plain IVP CPU) pairs, the first
/// `(cpu, ivp)` already measured; each further pair times the same
/// (deterministic) cold solve again, then the IVP.
fn ivp_equivalents(
    d: &Design,
    opts: &SolveOptions,
    (cpu, ivp): (f64, f64),
    repeat: usize,
    unknowns: &[f64],
    now: &dyn Fn() -> f64,
) -> f64 {
    let mut ratios = vec![cpu / ivp];
    for _ in 1..repeat {
        let t0 = now();
        let _ = std::hint::black_box(solve(&d.robot, &d.inputs, opts, None));
        let cpu = now() - t0;
        ratios.push(cpu / plain_ivp_cpu(d, opts, unknowns, now));
    }
    quantile(&sorted(ratios), 0.5)
}

/// With `TCAROD_TIPS=1`, print design `i`'s tip position \[m\] (to compare
/// two builds' solutions design by design).
fn print_tip(i: usize, sol: &tcarod::shooting::Solution) {
    if std::env::var("TCAROD_TIPS").is_ok_and(|v| v == "1") {
        let p = sol.tip_position();
        eprintln!("TIP #{i} {:.15e} {:.15e} {:.15e}", p.x, p.y, p.z);
    }
}

/// Design `d` solved cold with `equilibrium_tol` = the target: its
/// equilibrium error and CPU time \[s\] (`None` if the solve failed).
fn controlled(d: &Design, opts: &SolveOptions, now: &dyn Fn() -> f64) -> Option<(f64, f64)> {
    let fo = SolveOptions {
        equilibrium_tol: Some(EQUILIBRIUM_TOL),
        ..*opts
    };
    let t0 = now();
    let s = solve(&d.robot, &d.inputs, &fo, None).ok()?;
    Some((equilibrium(&d.robot, &s).relative, now() - t0))
}
