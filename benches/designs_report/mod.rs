//! The designs benchmark's outcomes, statistics and report (table,
//! listing, the `JSON ` line, the comparison with the committed baseline);
//! `benches/designs.rs` solves and times.
use tcarod::problems::EQUILIBRIUM_TOL;

pub(crate) mod baseline;
pub(crate) mod json;
mod sweeps;
use json::{count, fixed, json, sci, Json};
pub(crate) use sweeps::{End, Step, SweepOutcome};

/// Quantile `q` of sorted data (nearest rank).
pub(crate) fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
    sorted[k - 1]
}

pub(crate) fn sorted(mut v: Vec<f64>) -> Vec<f64> {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v
}

/// Median, p90, p99 and max of sorted data as a JSON object, each with
/// `digits` decimals (`null` for no data).
pub(crate) fn quantiles(v: &[f64], digits: usize) -> Json {
    let q = |p: f64| fixed(quantile(v, p), digits);
    json!({"median": q(0.5), "p90": q(0.9), "p99": q(0.99), "max": q(1.0)})
}

/// `median p90 p99 max` of sorted data for the table.
pub(crate) fn quantile_text(v: &[f64], digits: usize) -> String {
    format!(
        "median {:.digits$} p90 {:.digits$} p99 {:.digits$} max {:.digits$}",
        quantile(v, 0.5),
        quantile(v, 0.9),
        quantile(v, 0.99),
        quantile(v, 1.0)
    )
}

/// `k / n (p %)`.
pub(crate) fn share(k: usize, n: usize) -> String {
    format!("{k} / {n} ({:.1} %)", 100.0 * k as f64 / n.max(1) as f64)
}

/// A failure's reason with each number replaced by `x`, so that failures
/// of one kind are counted together (the listing keeps each full reason).
pub(crate) fn reason_kind(reason: &str) -> String {
    let mut out = String::with_capacity(reason.len());
    let mut chars = reason.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_ascii_digit() {
            while chars
                .peek()
                .is_some_and(|d| d.is_ascii_digit() || matches!(d, '.' | 'e' | '-'))
            {
                chars.next();
            }
            out.push('x');
        } else {
            out.push(c);
        }
    }
    out
}

/// A converged solve: IVPs (`Solution.evaluations`, the solver's own
/// count), iterations, equilibrium residual, IVP-equivalents (CPU time / CPU
/// time of one plain IVP at the solution), whether continuation was needed.
pub(crate) struct Converged {
    pub(crate) ivps: usize,
    pub(crate) iterations: usize,
    pub(crate) equilibrium: f64,
    pub(crate) ivp_equivalents: f64,
    /// Homotopy steps taken (0: the direct Newton run converged).
    pub(crate) continuation_steps: usize,
}

pub(crate) struct Outcome {
    pub(crate) index: usize,
    pub(crate) past: bool,
    /// Whether the design has gravity.
    pub(crate) gravity: bool,
    /// `hanging`, `upright`, `horizontal` (`problems::Orientation`) or
    /// `none` (no gravity).
    pub(crate) orientation: &'static str,
    pub(crate) cpu: f64,
    pub(crate) result: Result<Converged, String>,
    /// For converged designs above the equilibrium target: the cold solve
    /// again with `equilibrium_tol` = the target (the grid refined until the
    /// check holds), its equilibrium error and its IVP-equivalents (`None`:
    /// below the target, a solver without accuracy control, or the
    /// controlled solve failed).
    pub(crate) fine: Option<(f64, f64)>,
    /// The warm sweep from the reference inputs (`None`: sweeps off).
    pub(crate) sweep: Option<SweepOutcome>,
}

/// The solver a run uses, for the report.
pub(crate) struct SolverInfo<'a> {
    /// The solver's name (`multiple`).
    pub(crate) name: &'a str,
    /// The function it calls.
    pub(crate) function: &'a str,
    /// How its `Solution.evaluations` counts IVPs.
    pub(crate) ivp_count: &'a str,
    /// Whether it reads `SolveOptions::equilibrium_tol` (accuracy control).
    pub(crate) accuracy_control: bool,
}

/// What a run was: its solver, family, seed and options, for the report's
/// header and the baseline's match.
pub(crate) struct Run<'a> {
    pub(crate) solver: SolverInfo<'a>,
    pub(crate) family: &'a str,
    pub(crate) seed: u64,
    /// RK4 steps of the solves.
    pub(crate) steps: usize,
    pub(crate) equilibrium_tol: Option<f64>,
    /// Steps of each sweep (`None`: sweeps off).
    pub(crate) sweep_steps: Option<usize>,
    pub(crate) repeat: usize,
    /// Whether only some designs were solved (`TCAROD_ONLY`).
    pub(crate) subset: bool,
    pub(crate) clock: &'a str,
    /// Wall time of the run \[s\].
    pub(crate) wall: f64,
}

