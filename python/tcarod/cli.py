"""Command line: ``tcarod reproduce [NAME ...] [--out DIR] [--json]`` and
``tcarod solve DESIGN.toml [DESIGN.toml ...] [--temperature T [T ...]] [--out DIR] [--json]``.

``tcarod reproduce fig5`` prints the predicted table of the paper's Fig. 5 and
writes the figure ``DIR/fig5.png`` and the table ``DIR/fig5.txt`` (default
``DIR`` = ``tcarod-output``). Without a name, every registered experiment
(:data:`tcarod.paper.REGISTRY`) is run.

With ``--json`` the only output on stdout is one JSON document::

    {"tcarod_version": "...",
     "experiments": {"fig5": {<Fig5Result.to_json()>, "png_path": "..."}}}

whose keys carry their units (``temperature_c`` in C, ``displacement_m`` in m,
``force_per_half_n`` in N, ``mass_kg`` in kg); ``null`` where a value does not
exist (e.g. ``onset_temperature_c`` with no onset in range, ``published_data``
when the paper prints none).

``tcarod solve`` with several designs solves each in turn; with ``--json``
it prints ``{"tcarod_version": ..., "designs": [<one document per design>]}``
(one design: that design's document).

Exit status: 0 on success; 2 on bad arguments, on a ``ValueError`` or
``tcarod.ConvergenceError`` from the model, if an output cannot be written, or
if an optional package is missing (one line on stderr naming the extra to
install, no traceback). A closed output pipe (``tcarod ... --json | head``)
ends the command quietly with status 1, as other Unix tools do.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any, Sequence

from . import __version__
from ._core import ConvergenceError
from ._optional import MissingDependencyError, require
from .io.results import dumps_json, solution_json
from .paper import REGISTRY, ExperimentResult

__all__ = ["main"]

DEFAULT_OUT_DIR = "tcarod-output"


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="tcarod",
        description="Reproduce the experiments of Pawlowski et al., 'Modeling of Soft Robots "
        "Actuated by Twisted-and-Coiled Actuators', IEEE/ASME T-Mech 24(1), 2019.",
    )
    parser.add_argument("--version", action="version", version=f"tcarod {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    rep = sub.add_parser(
        "reproduce",
        help="predict the paper's experiments: print a table, write a PNG and the table",
        description="Predict the paper's experiments: print a table per experiment and write "
        "DIR/NAME.png and DIR/NAME.txt (the table). Without NAME, run every registered experiment.",
    )
    rep.add_argument(
        "names",
        nargs="*",
        metavar="NAME",
        help=f"experiment(s) to run, from: {', '.join(sorted(REGISTRY))} (default: all)",
    )
    rep.add_argument(
        "--out",
        metavar="DIR",
        default=DEFAULT_OUT_DIR,
        help=f"directory for the PNG and table files (default: {DEFAULT_OUT_DIR}/)",
    )
    rep.add_argument(
        "--json",
        action="store_true",
        help="print one machine-readable JSON document on stdout instead of the tables "
        "(temperatures in C, lengths in m, forces in N)",
    )
    _add_solve_parser(sub)
    from .bench import add_parser as _add_bench_parser

    _add_bench_parser(sub)
    return parser


def _add_solve_parser(sub: Any) -> None:
    """``tcarod solve DESIGN.toml --temperature T [T ...]`` (see :mod:`tcarod.io.design`)."""
    sol = sub.add_parser(
        "solve",
        help="solve a robot design file (TOML) at given temperatures: print the tip pose, write a plot",
        description="Load DESIGN.toml (see tcarod.io.design), solve the forward kinetostatics at the "
        "given temperatures [C] (one per actuator, or one for all; default: the file's "
        "temperatures_c), print the tip pose and write DIR/<design name>.png.",
    )
    sol.add_argument("designs", nargs="+", metavar="DESIGN.toml", help="robot design file(s)")
    sol.add_argument(
        "--temperature",
        "-T",
        nargs="+",
        type=float,
        metavar="T",
        help="temperature [C] of each actuator, or one for all",
    )
    sol.add_argument(
        "--out", metavar="DIR", default=DEFAULT_OUT_DIR, help=f"directory for the PNG (default: {DEFAULT_OUT_DIR}/)"
    )
    sol.add_argument(
        "--json", action="store_true", help="print one JSON document (tip position in m, rotation, tensions in N)"
    )


def _solve_designs(paths: Sequence[str], temperatures: Sequence[float] | None, out_dir: Path, as_json: bool) -> int:
    """Solve each design in turn; one JSON document (a list if several)."""
    require("matplotlib")  # the PNG needs the plot extra: say so before any work
    docs = [_solve_design(p, temperatures, out_dir, as_json, emit=not as_json or len(paths) == 1) for p in paths]
    if as_json and len(paths) > 1:
        print(dumps_json({"tcarod_version": __version__, "designs": docs}))
    return 0


def _solve_design(
    design_path: str, temperatures: Sequence[float] | None, out_dir: Path, as_json: bool, emit: bool = True
) -> dict[str, Any]:
    from .io.design import load_design

    design = load_design(design_path)
    n = len(design.robot.actuators)
    temps: list[float] | None
    if temperatures is None:
        temps = design.temperatures_c
        if temps is None:
            raise ValueError(f"{design_path}: no temperatures_c in the file; give --temperature T [T ...] ({n} values)")
    elif len(temperatures) == 1:
        temps = [float(temperatures[0])] * n
    elif len(temperatures) == n:
        temps = [float(t) for t in temperatures]
    elif n == 0:
        raise ValueError(f"--temperature: {design_path} has no actuators; give no temperatures")
    else:
        raise ValueError(f"--temperature: expected 1 or {n} values (one per actuator), got {len(temperatures)}")
    solution = design.solve(temps)
    png = out_dir / f"{Path(design_path).stem}.png"
    from .plotting import plot_solution, save_png

    save_png(plot_solution(solution), png)
    result = solution_json(solution)
    doc: dict[str, Any] = {
        "tcarod_version": __version__,
        "design": str(design_path),
        "temperature_c": temps,
        **result,
        "png_path": str(png),
    }
    tip, rot = result["tip_position_m"], result["tip_rotation"]
    if as_json:
        if emit:
            print(dumps_json(doc))
    else:
        print(f"design: {design_path} ({n} actuators)")
        print("temperatures [C]: " + ", ".join(f"{t:g}" for t in temps))
        print("tip position [mm]: " + ", ".join(f"{x * 1e3:.4f}" for x in tip))
        print("tip tangent [-]:   " + ", ".join(f"{row[2]:.6f}" for row in rot))
        print("tensions [mN]:     " + ", ".join(f"{float(x) * 1e3:.3f}" for x in solution.tensions))
        print(f"wrote {png}")
    return doc


def _reproduce(names: Sequence[str], out_dir: Path, as_json: bool) -> int:
    require("matplotlib")  # every experiment writes a PNG
    results: dict[str, tuple[ExperimentResult, Path]] = {}
    for name in names or sorted(REGISTRY):
        result = REGISTRY[name]()
        png = result.plot(out_dir / f"{name}.png")  # creates out_dir
        (out_dir / f"{name}.txt").write_text(result.table() + "\n", encoding="utf-8")
        results[name] = (result, png)
    if as_json:
        doc: dict[str, Any] = {
            "tcarod_version": __version__,
            "experiments": {
                name: {**result.to_json(), "png_path": str(png)} for name, (result, png) in results.items()
            },
        }
        print(dumps_json(doc))
    else:
        for result, png in results.values():
            print(result.table())
            print(f"wrote {png}")
            print()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status (0 ok, 2 error, 1 closed pipe)."""
    try:
        status = _main(argv)
        sys.stdout.flush()  # a closed pipe shows here, inside the handler
        return status
    except BrokenPipeError:
        _silence_stdout()
        return 1


