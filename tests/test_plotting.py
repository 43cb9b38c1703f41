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
