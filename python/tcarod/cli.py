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
(one design: that design's document). A design's document is
``Solution.to_dict()`` (:func:`tcarod.io.results.solution_dict`: shape,
strains, internal wrench, inputs with their units, tensions, the stability
verdict ``stable`` / ``stability_margin``, solver counts, version) plus
``design`` (the file), ``temperature_c``, ``stability_policy``,
``continued_route`` (``null`` unless ``--stability continue`` moved the
shape), ``png_path`` and ``output_paths``.

``--stability`` sets what a solve does with an unstable equilibrium (a
shape the robot cannot hold): ``report`` (default) prints a warning and
goes on, ``continue`` moves to a stable equilibrium at the same
temperatures, ``require`` stops with exit status 3, ``off`` computes no
verdict (``stable`` is ``null``). ``--output FILE`` (repeatable) writes the
shape, the format chosen by the suffix (``.json``, ``.csv``, ``.vtu``,
``.vtk``; see :func:`tcarod.io.write_shape`); with several designs FILE
must contain ``{design}``, replaced by each design file's name.

Warnings are printed as one line ``tcarod: warning: ...`` on stderr.

Exit status: 0 on success; 2 on bad arguments, on a ``ValueError`` or
``tcarod.ConvergenceError`` from the model, if an output cannot be written, or
if an optional package is missing (one line on stderr naming the extra to
install, no traceback); 3 if ``--stability require`` meets an unstable
equilibrium. A closed output pipe (``tcarod ... --json | head``)
ends the command quietly with status 1, as other Unix tools do.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path
from typing import Any, Sequence

from . import __version__
from ._core import ConvergenceError, UnstableEquilibriumWarning
from ._optional import MissingDependencyError, require
from .io.results import SHAPE_SUFFIXES, dumps_json
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
        "--json",
        action="store_true",
        help="print one JSON document: Solution.to_dict() (shape, strains, tensions, stability, "
        "solver counts; keys carry their units) plus the design, PNG and output paths",
    )
    sol.add_argument(
        "--stability",
        choices=STABILITY_CHOICES,
        default="report",
        help="what to do with an unstable equilibrium (a shape the robot cannot hold): report it in a "
        "warning (default), continue to a stable one, require stability (exit status 3), or off "
        "(no verdict)",
    )
    sol.add_argument(
        "--output",
        "-o",
        action="append",
        default=[],
        metavar="FILE",
        help=f"write the shape to FILE, format by suffix ({', '.join(SHAPE_SUFFIXES)}; .vtu/.vtk need "
        "tcarod[export]); repeatable; with several designs FILE must contain {design}",
    )


#: ``--stability`` values: the policies of ``Robot.solve``.
STABILITY_CHOICES = ("report", "continue", "require", "off")
#: Exit status when ``--stability require`` meets an unstable equilibrium.
EXIT_UNSTABLE = 3


class UnstableDesignError(Exception):
    """``--stability require`` met an unstable equilibrium (exit status 3)."""


def _solve_designs(
    paths: Sequence[str],
    temperatures: Sequence[float] | None,
    out_dir: Path,
    as_json: bool,
    stability: str = "report",
    outputs: Sequence[str] = (),
) -> int:
    """Solve each design in turn; one JSON document (a list if several)."""
    if len(paths) > 1 and any("{design}" not in o for o in outputs):
        raise ValueError("--output: with several designs each FILE must contain {design} (the design's name)")
    for o in outputs:
        if Path(o).suffix.lower() not in SHAPE_SUFFIXES:
            raise ValueError(f"--output: {o!r} must end in one of {', '.join(SHAPE_SUFFIXES)}")
        if Path(o).suffix.lower() in (".vtu", ".vtk"):
            require("meshio")  # say so before any work
    require("matplotlib")  # the PNG needs the plot extra: say so before any work
    emit = not as_json or len(paths) == 1
    docs = [_solve_design(p, temperatures, out_dir, as_json, emit, stability, outputs) for p in paths]
    if as_json and len(paths) > 1:
        print(dumps_json({"tcarod_version": __version__, "designs": docs}))
    return 0


def _temperatures(design_path: str, design: Any, temperatures: Sequence[float] | None) -> list[float]:
    """One temperature [C] per actuator: the file's, or ``--temperature`` (one for all, or one each)."""
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
    return temps


