"""Measure, and write ``docs/performance.md`` from scratch.

    python benches/report.py [--warm-up-time S] [--measurement-time S] [--no-cargo] [--no-designs]
                             [--no-baseline] [--out docs/performance.md] [--data FILE] [--render-only]

(``make perf-report`` runs it with the defaults.) In one run, in this order:

1. ``cargo bench --no-run`` for the benches below (the build is not timed);
2. ``tcarod bench --json``: the rod-model table timed in Rust, the Python
   call overhead, batch throughput on 1 and 2 threads, the peak memory of a
   100,000-row batch and the ratio to the NumPy/SciPy baseline (the baseline
   needs SciPy, the ``fit`` extra; without it, or with ``--no-baseline``, it
   is left out);
3. ``python benches/solve_speed.py --json``: the solver's target cases from
   the public Python API, interleaved, in thread-CPU time;
4. the criterion benches ``tca``, ``rod``, ``grasp`` and ``stability``
   (``cargo bench --bench NAME -- --warm-up-time S --measurement-time S``),
   read back from ``target/criterion/**/new/estimates.json`` (medians and
   their 95 % confidence intervals) and, for ``stability``, its ``JSON ``
   line (the interleaved verdict-cost ratio);
5. the design benchmarks, unless ``--no-designs``: ``cargo bench --bench
   designs`` (1,000 seeded random designs solved cold) and ``cargo bench
   --bench stability_designs`` (their stability verdicts, cold against warm),
   each read from its ``JSON `` line.

The page is written from scratch each time: what is measured, the commands,
then this run's numbers with the machine (CPU model, cores), the date and the
load average before and after. ``--no-cargo`` skips steps 1, 4 and 5 and
reports whatever criterion estimates ``target/criterion`` already holds,
dated by their files. The raw results are saved to ``--data``
(``target/perf-report.json``), and ``--render-only`` rewrites the page from
them without measuring. Standard library only.
"""

from __future__ import annotations

import argparse
import datetime
import importlib.util
import json
import os
import platform
import re
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
CRITERION = ROOT / "target" / "criterion"
ROWS_RS = ROOT / "benches" / "rows" / "mod.rs"
CRITERION_BENCHES = ("tca", "rod", "grasp", "stability")

#: What each criterion benchmark outside the rod rows times (the rod rows'
#: descriptions are read from ``benches/rows/mod.rs``).
DESCRIPTIONS = {
    "batch/sweep_400_threads_1": "400-row sweep batch (`solve_batch`), 1 thread, no verdict",
    "batch/sweep_400_threads_2": "the same, 2 threads",
    "sweep/fig6_circle_presolve": "Fig. 6 circle, warm sweep 25-160 C by 5 C (28 solves), coarse-grid pre-solve",
    "sweep/fig6_circle_full_grid": "the same, full-grid Newton",
    "sweep/fig6_square_presolve": "Fig. 6 square, warm sweep 25-160 C by 5 C (28 solves), coarse-grid pre-solve",
    "sweep/fig6_square_full_grid": "the same, full-grid Newton",
    "grasp/direct": "Table I grasp temperature (1 g), direct augmented Newton solve",
    "grasp/incremental": "the same by the paper's eq-43 increments (8)",
    "grasp/direct_verdict": "direct, with the blocked finger's stability verdict",
    "grasp/incremental_verdict": "eq 43, with the stability verdict",
    "grasp/free_solve": "free solve of the finger at contact",
    "grasp/tangent": "one tangent IVP of the finger (exact shooting Jacobian)",
    "stability/solve_off": "warm solve of the Fig. 6 square at 100 C, no verdict",
    "stability/solve_report": "the same with the verdict (`Policy::Report`, the default)",
    "stability/verdict": "the verdict alone",
    "stability/tangent_ivp": "one tangent IVP (the Newton Jacobian, full grid)",
    "stability/plain_ivp": "one plain IVP",
    "stability/tan4": "tangent pass, 4 directions, tip only",
    "stability/tan6": "tangent pass, 6 directions, tip only",
    "stability/tan8": "tangent pass, 8 directions, tip only",
    "stability/tan8rec": "tangent pass, 8 directions, every node recorded (what the verdict integrates)",
    "tca_displacement_fig5_100C": "displacement from (force, T), Fig. 5 TCA at 100 C",
    "tca_force_fig5_100C": "force from (displacement, T)",
    "tca_temperature_fig5": "temperature from (force, displacement)",
    "tca_onset_temperature_fig5": "onset temperature (displacement 0)",
}


