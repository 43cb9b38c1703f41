"""Segmented (distributed) actuation (``tcarod.models.segmented``; docs/extensions.md):
one TCA as segments in series, each anchored to the body at its ends and at
its own temperature. Interior anchors load the body with point forces and
the kinks of strings passing them (docs/choices.md, "String mechanics")."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tcarod import Robot, Routing, _core
from tcarod.paper.fig1b import FIG1B
from tcarod.models.segmented import segment_bounds, segmented_actuators

LENGTH = FIG1B.length_m


def _robot(
    segments: int, gravity: bool, tip_moment: tuple[float, float, float] = (0.0, 0.0, 0.0)
) -> tuple[Robot, object]:
    f = replace(FIG1B, segments=segments)
    body = f.body(gravity=gravity).replace(tip_moment=list(tip_moment))
    return Robot(body, f.actuators()), f


def test_segment_bounds_are_consecutive() -> None:
    # sums of the fractions times the span: rounding only
    b = segment_bounds([0.5, 0.25, 0.25], 0.01, 0.05)
    assert b == [(0.01, 0.03), (0.03, 0.04), (0.04, 0.05)]
    assert segment_bounds(3, 0.0, 0.06)[-1][1] == 0.06
    with pytest.raises(ValueError, match="sum"):
        segment_bounds([0.5, 0.4], 0.0, 1.0)
    with pytest.raises(ValueError, match="segments"):
        segment_bounds(0, 0.0, 1.0)


def test_segments_are_scaled_copies_of_the_tca() -> None:
    tca = FIG1B.tca()
    acts = segmented_actuators(tca, Routing.straight(4e-3, 0.0), [0.5, 0.3, 0.2], 0.0, LENGTH)
    assert [a.s_start for a in acts] == pytest.approx([0.0, 0.03, 0.048], abs=1e-15)
    # a segment scales l, L and N by its fraction: the same alpha0 and d0, rounding only
    for a, frac in zip(acts, [0.5, 0.3, 0.2]):
        seg = a.tca_model
        assert isinstance(seg, _core.Tca)  # the binding keeps the core class
        assert seg.coiled_length == pytest.approx(frac * tca.coiled_length, rel=1e-14)
        assert seg.alpha0 == pytest.approx(tca.alpha0, rel=1e-13)
        assert seg.d0 == pytest.approx(tca.d0, rel=1e-13)


def test_uniform_temperature_pure_moment_no_gravity_equals_one_tca() -> None:
    # A pure tip moment and no gravity: the internal moment is the same at
    # every section, the curvature is uniform, every segment stretches in
    # proportion to its length and so carries the whole TCA's tension; the
    # anchor loads of adjacent segments cancel. The shapes agree up to the
    # discretisation (RK4, 100 steps, on grids with different breakpoints)
    # and the Newton tolerance (1e-10): observed 3e-13 m at the tip.
    # Tolerance 1e-9 m (1.7e-8 of the length): room for rounding, still
    # six orders below the 3.4 mm difference gravity makes (next test).
    moment = (0.0, 2e-4, 0.0)
    whole_robot, f1 = _robot(1, gravity=False, tip_moment=moment)
    seg_robot, f4 = _robot(4, gravity=False, tip_moment=moment)
    temps = [100.0, 25.0, 25.0]
    whole = whole_robot.solve(f1.inputs(temps))  # type: ignore[attr-defined]
    seg = seg_robot.solve(f4.inputs(temps))  # type: ignore[attr-defined]
    assert np.linalg.norm(whole.tip_position - seg.tip_position) < 1e-9
    # each segment carries the whole TCA's tension, to the solve tolerance (relative)
    assert np.allclose(seg.tensions[:4], whole.tensions[0], rtol=1e-7)
    k_whole = np.interp(seg.s, whole.s, whole.omega[:, 1])
    assert np.max(np.abs(seg.omega[:, 1] - k_whole)) < 1e-6  # [1/m], of ~9 1/m


def _single_tca_robot(segments: int, gravity: tuple[float, float, float]) -> Robot:
    body = FIG1B.body(gravity=False).replace(gravity=list(gravity))
    acts = segmented_actuators(FIG1B.tca(), Routing.straight(FIG1B.offset_m, 0.0), segments, 0.0, LENGTH)
    return Robot(body, acts)


def _gravity_difference(temperature_c: float = 100.0) -> tuple[float, float]:
    """Tip distance [m] and largest curvature difference [1/m] between one
    whole TCA and four segments at one temperature, body horizontal (gravity
    along body +x, toward the TCA). Only the segmented TCA is in the body, so
    no other string passes over the segment anchors: the difference is the
    segments' own (the kink forces of passing strings are tested in
    tests/integration/properties.rs)."""
    g = (9.81, 0.0, 0.0)
    whole = _single_tca_robot(1, g).solve([temperature_c])
    seg = _single_tca_robot(4, g).solve([temperature_c] * 4)
    k_whole = np.interp(seg.s, whole.s, whole.omega[:, 1])
    return float(np.linalg.norm(whole.tip_position - seg.tip_position)), float(
        np.max(np.abs(seg.omega[:, 1] - k_whole))
    )


def test_with_gravity_segmented_differs_from_one_tca() -> None:
    # The weight makes the bending moment grow toward the base: each segment
    # takes its own share of the load (its tension follows its own
    # elongation), a whole TCA only the average. The difference is physical,
    # not numerical: it must exceed the 1e-9 m agreement of the load-free
    # case by orders of magnitude.
    tip_diff_m, curvature_diff = _gravity_difference()
    assert tip_diff_m > 1e-3  # observed 8.0 mm at 100 C
    assert curvature_diff > 1.0  # [1/m]; observed 13.1 1/m (peak curvature 34 1/m)


def test_with_gravity_in_the_3_tca_fixture_segmented_differs_too() -> None:
    # FIG1B standing base-down, TCA 0 in four segments at 100 C: 3.4 mm at
    # the tip (TCAs 1 and 2 pass over the segment anchors; their kink forces
    # there are applied by the core).
    whole_robot, f1 = _robot(1, gravity=True)
    seg_robot, f4 = _robot(4, gravity=True)
    temps = [100.0, 25.0, 25.0]
    whole = whole_robot.solve(f1.inputs(temps))  # type: ignore[attr-defined]
    seg = seg_robot.solve(f4.inputs(temps))  # type: ignore[attr-defined]
    assert np.linalg.norm(whole.tip_position - seg.tip_position) > 1e-3


@pytest.mark.parametrize("k", [0, 1, 2])
def test_one_heated_segment_bends_only_its_own_span(k: int) -> None:
    # Only the segmented TCA, no gravity, no tip load. The heated segment's
    # loads on the body (its anchor forces and its distributed load) are
    # self-equilibrated, so outside its span the internal force and moment
    # vanish, the other segments keep zero elongation and zero tension
    # (at the reference temperature), and the curvature is zero. Tolerance
    # 1e-7 1/m: the Newton tolerance is 1e-10 in scaled strain (L omega),
    # i.e. ~2e-9 1/m, plus rounding; the bent span has ~20 1/m.
    body = FIG1B.body(gravity=False)
    acts = segmented_actuators(FIG1B.tca(), Routing.straight(FIG1B.offset_m, 0.0), 3, 0.0, LENGTH)
    robot = Robot(body, acts)
    temps = [25.0, 25.0, 25.0]
    temps[k] = 140.0
    sol = robot.solve(temps)
    lo, hi = LENGTH * k / 3, LENGTH * (k + 1) / 3
    s = sol.s
    outside = (s < lo - 1e-12) | (s > hi + 1e-12)
    inside = ~outside
    assert outside.any()
    assert np.max(np.abs(sol.omega[outside, :2])) < 1e-7
    assert np.max(np.abs(sol.omega[inside, 1])) > 1.0  # it does bend inside
    others = [i for i in range(3) if i != k]
    assert np.max(np.abs(sol.tensions[others])) < 1e-9  # [N], vs ~0.1 N pushing
    assert sol.tensions[k] < -0.01


def test_gravity_tip_moment_and_heating_converge_and_balance() -> None:
    # The unheated TCAs are pressed into coil contact by the weight: Newton
    # converges through the contact onset because the law is C1-smoothed there
    # (docs/choices.md, "Coil contact inside a body").
    robot, f = _robot(1, gravity=True, tip_moment=(0.0, 2e-4, 0.0))
    sol = robot.solve(f.inputs([60.0, 25.0, 25.0]))  # type: ignore[attr-defined]
    body = robot.body
    # base force = weight (no tip force); solver tolerance 1e-10 in strain times
    # EA bounds the force error, x100 margin
    want = body.distributed_load * body.length
    np.testing.assert_allclose(sol.base_force, want, rtol=0.0, atol=100 * 1e-10 * body.stiffness()[0][2, 2])


def test_segmented_horizontal_cold_converges_and_balances() -> None:
    # A horizontal body with a TCA in four segments at ambient: the weight bends
    # it and presses/stretches the segments; the loads at each interior anchor
    # are solved together by a small Newton iteration (docs/choices.md,
    # "String mechanics").
    robot = _single_tca_robot(4, (9.81, 0.0, 0.0))
    sol = robot.solve([25.0] * 4)
    body = robot.body
    want = body.distributed_load * body.length
    # solver tolerance 1e-10 in scaled strain times EA bounds the force error; x100 margin
    np.testing.assert_allclose(sol.base_force, want, rtol=0.0, atol=100 * 1e-10 * body.stiffness()[0][2, 2])
    assert sol.tip_position[0] > 0.0  # sags along gravity (+x here)


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize(
    ("args", "exc", "name"),
    [
        ((3, 0.0, 1e30), None, ""),  # a huge span is fine: finite, increasing bounds
        ((10**7, 0.0, 0.04), ValueError, "segments"),  # beyond MAX_SEGMENTS: bounded work
        ((-1, 0.0, 0.04), ValueError, "segments"),
        ((2.0, 0.0, 0.04), TypeError, "segments"),
        (("3", 0.0, 0.04), TypeError, "segments"),
        ((3, "0", 0.04), TypeError, "s_start"),
        ((3, 0.0, float("nan")), ValueError, "s_end"),
        ((3, 0.0, 5e-324), ValueError, "span"),  # segments of zero length in floating point
        (([0.5, float("inf")], 0.0, 0.04), ValueError, "segments"),
    ],
)
def test_segment_bounds_contract(args: tuple[object, ...], exc: type | None, name: str) -> None:
    if exc is None:
        bounds = segment_bounds(*args)  # type: ignore[arg-type]
        edges = np.array([b for b in bounds]).ravel()
        assert np.all(np.isfinite(edges)) and all(a < b for a, b in bounds)
        return
    with pytest.raises(exc, match=name):
        segment_bounds(*args)  # type: ignore[arg-type]
