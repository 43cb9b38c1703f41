"""Plots: overlays on one axes and notebook display without magics."""

from __future__ import annotations

import numpy as np
import pytest

from tcarod.batch import fig6_square_robot
from tcarod.plotting import plot_solution

ROBOT = fig6_square_robot(gravity=False)
COOL = ROBOT.solve([25.0, 25.0])
HOT = ROBOT.solve([140.0, 140.0])  # bends toward -x, far from the straight shape


def _limits(ax: object) -> np.ndarray:
    return np.array([ax.get_xlim(), ax.get_ylim(), ax.get_zlim()])  # type: ignore[attr-defined]


def test_overlay_keeps_every_shape_in_view_and_one_legend_entry_per_label() -> None:
    fig = plot_solution(HOT)
    ax = fig.axes[0]
    hot_limits = _limits(ax)
    plot_solution(COOL, ax=ax)
    both = _limits(ax)
    # the union of both shapes: never smaller than the hot shape's cube alone
    assert np.all(both[:, 0] <= hot_limits[:, 0] + 1e-12) and np.all(both[:, 1] >= hot_limits[:, 1] - 1e-12)
    # the hot tip (x < 0) and the straight one (x ~ 0) are both inside the x range [mm]
    for sol in (HOT, COOL):
        x_mm = sol.tip_position[0] * 1e3
        assert both[0, 0] <= x_mm <= both[0, 1]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels.count("centre line") == 1 and labels.count("body outline") == 1
    assert len(labels) == len(set(labels))


def test_overlay_keeps_the_title_unless_one_is_given() -> None:
    fig = plot_solution(HOT, title="two temperatures")
    ax = fig.axes[0]
    plot_solution(COOL, ax=ax)
    assert ax.get_title() == "two temperatures"
    plot_solution(COOL, ax=ax, title="renamed")
    assert ax.get_title() == "renamed"


def test_plot_solution_argument_types() -> None:
    with pytest.raises(TypeError, match="solution"):
        plot_solution(None)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="rings"):
        plot_solution(HOT, rings="5")  # type: ignore[arg-type]


def test_figures_and_results_display_as_png_and_html_in_ipython() -> None:
    """The formatters tcarod registers in an IPython shell (no %matplotlib)."""
    globalipapp = pytest.importorskip("IPython.testing.globalipapp")
    from tcarod import _display
    from tcarod.models.workspace import workspace_map

    shell = globalipapp.start_ipython()
    assert _display.register(shell)
    fmt = shell.display_formatter
    fmt.active_types = list(fmt.formatters)  # a notebook front end asks for all of them
    png_magic = b"\x89PNG\r\n\x1a\n"
    data, _ = fmt.format(HOT.plot())
    assert data["image/png"][:8] == png_magic
    data, _ = fmt.format(HOT)
    assert data["image/png"][:8] == png_magic and "tip position [mm]" in data["text/html"]
    data, _ = fmt.format(ROBOT)
    assert "actuator" in data["text/html"] and "tca" in data["text/html"]
    data, _ = fmt.format(workspace_map(ROBOT, [25.0, 120.0]))
    assert data["image/png"][:8] == png_magic