def log(msg: str) -> None:
    print(f"report: {msg}", file=sys.stderr, flush=True)


def run(cmd: list[str], env: dict[str, str] | None = None) -> tuple[str, float]:
    """Run ``cmd`` in the repository root; its stdout and wall time [s]. Raises on failure."""
    log(" ".join(cmd))
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, env=env, check=False)
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        tail = "\n".join(proc.stderr.strip().splitlines()[-20:])
        raise SystemExit(f"report: {' '.join(cmd)} failed (exit status {proc.returncode}):\n{tail}")
    log(f"  done in {dt:.0f} s")
    return proc.stdout, dt


def json_line(stdout: str, bench: str | None = None) -> dict[str, Any] | None:
    """The last ``JSON `` line of a bench's output (of those whose ``bench`` is ``bench``, if given), parsed."""
    docs = [json.loads(line[5:]) for line in stdout.splitlines() if line.startswith("JSON ")]
    docs = [d for d in docs if bench is None or d.get("bench") == bench]
    return docs[-1] if docs else None


def loadavg() -> str:
    one, five, fifteen = os.getloadavg()
    return f"{one:.2f}, {five:.2f}, {fifteen:.2f}"


def uptime() -> str:
    """``uptime``'s line, or the load average where the command is missing."""
    try:
        out = subprocess.run(["uptime"], capture_output=True, text=True, check=True).stdout.strip()
        return " ".join(out.split())
    except (OSError, subprocess.CalledProcessError):
        return f"load average: {loadavg()}"


def machine() -> dict[str, str]:
    """CPU model, cores, memory, OS and tool versions of this machine."""
    cpu = platform.processor() or platform.machine()
    mem = ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal"):
                mem = f", {int(line.split()[1]) / 1024**2:.1f} GiB RAM"
                break
    except OSError:
        pass
    logical = os.cpu_count() or 0
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else logical
    try:
        rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        rustc = "rustc not found"
    return {
        "cpu": f"{cpu}, {logical} logical CPUs ({usable} usable by this process){mem}",
        "os": f"{platform.system()} {platform.release()} ({platform.machine()})",
        "tools": f"{rustc}; Python {platform.python_version()}",
    }


def row_specs() -> dict[str, tuple[str, float]]:
    """name -> (description, target [s]) of the rows in ``benches/rows/mod.rs``."""
    pat = re.compile(r'name:\s*"([^"]+)",\s*description:\s*"([^"]+)",\s*target:\s*([0-9.eE+-]+)')
    return {m[1]: (m[2], float(m[3])) for m in pat.finditer(ROWS_RS.read_text())}


def criterion_estimates(since: float | None) -> dict[str, dict[str, Any]]:
    """Criterion's estimates under ``target/criterion`` (written at or after ``since``, if given)."""
    out: dict[str, dict[str, Any]] = {}
    for est in sorted(CRITERION.glob("**/new/estimates.json")):
        mtime = est.stat().st_mtime
        if since is not None and mtime < since:
            continue
        meta_path = est.with_name("benchmark.json")
        if not meta_path.is_file():
            continue
        meta = json.loads(meta_path.read_text())
        median = json.loads(est.read_text())["median"]
        ci = median["confidence_interval"]
        throughput = meta.get("throughput") or {}
        out[meta["full_id"]] = {
            "median_s": median["point_estimate"] * 1e-9,
            "low_s": ci["lower_bound"] * 1e-9,
            "high_s": ci["upper_bound"] * 1e-9,
            "elements": throughput.get("Elements"),
            "mtime": mtime,
        }
    return out


