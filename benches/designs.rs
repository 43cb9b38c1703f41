//! The solvers' design benchmark: the seeded designs of `tcarod::problems`,
//! each solved cold and by a warm sweep (`cargo bench --bench designs`),
//! reported per solver, family and seed and compared with the committed
//! baseline `benches/designs_baseline.json`.
//!
//! # What is run
//! Every solve below, cold or warm, is `tcarod::shooting::solve`
//! (multiple shooting, `docs/solver.md`); a warm solve is passed the
//! previous solution as `warm`. It reads `SolveOptions::equilibrium_tol`
//! (accuracy control).
//!
//! `TCAROD_FAMILY` picks the family: `random` (the default,
//! `problems::random_design`) or `stress` (`problems::stress_design`, heavy
//! bodies hanging, upright or horizontal). `TCAROD_SEED` is a seed or a
//! comma-separated list of seeds (decimal or `0x` hex) and names: `tuning`
//! (`problems::TUNING_SEED`, the tests' set, the one to tune on),
//! `held-out` (both `problems::HELD_OUT_SEEDS`: for reporting only, never
//! for tuning), `stress` (`problems::STRESS_SEED`); the default is `tuning`
//! for the random family and `stress` for the stress family.
//! `TCAROD_DESIGNS` designs per seed (default 1000 random, 300 stress).
//!
//! Each design is solved once from the reference (straight) guess with the
//! default `SolveOptions` (100 RK4 steps, tol 1e-10, max_iter 50 per Newton
//! run), the solver's own fallback (continuation) included; the count of
//! converged solves that record a continuation path
//! (`Solution.continuation_steps`) is printed. Then, unless
//! `TCAROD_SWEEP=0`, a warm sweep: a cold solve at the reference inputs
//! (`Robot::reference_inputs`: the material's reference temperature for a
//! TCA, zero tension or pull for a tendon) and `TCAROD_SWEEP_STEPS` (default
//! 10) solves in equal steps of the inputs to the design's, each warm from
//! the previous solution. A sweep converges if every solve does; its end is
//! on the cold solve's equilibrium if the tips agree within
//! [`SAME_END_TOL`] (position over the length, rotation matrices in the
//! Frobenius norm), else both ends get a stability verdict
//! (`tcarod::stability::stability`, one tangent IVP each).
//!
//! # What is measured
//! IVPs are `Solution.evaluations`: a tangent IVP of k directions counts
//! 1 + k/8 (rounded up), a coarse-grid IVP its share of the full grid's.
//! IVP-equivalents, the measure that compares solvers, are a solve's
//! CPU time over the CPU time of one plain IVP of the same design at its
//! solution (a single-shooting IVP on the same grid, mean of 5),
//! the median of `TCAROD_REPEAT` (default 3) such pairs, solve then IVPs,
//! interleaved (on a shared machine a single pair can swing by 30 %); each
//! warm step is timed the same way, warm from the same previous solution.
//! Times are thread-CPU times from `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`
//! (`clock/mod.rs`), or wall time from `Instant` where that is unavailable.
//! Per seed: a table (converged cold among all designs, those not past
//! self-weight buckling and those without gravity; per orientation of
//! gravity; the sweeps; quantiles of IVPs and IVP-equivalents of the cold
//! solves and of the warm steps) and one `JSON ` line with all of it, its
//! `solver` naming the solver.
//!
//! # Baseline
//! Each seed's report is compared with its entry of the same solver, family
//! and seed in
//! `benches/designs_baseline.json` (or `TCAROD_BASELINE`): `REGRESSION`
//! lines where a convergence count drops or a work quantile rises (IVP
//! counts exactly, IVP-equivalents by more than 10 % at the median and p90,
//! 25 % at p99 and max; see `designs_report/baseline.rs`).
//! `TCAROD_WRITE_BASELINE=1` writes the run's reports into that file,
//! replacing the entries of the same solver, family and seed (every other
//! entry keeps its line).
//!
//! # Diagnostics
//! `TCAROD_VERBOSE=1` lists each failure, each equilibrium residual above
//! the target and each sweep end's distance from the cold end;
//! `TCAROD_ONLY=3,17` solves only these designs (not written to the
//! baseline), `TCAROD_STEPS` sets the RK4 steps, `TCAROD_TIPS=1` prints
//! every converged design's tip position, `TCAROD_LIST=1` lists every
//! converged design (index, IVP-equivalents, IVPs, iterations, homotopy
//! steps, `past` if past buckling). `TCAROD_EQUILIBRIUM_TOL=1e-8`
//! (`shooting` only) solves every design with that
//! `SolveOptions::equilibrium_tol` (the grid refined until the global
//! equilibrium check holds: the accuracy target), so that the statistics are
//! those of the controlled solve (IVP-equivalents stay in units of one plain
//! IVP on the `TCAROD_STEPS` grid).
use std::str::FromStr;
use std::time::Instant;