def test_notebook_shows_figures_as_images_without_magics(tmp_path: object) -> None:
    """A generated notebook run by a real kernel: the last expression of a
    cell, a tcarod figure, comes back as image/png."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_code_cell(
            "from tcarod.batch import fig6_square_robot\nsol = fig6_square_robot().solve([100.0, 100.0])"
        ),
        nbformat.v4.new_code_cell("sol.plot()"),
        nbformat.v4.new_code_cell("sol"),
    ]
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3").execute()
    for cell in nb.cells[1:]:
        outputs = [o for o in cell.outputs if o.get("output_type") == "execute_result"]
        assert outputs and "image/png" in outputs[0]["data"], cell.source


# ---------------------------------------------------------------------------
# Side views, titles and units, pyplot figures, the interactive view
# ---------------------------------------------------------------------------


def _line(ax: object, gid: str) -> object:
    (line,) = [ln for ln in ax.get_lines() if ln.get_gid() == gid]  # type: ignore[attr-defined]
    return line


@pytest.mark.parametrize("view,h,v", [("xz", 0, 2), ("yz", 1, 2)])
def test_side_view_draws_the_solution_in_mm_with_equal_aspect(view: str, h: int, v: int) -> None:
    fig = plot_solution(HOT, view=view)  # type: ignore[arg-type]
    (ax,) = fig.axes
    assert not hasattr(ax, "get_zlim")  # a 2-D axes
    centre = _line(ax, "centre-line")
    np.testing.assert_array_equal(centre.get_xdata(), HOT.positions[:, h] * 1e3)  # type: ignore[attr-defined]
    np.testing.assert_array_equal(centre.get_ydata(), HOT.positions[:, v] * 1e3)  # type: ignore[attr-defined]
    for k, path in enumerate(HOT.actuator_paths):
        act = _line(ax, f"actuator-{k}")
        np.testing.assert_array_equal(act.get_xdata(), path[:, h] * 1e3)  # type: ignore[attr-defined]
        np.testing.assert_array_equal(act.get_ydata(), path[:, v] * 1e3)  # type: ignore[attr-defined]
    assert ax.get_xlabel() == f"{'xyz'[h]} [mm]" and ax.get_ylabel() == "z [mm]"
    assert ax.get_aspect() == 1.0
    # the hot shape bends toward -x: the xz view shows the tip left of the base
    if view == "xz":
        assert centre.get_xdata()[-1] < -1.0  # type: ignore[attr-defined]


def test_titles_and_legends_carry_units_and_values() -> None:
    fig = plot_solution(HOT, view="xz")
    ax = fig.axes[0]
    assert ax.get_title() == "inputs: 140 °C, 140 °C"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for k, tension in enumerate(HOT.tensions):
        assert f"actuator {k}: {tension * 1e3:.1f} mN" in labels
    fig3d = plot_solution(HOT)
    ax3d = fig3d.axes[0]
    assert ax3d.get_title() == "inputs: 140 °C, 140 °C"
    assert (ax3d.get_xlabel(), ax3d.get_ylabel(), ax3d.get_zlabel()) == ("x [mm]", "y [mm]", "z [mm]")
    # the docstring names the legend's unit, mN, the same as the legend
    doc = plot_solution.__doc__ or ""
    assert "mN" in doc and "tension [N]" not in doc


def test_title_of_a_tendon_robot_gives_newtons() -> None:
    from tcarod import Actuator, Body, Robot, Routing, Section

    body = Body(0.05, Section.circle(0.01), 1e6, density=1000.0, gravity=(0.0, 0.0, 0.0))
    robot = Robot(body, [Actuator.tendon(Routing.straight(3e-3, 0.0))])
    fig = plot_solution(robot.solve([0.05]), view="yz")
    assert fig.axes[0].get_title() == "inputs: 0.05 N"


def test_solution_plot_forwards_view_and_keywords() -> None:
    fig = HOT.plot(view="xz", rings=0, title="side")
    ax = fig.axes[0]
    assert ax.get_title() == "side" and ax.get_xlabel() == "x [mm]"
    assert not [ln for ln in ax.get_lines() if str(ln.get_gid()).startswith("ring-")]
    fig3 = HOT.plot(camera=(30.0, 10.0))
    assert fig3.axes[0].elev == 30.0 and fig3.axes[0].azim == 10.0


def test_side_view_overlay_on_one_axes() -> None:
    fig = plot_solution(HOT, view="xz")
    ax = fig.axes[0]
    plot_solution(COOL, ax=ax, view="xz")
    assert len([ln for ln in ax.get_lines() if ln.get_gid() == "centre-line"]) == 2
    assert ax.get_title() == "inputs: 140 °C, 140 °C"  # the first title is kept
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels.count("centre line") == 1


def test_view_and_axes_errors() -> None:
    with pytest.raises(ValueError, match="view"):
        plot_solution(HOT, view="side")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="view"):
        plot_solution(HOT, view=3)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="backend"):
        plot_solution(HOT, backend="bokeh")
    with pytest.raises(ValueError, match="camera"):
        plot_solution(HOT, view="xz", camera=(10.0, 20.0))
    with pytest.raises(ValueError, match="view"):
        plot_solution(HOT, view="xz", backend="plotly")
    three_d = plot_solution(HOT).axes[0]
    with pytest.raises(TypeError, match="2-D"):
        plot_solution(HOT, ax=three_d, view="xz")
    flat = plot_solution(HOT, view="xz").axes[0]
    with pytest.raises(TypeError, match="3-D"):
        plot_solution(HOT, ax=flat)


def test_a_camera_tuple_is_the_3d_view_from_that_camera() -> None:
    ax = plot_solution(HOT, view=(20.0, 45.0)).axes[0]
    assert hasattr(ax, "get_zlim") and ax.elev == 20.0 and ax.azim == 45.0


_PYPLOT_SCRIPT = r"""
import sys, warnings
import matplotlib
matplotlib.use("Agg")
from tcarod.batch import fig6_square_robot
from tcarod.plotting import detached, plot_solution, save_png, uses_pyplot
sol = fig6_square_robot(gravity=False).solve([120.0, 25.0])
assert "matplotlib.pyplot" not in sys.modules and not uses_pyplot()
fig = sol.plot()
assert fig.canvas.manager is None  # no pyplot: a figure on the Agg canvas
import matplotlib.pyplot as plt
assert uses_pyplot() and plt.get_fignums() == []
fig = sol.plot(view="xz")
assert plt.get_fignums() == [fig.number], plt.get_fignums()
assert plt.gcf() is fig
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # Agg may say that it cannot show (not on a headless Linux)
    fig.show()  # pyplot's figure: no AttributeError