def in_order(keys: list[str]) -> list[str]:
    """``keys`` in the order of :data:`DESCRIPTIONS` (where "the same" refers to the row above), others last."""
    order = list(DESCRIPTIONS)
    return sorted(keys, key=lambda k: (order.index(k) if k in order else len(order), k))


def fmt_s(s: float) -> str:
    """A duration in s, ms, us or ns, with three significant digits (more above 1000 s)."""
    if s != s:  # NaN: no value
        return ""
    unit, scale = next(((u, k) for u, k in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6)) if s >= k), ("ns", 1e-9))
    v = s / scale
    return f"{v:.0f} {unit}" if v >= 100 else f"{v:.1f} {unit}" if v >= 10 else f"{v:.2f} {unit}"


def fmt_ci(e: dict[str, Any]) -> str:
    return f"{fmt_s(e['median_s'])} ({fmt_s(e['low_s'])} - {fmt_s(e['high_s'])})"


def stamp(t: float) -> str:
    return datetime.datetime.fromtimestamp(t, datetime.timezone.utc).strftime("%Y-%m-%d %H:%M %Z")


# -- the page ------------------------------------------------------------------------------------------

INTRO = """\
# Performance

<!-- Generated by `python benches/report.py` (`make perf-report`). Edit the script, not this page. -->

!!! note "A generated page"
    This page is written from scratch by `python benches/report.py` (or
    `make perf-report`), which runs the benchmarks listed below. Its numbers
    are one measurement on the machine named under
    [This measurement](#this-measurement); run the same commands for the
    numbers on yours.

## What is measured

* **The fixture.** Unless a row says otherwise: the paper's Fig. 6 square
  manipulator (40 mm, two U-shaped TCA legs, upright under gravity), both
  TCAs at 100 C, 100 RK4 steps, default tolerances, one core.
* **The build.** The Python rows time the installed `tcarod`: install it
  with the release profile of the wheel (`pip install .` or `pip install -e
  .`), not with `make install`, whose `fast` profile (no LTO) serves the
  tests. The cargo benches build with the `bench` profile (the release one).
* **Rust-timed medians.** `tcarod bench` times each row of its table inside
  the Rust core (`_core.bench_time`): a warm-up, then repeated runs of
  enough inner iterations to last `--min-time`, and the median over
  `--repeats` runs; Python's call overhead is a line of its own. The rows'
  problems are defined once, in `benches/rows/mod.rs`, and the criterion
  bench `rod` times the same closures.
* **IVP times.** One IVP is one RK4 integration of the rod from base to
  tip. A solve's cost divided by one IVP's, measured in the same run, is
  far less sensitive to the machine and its load than seconds are, so the
  targets of the solver are stated in IVP times where they can be.
* **Counted work.** Solves report their iterations and IVPs
  (`Solution.evaluations`; a tangent IVP, which carries the exact Jacobian,
  counts as one), so fewer iterations and a faster IVP are told apart.
* **Interleaving.** `benches/solve_speed.py`, the `stability` bench's first
  part, `benches/tangent.rs` and the design benchmark time their contenders
  alternately, round by round, in thread-CPU time, so a change of load hits
  all of them alike; `benches/inverse_vs_bruteforce.py` and
  `benches/numpy_baseline.py` time theirs one after the other in one
  process (medians of repeats). Criterion times wall clock.
* **Peak memory.** The 100,000-row batch runs in a fresh interpreter; the
  figure is the increase of that process's peak resident set size
  (`getrusage` `ru_maxrss`) over the batch, Rust and NumPy allocations
  alike (see `tcarod.bench`).
* **No timing assertions in tests.** Accuracy claims that come with a speed
  claim (10 RK4 steps within 1 um of a 5,000-step reference over 40-160 C)
  are tested; times are not.

## How to measure

| what | command |
|---|---|
| this page | `python benches/report.py` (`make perf-report`; `--help` for its options) |
| the rod-model table, call overhead, batch throughput and peak memory, NumPy ratio | `tcarod bench` (`--json` for a document) |
| criterion benches: TCA law, rod rows, batches and sweeps, grasp, stability verdict | `cargo bench --bench tca` (`rod`, `grasp`, `stability`); one row: `cargo bench --bench rod -- rod/ivp` |
| the solver's target cases from Python, interleaved, thread CPU | `python benches/solve_speed.py --json` |
| 1,000 seeded random designs solved cold and swept warm (IVPs, IVP-equivalents, equilibrium), against the committed baseline | `cargo bench --bench designs` (`TCAROD_SEED=tuning\|held-out`, `TCAROD_FAMILY=stress`, `TCAROD_DESIGNS`, `TCAROD_SWEEP=0`, `TCAROD_REPEAT`: see its module doc and [below](#held-out-solver-benchmark)) |
| stability verdicts over the designs, cold against warm | `cargo bench --bench stability_designs` |
| the tangent pass: hand-linearised lanes against the dual-number reference | `cargo bench --bench tangent` (`TCAROD_ROUNDS`, `TCAROD_REF=0`) |
| cold and warm solves of the speed fixtures in IVP times, interleaved, thread CPU | `cargo run --release --example fixture_costs` |
| the inverse against a brute-force optimiser (paper, Section IV) | `python benches/inverse_vs_bruteforce.py` |
| the NumPy/SciPy forward model against the core | `python benches/numpy_baseline.py` |
| a 10,000-row sweep on a Dask cluster, bit for bit against serial | `python benches/dask_batch.py` (the `dask` extra) |
| robustness of the public API (not speed) | `nice python benches/fuzz_long.py` (its last summary: `benches/fuzz_long_summary.md`) |

Criterion writes its estimates to `target/criterion/<group>/<bench>/new/estimates.json`
(nanoseconds); the benches that are not criterion's print a table and, where
noted, one `JSON ` line. On a shared machine quote the load (`uptime`) with
any number, and compare rows within one run.

### Held-out solver benchmark

`cargo bench --bench designs` solves each design cold, then sweeps it warm
from its reference inputs (TCAs at the reference temperature, tendons at zero
tension or pull) to its inputs in `TCAROD_SWEEP_STEPS` (default 10) equal
steps (`TCAROD_SWEEP=0`: cold only). The seeds have fixed roles:

* `TCAROD_SEED=tuning` (`problems::TUNING_SEED`, the set the tests use) is
  the only set a solver may be tuned on;
* `TCAROD_SEED=held-out` (the two `problems::HELD_OUT_SEEDS`) is for
  reporting only: no test and no tuning uses it, and a solver change is
  judged there after it is made;
* `TCAROD_FAMILY=stress` (`problems::STRESS_SEED`, 300 designs) draws heavy
  soft bodies, weight ratio `psi A g L^3 / (E I)` from 20 to 3,000, hanging,
  upright or horizontal with a 1-5 degree tilt.

Each set prints a table and one `JSON ` line (cold convergence over all
designs, below self-weight buckling and without gravity; per orientation;
sweeps converged and sweeps ending on another equilibrium, with both
stability verdicts; IVP and IVP-equivalent quantiles of cold solves and warm
steps) and is compared with `benches/designs_baseline.json`: `REGRESSION`
where a convergence count drops or an IVP quantile rises (both exact: the
solves are deterministic) or where IVP-equivalents rise by more than 10 %
(median, p90) or 25 % (p99, max), margins wider than the run-to-run spread of
thread-CPU ratios on a shared 2-core machine. `TCAROD_WRITE_BASELINE=1`
replaces the baseline's entries for the run's family and seeds; baseline runs
use `TCAROD_REPEAT=1` and quote `uptime`.
"""


