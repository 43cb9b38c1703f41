"""Notebook display without magics.

When tcarod is imported inside IPython (Jupyter), :func:`register` adds
display formatters, from Python, for

* matplotlib ``Figure`` objects (every tcarod plot returns one; in the
  inline backend, or without pyplot, a figure on the Agg canvas that
  nothing else displays): ``image/png``, so ``sol.plot()`` or
  ``plot_workspace(ws)`` as the last line of a cell shows the picture once,
  without ``%matplotlib inline`` (a ``%matplotlib`` magic, if used, installs
  its own formatter and wins);
* :class:`tcarod.Solution`: ``image/png`` (its 3-D plot) and ``text/html``
  (tip pose, inputs, tensions, iterations);
* :class:`tcarod.Robot`: ``text/html`` (body and actuators);
* :class:`tcarod.models.workspace.Workspace`: ``image/png`` (its scatter plot).

A class that defines its own ``_repr_png_`` / ``_repr_html_`` keeps it (a
type formatter would override the method, so none is registered for it).
Outside IPython nothing happens. Without matplotlib only the HTML tables are
registered.
"""

from __future__ import annotations

import html
import importlib.util
import io
import sys
from typing import Any, Callable
from . import _core

__all__ = ["register", "figure_png", "solution_html", "robot_html"]


def figure_png(fig: Any) -> bytes | None:
    """PNG bytes of a matplotlib ``Figure`` (tight bounding box, 100 dpi);
    ``None`` for a figure with no axes (nothing to show)."""
    if not getattr(fig, "axes", None):
        return None
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, bbox_inches="tight")
    return buf.getvalue()


def _plot_solution(sol: Any, **kwargs: Any) -> Any:
    """``Solution.plot(**kwargs)``: :func:`tcarod.plotting.plot_solution` with the
    same keywords (``view="3d" | "xz" | "yz" | "interactive"``, ``ax``,
    ``rings``, ``camera``, ``title``, ``backend``). The bindings call this
    (registered below) so that they never import Python modules themselves;
    matplotlib is imported on first use."""
    from .plotting import plot_solution

    return plot_solution(sol, **kwargs)


_core._register_plotter(_plot_solution)


def _solution_png(sol: Any) -> bytes | None:
    """The 3-D plot of a solution as PNG bytes, drawn outside pyplot (a preview, never a window)."""
    from .plotting import detached, plot_solution

    with detached():
        return figure_png(plot_solution(sol))


def _workspace_png(ws: Any) -> bytes | None:
    """The scatter plot of a workspace as PNG bytes, drawn outside pyplot."""
    from .plotting import detached, plot_workspace

    with detached():
        return figure_png(plot_workspace(ws))


def _row(cells: list[str], tag: str = "td") -> str:
    return "<tr>" + "".join(f"<{tag}>{html.escape(c)}</{tag}>" for c in cells) + "</tr>"


def _vec_mm(v: Any) -> str:
    return ", ".join(f"{float(x) * 1e3:.4g}" for x in v)


def solution_html(sol: Any) -> str:
    """An HTML table of a forward solution: tip position [mm], tip tangent,
    each actuator's input, tension [mN] and elongation [mm], iterations."""
    rows = [
        _row(["tip position [mm]", _vec_mm(sol.tip_position)]),
        _row(["tip tangent [-]", ", ".join(f"{float(r[2]):.4f}" for r in sol.tip_rotation)]),
        _row(["iterations", str(int(sol.iterations))]),
        _row(["residual [-]", f"{float(sol.residual):.3g}"]),
    ]
    acts = [
        _row([f"actuator {k}", f"{a.input_name} {float(x):g}", f"{float(t) * 1e3:.4g} mN", f"{float(e) * 1e3:.4g} mm"])
        for k, (a, x, t, e) in enumerate(zip(sol.robot.actuators, sol.inputs, sol.tensions, sol.elongations))
    ]
    head = _row(["actuator", "input", "tension", "elongation"], "th")
    return _html("Solution", rows, head, acts)


def _html(title: str, rows: list[str], head: str, acts: list[str]) -> str:
    """The notebook view: a table of ``rows`` and, if there are actuators, a table of ``acts`` under ``head``."""
    actuators = "<table>" + head + "".join(acts) + "</table>" if acts else ""
    return f"<div><b>tcarod {title}</b><table>{''.join(rows)}</table>{actuators}</div>"


def robot_html(robot: Any) -> str:
    """An HTML table of a robot: body length [mm], section, E_B [Pa] and one
    row per actuator (kind, span [mm], input range)."""
    b = robot.body
    rows = [
        _row(["body length [mm]", f"{float(b.length) * 1e3:g}"]),
        _row(["section", str(b.section.kind)]),
        _row(["E_B [Pa]", f"{float(b.youngs_modulus):g}"]),
        _row(["density [kg/m^3]", f"{float(b.density):g}"]),
    ]
    head = _row(["actuator", "kind", "s_start [mm]", "s_end [mm]", "input", "range"], "th")
    acts = []
    for k, a in enumerate(robot.actuators):
        lo, hi = a.input_bounds
        end = "tip" if a.s_end == float("inf") else f"{float(a.s_end) * 1e3:g}"
        acts.append(
            _row([str(k), str(a.kind), f"{float(a.s_start) * 1e3:g}", end, str(a.input_name), f"{lo:g} .. {hi:g}"])
        )
    return _html("Robot", rows, head, acts)


def _for_type(formatter: Any, cls: type, method: str, fn: Callable[[Any], Any]) -> None:
    if not callable(getattr(cls, method, None)):
        formatter.for_type(cls, fn)


def register(shell: Any | None = None) -> bool:
    """Register the formatters with ``shell`` (default: the running IPython
    shell, if any). Returns True if it registered anything."""
    if shell is None:
        ipython = sys.modules.get("IPython")
        if ipython is None:
            return False
        get = getattr(ipython, "get_ipython", None)
        shell = get() if get is not None else None
    formatters = getattr(getattr(shell, "display_formatter", None), "formatters", None)
    if not formatters:
        return False
    from .rod import Robot, Solution
    from .models.workspace import Workspace

    png = formatters.get("image/png")
    htm = formatters.get("text/html")
    if htm is not None:
        _for_type(htm, Solution, "_repr_html_", solution_html)
        _for_type(htm, Robot, "_repr_html_", robot_html)
    if png is not None and importlib.util.find_spec("matplotlib") is not None:
        # deferred by name: matplotlib is imported only when a Figure is shown;
        # a formatter already installed (e.g. by %matplotlib inline) is kept
        fig_mod = sys.modules.get("matplotlib.figure")
        installed = fig_mod is not None and fig_mod.Figure in getattr(png, "type_printers", {})
        if not installed and ("matplotlib.figure", "Figure") not in getattr(png, "deferred_printers", {}):
            png.for_type_by_name("matplotlib.figure", "Figure", figure_png)
        _for_type(png, Solution, "_repr_png_", _solution_png)
        _for_type(png, Workspace, "_repr_png_", _workspace_png)
    return True


register()  # on import of tcarod: a no-op outside IPython