use tcarod::problems::{
    equilibrium, random_design, stress_design, Design, Orientation, EQUILIBRIUM_TOL,
    HELD_OUT_SEEDS, STRESS_SEED, TUNING_SEED,
};
use tcarod::rod::Robot;
use tcarod::shooting::{Loads, Shot, Solution, SolveOptions};
use tcarod::stability::stability;
use tcarod::Error;

#[path = "clock/mod.rs"]
mod clock;
use clock::thread_cpu;
#[path = "designs_report/mod.rs"]
mod designs_report;
use designs_report::{
    baseline, quantile, report, sorted, Converged, End, Outcome, Run, SolverInfo, Step,
    SweepOutcome,
};

/// Largest tip distance (over the body length; rotation matrices in the
/// Frobenius norm) of a sweep's end from the cold solve's end on the same
/// equilibrium: two solves of one equilibrium to `tol` 1e-10 agree far more
/// closely, two equilibria differ by a finite amount.
const SAME_END_TOL: f64 = 1e-4;

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

/// The solver: `tcarod::shooting::solve`, multiple shooting.
const SOLVER: SolverInfo<'static> = SolverInfo {
    name: "multiple",
    function: "tcarod::shooting::solve",
    ivp_count: "a tangent IVP of k directions counts 1 + ceil(k/8)",
    accuracy_control: true,
};

/// Solve `robot` at `inputs` (warm from `warm`, or cold).
fn solve(
    robot: &Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> tcarod::Result<Solution> {
    tcarod::shooting::solve(robot, inputs, opts, warm)
}

/// The family of designs a run draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Family {
    Random,
    Stress,
}

impl Family {
    fn name(self) -> &'static str {
        match self {
            Family::Random => "random",
            Family::Stress => "stress",
        }
    }
    fn design(self, seed: u64, index: usize) -> Design {
        match self {
            Family::Random => random_design(seed, index),
            Family::Stress => stress_design(seed, index),
        }
    }
}

/// The run's settings, from the environment (see the module docs).
struct Config {
    family: Family,
    seeds: Vec<u64>,
    n: usize,
    only: Option<Vec<usize>>,
    verbose: bool,
    repeat: usize,
    opts: SolveOptions,
    sweep_steps: Option<usize>,
    write_baseline: bool,
}

/// Environment variable `name` parsed, `None` if unset or unparsable.
fn env<T: FromStr>(name: &str) -> Option<T> {
    std::env::var(name).ok().and_then(|v| v.trim().parse().ok())
}

fn flag(name: &str) -> bool {
    std::env::var(name).is_ok_and(|v| v == "1")
}