def section_machine(meta: dict[str, Any]) -> list[str]:
    m = meta["machine"]
    lines = [
        "## This measurement",
        "",
        "| | |",
        "|---|---|",
        f"| date | {meta['date']} |",
        f"| CPU | {m['cpu']} |",
        f"| system | {m['os']} |",
        f"| tools | {m['tools']}; tcarod {meta.get('version', '?')} |",
        f"| load at the start (`uptime`) | {meta['uptime_start']} |",
        f"| load at the end | {meta['uptime_end']} |",
        f"| criterion settings | {meta['criterion']} |",
        f"| duration of `benches/report.py` | {meta['duration_s']:.0f} s (any cargo build included) |",
        "",
        "The machine may be shared: the load average above is the measure of how",
        "much. Seconds move with it; IVP times and counts move far less.",
        "",
    ]
    return lines


def section_tcarod_bench(doc: dict[str, Any] | None) -> list[str]:
    lines = ["## The rod model: `tcarod bench`", ""]
    if doc is None:
        return lines + ["Not measured in this run: `tcarod bench`.", ""]
    ivp = next((r["median_s"] for r in doc["rows"] if r["name"] == "ivp"), float("nan"))
    lines += [
        f"Rust-timed medians, one core (the IVP row: {fmt_s(ivp)}).",
        "",
        "| operation | median | IVP times | target | met |",
        "|---|---:|---:|---:|---|",
    ]
    for r in doc["rows"]:
        ok = "yes" if r["meets_target"] else "no"
        lines.append(
            f"| {r['description']} | {fmt_s(r['median_s'])} | {r['median_s'] / ivp:.2f} | {fmt_s(r['target_s'])} | {ok} |"
        )
    o = doc["python_overhead"]
    ok = "yes" if o["fraction"] < o["target_fraction"] else "no"
    lines.append(
        f"| Python call overhead on a warm solve ({fmt_s(o['python_warm_solve_s'])} from Python) "
        f"| {o['fraction'] * 100:.1f} % | | < {o['target_fraction'] * 100:.0f} % | {ok} |"
    )
    lines.append("")
    for k, v in doc["batch_throughput"].items():
        lines.append(
            f"* Batch of {v['solves']:,} sweep solves (40-140 C, no verdict), {k.replace('_', ' ')}: "
            f"{v['solves_per_s']:,.0f} solves/s ({v['seconds']:.2f} s)."
        )
    mem = doc.get("batch_memory")
    if mem is not None:
        lines.append(
            f"* Peak memory of a {mem['rows']:,}-row sweep batch returning tip poses ({mem['threads']} threads, "
            f"{mem['seconds']:.1f} s): the process's peak RSS rose by **{mem['peak_rss_increase_mb']:.1f} MB** "
            f"over the batch (to {mem['peak_rss_mb']:.1f} MB, interpreter, NumPy and tcarod included); "
            f"allocations traced by `tracemalloc` peaked at {mem['python_peak_mb']:.1f} MB "
            "(buffers Rust allocates are not traced). MB = 10^6 bytes."
        )
    nb = doc.get("numpy_baseline")
    if nb is not None:
        lines.append(
            f"* The NumPy/SciPy forward model (`benches/numpy_baseline.py`): one IVP {fmt_s(nb['numpy_ivp_s'])} "
            f"({nb['ivp_ratio']:,.0f} times the core's), a cold solve {fmt_s(nb['numpy_cold_solve_s'])} "
            f"({nb['cold_solve_ratio']:,.0f} times)."
        )
    else:
        lines.append("* NumPy/SciPy baseline: not measured in this run (needs SciPy, the `fit` extra).")
    return lines + [""]


