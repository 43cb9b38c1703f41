"""Fig. 6 (Section V-B): the manipulator fixtures, the predicted bending
radii, the result object (table, JSON, PNG), ``tcarod reproduce fig6``, and
``tcarod.plotting.plot_solution``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from tcarod import Robot, inner_edge_radius
from tcarod._core import _experiment_robot
from tcarod.cli import main
from tcarod.paper import REGISTRY
from tcarod.paper.fig6 import CIRCLE_PRECURVATURE_RADIUS_M, FIG6, Fig6Result
from tcarod.plotting import plot_solution

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def result() -> Fig6Result:
    return FIG6.predict()


# ------------------------------------------------------------------ fixtures


@pytest.mark.parametrize("gravity", [True, False])
@pytest.mark.parametrize(("index", "rust_name"), [(0, "fig6_circle"), (1, "fig6_square")])
def test_fixture_matches_rust_fixture(index: int, rust_name: str, gravity: bool) -> None:
    ours = FIG6.manipulators[index].robot(gravity)
    rust: Robot = _experiment_robot(rust_name, gravity)  # type: ignore[arg-type]
    a, b = ours.body.kwargs(), rust.body.kwargs()
    assert repr(a.pop("section")) == repr(b.pop("section"))
    assert a == b
    assert [act.routing.evaluate(0.0)[0].tolist() for act in ours.actuators] == [
        act.routing.evaluate(0.0)[0].tolist() for act in rust.actuators
    ]
    # same TCA law: same tension at a few elongations and temperatures
    for act_ours, act_rust in zip(ours.actuators, rust.actuators):
        for d, t in [(0.0, 100.0), (1e-3, 60.0), (-1e-5, 160.0)]:
            assert act_ours.tension(d, t) == act_rust.tension(d, t)
    n = len(ours.actuators)
    np.testing.assert_array_equal(ours.solve([120.0] * n).tip_position, rust.solve([120.0] * n).tip_position)


def test_circle_is_precurved_by_the_assumed_radius() -> None:
    m = FIG6.manipulators[0]
    assert m.precurvature_radius_m == CIRCLE_PRECURVATURE_RADIUS_M == 0.2
    assert m.precurvature_is_assumption
    robot = m.robot(gravity=False)
    sol = robot.solve([25.0])
    # reference shape: the inner edge is the 0.2 m arc less the 4 mm half diameter;
    # the reference guess is exact (0 iterations), the arc exact to RK4 (~1e-12 m)
    assert sol.iterations == 0
    assert inner_edge_radius(sol) == pytest.approx(0.2 - 4e-3, rel=1e-9)
    assert sol.tip_position[0] < 0.0  # pre-curved toward -x, away from the TCA at +x


# ------------------------------------------------------------------ results


def test_radius_shrinks_with_temperature(result: Fig6Result) -> None:
    for pair in result.curves:
        for curve in pair:
            r = curve.radii_m
            # strictly decreasing where finite (a straight body has radius inf)
            finite = r[np.isfinite(r)]
            assert np.all(np.diff(finite) < 0.0), curve.manipulator.label
            # 160 C bends the 40 mm body to a radius near its length: below it for
            # the circle (76.4 turns), below 1.5 lengths for the square whose legs
            # share the U's 76.4 turns (per_tca: half the free stroke per leg)
            limit = 0.04 if curve.manipulator.section == "circle" else 0.07  # square: 56 / 67 mm
            assert 0.01 < r[-1] < limit


def test_turns_readings(result: Fig6Result) -> None:
    # the circle's single TCA has 76.4 turns in every reading: identical radii
    circle = [v for (label, _), v in result.readings.items() if label.startswith("circle")]
    assert len(circle) == 3 and circle[0] == circle[1] == circle[2]
    sq = {reading: v for (label, reading), v in result.readings.items() if label.startswith("square")}
    # 40 mm legs: per_length (76.4 per 40 mm) is per_leg; same robot, same radii
    assert sq["per_length"] == sq["per_leg"]
    # twice the turns per leg -> twice the free stroke -> tighter bending at every temperature
    assert all(a < b for a, b in zip(sq["per_leg"], sq["per_tca"]))
    # the default reading is the sweep itself (same equations: to the Newton tolerance)
    with_g = result.curves[1][0]
    for t, r in zip(FIG6.reading_temperatures_c, sq["per_tca"]):
        k = list(FIG6.temperatures_c).index(t)
        assert r == pytest.approx(with_g.radii_m[k], rel=1e-7)
    doc = result.to_json()
    assert doc["turns_reading"] == "per_tca" and len(doc["readings"]) == 6


def test_square_is_straight_at_25_c_without_gravity(result: Fig6Result) -> None:
    with_g, without = result.curves[1]
    assert math.isinf(without.radii_m[0])
    # upright, its own weight compresses the body; the TCAs at +x sit at coil contact
    # and resist, so it leans toward -x (radius ~1 m)
    assert 0.3 < with_g.radii_m[0] < 3.0
    assert with_g.tip_positions_m[0][0] < 0.0


def test_gravity_makes_the_radius_smaller(result: Fig6Result) -> None:
    # upright, the bent body sags further toward the concave side
    for k, (with_g, without) in enumerate(result.curves):
        change = result.gravity_radius_change_m(k)
        ok = np.isfinite(change)
        assert ok.sum() >= len(change) - 1
        assert np.all(change[ok] < 0.0)
        assert np.all(with_g.radii_m[ok] < without.radii_m[ok])


def test_cold_and_warm_sweeps_agree(result: Fig6Result) -> None:
    for pair in result.curves:
        for curve in pair:
            # same equations, tolerance 1e-10 in strain: radii agree to ~1e-9 relative
            assert curve.cold_warm_max_relative_difference < 1e-7
            assert len(curve.iterations_warm) == len(curve.iterations_cold) == len(FIG6.temperatures_c)
            # after the first step a warm start needs few iterations: it reuses the
            # previous solution's exact Jacobian (chord steps, one plain IVP each,
            # counted as iterations), so a warm step takes 3-12 here; cold steps
            # take fewer but costlier iterations (a tangent IVP each), so the
            # work comparison is in IVPs: fig6_sweeps_converge_cold_and_warm in
            # tests/integration/solver.rs
            assert max(curve.iterations_warm[1:]) <= 12


def test_table_reports_radii_gravity_and_iterations(result: Fig6Result) -> None:
    text = result.table()
    for part in (
        "R gravity [mm]",
        "R no gravity [mm]",
        "gravity change [mm]",
        "Newton it. warm",
        "cold",
        "ASSUMED",
        "0.2 m",
        "Published data: none",
        "inf",
    ):
        assert part in text, part
    # one row per temperature per manipulator
    assert sum(1 for line in text.splitlines() if line.strip().startswith("100 |")) == 2


def test_json_has_units_and_null_for_infinite_radius(result: Fig6Result) -> None:
    doc = result.to_json()
    text = json.dumps(doc, allow_nan=False)  # no NaN / inf anywhere
    assert json.loads(text) == doc
    assert doc["temperature_c"] == list(FIG6.temperatures_c)
    assert doc["published_data"] is None
    circle, square = doc["manipulators"]
    assert circle["precurvature_radius_m"] == 0.2 and circle["precurvature_is_assumption"] is True
    assert square["without_gravity"]["radius_m"][0] is None  # straight at 25 C
    assert square["gravity_radius_change_m"][0] is None
    for m in doc["manipulators"]:
        for case in ("with_gravity", "without_gravity"):
            c = m[case]
            assert len(c["radius_m"]) == len(doc["temperature_c"])
            assert len(c["newton_iterations_warm"]) == len(c["newton_iterations_cold"]) == len(doc["temperature_c"])
    assert circle["with_gravity"]["gravity_m_per_s2"] == [0.0, 0.0, -9.81]


def test_plot_writes_png(result: Fig6Result, tmp_path: Path) -> None:
    path = result.plot(tmp_path / "sub" / "fig6.png")
    data = path.read_bytes()
    assert data.startswith(PNG_MAGIC) and len(data) > 10_000  # a real plot, not an empty canvas


def test_reproduce_fig6_cli_json(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert "fig6" in REGISTRY
    assert main(["reproduce", "fig6", "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    fig6 = doc["experiments"]["fig6"]
    assert Path(fig6["png_path"]) == tmp_path / "fig6.png"
    assert (tmp_path / "fig6.png").read_bytes().startswith(PNG_MAGIC)
    assert len(fig6["manipulators"]) == 2


# ------------------------------------------------------------- plot_solution


@pytest.mark.parametrize("index", [0, 1])
def test_plot_solution_draws_each_actuator(index: int, tmp_path: Path) -> None:
    robot = FIG6.manipulators[index].robot(gravity=True)
    n = len(robot.actuators)
    sol = robot.solve([100.0] * n)
    fig = sol.plot()  # Solution.plot -> tcarod.plotting.plot_solution
    assert isinstance(fig, Figure)
    (ax,) = fig.axes
    gids = [line.get_gid() or "" for line in ax.get_lines()]
    actuator_lines = [g for g in gids if g.startswith("actuator-")]
    assert len(actuator_lines) == n
    assert "centre-line" in gids
    assert sum(g.startswith("outline-") for g in gids) >= 4
    assert sum(g.startswith("ring-") for g in gids) >= 2
    colours = {line.get_color() for line in ax.get_lines() if (line.get_gid() or "").startswith("actuator-")}
    assert len(colours) == n  # one colour per actuator
    # axes in mm: the tip (z ~ 30-40 mm) lies inside the z limits
    lo, hi = ax.get_zlim()
    assert lo <= sol.tip_position[2] * 1e3 <= hi and hi < 100.0
    assert "mm" in ax.get_xlabel() and "mm" in ax.get_zlabel()
    png = tmp_path / "solution.png"
    fig.savefig(png, format="png", dpi=80)
    data = png.read_bytes()
    assert data.startswith(PNG_MAGIC) and len(data) > 10_000


def test_plot_solution_into_given_axes() -> None:
    fig = Figure()
    ax = fig.add_subplot(projection="3d")
    sol = FIG6.manipulators[1].robot(gravity=False).solve([60.0, 60.0])
    assert plot_solution(sol, ax, rings=3, title="square") is fig
    assert ax.get_title() == "square"
    assert sum((line.get_gid() or "").startswith("ring-") for line in ax.get_lines()) == 3
