"""The public docstrings are numpydoc and their Examples run: what ``help()``
shows a user must be complete and must work as shown.

A walker enumerates the public objects of every entry of :data:`COVERED` (a
module's ``__all__``, or one class of the compiled core as ``module:Name``)
and the public methods and properties each class defines, and checks that

* every function, class, method and property has a one-line summary (the
  numpydoc short summary, followed by a blank line or nothing);
* every function and class has an ``Examples`` section, and a function that
  takes arguments a ``Parameters`` section;
* every property has a ``Returns`` section (its type and unit);

then runs every ``Examples`` section found as a doctest (globals ``tcarod``
and ``np``; ELLIPSIS and NORMALIZE_WHITESPACE; figures on matplotlib's Agg
canvas), in a scratch directory (examples may write files).

More modules are covered by adding one line to :data:`COVERED`.
"""

from __future__ import annotations

import doctest
import importlib
import inspect
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import tcarod

os.environ.setdefault("MPLBACKEND", "Agg")  # figures need no display

# One line per covered public module (its ``__all__``) or compiled class
# (``module:Name``).
COVERED = [
    "tcarod.batch",
    "tcarod.materials",
    "tcarod.io",
    "tcarod.io.results",
    "tcarod.plotting",
    "tcarod.plotting.solution",
    "tcarod.plotting.interactive",
    "tcarod.plotting.paper",
    "tcarod.plotting.models",
    "tcarod.plotting.batch",
    "tcarod.models.manipulators",
    "tcarod.paper",
    "tcarod.paper.fig5",
    "tcarod.paper.fig6",
    "tcarod.paper.fig8",
    "tcarod.paper.table1",
    "tcarod.paper.fig1b",
    "tcarod.paper.buckling",
    "tcarod.models.calibration",
    "tcarod.models.identification",
    "tcarod.models.studies",
    "tcarod.models.bruteforce",
    "tcarod.models.segmented",
    "tcarod.models.stability",
    "tcarod.models.trajectory",
    "tcarod.models.workspace",
    "tcarod._core:Robot.solve",
    "tcarod._core:Solution",
    "tcarod._core:InverseResult",
    "tcarod._core:BlockedResult",
    "tcarod._core:solve_batch",
    "tcarod._core:default_threads",
    "tcarod._core:bench_rows",
    "tcarod._core:bench_time",
    "tcarod._core:fixture_constants",
    "tcarod._core:fixture_manipulator",
    "tcarod._core:fixture_leg_turns",
    "tcarod._core:fixture_fig5_tca",
    "tcarod._core:fixture_fig5_half_tca",
    "tcarod._core:fixture_tendon_robot",
    "tcarod._core:stability",
    "tcarod._core:follow_branch",
    "tcarod._core:Tca",
    "tcarod.inverse",
    "tcarod.models.grasp",
    "tcarod.models.thermal",
    "tcarod.tca",
    "tcarod.rod",
    "tcarod",
]


def _section(doc: str, name: str) -> bool:
    return f"\n{name}\n{'-' * len(name)}\n" in f"\n{doc}"


def _is_property(obj: Any) -> bool:
    return isinstance(obj, property) or inspect.isgetsetdescriptor(obj) or inspect.ismemberdescriptor(obj)


def _public_members(cls: type) -> Iterator[tuple[str, Any]]:
    """Public methods and properties defined by ``cls`` itself (not inherited,
    not dataclass fields or other plain values)."""
    for name, raw in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(raw, (staticmethod, classmethod)):
            raw = raw.__func__
        if _is_property(raw) or inspect.isroutine(raw):
            yield f"{cls.__qualname__}.{name}", raw


def _resolve(entry: str) -> list[tuple[str, Any]]:
    """The (qualified name, object) pairs an entry of COVERED stands for."""
    module_name, _, attr = entry.partition(":")
    module = importlib.import_module(module_name)
    if attr:
        obj: Any = module
        for part in attr.split("."):
            obj = getattr(obj, part)
        return [(f"{module_name}.{attr}", obj)]
    out = []
    for name in module.__all__:
        obj = getattr(module, name)
        if inspect.isclass(obj) or inspect.isroutine(obj):
            out.append((f"{module_name}.{name}", obj))
    return out


def _objects() -> dict[str, tuple[str, Any]]:
    """Every covered object by qualified name, with its kind: "function",
    "class", "method" or "property"; an object reached twice (re-exported)
    is walked once."""
    seen: dict[int, str] = {}
    out: dict[str, tuple[str, Any]] = {}
    for entry in COVERED:
        for qual, obj in _resolve(entry):
            if id(obj) in seen:
                continue
            # named where it is defined, however it was reached
            if hasattr(obj, "__module__") and hasattr(obj, "__qualname__"):
                qual = f"{obj.__module__}.{obj.__qualname__}"
            seen[id(obj)] = qual
            if inspect.isclass(obj):
                out[qual] = ("class", obj)
                for mqual, member in _public_members(obj):
                    kind = "property" if _is_property(member) else "method"
                    out[f"{obj.__module__}.{mqual}"] = (kind, member)
            else:
                out[qual] = ("method" if "." in getattr(obj, "__qualname__", "") else "function", obj)
    return out


OBJECTS = _objects()


def _takes_arguments(obj: Any) -> bool:
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return True  # a compiled function without a text signature: assume so
    return any(p.name not in ("self", "cls") for p in sig.parameters.values())


@pytest.mark.parametrize("qual", sorted(OBJECTS))
def test_public_docstring_is_numpydoc(qual: str) -> None:
    kind, obj = OBJECTS[qual]
    doc = inspect.cleandoc(obj.__doc__ or "")
    assert doc, f"{qual}: no docstring"
    lines = doc.splitlines()
    assert lines[0].strip(), f"{qual}: the docstring starts with a blank line"
    assert len(lines) == 1 or not lines[1].strip(), f"{qual}: the summary is not one line followed by a blank line"
    if kind == "function" or (kind == "class" and not issubclass(obj, BaseException)):
        assert _section(doc, "Examples"), f"{qual}: no Examples section"
    if kind == "function" and _takes_arguments(obj):
        assert _section(doc, "Parameters"), f"{qual}: no Parameters section"
    if kind == "property":
        assert _section(doc, "Returns"), f"{qual}: no Returns section (type and unit)"


EXAMPLES = sorted(q for q, (_, obj) in OBJECTS.items() if _section(inspect.cleandoc(obj.__doc__ or ""), "Examples"))


def test_the_walker_finds_the_covered_api() -> None:
    # the walker really walks: the core of the batch API, a plot and a core
    # method are among what it checks, and most of it carries examples
    for name in ("tcarod.batch.solve_batch", "tcarod.batch.BatchResult", "tcarod.plotting.solution.plot_solution"):
        assert name in OBJECTS, name
    assert len(OBJECTS) > 50 and len(EXAMPLES) > 20


@pytest.mark.parametrize("qual", EXAMPLES)
def test_docstring_examples_run(qual: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    _, obj = OBJECTS[qual]
    doc = inspect.cleandoc(obj.__doc__ or "")
    test = doctest.DocTestParser().get_doctest(doc, {"tcarod": tcarod, "np": np}, qual, None, 0)
    assert test.examples, f"{qual}: an Examples section without examples"
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    try:
        runner.run(test)
    finally:
        if "matplotlib.pyplot" in __import__("sys").modules:
            import matplotlib.pyplot as plt

            plt.close("all")
    assert runner.failures == 0, f"{qual}: doctest failed (output above)"