def section_solve_speed(doc: dict[str, Any] | None) -> list[str]:
    lines = ["## The solver's target cases from Python: `benches/solve_speed.py`", ""]
    if doc is None:
        return lines + ["Not measured in this run.", ""]
    lines += [
        f"Interleaved thread-CPU medians of {doc['repeats']} rounds, through the public Python API with its "
        "defaults, so every solve includes the stability verdict (one tangent integration; the Rust rows above "
        f"time the solve alone); one full-grid IVP of the Fig. 6 square {fmt_s(doc['ivp_s'])}.",
        "",
        "| case | median | IVPs | IVP times | target |",
        "|---|---:|---:|---:|---|",
    ]
    for r in doc["rows"]:
        n = str(r["ivps"]) if r["ivps"] >= 0 else ""
        ratio = f"{r['median_s'] / doc['ivp_s']:.2f}" if r["case"].startswith("fig6") else ""
        lines.append(
            f"| `{r['case']}` | {fmt_s(r['median_s'])} | {n} | {ratio} | {r['target'].replace('<=', '&le;')} |"
        )
    return lines + [""]


def section_criterion(
    est: dict[str, dict[str, Any]], stability: dict[str, Any] | None, meta: dict[str, Any]
) -> list[str]:
    lines = ["## Criterion benches", ""]
    if not est:
        return lines + ["Not measured in this run: `cargo bench --bench rod` (and `tca`, `grasp`, `stability`).", ""]
    lines += [
        f"Medians of the criterion runs, with the 95 % confidence interval of the median; {meta['criterion_note']}",
        "",
    ]
    specs = row_specs()
    ivp = est.get("rod/ivp", {}).get("median_s")
    rod = [k for k in est if k.startswith("rod/")]
    if rod:
        lines += [
            "### Rod rows: `cargo bench --bench rod`",
            "",
            "| row | what | median (95 % CI) | IVP times | target |",
            "|---|---|---|---:|---:|",
        ]
        order = list(specs)
        for k in sorted(rod, key=lambda k: order.index(k[4:]) if k[4:] in order else len(order)):
            desc, target = specs.get(k[4:], ("", float("nan")))
            ratio = f"{est[k]['median_s'] / ivp:.2f}" if ivp else ""
            lines.append(f"| `{k[4:]}` | {desc} | {fmt_ci(est[k])} | {ratio} | {fmt_s(target)} |")
        lines.append("")
    other = [k for k in est if k.startswith(("batch/", "sweep/"))]
    if other:
        lines += [
            "### Batches and sweeps: `cargo bench --bench rod`",
            "",
            "| bench | what | median (95 % CI) | solves/s |",
            "|---|---|---|---:|",
        ]
        for k in in_order(other):
            e = est[k]
            n = e["elements"] or (28 if k.startswith("sweep/") else None)
            rate = f"{n / e['median_s']:,.0f}" if n else ""
            lines.append(f"| `{k}` | {DESCRIPTIONS.get(k, '')} | {fmt_ci(e)} | {rate} |")
        lines.append("")
    for group, title in (
        ("grasp/", "### The Table I grasp: `cargo bench --bench grasp`"),
        ("stability/", "### The stability verdict: `cargo bench --bench stability`"),
        ("tca_", "### The TCA law: `cargo bench --bench tca`"),
    ):
        keys = [k for k in est if k.startswith(group)]
        if not keys:
            continue
        lines += [title, "", "| bench | what | median (95 % CI) |", "|---|---|---|"]
        for k in in_order(keys):
            lines.append(f"| `{k}` | {DESCRIPTIONS.get(k, '')} | {fmt_ci(est[k])} |")
        lines.append("")
        if group == "stability/" and stability is not None:
            lines += [
                f"Interleaved thread-CPU medians ({stability['rounds']} rounds): the verdict adds "
                f"**{stability['report_minus_off_per_tangent']:.3f}** tangent IVPs to a warm solve "
                f"(`(report - off) / tangent IVP`, target at most 1); the verdict alone costs "
                f"{stability['verdict_per_tangent']:.3f} tangent IVPs.",
                "",
            ]
    return lines


