//! The committed baseline of the designs benchmark
//! (`benches/designs_baseline.json`: one report per solver, family and
//! seed, the `JSON ` lines' objects; an entry without `solver` is the
//! `shooting` solver's) and a run's comparison with it.
//!
//! The file is an object of `about` (what it is) and `runs` (the entries,
//! one a line). Writing it replaces the entries of the run's solver, family
//! and seeds and keeps every other entry's line as it stands.
//!
//! A run is compared with the baseline's entry of the same solver, family
//! and seed when both solved the same number of designs with the same grid,
//! accuracy control and (for the sweeps' keys) sweep steps. Each rule below
//! prints a `REGRESSION` line when the run is worse and an `IMPROVED` line
//! when it is better:
//!
//! * convergence counts (cold, not past buckling, without gravity, sweeps):
//!   any drop; the solves are deterministic, so counts are exact;
//! * IVP quantiles (cold solves, warm steps; each solver's own count): any
//!   rise; IVP counts are deterministic too (on one build and machine). A
//!   solver that converges on more designs may raise them by taking on
//!   harder designs: read them with the counts;
//! * IVP-equivalent quantiles (CPU time): a rise above [`MEDIAN_MARGIN`]
//!   (median, p90) or [`TAIL_MARGIN`] (p99, max), since times on a shared
//!   machine swing by tens of percent.
//!
//! A change in the count of sweeps ending on another equilibrium than the
//! cold solve's prints a `NOTE` (neither end is wrong).

use std::path::PathBuf;

use serde::Deserialize;

use super::json::{at, num, text, Json};

/// The solver of an entry without `solver`.
const DEFAULT_SOLVER: &str = "shooting";

/// What the file says it is (its `about`).
const ABOUT: &str = "The designs benchmark's committed report (benches/designs.rs): one entry per \
                     solver, family and seed, the content of its JSON line (an entry without \
                     solver is the shooting solver's). Each run is compared with its entry; \
                     TCAROD_WRITE_BASELINE=1 replaces the entries of the run's solver, family \
                     and seeds.";

/// The baseline file.
#[derive(Deserialize)]
struct File {
    runs: Vec<Json>,
}

/// Tolerated relative rise of the IVP-equivalents' median and p90.
pub(crate) const MEDIAN_MARGIN: f64 = 0.10;

/// Tolerated relative rise of the IVP-equivalents' p99 and max.
pub(crate) const TAIL_MARGIN: f64 = 0.25;

/// How a key is compared.
#[derive(Clone, Copy)]
enum Rule {
    /// A count that must not drop.
    Count,
    /// An IVP count that must not rise.
    Ivps,
    /// A time that must not rise by more than the margin.
    Time(f64),
}

/// The keys of the cold solves.
const COLD: [(&str, Rule); 11] = [
    ("converged", Rule::Count),
    ("converged_not_past", Rule::Count),
    ("converged_no_gravity", Rule::Count),
    ("ivp.median", Rule::Ivps),
    ("ivp.p90", Rule::Ivps),
    ("ivp.p99", Rule::Ivps),
    ("ivp.max", Rule::Ivps),
    ("ivp_equivalents.median", Rule::Time(MEDIAN_MARGIN)),
    ("ivp_equivalents.p90", Rule::Time(MEDIAN_MARGIN)),
    ("ivp_equivalents.p99", Rule::Time(TAIL_MARGIN)),
    ("ivp_equivalents.max", Rule::Time(TAIL_MARGIN)),
];

/// The keys of the sweeps.
const SWEEP: [(&str, Rule); 9] = [
    ("sweep.converged", Rule::Count),
    ("sweep.step_ivp.median", Rule::Ivps),
    ("sweep.step_ivp.p90", Rule::Ivps),
    ("sweep.step_ivp.p99", Rule::Ivps),
    ("sweep.step_ivp.max", Rule::Ivps),
    (
        "sweep.step_ivp_equivalents.median",
        Rule::Time(MEDIAN_MARGIN),
    ),
    ("sweep.step_ivp_equivalents.p90", Rule::Time(MEDIAN_MARGIN)),
    ("sweep.step_ivp_equivalents.p99", Rule::Time(TAIL_MARGIN)),
    ("sweep.step_ivp_equivalents.max", Rule::Time(TAIL_MARGIN)),
];

/// The baseline file: `TCAROD_BASELINE`, else the committed one.
pub(crate) fn path() -> PathBuf {
    std::env::var("TCAROD_BASELINE").map_or_else(
        |_| {
            PathBuf::from(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/benches/designs_baseline.json"
            ))
        },
        PathBuf::from,
    )
}

/// The baseline's runs (none if the file is missing; an unreadable file is
/// reported and counts as none).
pub(crate) fn load(path: &PathBuf) -> Vec<Json> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Vec::new();
    };
    match serde_json::from_str::<File>(&text) {
        Ok(file) => file.runs,
        Err(e) => {
            println!("BASELINE {}: unreadable ({e})", path.display());
            Vec::new()
        }
    }
}

/// The solver of a run or entry.
fn solver(run: &Json) -> &str {
    text(run, "solver").unwrap_or(DEFAULT_SOLVER)
}