def _silence_stdout() -> None:
    """After a closed pipe: point stdout at /dev/null so the interpreter's
    final flush does not print a BrokenPipeError (Python docs, signal notes)."""
    try:
        if sys.stdout is sys.__stdout__ and sys.stdout is not None:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # no real file descriptor: nothing to silence
        pass


def _main(argv: Sequence[str] | None) -> int:
    parser = _parser()
    args = parser.parse_args(argv)  # exits 2 on bad arguments
    if args.command == "reproduce":
        # validated here, not with argparse `choices`, which rejects an empty
        # `nargs="*"` list on Python < 3.12
        unknown = [n for n in args.names if n not in REGISTRY]
        if unknown:
            parser.error(f"unknown experiment {unknown[0]!r} (choose from {', '.join(sorted(REGISTRY))})")
        args.names = list(dict.fromkeys(args.names))  # drop repeats, keep order
    try:
        if args.command == "reproduce":
            return _reproduce(args.names, Path(args.out), args.json)
        if args.command == "solve":
            return _solve_designs(args.designs, args.temperature, Path(args.out), args.json)
        if args.command == "bench":
            from .bench import run as _run_bench

            return _run_bench(args)
    except MissingDependencyError as exc:
        print(f"tcarod: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        raise
    except (ValueError, ConvergenceError, OSError) as exc:
        message = " ".join(str(exc).split())  # one line
        print(f"tcarod: error: {type(exc).__name__}: {message}", file=sys.stderr)
        return 2
    raise AssertionError(f"unhandled command {args.command!r}")  # argparse restricts commands


if __name__ == "__main__":
    sys.exit(main())