def section_designs(doc: dict[str, Any] | None, seconds: float | None) -> list[str]:
    lines = ["## The random designs: `cargo bench --bench designs`", ""]
    if doc is None:
        return lines + [
            "Not run this time (`benches/report.py --no-designs` or `--no-cargo`); "
            "`cargo bench --bench designs` prints the table and a `JSON ` line.",
            "",
        ]

    def q(d: dict[str, Any], digits: int = 1) -> str:
        vals = [d.get(k) for k in ("median", "p90", "p99", "max")]
        return " / ".join("-" if v is None else f"{v:.{digits}f}" for v in vals)

    took = f" ({seconds:.0f} s in all)" if seconds is not None else ""
    cpu = doc["cpu_s"]
    eq = doc["equilibrium"]
    lines += [
        f"{doc['n']:,} designs (seed `{doc['seed']:#x}`), each solved once cold from the straight guess with the "
        f"default options, the solver's fallback included{took}. IVP-equivalents: the solve's thread-CPU time "
        "over that of one plain IVP of the same design at its solution (median of 3 interleaved pairs).",
        "",
        "| | value |",
        "|---|---|",
        f"| converged | {doc['converged']} of {doc['n']}; not past self-weight buckling: "
        f"{doc['converged_not_past']} of {doc['not_past']} |",
        f"| via continuation | {doc['via_continuation']} |",
        f"| IVPs per solve, median / p90 / p99 / max | {q(doc['ivp'], 0)} |",
        f"| IVP-equivalents, median / p90 / p99 / max | {q(doc['ivp_equivalents'])} |",
        f"| the same, designs not past buckling | {q(doc['ivp_equivalents_not_past'])} |",
        f"| iterations, median / max | {doc['iterations']['median']:.0f} / {doc['iterations']['max']:.0f} |",
        f"| CPU per solve, median / p99 / max | {fmt_s(cpu['median'])} / {fmt_s(cpu['p99'])} / {fmt_s(cpu['max'])} |",
        f"| CPU of all first solves | {cpu['total']:.2f} s |",
        f"| global equilibrium (relative), max | {eq['max']:.1e}; above the check's tolerance: {eq['above_tol']} |",
    ]
    if eq["fine_resolved"]:
        lines.append(
            f"| of those, re-solved with `equilibrium_tol` | {eq['fine_resolved']} converged, "
            f"{eq['fine_above_tol']} still above (max {eq['fine_max']:.1e}) |"
        )
    for f in doc["failures"]:
        lines.append(f"| failed: {f['reason']} | {f['count']} ({f['past_buckling']} past buckling) |")
    return lines + [""]


