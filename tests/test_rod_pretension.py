"""Pre-tension of contraction TCAs (`Actuator.tca(..., pretension_n=...)`).

A contraction TCA installed with its coils touching cannot get shorter when
heated: it only presses harder on its own coils, so the body barely moves.
Installed stretched (pre-tensioned), it has room to contract and bends the
body by millimetres. Body: 40 mm long, 10 mm square, E = 1 MPa (a stiffer
silicone than the paper's EcoFlex, so that 0.3 N of pre-tension does not
already fold it at ambient); TCA as the paper's manipulator TCAs but
homochiral (contraction), 3 mm off the centre line.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tcarod import Actuator, Body, Robot, Routing, Section, Tca

LENGTH = 0.040
BODY = Body(LENGTH, Section.rectangle(0.01, 0.01), 1e6, density=1040.0, gravity=(0.0, 0.0, 0.0))
TCA = Tca.from_pitch_angle(LENGTH, math.radians(15.0), 1.7e-3, 76.4, "contraction")


def _robot(pretension_n: float | None) -> Robot:
    return Robot(BODY, [Actuator.tca(TCA, Routing.straight(3e-3, 0.0), pretension_n=pretension_n)])


def _tip_travel_mm(robot: Robot) -> float:
    cold, hot = robot.solve([25.0]), robot.solve([160.0])
    return float(np.linalg.norm(hot.tip_position - cold.tip_position)) * 1e3


def test_a_pretensioned_contraction_tca_heated_to_160_c_moves_the_tip_by_millimetres() -> None:
    without = _tip_travel_mm(_robot(None))
    with_pre = _tip_travel_mm(_robot(0.3))
    # Without pre-tension only the coil-contact column's thermal change acts:
    # measured 0.12 mm. With 0.3 N the TCA is stretched by ~0.7 mm at 25 C and
    # contracts back onto its coils when heated: measured 2.6 mm. The bounds
    # (< 0.3 mm, > 1.5 mm) leave room for solver changes, not for the effect
    # to vanish.
    assert without < 0.3
    assert with_pre > 1.5
    # a contraction TCA at +x pulls the tip toward +x when heated
    robot = _robot(0.3)
    assert robot.solve([160.0]).tip_position[0] > robot.solve([25.0]).tip_position[0]


def test_pretension_sets_the_length_ratio_and_stretches_the_tca_at_ambient() -> None:
    robot = _robot(0.3)
    (act,) = robot.actuators
    assert act.pretension_n == 0.3 and act.length_ratio is None  # resolved inside the robot
    cold = robot.solve([25.0])
    # stretched (elongation > 0) and pulling (tension > 0), but less than the
    # installed 0.3 N: the body shortens and bends under it
    assert cold.elongations[0] > 0.0
    assert 0.0 < cold.tensions[0] < 0.3
    # the same robot built from the equivalent constant length ratio L_i
    stretch = TCA.displacement(0.3, 25.0)
    ratio = 1.0 - stretch / LENGTH
    same = Robot(BODY, [Actuator.tca(TCA, Routing.straight(3e-3, 0.0), length_ratio=ratio)])
    # the same equations from the same ratio: rounding only
    np.testing.assert_allclose(same.solve([25.0]).tip_position, cold.tip_position, rtol=0, atol=1e-12)


def test_zero_pretension_is_the_plain_actuator() -> None:
    a, b = _robot(0.0).solve([120.0]), _robot(None).solve([120.0])
    # no stretch, the reference length: the same equations, rounding only
    np.testing.assert_allclose(a.tip_position, b.tip_position, rtol=0, atol=1e-12)


def test_pretension_errors_name_the_argument() -> None:
    with pytest.raises(ValueError, match="pretension_n"):
        Actuator.tca(TCA, Routing.straight(3e-3, 0.0), pretension_n=-1.0)
    with pytest.raises(ValueError, match="pretension_n / length_ratio"):
        Actuator.tca(TCA, Routing.straight(3e-3, 0.0), length_ratio=0.99, pretension_n=0.1)
    curved = Body(LENGTH, Section.rectangle(0.01, 0.01), 1e6, omega_star=[0.0, 5.0, 0.0])
    # a helix in a curved body has a non-constant reference length rate
    with pytest.raises(ValueError, match=r"actuators\[0\]\.pretension_n"):
        Robot(curved, [Actuator.tca(TCA, Routing.helix(3e-3, 50.0), pretension_n=0.1)])
    # a straight routing in a uniformly curved body is fine (constant rate)
    Robot(curved, [Actuator.tca(TCA, Routing.straight(3e-3, 0.0), pretension_n=0.1)])