/// Whether two runs are of the same solver, family and seed.
fn same_set(a: &Json, b: &Json) -> bool {
    solver(a) == solver(b)
        && text(a, "family") == text(b, "family")
        && a.get("seed") == b.get("seed")
}

/// Compare `run` with its entry in `baseline`, printing one line per rule
/// broken or bettered and a summary; the number of regressions.
pub(crate) fn compare(run: &Json, baseline: &[Json]) -> usize {
    let label = format!(
        "{} {} seed {:#x}",
        solver(run),
        text(run, "family").unwrap_or("?"),
        seed_of(run)
    );
    let Some(base) = baseline.iter().find(|b| same_set(b, run)) else {
        println!("BASELINE {label}: no entry to compare with");
        return 0;
    };
    let differs = |key: &str| at(run, key) != at(base, key);
    if at(run, "options.subset") == Some(&Json::Bool(true)) {
        println!("BASELINE {label}: a subset of the designs (TCAROD_ONLY), not compared");
        return 0;
    }
    let show = |v: Option<&Json>| v.map_or("missing".to_string(), Json::to_string);
    let mismatch: Vec<String> = ["n", "options.steps", "options.equilibrium_tol"]
        .into_iter()
        .filter(|k| differs(k))
        .map(|k| format!("{k} {} (baseline {})", show(at(run, k)), show(at(base, k))))
        .collect();
    if !mismatch.is_empty() {
        println!("BASELINE {label}: not comparable: {}", mismatch.join(", "));
        return 0;
    }
    let mut rules: Vec<(&str, Rule)> = COLD.to_vec();
    if differs("options.sweep_steps") {
        println!("BASELINE {label}: sweep steps differ, sweeps not compared");
    } else {
        rules.extend(SWEEP);
        let key = "sweep.other_equilibrium";
        if let (Some(a), Some(b)) = (num(base, key), num(run, key)) {
            if a != b {
                println!("NOTE {label}: {key} {a} -> {b}");
            }
        }
    }
    let (mut worse, mut better) = (0, 0);
    for (key, rule) in rules {
        let (Some(a), Some(b)) = (num(base, key), num(run, key)) else {
            continue;
        };
        match verdict(rule, a, b) {
            Some((true, note)) => {
                worse += 1;
                println!("REGRESSION {label}: {key} {a} -> {b}{note}");
            }
            Some((false, note)) => {
                better += 1;
                println!("IMPROVED {label}: {key} {a} -> {b}{note}");
            }
            None => {}
        }
    }
    println!("BASELINE {label}: {worse} regressions, {better} improvements");
    worse
}

/// Baseline `a` against run `b` under `rule`: `Some((true, note))` worse,
/// `Some((false, note))` better, `None` within the rule.
fn verdict(rule: Rule, a: f64, b: f64) -> Option<(bool, String)> {
    match rule {
        Rule::Count => (a != b).then(|| (b < a, String::new())),
        Rule::Ivps => (a != b).then(|| (b > a, String::new())),
        Rule::Time(_) if a <= 0.0 => None,
        Rule::Time(margin) => {
            let rel = b / a - 1.0;
            let note = format!(" ({:+.0} %, margin {:.0} %)", 100.0 * rel, 100.0 * margin);
            (rel.abs() > margin).then_some((rel > 0.0, note))
        }
    }
}

/// The run's seed.
fn seed_of(run: &Json) -> u64 {
    run.get("seed").and_then(Json::as_u64).unwrap_or(0)
}

/// Write `runs` into the baseline at `path`: each replaces the entry of its
/// solver, family and seed, the other entries are kept with their lines.
pub(crate) fn write(path: &PathBuf, runs: &[Json]) -> std::io::Result<()> {
    let old = std::fs::read_to_string(path).unwrap_or_default();
    let mut all = lines(&old, load(path));
    for run in runs {
        let line = run.to_string();
        match all.iter_mut().find(|(b, _)| same_set(b, run)) {
            Some(b) => *b = (run.clone(), line),
            None => all.push((run.clone(), line)),
        }
    }
    let entries: Vec<&str> = all.iter().map(|(_, line)| line.as_str()).collect();
    let text = format!(
        "{{\"about\":{},\n\"runs\":[\n{}\n]}}\n",
        Json::from(ABOUT),
        entries.join(",\n")
    );
    std::fs::write(path, text)?;
    println!(
        "BASELINE written: {} ({} entries)",
        path.display(),
        all.len()
    );
    Ok(())
}

/// The entries `runs` of the baseline file `text`, each with its line: the
/// file's line of the entry where one holds exactly that entry, else the
/// entry written anew.
fn lines(text: &str, runs: Vec<Json>) -> Vec<(Json, String)> {
    let mut lines = text.lines().map(|l| l.trim().trim_end_matches(','));
    runs.into_iter()
        .map(|run| {
            let kept = lines
                .by_ref()
                .find(|l| serde_json::from_str::<Json>(l).is_ok_and(|v| v == run))
                .map(str::to_string);
            let line = kept.unwrap_or_else(|| run.to_string());
            (run, line)
        })
        .collect()
}