def section_verdicts(doc: dict[str, Any] | None) -> list[str]:
    lines = ["## Stability over the designs: `cargo bench --bench stability_designs`", ""]
    if doc is None:
        return lines + ["Not run this time; `cargo bench --bench stability_designs` prints the counts.", ""]
    per_tangent, per_ivp = doc["verdict_per_tangent_ivp"], doc["verdict_per_plain_ivp"]
    cost = "" if per_tangent is None else f"{per_tangent:.2f} tangent IVPs = {per_ivp:.2f} plain IVPs"
    return lines + [
        f"The same {doc['n']:,} designs, each solved cold and by a warm sweep of 8 steps from its reference "
        "inputs, both with the stability verdict (`Policy::Report`).",
        "",
        "| | value |",
        "|---|---|",
        f"| converged: cold / warm sweep | {doc['cold_converged']} / {doc['warm_converged']} |",
        f"| solutions with a verdict | {doc['with_verdict']} of {doc['solutions']} |",
        f"| stable: cold / warm | {doc['stable_cold']} / {doc['stable_warm']} |",
        f"| cold and warm tips more than 1 % of the length apart | {doc['differ']} (one of the pair unstable: "
        f"{doc['one_unstable']}; both stable: {doc['both_stable']}; both unstable: {doc['both_unstable']}) |",
        f"| still apart after both continue to a stable shape (two stable shapes) | {doc['differ_after_continue']} |",
        f"| the verdict's cost, median over the cold solutions (thread CPU) | {cost} |",
        "",
    ]


# -- the run -------------------------------------------------------------------------------------------


def tcarod_bench(baseline: bool) -> dict[str, Any]:
    cmd = [sys.executable, "-c", "import sys; from tcarod.cli import main; sys.exit(main(sys.argv[1:]))"]
    cmd += ["bench", "--json"] + ([] if baseline else ["--no-baseline"])
    out, _ = run(cmd)
    doc: dict[str, Any] = json.loads(out)
    return doc


