"""Long fuzz profile of tcarod's public Python API.

    nice python benches/fuzz_long.py [--calls 100000] [--timeout 10] [--seed 0] [--workers 2]

Draws calls from the hypothesis strategies of ``tests/fuzz/strategies.py``
(the same ones as the quick profile ``tests/test_fuzz.py``), a fixed share
per entry point, after the quick profile's ``REGRESSIONS`` (calls that once
broke the contract), and runs each in
a pool of long-lived worker subprocesses (``tests/fuzz/harness.py``), each
call under a time limit: a worker that exceeds it (a hang) or dies (a crash)
is killed and replaced, and the call is recorded as such. Prints a summary
table by outcome class and by entry point, and the first reproducer of each
(entry point, violation) pair. Each entry point's share of the calls is
proportional to ``1/sqrt(relative cost)``: cheap calls are tried more often,
the expensive ones (a calibration, a workspace map, the CLI) still hundreds
of times per 100,000 calls.

Exit status: 0 if no contract violation was seen, 1 otherwise.
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import os
import select
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

TESTS = Path(__file__).resolve().parents[1] / "tests"
sys.path.insert(0, str(TESTS))

from hypothesis import HealthCheck, Phase, given, seed, settings  # noqa: E402

from fuzz.harness import ALLOWED, receive, send  # noqa: E402
from fuzz.strategies import ENTRIES, Call  # noqa: E402
from test_fuzz import REGRESSIONS  # noqa: E402

CHUNK = 5000  # calls per hypothesis run (bounds the engine's memory)
START_TIMEOUT_S = 300.0  # worker start-up: imports and fixtures, on a busy machine


class Worker:
    """One long-lived worker subprocess."""

    def __init__(self) -> None:
        env = dict(
            os.environ,
            PYTHONPATH=os.pathsep.join([str(TESTS), os.environ.get("PYTHONPATH", "")]),
            MPLBACKEND="Agg",
            PYTHONHASHSEED="0",
        )
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "fuzz.harness"],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            env=env,
            cwd=str(TESTS),
        )
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.stdin, self.stdout = self.proc.stdin, self.proc.stdout
        self.job: tuple[int, Call, float] | None = None
        ready, _, _ = select.select([self.stdout], [], [], START_TIMEOUT_S)
        if not ready or receive(self.stdout)[0] != "ready":
            self.kill()
            raise RuntimeError("a fuzz worker did not start")

    def kill(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()
        for s in (self.stdin, self.stdout):
            try:
                s.close()
            except OSError:
                pass


class Pool:
    """Workers, each with at most one call in flight."""

    def __init__(self, n: int, timeout: float) -> None:
        self.timeout = timeout
        self.workers = [Worker() for _ in range(n)]
        self.results: list[tuple[Call, str, str]] = []
        self.restarts = 0
        self.key = 0

    def submit(self, call: Call) -> None:
        while all(w.job is not None for w in self.workers):
            self.wait_one()
        w = next(w for w in self.workers if w.job is None)
        self.key += 1
        try:
            send(w.stdin, (self.key, call))
            w.job = (self.key, call, time.monotonic() + self.timeout)
        except (BrokenPipeError, OSError):
            self._replace(w, call, "crash", "worker gone before the call")

    def wait_one(self) -> None:
        busy = [w for w in self.workers if w.job is not None]
        if not busy:
            return
        now = time.monotonic()
        wait = max(0.0, min(w.job[2] for w in busy if w.job) - now)
        ready, _, _ = select.select([w.stdout for w in busy], [], [], wait)
        for w in busy:
            assert w.job is not None
            key, call, deadline = w.job
            if w.stdout in ready:
                try:
                    got, (outcome, detail) = receive(w.stdout)
                except (EOFError, OSError, ValueError):
                    code = w.proc.poll()
                    self._replace(w, call, "crash", f"worker died (exit status {code})")
                    continue
                assert got == key
                self.results.append((call, outcome, detail))
                w.job = None
            elif time.monotonic() >= deadline:
                self._replace(w, call, "hang", f"no answer within {self.timeout} s")

    def _replace(self, w: Worker, call: Call, outcome: str, detail: str) -> None:
        self.results.append((call, outcome, detail))
        w.kill()
        self.restarts += 1
        self.workers[self.workers.index(w)] = Worker()

    def drain(self) -> None:
        while any(w.job is not None for w in self.workers):
            self.wait_one()

    def close(self) -> None:
        for w in self.workers:
            w.kill()


def allocation(calls: int) -> dict[str, int]:
    """Calls per entry point, proportional to ``1/sqrt(relative cost)``, at least one each."""
    w = {e: 1.0 / math.sqrt(cost) for e, (_, cost) in ENTRIES.items()}
    total = sum(w.values())
    out = {e: max(1, round(calls * x / total)) for e, x in w.items()}
    cheapest = max(w, key=lambda e: w[e])
    out[cheapest] += max(0, calls - sum(out.values()))  # rounding: at least ``calls`` in all
    return out


def run(calls: int, timeout: float, seed_value: int, workers: int) -> tuple[Pool, float]:
    """Each entry point's share of ``calls``, drawn by hypothesis in chunks
    of at most ``CHUNK`` (entry points interleaved chunk by chunk)."""
    pool = Pool(workers, timeout)
    left = allocation(calls)
    t0 = time.perf_counter()
    round_no = 0
    try:
        # the calls that once broke the contract, before the random draws
        for call, _ in REGRESSIONS.values():
            pool.submit(call)
        while any(left.values()):
            per_round = max(1, CHUNK // len(ENTRIES))
            for k, entry in enumerate(sorted(left)):
                n = min(left[entry], max(1, round(per_round * allocation(CHUNK)[entry] / (CHUNK / len(ENTRIES)))))
                if n == 0:
                    continue
                submitted = [0]

                @seed(seed_value * 1_000_003 + round_no * 1000 + k)
                @settings(
                    max_examples=n,
                    deadline=None,
                    database=None,
                    phases=[Phase.generate],
                    suppress_health_check=list(HealthCheck),
                )
                @given(ENTRIES[entry][0])
                def chunk(call: Call) -> None:
                    pool.submit(call)
                    submitted[0] += 1

                chunk()
                if submitted[0] < n:
                    # hypothesis stopped early: it has exhausted this entry's (small) space;
                    # hand the rest of its share to the other entry points
                    spare = left[entry] - submitted[0]
                    left[entry] = 0
                    others = [e for e in left if left[e] > 0]
                    for j, e in enumerate(others if spare > 0 else []):
                        left[e] += spare // len(others) + (1 if j < spare % len(others) else 0)
                else:
                    left[entry] -= n
            pool.drain()
            round_no += 1
            print(
                f"  {len(pool.results)} calls, {time.perf_counter() - t0:.0f} s, "
                f"{sum(1 for _, o, _ in pool.results if o not in ALLOWED)} violations",
                file=sys.stderr,
                flush=True,
            )
    except KeyboardInterrupt:
        print("interrupted: summary of the calls so far", file=sys.stderr)
        pool.drain()
    finally:
        pool.close()
    return pool, time.perf_counter() - t0


COLUMNS = ["ok", "ValueError", "TypeError", "ConvergenceError", "OSError", "exit"]


def summary(pool: Pool, elapsed: float, args: argparse.Namespace) -> tuple[str, dict[str, Any]]:
    by_class: collections.Counter[str] = collections.Counter(o for _, o, _ in pool.results)
    by_entry: dict[str, collections.Counter[str]] = collections.defaultdict(collections.Counter)
    first: dict[tuple[str, str], tuple[str, str]] = {}
    for call, outcome, detail in pool.results:
        by_entry[call.entry][outcome] += 1
        if outcome not in ALLOWED and (call.entry, outcome) not in first:
            first[(call.entry, outcome)] = (repr(call), detail)
    total = len(pool.results)
    violations = sum(n for o, n in by_class.items() if o not in ALLOWED)
    lines = [
        f"tcarod long fuzz profile: {total} calls in {elapsed:.0f} s, {args.workers} worker(s), "
        f"timeout {args.timeout:g} s, seed {args.seed}, {pool.restarts} worker restarts; "
        f"load average at the end {os.getloadavg()[0]:.2f}",
        "",
        "| outcome class | calls |",
        "|---|---|",
    ]
    for o in COLUMNS + sorted(set(by_class) - set(COLUMNS)):
        tag = "" if o in ALLOWED else " (VIOLATION)"
        lines.append(f"| {o}{tag} | {by_class.get(o, 0)} |")
    lines.append(f"| **contract violations** | **{violations}** |")
    lines += [
        "",
        "| entry point | calls | " + " | ".join(COLUMNS) + " | violations |",
        "|---|---:|" + "---:|" * (len(COLUMNS) + 1),
    ]
    for e in sorted(ENTRIES):
        c = by_entry.get(e, collections.Counter())
        bad = sum(n for o, n in c.items() if o not in ALLOWED)
        bad_s = (
            str(bad) if not bad else f"{bad} (" + ", ".join(f"{o} {n}" for o, n in c.items() if o not in ALLOWED) + ")"
        )
        lines.append(f"| {e} | {sum(c.values())} | " + " | ".join(str(c.get(o, 0)) for o in COLUMNS) + f" | {bad_s} |")
    if first:
        lines += ["", "First reproducer of each (entry point, violation):"]
        for (e, o), (r, d) in sorted(first.items()):
            lines.append(f"- {o}: {r[:300]} -> {d[:200]}")
    doc = {
        "calls": total,
        "elapsed_s": elapsed,
        "by_class": dict(by_class),
        "violations": violations,
        "by_entry": {e: dict(c) for e, c in by_entry.items()},
        "first": [{"entry": e, "outcome": o, "call": r, "detail": d} for (e, o), (r, d) in sorted(first.items())],
    }
    return "\n".join(lines), doc


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--calls", type=int, default=100_000, help="number of calls (default 100000)")
    p.add_argument("--timeout", type=float, default=10.0, help="time limit per call [s] (default 10)")
    p.add_argument("--seed", type=int, default=0, help="hypothesis seed (default 0)")
    p.add_argument("--workers", type=int, default=2, help="worker subprocesses (default 2)")
    p.add_argument("--json", metavar="FILE", help="also write the summary as JSON")
    args = p.parse_args(argv)
    if args.calls < 1 or args.workers < 1 or not args.timeout > 0:
        p.error("--calls and --workers must be >= 1, --timeout > 0")
    pool, elapsed = run(args.calls, args.timeout, args.seed, args.workers)
    text, doc = summary(pool, elapsed, args)
    print(text)
    if args.json:
        Path(args.json).write_text(json.dumps(doc, indent=1), encoding="utf-8")
    return 1 if doc["violations"] else 0


if __name__ == "__main__":
    sys.exit(main())
