"""Solver speed on the solver's target cases, from the public Python API.

Run as a script (``python benches/solve_speed.py [--repeats N] [--json]``).
Cases (100 RK4 steps, default tolerances, one thread, and the API's default
stability verdict, ``stability="report"``: one tangent integration per solve
on top of the solve itself):

* ``fig6_cold``: Fig. 6 square manipulator (40 mm, upright, gravity), both
  TCA legs at 100 C, solved from the straight guess (target <= 200 us);
* ``fig6_warm``: the same, warm-started from the solution at 95 C (target
  <= 3 full-grid IVP times);
* ``fig6_jc`` / ``fig6_jc_exact``: J and C (eqs 39-42) at the 100 C
  solution, both legs one variable, by forward differences (the paper's) and
  from the tangent IVP (``_core.sensitivities(..., "exact")``; the
  ``tcarod.inverse`` wrapper offers the difference schemes only) (target
  <= 3 IVP times);
* ``grasp_1g``: Table I grasp temperature for 1 g (target <= 1 ms);
* ``steel_cold``: the steel tendon robot (L 0.5 m, r 1 mm, E 200 GPa, G 80
  GPa, 8000 kg/m^3, gravity 9.81 m/s^2 along base-frame +x, four straight
  tendons at 15.06 mm offset at 0/90/180/270 deg to the tip), tensions
  15/0/0/0 N, from the straight guess (target <= 300 us);
* ``steel_warm``: the same after +1 % tension, warm-started (target <= 300 us).

Contenders are interleaved: each repeat runs every case once, in turn, so
that a change of machine load hits all of them alike. Each sample is the
``time.thread_time()`` of enough back-to-back calls to last >= 2 ms, divided
by the calls; the table shows the median over repeats. IVP counts are
``Solution.evaluations`` (``InverseResult.evaluations`` for the grasp's
blocked solve). The "IVP" reference time of the Fig. 6 robot is the Rust
row ``ivp`` of ``tcarod bench`` (one full-grid IVP at the 100 C solution),
interleaved with the rest as one more case; that row is timed in wall time by
Rust, so it is converted to thread-CPU time by the ratio of this thread's CPU
time to the wall time of the whole call (which includes the row's set-up, a
cold solve: +2-3 %). The load average is printed before and after. No test
asserts these times.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from typing import Any, Callable

from tcarod import Robot, Solution, _core
from tcarod.models.grasp import grasp
from tcarod.inverse import jacobian_and_compliance
from tcarod.models.manipulators import square_manipulator

#: Temperature [C] of the Fig. 6 cases and the warm start's offset [C].
FIG6_TEMPERATURE_C = 100.0
WARM_STEP_C = 5.0
#: Tensions [N] of the steel tendon robot's four tendons.
STEEL_TENSIONS_N = list(_core.fixture_constants()["steel_tendon_tensions"])
STEPS = 100
#: Minimum CPU time of one sample [s].
MIN_SAMPLE_S = 2e-3


def steel_tendon_robot() -> Robot:
    """The steel tendon robot (the core's fixture; see the module docstring)."""
    return _core.fixture_tendon_robot("steel")


def sample(fn: Callable[[], Any]) -> tuple[float, Any]:
    """Thread-CPU time [s] per call of ``fn`` over >= MIN_SAMPLE_S, and its last result."""
    calls = 0
    t0 = time.thread_time()
    while True:
        out = fn()
        calls += 1
        dt = time.thread_time() - t0
        if dt >= MIN_SAMPLE_S:
            return dt / calls, out


def ivp_cpu() -> tuple[float, None]:
    """Thread-CPU time [s] of one full-grid IVP of the Fig. 6 square (see the module docstring)."""
    c0, w0 = time.thread_time(), time.perf_counter()
    runs = _core.bench_time("ivp", 1, 0.02)
    c1, w1 = time.thread_time(), time.perf_counter()
    return runs[0] * (c1 - c0) / (w1 - w0), None


def cases() -> dict[str, tuple[Callable[[], Any], Callable[[Any], int], str]]:
    """name -> (operation, IVP count of its result, what the target is)."""
    sq = square_manipulator(0.040)
    t = [FIG6_TEMPERATURE_C] * 2
    warm = sq.solve([FIG6_TEMPERATURE_C - WARM_STEP_C] * 2, steps=STEPS)
    sol100 = sq.solve(t, steps=STEPS)
    steel = steel_tendon_robot()
    steel_sol = steel.solve(STEEL_TENSIONS_N, steps=STEPS)
    steel_up = [1.01 * x for x in STEEL_TENSIONS_N]

    def evals(s: Solution) -> int:
        return int(s.evaluations)

    return {
        "fig6_cold": (lambda: sq.solve(t, steps=STEPS), evals, "<= 200 us"),
        "fig6_warm": (lambda: sq.solve(t, steps=STEPS, warm_start=warm), evals, "<= 3 IVP"),
        "fig6_jc": (lambda: jacobian_and_compliance(sol100, groups=[0, 0]), lambda _: -1, "<= 3 IVP"),
        "fig6_jc_exact": (lambda: _core.sensitivities(sol100, [0, 0], "exact"), lambda _: -1, "<= 3 IVP"),
        "grasp_1g": (lambda: grasp(1e-3, steps=STEPS), lambda g: int(g.blocked.evaluations), "<= 1 ms"),
        "steel_cold": (lambda: steel.solve(STEEL_TENSIONS_N, steps=STEPS), evals, "<= 300 us"),
        "steel_warm": (lambda: steel.solve(steel_up, steps=STEPS, warm_start=steel_sol), evals, "<= 300 us"),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="interleaved rounds (default 7)")
    parser.add_argument("--json", action="store_true", help="also print one JSON line")
    args = parser.parse_args()
    load_before = os.getloadavg()
    ops = cases()
    times: dict[str, list[float]] = {k: [] for k in ops}
    ivps: dict[str, int] = {}
    for k, (fn, _, _) in ops.items():  # warm-up: first call of each
        fn()
    ivp_times: list[float] = []
    for _ in range(args.repeats):
        ivp_times.append(ivp_cpu()[0])
        for k, (fn, count, _) in ops.items():
            dt, out = sample(fn)
            times[k].append(dt)
            ivps[k] = count(out)
    ivp_s = statistics.median(ivp_times)
    load_after = os.getloadavg()
    print(
        f"load average before {load_before[0]:.2f} {load_before[1]:.2f} {load_before[2]:.2f}, "
        f"after {load_after[0]:.2f} {load_after[1]:.2f} {load_after[2]:.2f}; {os.cpu_count()} CPUs"
    )
    print(f"Fig. 6 square: one full-grid IVP (Rust row 'ivp', CPU) {ivp_s * 1e6:.1f} us")
    print(f"{'case':<14} {'median':>10} {'min':>10} {'IVPs':>5} {'xIVP':>6}  target")
    rows = []
    for k, (_, _, target) in ops.items():
        med = statistics.median(times[k])
        ratio = med / ivp_s if k.startswith("fig6") else float("nan")
        n = ivps[k]
        print(
            f"{k:<14} {med * 1e6:8.1f}us {min(times[k]) * 1e6:8.1f}us {n if n >= 0 else '-':>5} {ratio:6.2f}  {target}"
        )
        rows.append({"case": k, "median_s": med, "min_s": min(times[k]), "ivps": n, "target": target})
    if args.json:
        doc = {
            "bench": "solve_speed",
            "repeats": args.repeats,
            "ivp_s": ivp_s,
            "load_before": load_before,
            "load_after": load_after,
            "rows": rows,
        }
        print("JSON " + json.dumps(doc))


if __name__ == "__main__":
    main()