def measure(args: argparse.Namespace) -> dict[str, Any]:
    """Run every benchmark; the raw results the page is rendered from."""
    t_start = time.time()
    meta: dict[str, Any] = {"machine": machine(), "uptime_start": uptime()}
    log(f"start: {meta['uptime_start']}")
    cargo = not args.no_cargo
    if cargo:
        names = list(CRITERION_BENCHES) + ([] if args.no_designs else ["designs", "stability_designs"])
        run(["cargo", "bench", "--no-run"] + [a for n in names for a in ("--bench", n)])

    baseline = not args.no_baseline and importlib.util.find_spec("scipy") is not None
    bench = tcarod_bench(baseline)
    meta["version"] = bench.get("tcarod_version")
    speed_out, _ = run([sys.executable, str(ROOT / "benches" / "solve_speed.py"), "--json"])

    stability: dict[str, Any] | None = None
    since: float | None = None
    crit = ["--warm-up-time", f"{args.warm_up_time:g}", "--measurement-time", f"{args.measurement_time:g}"]
    if cargo:
        since = time.time() - 1.0
        for name in CRITERION_BENCHES:
            out, _ = run(["cargo", "bench", "--bench", name, "--"] + crit)
            if name == "stability":
                stability = json_line(out, "stability")
        meta["criterion"] = f"`--warm-up-time {args.warm_up_time:g} --measurement-time {args.measurement_time:g}`"
        meta["criterion_note"] = "measured in this run."
    else:
        meta["criterion"] = "not run (`--no-cargo`): earlier estimates from `target/criterion`"
    est = criterion_estimates(since)
    if not cargo and est:
        times = [e["mtime"] for e in est.values()]
        meta["criterion_note"] = (
            f"**not measured in this run**: the estimates in `target/criterion`, written "
            f"{stamp(min(times))} to {stamp(max(times))}."
        )

    designs: dict[str, Any] | None = None
    verdicts: dict[str, Any] | None = None
    designs_s: float | None = None
    if cargo and not args.no_designs:
        out, designs_s = run(["cargo", "bench", "--bench", "designs"])
        designs = json_line(out)
        out, _ = run(["cargo", "bench", "--bench", "stability_designs"])
        verdicts = json_line(out)

    meta["uptime_end"] = uptime()
    meta["duration_s"] = time.time() - t_start
    meta["date"] = stamp(t_start)
    log(f"end: {meta['uptime_end']}")
    return {
        "meta": meta,
        "tcarod_bench": bench,
        "solve_speed": json_line(speed_out),
        "criterion": est,
        "stability": stability,
        "designs": designs,
        "designs_s": designs_s,
        "stability_designs": verdicts,
    }


def render(data: dict[str, Any]) -> str:
    """The page, from the results of :func:`measure`."""
    meta = data["meta"]
    lines = [INTRO]
    lines += section_machine(meta)
    lines += section_tcarod_bench(data["tcarod_bench"])
    lines += section_solve_speed(data["solve_speed"])
    lines += section_criterion(data["criterion"], data["stability"], meta)
    lines += section_designs(data["designs"], data["designs_s"])
    lines += section_verdicts(data["stability_designs"])
    return "\n".join(lines).rstrip() + "\n"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--warm-up-time", type=float, default=1.0, metavar="S", help="criterion warm-up [s] (default 1)")
    p.add_argument(
        "--measurement-time", type=float, default=3.0, metavar="S", help="criterion measurement [s] (default 3)"
    )
    p.add_argument("--no-cargo", action="store_true", help="run no cargo bench; report target/criterion as it is")
    p.add_argument("--no-designs", action="store_true", help="skip the two 1,000-design benchmarks")
    p.add_argument("--no-baseline", action="store_true", help="skip the NumPy/SciPy baseline of tcarod bench")
    p.add_argument("--out", type=Path, default=ROOT / "docs" / "performance.md", help="the page to write")
    p.add_argument(
        "--data",
        type=Path,
        default=ROOT / "target" / "perf-report.json",
        help="where the raw results are saved (default target/perf-report.json)",
    )
    p.add_argument(
        "--render-only", action="store_true", help="measure nothing: write the page from the results saved in --data"
    )
    args = p.parse_args(argv)
    if args.render_only:
        data = json.loads(args.data.read_text(encoding="utf-8"))
    else:
        data = measure(args)
        args.data.parent.mkdir(parents=True, exist_ok=True)
        args.data.write_text(json.dumps(data, indent=1), encoding="utf-8")
    text = render(data)
    args.out.write_text(text, encoding="utf-8")
    log(f"wrote {args.out} ({text.count(chr(10))} lines); measuring took {data['meta']['duration_s']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
