//! Issue-10 benchmark: cold solves of the seeded random designs of
//! `tcarod::problems` (`cargo bench --bench designs`).
//!
//! Environment: `TCAROD_DESIGNS` (default 1000) designs, `TCAROD_SEED`
//! (default `problems::DEFAULT_SEED`), `TCAROD_VERBOSE=1` lists each failure
//! and each equilibrium residual above the target; diagnostics:
//! `TCAROD_ONLY=3,17` solves only these designs, `TCAROD_STEPS` sets the RK4 steps,
//! `TCAROD_TIPS=1` prints every converged design's tip position,
//! `TCAROD_LIST=1` lists every converged design (index, IVP-equivalents,
//! IVPs, iterations, homotopy steps). `TCAROD_EQUILIBRIUM_TOL=1e-8` solves
//! every design with that `SolveOptions::equilibrium_tol` (the grid refined
//! until the global equilibrium check holds; the accuracy target),
//! so that the statistics are those of the controlled solve (IVP-equivalents
//! stay in units of one plain IVP on the `TCAROD_STEPS` grid).
//!
//! Each design is solved once from the reference (straight) guess with the
//! default `SolveOptions` (100 RK4 steps, tol 1e-10, max_iter 50 per Newton
//! run), the solver's own fallback (homotopy continuation) included; the
//! count of converged solves that needed it is printed. IVPs are
//! `Solution.evaluations` (a tangent IVP, which carries the Jacobian, counts
//! as one); IVP-equivalents are the solve's CPU time over the CPU time of one
//! plain IVP of the same design at its solution (mean of 5). Times are thread-CPU
//! times from `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` (declared here: no
//! `libc` dependency), or wall time from `Instant` where that is unavailable. Prints a table and one `JSON ` line.
use std::time::Instant;

use tcarod::problems::{equilibrium, random_design, Design, DEFAULT_SEED, EQUILIBRIUM_TOL};
use tcarod::shooting::{solve, Loads, Shot, SolveOptions};
use tcarod::Error;

#[path = "clock/mod.rs"]
mod clock;
use clock::thread_cpu;

/// Quantile `q` of sorted data (nearest rank).
fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
    sorted[k - 1]
}

fn sorted(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v
}

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

/// A converged solve: IVPs (`Solution.evaluations`), iterations, equilibrium
/// residual, IVP-equivalents (CPU time / CPU time of one plain IVP at the
/// solution), whether continuation was needed.
struct Converged {
    ivps: usize,
    iterations: usize,
    equilibrium: f64,
    ivp_equivalents: f64,
    /// Homotopy steps taken (0: the direct Newton run converged).
    continuation_steps: usize,
}

struct Outcome {
    index: usize,
    past: bool,
    cpu: f64,
    result: Result<Converged, String>,
    /// For converged designs above the equilibrium target: the cold solve
    /// again with `equilibrium_tol` = the target (the grid refined until the
    /// check holds), its equilibrium error and its IVP-equivalents (`None`:
    /// below the target, or the controlled solve failed).
    fine: Option<(f64, f64)>,
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
        out.push(solve_one(&d, &opts, verbose, only.is_some(), &now));
    }
    let wall = wall.elapsed().as_secs_f64();
    report(&out, n, seed, clock, wall);
}