impl Config {
    fn from_env() -> Config {
        let family = match std::env::var("TCAROD_FAMILY").as_deref() {
            Err(_) | Ok("random") => Family::Random,
            Ok("stress") => Family::Stress,
            Ok(other) => panic!("TCAROD_FAMILY={other}: expected random or stress"),
        };
        let seeds = match std::env::var("TCAROD_SEED") {
            Ok(list) => list.split(',').flat_map(parse_seeds).collect(),
            Err(_) if family == Family::Stress => vec![STRESS_SEED],
            Err(_) => vec![TUNING_SEED],
        };
        let default_n = if family == Family::Stress { 300 } else { 1000 };
        let mut opts = SolveOptions::default();
        if let Some(steps) = env("TCAROD_STEPS") {
            opts.steps = steps;
        }
        opts.equilibrium_tol = env("TCAROD_EQUILIBRIUM_TOL");
        Config {
            family,
            seeds,
            n: env("TCAROD_DESIGNS").unwrap_or(default_n),
            // TCAROD_ONLY=i,j,...: just these designs (diagnostics)
            only: std::env::var("TCAROD_ONLY")
                .ok()
                .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect()),
            verbose: flag("TCAROD_VERBOSE"),
            repeat: env("TCAROD_REPEAT").unwrap_or(3).max(1),
            opts,
            sweep_steps: (std::env::var("TCAROD_SWEEP").as_deref() != Ok("0"))
                .then(|| env("TCAROD_SWEEP_STEPS").unwrap_or(10).max(1)),
            write_baseline: flag("TCAROD_WRITE_BASELINE"),
        }
    }
}

/// The seeds one item of `TCAROD_SEED` names: `tuning`, `held-out`,
/// `stress`, or a number (decimal or `0x` hex, `_` separators allowed).
fn parse_seeds(item: &str) -> Vec<u64> {
    let t = item.trim().replace('_', "");
    match t.as_str() {
        "tuning" => vec![TUNING_SEED],
        "held-out" | "heldout" => HELD_OUT_SEEDS.to_vec(),
        "stress" => vec![STRESS_SEED],
        _ => vec![t
            .strip_prefix("0x")
            .map_or_else(|| t.parse().ok(), |h| u64::from_str_radix(h, 16).ok())
            .unwrap_or_else(|| panic!("TCAROD_SEED item {item:?}: not a seed or a seed name"))],
    }
}

fn main() {
    let cfg = Config::from_env();
    let clock = if thread_cpu().is_some() {
        "thread-cpu (clock_gettime)"
    } else {
        "wall (Instant)"
    };
    let path = baseline::path();
    let base = baseline::load(&path);
    let indices: Vec<usize> = cfg.only.clone().unwrap_or_else(|| (0..cfg.n).collect());
    let mut runs = Vec::new();
    for &seed in &cfg.seeds {
        let wall = Instant::now();
        let now = || thread_cpu().unwrap_or_else(|| wall.elapsed().as_secs_f64());
        let out: Vec<Outcome> = indices
            .iter()
            .map(|&i| run_design(&cfg.family.design(seed, i), &cfg, &now))
            .collect();
        let run = Run {
            solver: SOLVER,
            family: cfg.family.name(),
            seed,
            steps: cfg.opts.steps,
            equilibrium_tol: cfg.opts.equilibrium_tol,
            sweep_steps: cfg.sweep_steps,
            repeat: cfg.repeat,
            subset: cfg.only.is_some(),
            clock,
            wall: wall.elapsed().as_secs_f64(),
        };
        let doc = report(&out, &run);
        baseline::compare(&doc, &base);
        runs.push(doc);
    }
    if cfg.write_baseline {
        if cfg.only.is_some() {
            println!("BASELINE not written: TCAROD_ONLY solves a subset of the designs");
        } else if let Err(e) = baseline::write(&path, &runs) {
            panic!("writing {}: {e}", path.display());
        }
    }
}

/// Design `d` solved cold, then swept (unless sweeps are off).
fn run_design(d: &Design, cfg: &Config, now: &dyn Fn() -> f64) -> Outcome {
    let (mut outcome, cold) = solve_one(d, cfg, now);
    outcome.sweep = cfg.sweep_steps.map(|k| {
        let s = sweep(d, cfg, k, cold.as_ref(), now);
        if cfg.verbose {
            if let Some(e) = &s.end {
                eprintln!("END #{} distance {:.2e}", d.index, e.distance);
            }
        }
        s
    });
    outcome
}

