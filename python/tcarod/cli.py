"""Command line: ``tcarod reproduce [NAME ...] [--out DIR] [--json]`` and
``tcarod solve DESIGN.toml [--temperature T [T ...]] [--out DIR] [--json]``.

``tcarod reproduce fig5`` prints the predicted table of the paper's Fig. 5 and
writes ``DIR/fig5.png`` (default ``DIR`` = ``tcarod-output``). Without a name,
every registered experiment (:data:`tcarod.experiments.REGISTRY`) is run.

With ``--json`` the only output on stdout is one JSON document::

    {"tcarod_version": "...",
     "experiments": {"fig5": {<Fig5Result.to_json()>, "png_path": "..."}}}

whose keys carry their units (``temperature_c`` in C, ``displacement_m`` in m,
``force_per_half_n`` in N, ``mass_kg`` in kg); ``null`` where a value does not
exist (e.g. ``onset_temperature_c`` with no onset in range, ``published_data``
when the paper prints none).

Exit status: 0 on success; 2 on bad arguments, on a ``ValueError`` or
``tcarod.ConvergenceError`` from the model, or if an output cannot be written
(one line on stderr, no traceback).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any, Sequence

from . import __version__
from ._core import ConvergenceError
from .experiments import REGISTRY, ExperimentResult

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
        help="predict the paper's experiments: print a table, write a PNG",
        description="Predict the paper's experiments: print a table per experiment and write "
        "DIR/NAME.png. Without NAME, run every registered experiment.",
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
        help=f"directory for the PNG files (default: {DEFAULT_OUT_DIR}/)",
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
    """``tcarod solve DESIGN.toml --temperature T [T ...]`` (see :mod:`tcarod.design`)."""
    sol = sub.add_parser(
        "solve",
        help="solve a robot design file (TOML) at given temperatures: print the tip pose, write a plot",
        description="Load DESIGN.toml (see tcarod.design), solve the forward kinetostatics at the "
        "given temperatures [C] (one per actuator, or one for all; default: the file's "
        "temperatures_c), print the tip pose and write DIR/<design name>.png.",
    )
    sol.add_argument("design", metavar="DESIGN.toml", help="robot design file")
    sol.add_argument("--temperature", "-T", nargs="+", type=float, metavar="T",
                     help="temperature [C] of each actuator, or one for all")
    sol.add_argument("--out", metavar="DIR", default=DEFAULT_OUT_DIR,
                     help=f"directory for the PNG (default: {DEFAULT_OUT_DIR}/)")
    sol.add_argument("--json", action="store_true",
                     help="print one JSON document (tip position in m, rotation, tensions in N)")


def _solve_design(design_path: str, temperatures: Sequence[float] | None, out_dir: Path, as_json: bool) -> int:
    from .design import load_design

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
    else:
        raise ValueError(f"--temperature: expected 1 or {n} values (one per actuator), got {len(temperatures)}")
    solution = design.solve(temps)
    png = out_dir / f"{Path(design_path).stem}.png"
    from . import plotting

    plot = getattr(plotting, "plot_solution", None)
    if plot is not None:
        fig = plot(solution)
    else:  # pragma: no cover - plot_solution is part of tcarod.plotting
        raise RuntimeError("tcarod.plotting.plot_solution is missing")
    plotting.save_png(fig, png)
    tip = [float(x) for x in solution.tip_position]
    rot = [[float(x) for x in row] for row in solution.tip_rotation]
    if as_json:
        doc = {
            "tcarod_version": __version__,
            "design": str(design_path),
            "temperature_c": temps,
            "tip_position_m": tip,
            "tip_rotation": rot,
            "tensions_n": [float(x) for x in solution.tensions],
            "iterations": int(solution.iterations),
            "png_path": str(png),
        }
        print(json.dumps(doc, indent=2, allow_nan=False))
    else:
        print(f"design: {design_path} ({n} actuators)")
        print("temperatures [C]: " + ", ".join(f"{t:g}" for t in temps))
        print("tip position [mm]: " + ", ".join(f"{x * 1e3:.4f}" for x in tip))
        print("tip tangent [-]:   " + ", ".join(f"{row[2]:.6f}" for row in rot))
        print("tensions [mN]:     " + ", ".join(f"{float(x) * 1e3:.3f}" for x in solution.tensions))
        print(f"wrote {png}")
    return 0


def _reproduce(names: Sequence[str], out_dir: Path, as_json: bool) -> int:
    results: dict[str, tuple[ExperimentResult, Path]] = {}
    for name in names or sorted(REGISTRY):
        result = REGISTRY[name]()
        png = result.plot(out_dir / f"{name}.png")
        results[name] = (result, png)
    if as_json:
        doc: dict[str, Any] = {
            "tcarod_version": __version__,
            "experiments": {
                name: {**result.to_json(), "png_path": str(png)} for name, (result, png) in results.items()
            },
        }
        # allow_nan=False: a NaN would make the document invalid JSON; fail loudly instead.
        print(json.dumps(doc, indent=2, allow_nan=False))
    else:
        for result, png in results.values():
            print(result.table())
            print(f"wrote {png}")
            print()
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status (0 ok, 2 error)."""
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
            return _solve_design(args.design, args.temperature, Path(args.out), args.json)
        if args.command == "bench":
            from .bench import run as _run_bench

            return _run_bench(args)
    except (ValueError, ConvergenceError, OSError) as exc:
        message = " ".join(str(exc).split())  # one line
        print(f"tcarod: error: {type(exc).__name__}: {message}", file=sys.stderr)
        return 2
    raise AssertionError(f"unhandled command {args.command!r}")  # argparse restricts commands


if __name__ == "__main__":
    sys.exit(main())