/// Solve design `d` cold, time it, check its equilibrium (and, above the
/// target, solve it again with the grid refined until the check holds).
fn solve_one(
    d: &Design,
    opts: &SolveOptions,
    verbose: bool,
    diagnose: bool,
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
            // one plain IVP at the solution, 5 times
            let loads = Loads::of(&d.robot);
            let t1 = now();
            for _ in 0..5 {
                let _ = std::hint::black_box(
                    Shot::new(&d.robot, &d.inputs, &loads, opts.steps)
                        .residual(&sol.unknowns, false),
                );
            }
            let ivp = (now() - t1) / 5.0;
            let fine = (eq.relative > EQUILIBRIUM_TOL)
                .then(|| controlled(d, &opts, now))
                .flatten()
                .map(|(e, cpu)| (e, cpu / ivp));
            Ok((
                Converged {
                    ivps: sol.evaluations,
                    iterations: sol.iterations,
                    equilibrium: eq.relative,
                    ivp_equivalents: cpu / ivp,
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

/// The benchmark's statistics over all outcomes.
struct Stats<'a> {
    ok: Vec<&'a Converged>,
    via_cont: usize,
    not_past: usize,
    ok_not_past: usize,
    ivp: Vec<f64>,
    it: Vec<f64>,
    eq: Vec<f64>,
    ive: Vec<f64>,
    cpu: Vec<f64>,
    cpu_ok: Vec<f64>,
    /// (reason, count, of them past buckling)
    fails: Vec<(String, usize, usize)>,
    eq_bad: usize,
}

fn stats(out: &[Outcome]) -> Stats<'_> {
    let ok: Vec<&Converged> = out.iter().filter_map(|o| o.result.as_ref().ok()).collect();
    let via_cont = ok.iter().filter(|c| c.continuation_steps > 0).count();
    let not_past = out.iter().filter(|o| !o.past).count();
    let ok_not_past = out.iter().filter(|o| !o.past && o.result.is_ok()).count();
    let ivp = sorted(ok.iter().map(|r| r.ivps as f64).collect());
    let it = sorted(ok.iter().map(|r| r.iterations as f64).collect());
    let eq = sorted(ok.iter().map(|r| r.equilibrium).collect());
    let ive = sorted(ok.iter().map(|r| r.ivp_equivalents).collect());
    let cpu = sorted(out.iter().map(|o| o.cpu).collect());
    let cpu_ok = sorted(
        out.iter()
            .filter(|o| o.result.is_ok())
            .map(|o| o.cpu)
            .collect(),
    );
    let mut fails: Vec<(String, usize, usize)> = Vec::new();
    for o in out {
        if let Err(r) = &o.result {
            match fails.iter_mut().find(|f| &f.0 == r) {
                Some(f) => {
                    f.1 += 1;
                    f.2 += usize::from(o.past);
                }
                None => fails.push((r.clone(), 1, usize::from(o.past))),
            }
        }
    }
    fails.sort_by_key(|f| std::cmp::Reverse(f.1));
    let eq_bad = eq.iter().filter(|&&x| x > EQUILIBRIUM_TOL).count();
    Stats {
        ok,
        via_cont,
        not_past,
        ok_not_past,
        ivp,
        it,
        eq,
        ive,
        cpu,
        cpu_ok,
        fails,
        eq_bad,
    }
}

fn report(out: &[Outcome], n: usize, seed: u64, clock: &str, wall: f64) {
    let st = stats(out);
    let (ok, ivp, it, eq, ive) = (&st.ok, &st.ivp, &st.it, &st.eq, &st.ive);
    let (cpu, cpu_ok, fails) = (&st.cpu, &st.cpu_ok, &st.fails);
    let (not_past, ok_not_past, via_cont, eq_bad) =
        (st.not_past, st.ok_not_past, st.via_cont, st.eq_bad);
    println!("designs: {n} (seed {seed:#x}), {} past self-weight buckling; clock: {clock}; wall {wall:.1} s", n - not_past);
    println!("converged cold: {} / {n} all, {ok_not_past} / {not_past} not past buckling; {via_cont} of them via continuation", ok.len());
    println!(
        "IVPs per converged solve: median {} p90 {} p99 {} max {}",
        quantile(ivp, 0.5),
        quantile(ivp, 0.9),
        quantile(ivp, 0.99),
        quantile(ivp, 1.0)
    );
    println!(
        "IVP-equivalents (CPU of the solve / CPU of one plain IVP at its solution): median {:.1} p90 {:.1} p99 {:.1} max {:.1}",
        quantile(ive, 0.5),
        quantile(ive, 0.9),
        quantile(ive, 0.99),
        quantile(ive, 1.0)
    );
    println!(
        "iterations: median {} p90 {} p99 {} max {}",
        quantile(it, 0.5),
        quantile(it, 0.9),
        quantile(it, 0.99),
        quantile(it, 1.0)
    );
    println!(
        "CPU per solve (all) [ms]: median {:.3} p99 {:.1} max {:.1}; converged only: median {:.3} p99 {:.1} max {:.1}; total {:.1} s",
        quantile(cpu, 0.5) * 1e3,
        quantile(cpu, 0.99) * 1e3,
        quantile(cpu, 1.0) * 1e3,
        quantile(cpu_ok, 0.5) * 1e3,
        quantile(cpu_ok, 0.99) * 1e3,
        quantile(cpu_ok, 1.0) * 1e3,
        cpu.iter().sum::<f64>()
    );
    println!(
        "equilibrium (relative) of converged: median {:.1e} p99 {:.1e} max {:.1e}; {eq_bad} above {EQUILIBRIUM_TOL:.0e}",
        quantile(eq, 0.5),
        quantile(eq, 0.99),
        quantile(eq, 1.0)
    );
    let fine = sorted(out.iter().filter_map(|o| o.fine.map(|f| f.0)).collect());
    let fine_bad = fine.iter().filter(|&&x| x > EQUILIBRIUM_TOL).count();
    let fine_ive = sorted(out.iter().filter_map(|o| o.fine.map(|f| f.1)).collect());
    println!(
        "  of the {eq_bad} above: re-solved cold with equilibrium_tol {EQUILIBRIUM_TOL:.0e}: {} converged (max {:.1e}), {fine_bad} still above; IVP-equivalents median {:.1} max {:.1}",
        fine.len(),
        quantile(&fine, 1.0),
        quantile(&fine_ive, 0.5),
        quantile(&fine_ive, 1.0)
    );
    for (r, k, p) in fails.iter() {
        println!("  failed: {k:4} ({p} past buckling)  {r}");
    }
    listing(out);
    json(&st, out, n, seed);
}

/// Each failing design (index, past buckling, reason) and the 20 converged
/// designs with the most IVP-equivalents (index, IVP-equivalents, IVPs,
/// iterations, homotopy steps).
fn listing(out: &[Outcome]) {
    for o in out {
        if let Err(r) = &o.result {
            let past = if o.past { "past buckling" } else { "not past" };
            println!("  FAIL #{} ({past}): {r}", o.index);
        }
    }
    let mut worst: Vec<(usize, &Converged)> = out
        .iter()
        .filter_map(|o| o.result.as_ref().ok().map(|c| (o.index, c)))
        .collect();
    if std::env::var("TCAROD_LIST").is_ok_and(|v| v == "1") {
        for (i, c) in &worst {
            println!(
                "  DESIGN #{i} {:.1} {} {} {}",
                c.ivp_equivalents, c.ivps, c.iterations, c.continuation_steps
            );
        }
    }
    worst.sort_by(|a, b| b.1.ivp_equivalents.total_cmp(&a.1.ivp_equivalents));
    println!("  worst 20 by IVP-equivalents: #index ive ivps iterations homotopy-steps");
    for (i, c) in worst.iter().take(20) {
        println!(
            "  WORST #{i} {:.1} {} {} {}",
            c.ivp_equivalents, c.ivps, c.iterations, c.continuation_steps
        );
    }
}

/// `x` as a JSON number (`sci`: exponent form) with `digits` decimals, or
/// `null` where it is undefined (a quantile of no values: NaN).
fn jnum(x: f64, digits: usize, sci: bool) -> String {
    match (x.is_finite(), sci) {
        (false, _) => "null".to_string(),
        (true, true) => format!("{x:.digits$e}"),
        (true, false) => format!("{x:.digits$}"),
    }
}

/// The one `JSON ` line (strict JSON: an empty quantile is `null`).
fn json(st: &Stats<'_>, out: &[Outcome], n: usize, seed: u64) {
    let (ivp, ive, it, eq) = (&st.ivp, &st.ive, &st.it, &st.eq);
    let (not_past, ok_not_past, via_cont, eq_bad) =
        (st.not_past, st.ok_not_past, st.via_cont, st.eq_bad);
    let fine = sorted(out.iter().filter_map(|o| o.fine.map(|f| f.0)).collect());
    let fine_bad = fine.iter().filter(|&&x| x > EQUILIBRIUM_TOL).count();
    let fails_json: Vec<String> = st
        .fails
        .iter()
        .map(|(r, k, p)| format!("{{\"reason\":{:?},\"count\":{k},\"past_buckling\":{p}}}", r))
        .collect();
    let q = |v: &[f64], digits: usize, sci: bool| {
        [0.5, 0.9, 0.99, 1.0].map(|p| jnum(quantile(v, p), digits, sci))
    };
    let (ivp, ive, it, cpu) = (
        q(ivp, 0, false),
        q(ive, 2, false),
        q(it, 0, false),
        q(&st.cpu, 6, true),
    );
    let (eq_max, fine_max) = (
        jnum(quantile(eq, 1.0), 3, true),
        jnum(quantile(&fine, 1.0), 3, true),
    );
    println!(
        "JSON {{\"bench\":\"designs\",\"n\":{n},\"seed\":{seed},\"past_buckling\":{},\"converged\":{},\"converged_not_past\":{ok_not_past},\"not_past\":{not_past},\
\"via_continuation\":{via_cont},\"ivp\":{{\"median\":{},\"p90\":{},\"p99\":{},\"max\":{}}},\"ivp_equivalents\":{{\"median\":{},\"p90\":{},\"p99\":{},\"max\":{}}},\"iterations\":{{\"median\":{},\"max\":{}}},\
\"cpu_s\":{{\"median\":{},\"p99\":{},\"max\":{},\"total\":{:.3}}},\"equilibrium\":{{\"max\":{eq_max},\"above_tol\":{eq_bad},\"fine_resolved\":{},\"fine_above_tol\":{fine_bad},\"fine_max\":{fine_max}}},\"failures\":[{}]}}",
        n - not_past,
        st.ok.len(),
        ivp[0],
        ivp[1],
        ivp[2],
        ivp[3],
        ive[0],
        ive[1],
        ive[2],
        ive[3],
        it[0],
        it[3],
        cpu[0],
        cpu[2],
        cpu[3],
        st.cpu.iter().sum::<f64>(),
        fine.len(),
        fails_json.join(",")
    );
}