/// The benchmark's statistics over all outcomes.
pub(crate) struct Stats<'a> {
    pub(crate) ok: Vec<&'a Converged>,
    pub(crate) via_cont: usize,
    pub(crate) not_past: usize,
    pub(crate) ok_not_past: usize,
    /// Designs without gravity, and of them converged.
    pub(crate) no_gravity: usize,
    pub(crate) ok_no_gravity: usize,
    pub(crate) ivp: Vec<f64>,
    pub(crate) it: Vec<f64>,
    pub(crate) eq: Vec<f64>,
    pub(crate) ive: Vec<f64>,
    /// IVP-equivalents of the converged designs not past buckling.
    pub(crate) ive_not_past: Vec<f64>,
    pub(crate) cpu: Vec<f64>,
    pub(crate) cpu_ok: Vec<f64>,
    /// (reason with its numbers as `x`, count, of them past buckling)
    pub(crate) fails: Vec<(String, usize, usize)>,
    pub(crate) eq_bad: usize,
}

pub(crate) fn stats(out: &[Outcome]) -> Stats<'_> {
    let ok: Vec<&Converged> = out.iter().filter_map(|o| o.result.as_ref().ok()).collect();
    let via_cont = ok.iter().filter(|c| c.continuation_steps > 0).count();
    let not_past = out.iter().filter(|o| !o.past).count();
    let ok_not_past = out.iter().filter(|o| !o.past && o.result.is_ok()).count();
    let no_gravity = out.iter().filter(|o| !o.gravity).count();
    let ok_no_gravity = out
        .iter()
        .filter(|o| !o.gravity && o.result.is_ok())
        .count();
    let ivp = sorted(ok.iter().map(|r| r.ivps as f64).collect());
    let it = sorted(ok.iter().map(|r| r.iterations as f64).collect());
    let eq = sorted(ok.iter().map(|r| r.equilibrium).collect());
    let ive = sorted(ok.iter().map(|r| r.ivp_equivalents).collect());
    let ive_not_past = sorted(
        out.iter()
            .filter(|o| !o.past)
            .filter_map(|o| o.result.as_ref().ok().map(|c| c.ivp_equivalents))
            .collect(),
    );
    let cpu = sorted(out.iter().map(|o| o.cpu).collect());
    let cpu_ok = sorted(
        out.iter()
            .filter(|o| o.result.is_ok())
            .map(|o| o.cpu)
            .collect(),
    );
    let mut fails: Vec<(String, usize, usize)> = Vec::new();
    for o in out {
        if let Err(r) = o.result.as_ref().map_err(|r| reason_kind(r)) {
            match fails.iter_mut().find(|f| f.0 == r) {
                Some(f) => {
                    f.1 += 1;
                    f.2 += usize::from(o.past);
                }
                None => fails.push((r, 1, usize::from(o.past))),
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
        no_gravity,
        ok_no_gravity,
        ivp,
        it,
        eq,
        ive,
        ive_not_past,
        cpu,
        cpu_ok,
        fails,
        eq_bad,
    }
}

/// Print the run's table, listing and `JSON ` line; the run's JSON object
/// (the line's content) for the baseline.
pub(crate) fn report(out: &[Outcome], run: &Run<'_>) -> Json {
    let st = stats(out);
    let n = out.len();
    let (ok, ivp, it, eq, ive) = (&st.ok, &st.ivp, &st.it, &st.eq, &st.ive);
    let (cpu, cpu_ok, fails) = (&st.cpu, &st.cpu_ok, &st.fails);
    let (not_past, eq_bad) = (st.not_past, st.eq_bad);
    println!(
        "designs: {n} ({} family, seed {:#x}); solver: {} ({}); {} past self-weight buckling, {} without gravity; clock: {}; wall {:.1} s",
        run.family,
        run.seed,
        run.solver.name,
        run.solver.function,
        n - not_past,
        st.no_gravity,
        run.clock,
        run.wall
    );
    println!(
        "converged cold: {} all; {} not past buckling; {} without gravity; {} of them via continuation",
        share(ok.len(), n),
        share(st.ok_not_past, not_past),
        share(st.ok_no_gravity, st.no_gravity),
        st.via_cont
    );
    println!(
        "IVPs: the {} solver's own count (Solution.evaluations: {}), not comparable between solvers",
        run.solver.name, run.solver.ivp_count
    );
    println!(
        "IVPs per converged solve (own count): {}",
        quantile_text(ivp, 0)
    );
    println!(
        "IVP-equivalents (CPU of the solve / CPU of one plain IVP at its solution; comparable between solvers): {}",
        quantile_text(ive, 1)
    );
    println!(
        "  of designs not past buckling: {}",
        quantile_text(&st.ive_not_past, 1)
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
    if run.solver.accuracy_control {
        println!(
            "  of the {eq_bad} above: re-solved cold with equilibrium_tol {EQUILIBRIUM_TOL:.0e}: {} converged (max {:.1e}), {fine_bad} still above; IVP-equivalents median {:.1} max {:.1}",
            fine.len(),
            quantile(&fine, 1.0),
            quantile(&fine_ive, 0.5),
            quantile(&fine_ive, 1.0)
        );
    } else {
        println!(
            "  of the {eq_bad} above: not re-solved (the {} solver does not read equilibrium_tol)",
            run.solver.name
        );
    }
    for (r, k, p) in fails.iter() {
        println!("  failed: {k:4} ({p} past buckling)  {r}");
    }
    let orientations = sweeps::orientations(out);
    let sweep = run.sweep_steps.map(|k| sweeps::report(out, k));
    listing(out);
    let doc = json(&st, out, run, orientations, sweep.unwrap_or(Json::Null));
    println!("JSON {doc}");
    doc
}

/// Each failing design (index, past buckling, reason) and the 20 converged
/// designs with the most IVP-equivalents (index, IVP-equivalents, IVPs,
/// iterations, homotopy steps).
pub(crate) fn listing(out: &[Outcome]) {
    for o in out {
        if let Err(r) = &o.result {
            let past = if o.past { "past buckling" } else { "not past" };
            println!("  FAIL #{} ({past}): {r}", o.index);
        }
    }
    let mut worst: Vec<(usize, &Converged, &str)> = out
        .iter()
        .filter_map(|o| {
            let past = if o.past { " past" } else { "" };
            o.result.as_ref().ok().map(|c| (o.index, c, past))
        })
        .collect();
    if std::env::var("TCAROD_LIST").is_ok_and(|v| v == "1") {
        for (i, c, past) in &worst {
            println!(
                "  DESIGN #{i} {:.1} {} {} {}{past}",
                c.ivp_equivalents, c.ivps, c.iterations, c.continuation_steps
            );
        }
    }
    worst.sort_by(|a, b| b.1.ivp_equivalents.total_cmp(&a.1.ivp_equivalents));
    println!(
        "  worst 20 by IVP-equivalents: #index ive ivps(own count) iterations homotopy-steps [past buckling]"
    );
    for (i, c, past) in worst.iter().take(20) {
        println!(
            "  WORST #{i} {:.1} {} {} {}{past}",
            c.ivp_equivalents, c.ivps, c.iterations, c.continuation_steps
        );
    }
}

/// The run's JSON object (strict JSON: an empty quantile is `null`): the
/// cold solves' statistics, per orientation, the sweeps'. The controlled
/// re-solves' keys (`equilibrium.fine_*`) are `null` for a solver without
/// accuracy control.
fn json(st: &Stats<'_>, out: &[Outcome], run: &Run<'_>, orient: Json, sweep: Json) -> Json {
    let fine = sorted(out.iter().filter_map(|o| o.fine.map(|f| f.0)).collect());
    let fine_bad = fine.iter().filter(|&&x| x > EQUILIBRIUM_TOL).count();
    let controlled = |v: Json| {
        if run.solver.accuracy_control {
            v
        } else {
            Json::Null
        }
    };
    let failures: Vec<Json> = st
        .fails
        .iter()
        .map(|(r, k, p)| json!({"reason": r, "count": k, "past_buckling": p}))
        .collect();
    let cpu = |q: f64| sci(quantile(&st.cpu, q), 6);
    let n = out.len();
    json!({
        "bench": "designs",
        "solver": run.solver.name,
        "family": run.family,
        "seed": run.seed,
        "n": n,
        "options": options(run),
        "past_buckling": n - st.not_past,
        "converged": st.ok.len(),
        "converged_not_past": st.ok_not_past,
        "not_past": st.not_past,
        "converged_no_gravity": st.ok_no_gravity,
        "no_gravity": st.no_gravity,
        "via_continuation": st.via_cont,
        "ivp": quantiles(&st.ivp, 0),
        "ivp_equivalents": quantiles(&st.ive, 2),
        "ivp_equivalents_not_past": quantiles(&st.ive_not_past, 2),
        "iterations": {
            "median": fixed(quantile(&st.it, 0.5), 0),
            "max": fixed(quantile(&st.it, 1.0), 0),
        },
        "cpu_s": {
            "median": cpu(0.5),
            "p99": cpu(0.99),
            "max": cpu(1.0),
            "total": fixed(st.cpu.iter().sum::<f64>(), 3),
        },
        "equilibrium": {
            "max": sci(quantile(&st.eq, 1.0), 3),
            "above_tol": st.eq_bad,
            "fine_resolved": controlled(count(fine.len())),
            "fine_above_tol": controlled(count(fine_bad)),
            "fine_max": controlled(sci(quantile(&fine, 1.0), 3)),
        },
        "failures": failures,
        "orientations": orient,
        "sweep": sweep,
        "wall_s": fixed(run.wall, 1),
    })
}

/// The options a baseline must share with a run to be compared with it.
fn options(run: &Run<'_>) -> Json {
    json!({
        "steps": run.steps,
        "equilibrium_tol": run.equilibrium_tol.map_or(Json::Null, |t| sci(t, 3)),
        "sweep_steps": run.sweep_steps,
        "repeat": run.repeat,
        "subset": run.subset,
    })
}