assert fig.canvas.manager is not None
fig2 = plot_solution(sol)
assert len(plt.get_fignums()) == 2
save_png(fig2, sys.argv[1])  # written, then released from pyplot
assert len(plt.get_fignums()) == 1
with detached():
    plot_solution(sol)
assert len(plt.get_fignums()) == 1
print("ok")
"""


def test_figures_are_pyplot_figures_when_pyplot_is_in_use(tmp_path: object) -> None:
    """In a fresh interpreter (as a user's script): no pyplot, an Agg figure;
    pyplot imported, pyplot figures (``plt.get_fignums()`` grows, ``fig.show()`` works)."""
    import subprocess
    import sys

    png = str(tmp_path) + "/shape.png"  # type: ignore[operator]
    done = subprocess.run([sys.executable, "-c", _PYPLOT_SCRIPT, png], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_interactive_view_with_plotly() -> None:
    pytest.importorskip("plotly")
    fig = plot_solution(HOT, view="interactive")
    assert type(fig).__module__.startswith("plotly")
    centre = [t for t in fig.data if t.name == "centre line"]
    assert len(centre) == 1
    np.testing.assert_allclose(centre[0].x, HOT.positions[:, 0] * 1e3)
    np.testing.assert_allclose(centre[0].z, HOT.positions[:, 2] * 1e3)
    names = [t.name for t in fig.data if t.showlegend]
    assert names[:2] == ["centre line", "body outline"]
    assert f"actuator 0: {HOT.tensions[0] * 1e3:.1f} mN" in names
    assert fig.layout.scene.xaxis.title.text == "x [mm]" and fig.layout.scene.zaxis.title.text == "z [mm]"
    assert fig.layout.scene.aspectmode == "data"
    assert fig.layout.title.text == "inputs: 140 °C, 140 °C"
    same = HOT.plot(backend="plotly")
    assert [t.name for t in same.data] == [t.name for t in fig.data]


def test_interactive_view_without_plotly_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    import importlib

    from tcarod.plotting import interactive

    real = importlib.import_module

    def no_plotly(name: str, package: str | None = None) -> object:
        if name.startswith("plotly"):
            raise ImportError(f"No module named {name!r}")
        return real(name, package)

    monkeypatch.setattr(interactive.importlib, "import_module", no_plotly)
    with pytest.raises(ImportError, match=r"tcarod\[interactive\]"):
        plot_solution(HOT, view="interactive")