def _solve_design(
    design_path: str,
    temperatures: Sequence[float] | None,
    out_dir: Path,
    as_json: bool,
    emit: bool = True,
    stability: str = "report",
    outputs: Sequence[str] = (),
) -> dict[str, Any]:
    from .io.design import load_design
    from .io.results import write_shape

    design = load_design(design_path)
    temps = _temperatures(design_path, design, temperatures)
    solution = _solve_checked(design, design_path, temps, stability)
    png = out_dir / f"{Path(design_path).stem}.png"
    from .plotting import plot_solution, save_png

    save_png(plot_solution(solution), png)
    written = [write_shape(solution, o.replace("{design}", Path(design_path).stem)) for o in outputs]
    continued = solution.continued
    doc: dict[str, Any] = {
        **solution.to_dict(),
        "design": str(design_path),
        "temperature_c": temps,
        "stability_policy": stability,
        "continued_route": None if continued is None else str(continued.route),
        "png_path": str(png),
        "output_paths": [str(p) for p in written],
    }
    if as_json:
        if emit:
            print(dumps_json(doc))
    else:
        _print_summary(design_path, doc, [png, *written])
    return doc


def _solve_checked(design: Any, design_path: str, temps: list[float], stability: str) -> Any:
    """Solve with the ``--stability`` policy; an unstable equilibrium becomes
    a CLI warning (``report``) or :class:`UnstableDesignError` (``require``),
    in words that name the CLI's options."""
    policy = "report" if stability == "require" else stability
    with warnings.catch_warnings():
        # the model's own warning names Python arguments; the CLI words it below
        warnings.simplefilter("ignore", UnstableEquilibriumWarning)
        solution = design.solve(temps, stability=policy)
    if stability == "off" or solution.stable:
        return solution
    where = ", ".join(f"{x * 1e3:.2f}" for x in solution.tip_position)
    what = (
        f"{design_path}: the equilibrium found at {', '.join(f'{t:g}' for t in temps)} C (tip at {where} mm) "
        f"is unstable (stability margin {solution.stability_margin:.3g} < 0): a shape the robot cannot hold"
    )
    if stability == "require":
        raise UnstableDesignError(f"{what} (--stability require); --stability continue moves to a stable one")
    warnings.warn(f"{what}; --stability continue moves to a stable one", UnstableEquilibriumWarning, stacklevel=1)
    return solution


def _print_summary(design_path: str, doc: dict[str, Any], written: Sequence[Path]) -> None:
    """The human-readable report of one solved design."""
    n = len(doc["inputs"])
    print(f"design: {design_path} ({n} actuators)")
    print("temperatures [C]: " + ", ".join(f"{t:g}" for t in doc["temperature_c"]))
    print("tip position [mm]: " + ", ".join(f"{x * 1e3:.4f}" for x in doc["tip_position_m"]))
    print("tip tangent [-]:   " + ", ".join(f"{row[2]:.6f}" for row in doc["tip_rotation"]))
    print("tensions [mN]:     " + ", ".join(f"{float(x) * 1e3:.3f}" for x in doc["tensions_n"]))
    if doc["stable"] is None:
        print("stability:         not computed (--stability off)")
    else:
        verdict = "stable" if doc["stable"] else "UNSTABLE"
        print(f"stability:         {verdict} (margin {doc['stability_margin']:.3g})")
    if doc["continued_route"] is not None:
        print(f"continued:         {doc['continued_route']}")
    for path in written:
        print(f"wrote {path}")


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
    """Run the command line; return the exit status (0 ok, 2 error, 3 unstable
    under ``--stability require``, 1 closed pipe)."""
    try:
        with warnings.catch_warnings():  # restores the warning display on return
            warnings.showwarning = _show_warning
            status = _main(argv)
        sys.stdout.flush()  # a closed pipe shows here, inside the handler
        return status
    except BrokenPipeError:
        _silence_stdout()
        return 1


def _show_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: Any = None,
    line: str | None = None,
) -> None:
    """One line per warning, ``tcarod: warning: ...``: a command-line user
    has no use for the source line that raised it."""
    text = " ".join(str(message).split())
    print(f"tcarod: warning: {text} ({category.__name__})", file=sys.stderr if file is None else file)


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
            return _solve_designs(
                args.designs, args.temperature, Path(args.out), args.json, args.stability, args.output
            )
        if args.command == "bench":
            from .bench import run as _run_bench

            return _run_bench(args)
    except MissingDependencyError as exc:
        print(f"tcarod: error: {exc}", file=sys.stderr)
        return 2
    except UnstableDesignError as exc:
        print(f"tcarod: error: {exc}", file=sys.stderr)
        return EXIT_UNSTABLE
    except BrokenPipeError:
        raise
    except (ValueError, ConvergenceError, OSError) as exc:
        message = " ".join(str(exc).split())  # one line
        print(f"tcarod: error: {type(exc).__name__}: {message}", file=sys.stderr)
        return 2
    raise AssertionError(f"unhandled command {args.command!r}")  # argparse restricts commands


if __name__ == "__main__":
    sys.exit(main())
