"""Command line: ``tcarod reproduce [NAME ...] [--out DIR] [--json]``.

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
    from .bench import add_parser as _add_bench_parser

    _add_bench_parser(sub)
    return parser


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
