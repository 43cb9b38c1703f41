"""Actuators held at fixed inputs in the inverse problems (``fixed_inputs``),
and the grasp that no temperature in range can hold, on the getting-started
finger: 60 mm, 12 mm square Ecoflex 00-30, upright, the paper's TCA on
opposite sides 4 mm off the axis (heating the one at +x bends it toward -x)."""

from __future__ import annotations

import re
import warnings

import pytest

from tcarod import Actuator, Body, Robot, Routing, Section, UnstableEquilibriumWarning
from tcarod.inverse import blocked_force, blocked_temperature, blocked_temperature_direct
from tcarod.models.grasp import FRICTION_COEFFICIENT, grasp, grasp_temperature
from tcarod.models.manipulators import GRAVITY_M_PER_S2, leg_turns, manipulator_tca

MINUS_X = (-1.0, 0.0, 0.0)
AMBIENT_C = 25.0


@pytest.fixture(scope="module")
def finger() -> Robot:
    body = Body.from_material("ecoflex-00-30", 0.060, Section.rectangle(12e-3, 12e-3), gravity=(0.0, 0.0, -9.81))
    tca = manipulator_tca(0.060, turns=leg_turns(0.060, 1, "per_length"))
    return Robot(body, [Actuator.tca(tca, Routing.straight(x, 0.0)) for x in (4e-3, -4e-3)])


def _force_needed(mass_kg: float) -> float:
    """Blocked force [N] per finger that holds ``mass_kg`` (eq 44, two fingers, the default mu)."""
    return mass_kg * GRAVITY_M_PER_S2 / (FRICTION_COEFFICIENT * 2)


@pytest.mark.parametrize("method", ["incremental", "direct"])
def test_one_heated_tca_holds_the_mass(finger: Robot, method: str) -> None:
    g = grasp(0.002, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}, method=method)
    assert AMBIENT_C < g.temperature_c < 160.0
    # the blocked force at the returned temperature, solved afresh with the
    # other TCA at ambient, is m g / (mu n): both solves converge the same
    # equations to Newton tol 1e-10 (tip gap 1e-9 L), so 1e-6 relative holds
    check = blocked_force(finger, g.block_point_m, MINUS_X, [g.temperature_c], fixed_inputs={1: AMBIENT_C})
    assert check.force == pytest.approx(_force_needed(0.002), rel=1e-6)
    # the idle TCA stayed at its fixed input
    assert g.blocked.solution.inputs[1] == AMBIENT_C


def test_both_grasp_methods_and_groups_conventions_agree(finger: Robot) -> None:
    temps = [
        grasp_temperature(0.002, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}),
        grasp_temperature(0.002, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}, groups=[0, None]),
        grasp_temperature(0.002, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}, groups=[0]),
        grasp_temperature(0.002, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}, method="direct"),
    ]
    # the three spellings are one problem: the same numbers bit for bit
    assert temps[0] == temps[1] == temps[2]
    # eq 43 and the direct solve agree as on the Table I finger (tests/test_inverse.py: 1e-6 C)
    assert temps[3] == pytest.approx(temps[0], abs=1e-6)


def _peak(message: str) -> tuple[float, float, float]:
    """(force [N], mass [g], temperature [C]) of the largest blocked force in a "cannot hold" message."""
    m = re.search(r"the largest blocked force in \[25, 160\] C is (\S+) N \((\S+) g\) at (\S+) C", message)
    assert m, message
    return float(m.group(1)), float(m.group(2)), float(m.group(3))


def test_a_mass_out_of_reach_names_the_largest_one_held(finger: Robot) -> None:
    messages = []
    for method in ("incremental", "direct"):
        with pytest.raises(ValueError, match="the finger cannot hold 500 g") as err:
            grasp(0.5, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}, method=method)
        messages.append(str(err.value))
    # both methods fail alike: the same peak, found by the same sweep
    assert messages[0] == messages[1]
    force, grams, temp = _peak(messages[0])
    # the blocked force at the stated temperature is the stated force (printed
    # to 6 significant digits: a rounding of at most 5e-6 of itself)
    point = grasp(0.001, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C}).block_point_m
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", UnstableEquilibriumWarning)
        check = blocked_force(finger, point, MINUS_X, [temp], fixed_inputs={1: AMBIENT_C})
    assert check.force == pytest.approx(force, rel=5e-6)
    # the message says whether that equilibrium is unstable exactly when the solve warns
    assert ("unstable equilibrium" in messages[0]) == (not check.solution.stable) == bool(caught)
    # the stated mass is the one that force holds (eq 44), and less than asked
    assert grams == pytest.approx(1e3 * force * FRICTION_COEFFICIENT * 2 / GRAVITY_M_PER_S2, rel=1e-5)
    assert 0.0 < grams < 500.0
    # a mass below the peak is held, at a temperature below the peak's
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnstableEquilibriumWarning)
        held = grasp(0.5 * grams * 1e-3, finger, normal=MINUS_X, fixed_inputs={1: AMBIENT_C})
    assert AMBIENT_C < held.temperature_c < temp