/// Solve design `d` cold with the run's solver, time it (`cfg.repeat`
/// times), check its equilibrium (and, above the target, with a solver that
/// has accuracy control, solve it again with the grid refined until the
/// check holds); `TCAROD_VERBOSE` and `TCAROD_ONLY` print more. The outcome
/// (no sweep yet) and the solution.
fn solve_one(d: &Design, cfg: &Config, now: &dyn Fn() -> f64) -> (Outcome, Option<Solution>) {
    let i = d.index;
    let (verbose, diagnose) = (cfg.verbose, cfg.only.is_some());
    let opts = cfg.opts;
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
            let ivp = plain_ivp_cpu(d, &d.inputs, &opts, &sol.unknowns, now);
            let ive = ivp_equivalents(d, (&d.inputs, None), cfg, (cpu, ivp), &sol, now);
            let fine = (eq.relative > EQUILIBRIUM_TOL && SOLVER.accuracy_control)
                .then(|| controlled(d, cfg, now))
                .flatten()
                .map(|(e, cpu)| (e, cpu / ivp));
            let c = Converged {
                ivps: sol.evaluations,
                iterations: sol.iterations,
                equilibrium: eq.relative,
                ivp_equivalents: ive,
                continuation_steps: sol.continuation_steps.len(),
            };
            Ok((c, fine, sol))
        }
        Err(e) => {
            if verbose {
                eprintln!("FAIL {}: {e}", d.summary());
            }
            Err(reason(&e))
        }
    };
    if verbose {
        if let Ok((c, _, _)) = &result {
            if c.equilibrium > EQUILIBRIUM_TOL {
                eprintln!("EQUILIBRIUM {:.2e} {}", c.equilibrium, d.summary());
            }
        }
    }
    let (result, fine, sol) = match result {
        Ok((c, fine, sol)) => (Ok(c), fine, Some(sol)),
        Err(e) => (Err(e), None, None),
    };
    if let (true, Some((f, _))) = (verbose, fine) {
        eprintln!("EQUILIBRIUM with equilibrium_tol #{i} {f:.2e}");
    }
    let body = &d.robot.body;
    let outcome = Outcome {
        index: i,
        past: d.past_buckling(),
        gravity: body.gravity.norm() > 0.0,
        orientation: Orientation::of(body).map_or("none", Orientation::name),
        cpu,
        result,
        fine,
        sweep: None,
    };
    (outcome, sol)
}

/// CPU time \[s\] of one plain IVP of design `d` at `inputs` and
/// `unknowns` (mean of 5).
fn plain_ivp_cpu(
    d: &Design,
    inputs: &[f64],
    opts: &SolveOptions,
    unknowns: &[f64],
    now: &dyn Fn() -> f64,
) -> f64 {
    let loads = Loads::of(&d.robot);
    let shot = Shot::new(&d.robot, inputs, &loads, opts.steps);
    let t1 = now();
    for _ in 0..5 {
        let _ = std::hint::black_box(shot.residual(unknowns, false));
    }
    (now() - t1) / 5.0
}

/// The median over `cfg.repeat` (solve CPU / plain IVP CPU) pairs of the
/// solve of `d` at `inputs` (warm from `warm`, or cold), the first
/// `(cpu, ivp)` already measured; each further pair times the same
/// (deterministic) solve again, then the IVP at its solution `sol`.
fn ivp_equivalents(
    d: &Design,
    (inputs, warm): (&[f64], Option<&Solution>),
    cfg: &Config,
    (cpu, ivp): (f64, f64),
    sol: &Solution,
    now: &dyn Fn() -> f64,
) -> f64 {
    let opts = &cfg.opts;
    let mut ratios = vec![cpu / ivp];
    for _ in 1..cfg.repeat {
        let t0 = now();
        let _ = std::hint::black_box(solve(&d.robot, inputs, opts, warm));
        let cpu = now() - t0;
        ratios.push(cpu / plain_ivp_cpu(d, inputs, opts, &sol.unknowns, now));
    }
    quantile(&sorted(ratios), 0.5)
}

