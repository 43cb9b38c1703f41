"""The paper's fixtures bound from the core (``tcarod::experiments``): the
same objects as the Python builders (``tcarod.models.manipulators``), and
eq 44 (``grasp_temperature``) bound."""

from __future__ import annotations

import pickle

import pytest

from tcarod import _core
from tcarod.models.manipulators import HANGING, square_manipulator


def test_fixture_manipulators_equal_the_python_builders() -> None:
    assert _core.fixture_manipulator("fig6_square") == square_manipulator(0.040)
    assert _core.fixture_manipulator("fig8") == square_manipulator(0.026)
    assert _core.fixture_manipulator("table1_finger") == square_manipulator(0.020, gravity_m_per_s2=HANGING)
    per_leg = _core.fixture_manipulator("square", length=0.026, turns_reading="per_leg")
    assert per_leg == square_manipulator(0.026, turns_reading="per_leg")
    robot = _core.fixture_manipulator("fig6_circle")
    assert pickle.loads(pickle.dumps(robot)) == robot


def test_fixture_constants_and_tcas() -> None:
    k = _core.fixture_constants()
    assert k["gravity"] == 9.81 and k["ecoflex10_youngs_modulus"] == 37.8e3
    # the zero-force intercept of the paper's Table I predictions (by hand: 72.333 C)
    assert k["table1_contact_temperature"] == pytest.approx(72.3333333333, abs=1e-9)
    whole, half = _core.fixture_fig5_tca(3), _core.fixture_fig5_half_tca(3)
    assert half == whole.segment(0.5)
    # per_length keeps 76.4 turns per 40 mm: 76.4 x 26 / 40 = 49.66 per 26 mm leg, rounding only
    assert _core.fixture_leg_turns(0.026, 2, "per_length") == pytest.approx(49.66, abs=1e-12)


def test_bad_fixture_arguments_raise_value_error() -> None:
    with pytest.raises(ValueError, match="name"):
        _core.fixture_manipulator("fig9")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="turns_reading"):
        _core.fixture_manipulator("fig8", turns_reading="per_thread")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="threads"):
        _core.fixture_fig5_tca(5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="legs"):
        _core.fixture_leg_turns(0.02, -1)


def test_grasp_temperature_presses_with_the_eq_44_force() -> None:
    finger = _core.fixture_manipulator("table1_finger")
    k = _core.fixture_constants()
    res, point = _core.grasp_temperature(finger, k["table1_normal"], 1e-3, k["table1_mu"], 2, groups=[0, 0])
    # the tip is blocked where it rests at the reference inputs
    rest = finger.solve(finger.reference_inputs, stability="off").tip_position
    assert point == pytest.approx(list(rest), abs=1e-12)  # same solve, same unknowns: to rounding
    # eq 44: mu n F = m g, so F = 1e-3 * 9.81 / (1.1 * 2) N, exactly
    assert res.force == pytest.approx(1e-3 * 9.81 / 2.2, rel=1e-12)
    lo, hi = finger.actuators[0].input_bounds
    assert lo < res.variables[0] < hi
    with pytest.raises(ValueError, match="mass"):
        _core.grasp_temperature(finger, k["table1_normal"], -1.0, 1.1, 2, groups=[0, 0])
    with pytest.raises(ValueError, match="method"):
        _core.grasp_temperature(finger, k["table1_normal"], 1e-3, 1.1, 2, method="bisection")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="contact"):
        _core.grasp_temperature(finger, k["table1_normal"], 1e-3, 1.1, 2, contact=[72.0])


def test_tendon_fixtures_and_spacer_disks_round_trip() -> None:
    import pickle

    steel = _core.fixture_tendon_robot("steel")
    assert steel.spacer_disks and "spacer_disks=True" in repr(steel)
    assert pickle.loads(pickle.dumps(steel)) == steel
    tensions = _core.fixture_constants()["steel_tendon_tensions"]
    assert steel.solve(tensions, stability="off").success
    # the same layout without spacer disks breaks the routing-inside-the-section rule
    with pytest.raises(ValueError, match="routing"):
        _core.Robot(steel.body, steel.actuators)
    assert not _core.fixture_tendon_robot("soft").spacer_disks
    with pytest.raises(ValueError, match="name"):
        _core.fixture_tendon_robot("brass")  # type: ignore[arg-type]