def test_heating_both_opposite_tcas_says_no_mass_is_held(finger: Robot) -> None:
    # the two TCAs heated together cancel their bending: no blocked force to speak of
    with pytest.raises(ValueError, match="the finger cannot hold 2 g") as err:
        grasp(0.002, finger, normal=MINUS_X)
    force, grams, _ = _peak(str(err.value))
    assert abs(force) < 1e-3 * _force_needed(0.002)
    assert "reached" not in str(err.value)
    assert "fixed_inputs" in str(err.value)


def test_blocked_temperature_with_a_fixed_input(finger: Robot) -> None:
    point = finger.solve([AMBIENT_C, AMBIENT_C]).tip_position
    f = _force_needed(0.002)
    inc = blocked_temperature(finger, point, MINUS_X, f, fixed_inputs={1: AMBIENT_C})
    direct = blocked_temperature_direct(finger, point, MINUS_X, f, guess=60.0, fixed_inputs={1: AMBIENT_C})
    assert inc.force == pytest.approx(f, rel=1e-12)
    assert direct.variables[0] == pytest.approx(inc.variables[0], abs=1e-6)
    # a start whose idle TCA is not at its fixed input is refused, naming it
    hot = finger.solve([AMBIENT_C, 40.0])
    with pytest.raises(ValueError, match=r"fixed_inputs\[1\]"):
        blocked_temperature(finger, hot.tip_position, MINUS_X, f, start=hot, fixed_inputs={1: AMBIENT_C})


@pytest.mark.parametrize(
    ("kwargs", "error", "pattern"),
    [
        ({"fixed_inputs": {2: AMBIENT_C}}, ValueError, r"fixed_inputs key \(actuator index\) = 2"),
        ({"fixed_inputs": {-1: AMBIENT_C}}, ValueError, r"fixed_inputs key"),
        ({"fixed_inputs": {1: float("nan")}}, ValueError, r"fixed_inputs\[1\]"),
        ({"fixed_inputs": {1: 200.0}}, ValueError, r"fixed_inputs\[1\] \(temperature\) = 200 C"),
        ({"fixed_inputs": {1: 20.0}}, ValueError, r"fixed_inputs\[1\]"),
        ({"fixed_inputs": [AMBIENT_C]}, TypeError, r"fixed_inputs"),
        ({"fixed_inputs": {1: "25"}}, TypeError, r"fixed_inputs\[1\]"),
        ({"fixed_inputs": {"1": AMBIENT_C}}, TypeError, r"fixed_inputs"),
        ({"fixed_inputs": {True: AMBIENT_C}}, TypeError, r"fixed_inputs"),
        ({"fixed_inputs": {1: AMBIENT_C}, "groups": [0, 0]}, ValueError, r"groups / fixed_inputs"),
        ({"groups": [None, None], "fixed_inputs": {0: AMBIENT_C}}, ValueError, r"groups / fixed_inputs"),
        ({"groups": [0, None]}, TypeError, r"groups: .*fixed_inputs"),
        ({"fixed_inputs": {1: AMBIENT_C}, "groups": [0, 1, 0]}, ValueError, r"groups"),
    ],
)
def test_bad_fixed_inputs_are_named(finger: Robot, kwargs: dict, error: type, pattern: str) -> None:  # type: ignore[type-arg]
    point = finger.solve([AMBIENT_C, AMBIENT_C]).tip_position
    with pytest.raises(error, match=pattern):
        blocked_force(finger, point, MINUS_X, [60.0], **kwargs)
    with pytest.raises(error, match=pattern):
        grasp(0.002, finger, normal=MINUS_X, **kwargs)


def test_out_of_range_fixed_input_says_what_robot_solve_says(finger: Robot) -> None:
    with pytest.raises(ValueError) as solve_err:
        finger.solve([AMBIENT_C, 200.0])
    point = finger.solve([AMBIENT_C, AMBIENT_C]).tip_position
    with pytest.raises(ValueError) as fixed_err:
        blocked_force(finger, point, MINUS_X, [60.0], fixed_inputs={1: 200.0})
    assert str(fixed_err.value).replace("fixed_inputs[1]", "inputs[1]") == str(solve_err.value)