/// The warm sweep of design `d` in `k` steps with the run's solver (see
/// the module docs), each step timed `cfg.repeat` times; its end compared
/// with the cold solution `cold` if there is one.
fn sweep(
    d: &Design,
    cfg: &Config,
    k: usize,
    cold: Option<&Solution>,
    now: &dyn Fn() -> f64,
) -> SweepOutcome {
    let opts = &cfg.opts;
    let reference = d.robot.reference_inputs();
    let mut out = SweepOutcome {
        steps: Vec::with_capacity(k),
        start_ivps: None,
        failed: None,
        end: None,
    };
    let mut prev = match solve(&d.robot, &reference, opts, None) {
        Ok(s) => s,
        Err(e) => {
            out.failed = Some((0, reason(&e)));
            return out;
        }
    };
    out.start_ivps = Some(prev.evaluations);
    for j in 1..=k {
        // the last step at the design's inputs exactly
        let inputs: Vec<f64> = if j == k {
            d.inputs.clone()
        } else {
            let t = j as f64 / k as f64;
            reference
                .iter()
                .zip(&d.inputs)
                .map(|(r, x)| r + (x - r) * t)
                .collect()
        };
        let t0 = now();
        let r = solve(&d.robot, &inputs, opts, Some(&prev));
        let cpu = now() - t0;
        let sol = match r {
            Ok(sol) => sol,
            Err(e) => {
                out.failed = Some((j, reason(&e)));
                return out;
            }
        };
        let ivp = plain_ivp_cpu(d, &inputs, opts, &sol.unknowns, now);
        let warm = (inputs.as_slice(), Some(&prev));
        let ive = ivp_equivalents(d, warm, cfg, (cpu, ivp), &sol, now);
        out.steps.push(Step {
            ivps: sol.evaluations,
            ivp_equivalents: ive,
        });
        prev = sol;
    }
    out.end = cold.map(|c| compare_ends(d, c, &prev));
    out
}

/// The sweep's end `end` against the cold solution `cold` of design `d`:
/// their tip distance and, if apart, both stability verdicts.
fn compare_ends(d: &Design, cold: &Solution, end: &Solution) -> End {
    let dp = (end.tip_position() - cold.tip_position()).norm() / d.robot.body.length;
    let dr = (end.tip_rotation() - cold.tip_rotation()).norm();
    let distance = dp.max(dr);
    let apart = distance > SAME_END_TOL;
    let verdict = |s: &Solution| stability(&d.robot, s, &[]).ok().map(|v| v.stable);
    End {
        distance,
        apart,
        verdicts: apart.then(|| (verdict(cold), verdict(end))),
    }
}

/// With `TCAROD_TIPS=1`, print design `i`'s tip position \[m\] (to compare
/// two builds' solutions design by design).
fn print_tip(i: usize, sol: &Solution) {
    if std::env::var("TCAROD_TIPS").is_ok_and(|v| v == "1") {
        let p = sol.tip_position();
        eprintln!("TIP #{i} {:.15e} {:.15e} {:.15e}", p.x, p.y, p.z);
    }
}

/// Design `d` solved cold by the run's solver with `equilibrium_tol` = the
/// target: its equilibrium error and CPU time \[s\] (`None` if the solve
/// failed).
fn controlled(d: &Design, cfg: &Config, now: &dyn Fn() -> f64) -> Option<(f64, f64)> {
    let fo = SolveOptions {
        equilibrium_tol: Some(EQUILIBRIUM_TOL),
        ..cfg.opts
    };
    let t0 = now();
    let s = solve(&d.robot, &d.inputs, &fo, None).ok()?;
    Some((equilibrium(&d.robot, &s).relative, now() - t0))
}
