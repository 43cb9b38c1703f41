//! The designs benchmark's outcomes, statistics and report (table,
//! listing, the `JSON ` line); `benches/designs.rs` solves and times.
use tcarod::problems::EQUILIBRIUM_TOL;

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

/// A converged solve: IVPs (`Solution.evaluations`), iterations, equilibrium
/// residual, IVP-equivalents (CPU time / CPU time of one plain IVP at the
/// solution), whether continuation was needed.
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
    pub(crate) cpu: f64,
    pub(crate) result: Result<Converged, String>,
    /// For converged designs above the equilibrium target: the cold solve
    /// again with `equilibrium_tol` = the target (the grid refined until the
    /// check holds), its equilibrium error and its IVP-equivalents (`None`:
    /// below the target, or the controlled solve failed).
    pub(crate) fine: Option<(f64, f64)>,
}

/// The benchmark's statistics over all outcomes.
pub(crate) struct Stats<'a> {
    pub(crate) ok: Vec<&'a Converged>,
    pub(crate) via_cont: usize,
    pub(crate) not_past: usize,
    pub(crate) ok_not_past: usize,
    pub(crate) ivp: Vec<f64>,
    pub(crate) it: Vec<f64>,
    pub(crate) eq: Vec<f64>,
    pub(crate) ive: Vec<f64>,
    /// IVP-equivalents of the converged designs not past buckling.
    pub(crate) ive_not_past: Vec<f64>,
    pub(crate) cpu: Vec<f64>,
    pub(crate) cpu_ok: Vec<f64>,
    /// (reason, count, of them past buckling)
    pub(crate) fails: Vec<(String, usize, usize)>,
    pub(crate) eq_bad: usize,
}

pub(crate) fn stats(out: &[Outcome]) -> Stats<'_> {
    let ok: Vec<&Converged> = out.iter().filter_map(|o| o.result.as_ref().ok()).collect();
    let via_cont = ok.iter().filter(|c| c.continuation_steps > 0).count();
    let not_past = out.iter().filter(|o| !o.past).count();
    let ok_not_past = out.iter().filter(|o| !o.past && o.result.is_ok()).count();
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
        ive_not_past,
        cpu,
        cpu_ok,
        fails,
        eq_bad,
    }
}

pub(crate) fn report(out: &[Outcome], n: usize, seed: u64, clock: &str, wall: f64) {
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
    let ivn = &st.ive_not_past;
    println!(
        "  of designs not past buckling: median {:.1} p90 {:.1} p99 {:.1} max {:.1}",
        quantile(ivn, 0.5),
        quantile(ivn, 0.9),
        quantile(ivn, 0.99),
        quantile(ivn, 1.0)
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
        "  worst 20 by IVP-equivalents: #index ive ivps iterations homotopy-steps [past buckling]"
    );
    for (i, c, past) in worst.iter().take(20) {
        println!(
            "  WORST #{i} {:.1} {} {} {}{past}",
            c.ivp_equivalents, c.ivps, c.iterations, c.continuation_steps
        );
    }
}

/// `x` as a JSON number (`sci`: exponent form) with `digits` decimals, or
/// `null` where it is undefined (a quantile of no values: NaN).
pub(crate) fn jnum(x: f64, digits: usize, sci: bool) -> String {
    match (x.is_finite(), sci) {
        (false, _) => "null".to_string(),
        (true, true) => format!("{x:.digits$e}"),
        (true, false) => format!("{x:.digits$}"),
    }
}

/// The one `JSON ` line (strict JSON: an empty quantile is `null`).
pub(crate) fn json(st: &Stats<'_>, out: &[Outcome], n: usize, seed: u64) {
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
    let ive_np = q(&st.ive_not_past, 2, false);
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
\"via_continuation\":{via_cont},\"ivp\":{{\"median\":{},\"p90\":{},\"p99\":{},\"max\":{}}},\"ivp_equivalents\":{{\"median\":{},\"p90\":{},\"p99\":{},\"max\":{}}},\"ivp_equivalents_not_past\":{{\"median\":{},\"p90\":{},\"p99\":{},\"max\":{}}},\"iterations\":{{\"median\":{},\"max\":{}}},\
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
        ive_np[0],
        ive_np[1],
        ive_np[2],
        ive_np[3],
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
