"""Inverse kinetostatics from Python (tcarod.inverse, tcarod.models.grasp,
tcarod.models.bruteforce): wrappers, physics signs, agreement of the paper's
finite-difference method with a brute-force optimiser, bad input."""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tcarod import ConvergenceError
from tcarod.models.bruteforce import brute_force_blocked_temperature, brute_force_tip_position
from tcarod.models.grasp import grasp, grasp_temperature, table1_finger
from tcarod.inverse import (
    blocked_force,
    blocked_temperature,
    blocked_temperature_direct,
    jacobian_and_compliance,
    tip_position,
)
from tcarod.batch import fig6_square_robot
from tcarod.models.manipulators import square_manipulator

MINUS_X = (-1.0, 0.0, 0.0)


@pytest.fixture(scope="module")
def square40():  # type: ignore[no-untyped-def]
    return square_manipulator(0.040)


@pytest.fixture(scope="module")
def fig8_setup():  # type: ignore[no-untyped-def]
    """26 mm manipulator, upright; tip blocked where it is at 55 C, pressing along -x."""
    robot = square_manipulator(0.026)
    free = robot.solve([55.0, 55.0])
    return robot, free, [float(x) for x in free.tip_position]


def test_jacobian_matches_bvp_differences_and_heating_bends_toward_minus_x(square40) -> None:  # type: ignore[no-untyped-def]
    sol = square40.solve([100.0, 100.0])
    j, c = jacobian_and_compliance(sol, groups=[0, 0], scheme="central")
    assert j.shape == (6, 1) and c.shape == (6, 6)
    assert j.dtype == np.float64 and c.dtype == np.float64
    # brute-force column: central difference of two BVP solves, h = 0.01 C
    # (O(h^2) truncation ~1e-8 relative for this smooth response)
    h = 0.01
    plus = square40.solve([100.0 + h] * 2, tol=1e-12).tip_position
    minus = square40.solve([100.0 - h] * 2, tol=1e-12).tip_position
    fd = (plus - minus) / (2 * h)
    # central FD of IVPs vs central FD of BVPs: both ~1e-8 relative; 1e-5 leaves margin
    assert np.allclose(j[:3, 0], fd, rtol=1e-5, atol=1e-5 * np.abs(fd).max())
    assert j[0, 0] < 0.0  # TCA at +x: heating moves the tip toward -x
    # conservative loads: C is symmetric (central differences, ~1e-8) and positive on its diagonal
    assert np.abs(c - c.T).max() < 1e-6 * np.abs(c).max()
    assert np.all(np.diag(c) > 0)


def test_tip_position_reaches_a_reachable_target(square40) -> None:  # type: ignore[no-untyped-def]
    truth = square40.solve([90.0, 140.0])
    res = tip_position(square40, truth.tip_position, groups=[0, 1], start=[25.0, 25.0])
    assert res.reached
    assert res.error <= 1e-7  # the default tol [m]
    assert np.linalg.norm(res.solution.tip_position - truth.tip_position) <= 1e-7
    assert res.at_bound == [False, False]
    # the two legs' temperatures are identifiable (they bend about different axes):
    # a 1e-7 m tip error maps to ~1e-3 C through the smallest singular value of J
    assert res.variables == pytest.approx([90.0, 140.0], abs=5e-3)


def test_tip_position_unreachable_target_returns_closest_configuration(square40) -> None:  # type: ignore[no-untyped-def]
    # extension TCAs at +x only bend the body toward -x: a target at +x is unreachable
    res = tip_position(square40, [0.02, 0.0, 0.03], groups=[0, 0], start=[60.0])
    assert not res.reached
    assert res.at_bound == [True]
    assert res.variables == pytest.approx([25.0], abs=1e-9)  # closest: not heated at all
    free = square40.solve([25.0, 25.0])
    # the same configuration as the free solve at the bound, to its tolerance
    assert res.error == pytest.approx(float(np.linalg.norm(free.tip_position - [0.02, 0.0, 0.03])), rel=1e-9)


def test_blocked_force_and_both_inverse_methods_round_trip(fig8_setup) -> None:  # type: ignore[no-untyped-def]
    robot, free, point = fig8_setup
    at_100 = blocked_force(robot, point, MINUS_X, 100.0, groups=[0, 0])
    assert at_100.force > 0.0  # heated past the taut temperature: the tip presses on the wire
    # the mixed solve holds the tip on the plane to its tolerance, 1e-9 of the 26 mm length
    assert at_100.solution.tip_position[0] == pytest.approx(point[0], abs=1e-9 * 0.026)
    inc = blocked_temperature(robot, point, MINUS_X, at_100.force, free, groups=[0, 0])
    direct = blocked_temperature_direct(robot, point, MINUS_X, at_100.force, groups=[0, 0])
    # both close the tip gap to 1e-9 L (~3e-11 m); dT/dx ~ 1e4 C/m: agreement << 1e-6 C
    assert inc.variables[0] == pytest.approx(100.0, abs=1e-6)
    assert direct.variables[0] == pytest.approx(100.0, abs=1e-6)
    assert inc.force == pytest.approx(at_100.force, rel=1e-12)


def test_blocked_temperature_at_the_top_of_the_range(fig8_setup) -> None:  # type: ignore[no-untyped-def]
    robot, free, point = fig8_setup
    top = blocked_force(robot, point, MINUS_X, [160.0], groups=[0, 0])
    inc = blocked_temperature(robot, point, MINUS_X, top.force, free, groups=[0, 0])
    # as above: a tip gap of 1e-9 L is far below 1e-6 C
    assert inc.variables[0] == pytest.approx(160.0, abs=1e-6)
    with pytest.raises(ValueError, match="outside"):
        blocked_temperature(robot, point, MINUS_X, 1.05 * top.force, free, groups=[0, 0])


def _opposing_linear_tendons(length: float, radius: float, k_outer: float, k_inner: float):  # type: ignore[no-untyped-def]
    """A 1 MPa rod [m] with two linear tendons [N/m] 3 mm off its axis, opposing."""
    from tcarod import Actuator, Body, Robot, Routing, Section

    body = Body(length, Section.circle(radius), 1e6, poisson=0.5, density=1000.0, gravity=(0.0, 0.0, 0.0))
    acts = [Actuator.linear_tendon(k, Routing.straight(x, 0.0)) for k, x in ((k_outer, 3e-3), (k_inner, -3e-3))]
    return Robot(body, acts)


def test_blocked_force_through_a_linear_tendons_onset() -> None:
    # Two opposing linear tendons (200 N/m, 3 mm off the axis): pulled 0.5 mm
    # and 0, the free rod bends toward +x and stretches the outer tendon taut
    # (4.5 mN). A wall 30 % of the tip's deflection back pushes the tip in,
    # which slackens it: the mixed solve has to cross that tendon's onset,
    # a kink of its tension law, without the forward solve's semismooth
    # step. Measured 3 iterations, 9 IVPs, the outer tendon exactly slack.
    robot = _opposing_linear_tendons(0.2, 10e-3, 200.0, 200.0)
    free = robot.solve([5e-4, 0.0])
    assert free.tensions[1] > 1e-3  # [N] taut in the free bend
    tip = free.tip_position
    wall = tip - [0.3 * tip[0], 0.0, 0.0]
    held = blocked_force(robot, wall, (1.0, 0.0, 0.0), [5e-4, 0.0], groups=[0, 1])
    assert held.success and held.force > 0.0  # [N] the tip presses on the wall
    assert held.solution.tensions[1] == 0.0  # slack: on the law's zero piece, exactly
    # on the wall to the mixed solve's tolerance, 1e-9 of the 0.2 m length
    assert held.solution.tip_position[0] == pytest.approx(wall[0], abs=1e-9 * 0.2)
    # 3 measured; 8 leaves room for a changed line search but fails a solve
    # that stalls at the kink
    assert held.nit <= 8, held


@pytest.mark.parametrize("pulls", [(5e-4, -1e-4), (-1e-4, 5e-4), (5e-4, -4.4e-5)])
def test_tip_position_reaches_a_shape_with_a_slack_tendon(pulls: tuple[float, float]) -> None:
    # Two opposing linear tendons (200 N/m); the target is the tip of a solve
    # in which one tendon is released past its onset (slack, tension 0) or
    # just short of it (0.5 mN): the inverse starts from both at their onset
    # (pulls 0, straight rod) and must step across the kink of the slack law.
    # The slack pull is not unique (any pull past the onset gives the same
    # shape), so only the tip is checked. Measured 2 iterations, 9 IVPs, tip
    # error 1e-9 to 5e-9 m from every start tried.
    robot = _opposing_linear_tendons(0.2, 10e-3, 200.0, 200.0)
    goal = robot.solve(list(pulls))
    assert min(goal.tensions) < 1e-3  # [N] one tendon slack or nearly
    r = tip_position(robot, goal.tip_position)
    assert r.reached and r.status == 0, r
    assert r.error <= 1e-7  # [m] the default tol
    # the same tolerance on every coordinate
    assert np.allclose(r.solution.tip_position, goal.tip_position, atol=1e-7)
    assert r.nit <= 5, r  # 2 measured; a solve stalling at the kink takes the 50 allowed


def test_grasp_through_a_linear_tendons_onset() -> None:
    # A tendon finger (one variable: both tendons' pull [m], 200 and 100 N/m,
    # opposing): at contact (pulls 0) both sit exactly at their onset, the
    # kink of the slack law. Eq 44 fixes the force, mu n F = m g; the
    # incremental (eq 43) and direct solves must converge to the same pull.
    # Measured 2.088072e-03 m both ways, direct in 20 IVPs, incremental 55.
    robot = _opposing_linear_tendons(0.1, 8e-3, 200.0, 100.0)
    inc = grasp(1e-3, robot, normal=(1.0, 0.0, 0.0), groups=[0, 0])
    direct = grasp(1e-3, robot, normal=(1.0, 0.0, 0.0), groups=[0, 0], method="direct")
    assert inc.blocked.force == pytest.approx(1e-3 * 9.81 / (1.1 * 2), rel=1e-12)  # eq 44
    assert min(inc.blocked.solution.tensions) > 0.0  # [N] both taut past their onset
    # both solve the same equations to tol 1e-10: the pulls agree to far below
    # the 2 mm they are (1e-9 m is 5e-7 relative)
    assert direct.temperature_c == pytest.approx(inc.temperature_c, abs=1e-9)
    assert direct.blocked.nfev < inc.blocked.nfev


@settings(max_examples=8, deadline=None)  # each example: two ~5 ms mixed solves
@given(st.floats(60.0, 155.0), st.floats(0.5, 5.0))
def test_blocked_force_rises_with_temperature(t: float, dt: float) -> None:
    robot = square_manipulator(0.026)
    point = [float(x) for x in robot.solve([55.0, 55.0]).tip_position]
    lo = blocked_force(robot, point, MINUS_X, [t], groups=[0, 0])
    hi = blocked_force(robot, point, MINUS_X, [t + dt], groups=[0, 0], warm_start=lo)
    assert hi.force > lo.force > 0.0


def test_grasp_eq44_and_monotone_in_mass() -> None:
    temps = [grasp_temperature(m) for m in (1e-3, 2e-3, 3e-3)]
    assert 25.0 < temps[0] < temps[1] < temps[2] < 160.0
    g = grasp(2e-3)
    # eq 44 in closed form (rounding only); the blocked solve presses with it to 1e-12
    assert g.force_per_finger_n == pytest.approx(2e-3 * 9.81 / (1.1 * 2), rel=1e-15)
    assert g.blocked.force == pytest.approx(g.force_per_finger_n, rel=1e-12)
    assert g.temperature_c == temps[1]
    # the tip stays on the block (reference tip position) along the normal
    assert g.blocked.solution.tip_position[0] == pytest.approx(g.block_point_m[0], abs=1e-9 * 0.02)
    # eq 44 only sees m / (mu n): 4 fingers holding 2 g == 2 fingers holding 1 g
    assert grasp_temperature(2e-3, fingers=4) == pytest.approx(temps[0], abs=1e-9)
    # incremental (eq 43) and direct solves converge the same equations
    assert grasp_temperature(2e-3, method="direct") == pytest.approx(temps[1], abs=1e-6)


def test_grasp_temperature_shows_grasps_parameters() -> None:
    # Jupyter, help() and IDEs read inspect.signature: the real keywords, not (*args, **kwargs)
    sig = inspect.signature(grasp_temperature)
    assert sig.parameters == inspect.signature(grasp).parameters
    assert list(sig.parameters)[:5] == ["mass_kg", "finger", "mu", "fingers", "gravity"]
    assert {"normal", "groups", "method", "increments", "steps", "tol", "contact_temperature_c"} <= set(sig.parameters)
    assert sig.return_annotation == "float"
    assert grasp_temperature.__name__ == "grasp_temperature"
    with pytest.raises(TypeError):
        grasp_temperature(1e-3, no_such_keyword=1)  # type: ignore[call-arg]


def test_grasp_default_finger_hangs_and_bends_toward_minus_x() -> None:
    finger = table1_finger()
    cold = finger.solve([25.0, 25.0])
    hot = finger.solve([60.0, 60.0])
    assert cold.tip_position[2] > 0.020  # hanging: gravity stretches it along +z (body-aligned frame)
    assert hot.tip_position[0] < cold.tip_position[0]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"mass_kg": 0.0}, "mass_kg"),
        ({"mass_kg": math.nan}, "mass_kg"),
        ({"mass_kg": 1e-3, "mu": -1.0}, "mu"),
        ({"mass_kg": 1e-3, "fingers": 0}, "fingers"),
        ({"mass_kg": 1e-3, "method": "newton"}, "method"),
        # 50 g needs more than 160 C: the error names the largest mass held
        (
            {"mass_kg": 0.05},
            r"cannot hold 50 g .*: the largest blocked force in \[25, 160\] C is .* N \(.* g\) at 160 C",
        ),
    ],
)
def test_grasp_bad_input(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        grasp(**kwargs)  # type: ignore[arg-type]


def test_wrapper_bad_input(square40) -> None:  # type: ignore[no-untyped-def]
    sol = square40.solve([25.0, 25.0])
    with pytest.raises(ValueError, match="scheme"):
        jacobian_and_compliance(sol, scheme="backward")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="groups"):
        jacobian_and_compliance(sol, groups=[0, -1])
    with pytest.raises(ValueError, match="groups"):
        jacobian_and_compliance(sol, groups=[1, 1])  # variable 0 drives nothing
    with pytest.raises(ValueError, match="target"):
        tip_position(square40, [0.0, 0.04])
    with pytest.raises(ValueError, match="target"):
        tip_position(square40, [0.0, math.nan, 0.04])
    # the core keeps targets within 1000 body lengths (40 m here), so the error stays finite
    with pytest.raises(ValueError, match=r"target = 1000000000 m.*1000 body lengths"):
        tip_position(square40, [1e9, 0.0, 0.0])
    with pytest.raises(TypeError, match="target"):
        tip_position(square40, None)  # type: ignore[arg-type]
    # a negative weight is refused even without a target rotation (it is never silently ignored)
    with pytest.raises(ValueError, match=r"orientation_weight = -1 m/rad.*> 0"):
        tip_position(square40, [0.0, 0.0, 0.03], orientation_weight=-1.0)
    with pytest.raises(TypeError, match="point"):
        blocked_force(square40, None, MINUS_X, [50.0], groups=[0, 0])  # type: ignore[arg-type]  # not the origin
    with pytest.raises(ValueError, match="normal"):
        blocked_force(square40, [0.0, 0.0, 0.04], [0.0, 0.0, 0.0], [50.0], groups=[0, 0])
    with pytest.raises(ValueError, match="variables"):
        blocked_force(square40, [0.0, 0.0, 0.04], MINUS_X, [50.0, 60.0], groups=[0, 0])
    with pytest.raises(ValueError):
        blocked_temperature(square40, [0.0, 0.0, 0.04], MINUS_X, 1e-3, sol)  # two variables: needs one


def test_direct_solve_from_a_hopeless_guess_raises_convergence_error(fig8_setup) -> None:  # type: ignore[no-untyped-def]
    robot, _, point = fig8_setup
    # a force the actuator cannot reach within its range: Newton cannot converge in range
    with pytest.raises((ConvergenceError, ValueError)):
        blocked_temperature_direct(robot, point, MINUS_X, 10.0, guess=150.0, groups=[0, 0], max_iter=10)


# --------------------------------------------------------------------------
# The paper's finite-difference method and brute force agree
# --------------------------------------------------------------------------


def test_brute_force_grasp_temperature_agrees_with_eq43() -> None:
    finger = table1_finger()
    g = grasp(2e-3, finger)
    bf = brute_force_blocked_temperature(finger, g.block_point_m, g.normal, g.force_per_finger_n)
    # Brent stops at xatol = 1e-6 C; eq 43 closes the gap to 2e-11 m (~1e-7 C)
    assert bf.variables[0] == pytest.approx(g.temperature_c, abs=1e-4)
    assert bf.error_m < 1e-8
    assert bf.forward_solves > 10  # it really is an optimisation over BVP solves


def test_brute_force_tip_position_agrees_with_finite_differences(square40) -> None:  # type: ignore[no-untyped-def]
    target = square40.solve([90.0, 140.0]).tip_position
    fd = tip_position(square40, target, groups=[0, 1], start=[25.0, 25.0])
    bf = brute_force_tip_position(square40, target, groups=[0, 1], start=[25.0, 25.0])
    assert fd.reached and bf.error_m < 1e-7
    # both within 1e-7 m of the target; the worst-conditioned direction of J
    # turns that into up to ~1e-3 C, so 5e-3 C
    assert bf.variables == pytest.approx(tuple(fd.variables), abs=5e-3)
    assert bf.forward_solves > 3 * fd.iterations


# ------------------------------------------------------------ SciPy-style results

FIG6 = fig6_square_robot()


@pytest.mark.parametrize(
    "temps", [(40.0, 40.0), (90.0, 90.0), (130.0, 130.0), (40.0, 90.0), (130.0, 90.0), (40.0, 130.0)]
)
def test_reachable_fig6_targets_are_reached_with_the_default_budget(temps: tuple[float, float]) -> None:
    target = FIG6.solve(list(temps)).tip_position
    res = tip_position(FIG6, target)  # defaults: tol 1e-7 m, max_iter 50
    assert res.success and res.reached and res.status == 0, res
    assert res.error <= 1e-7 and res.nit < res.max_iter
    assert "reached" in res.message
    # the temperatures that made the target come back (the map is 1:1 here);
    # 5e-3 C: a 1e-7 m tip tolerance over the weakest sensitivity, one leg at
    # 40 C with 38.2 turns per leg (4.6e-5 m/C, so ~2.2e-3 C), with margin
    np.testing.assert_allclose(res.variables, temps, rtol=0, atol=5e-3)
    np.testing.assert_array_equal(res.tip_position, res.solution.tip_position)
    assert res.nfev == res.evaluations > 0


def test_unreachable_is_told_from_out_of_budget() -> None:
    # toward +x: heating an extension TCA at +x bends the tip toward -x, so
    # the closest point is the unheated body, both legs at 25 C (a bound)
    far = tip_position(FIG6, [0.01, 0.0, 0.04], groups=[0, 0])
    assert not far.success and far.status == 1 and "unreachable" in far.message
    assert far.at_bound == [True] and far.variables == [25.0]
    # a reachable target with a budget of one iteration: out of budget
    target = FIG6.solve([120.0, 120.0]).tip_position
    short = tip_position(FIG6, target, groups=[0, 0], max_iter=1)
    assert not short.success and short.status == 2 and "budget" in short.message
    assert short.nit == 1  # (the first step may overshoot to a bound: budget, not reachability, stopped it)
    # ...and continuing from where it stopped reaches it
    more = tip_position(FIG6, target, groups=[0, 0], start=short.variables)
    assert more.status == 0


def test_solution_and_blocked_results_read_like_scipy() -> None:
    sol = FIG6.solve([90.0, 90.0])
    assert (sol.success, sol.status, sol.nit, sol.nfev) == (True, 0, sol.iterations, sol.evaluations)
    assert "converged" in sol.message
    tip = FIG6.solve([25.0, 25.0]).tip_position
    b = blocked_force(FIG6, tip, [-1.0, 0.0, 0.0], [60.0], groups=[0, 0])
    assert (b.success, b.status, b.nit, b.nfev) == (True, 0, b.iterations, b.evaluations)
    # the tip is held on the plane x = tip_x: its x is unchanged (1e-9 m:
    # the mixed BVP's residual tolerance on the plane condition)
    assert abs(b.tip_position[0] - tip[0]) < 1e-9


@pytest.fixture(scope="module")
def planar_finger():  # type: ignore[no-untyped-def]
    """The getting-started finger: two opposite TCAs in the x-z plane, so the tip never leaves it."""
    from tcarod import Actuator, Body, Robot, Routing, Section
    from tcarod.models.manipulators import leg_turns, manipulator_tca

    body = Body.from_material("ecoflex-00-30", 0.060, Section.rectangle(12e-3, 12e-3), gravity=(0.0, 0.0, -9.81))
    tca = manipulator_tca(0.060, turns=leg_turns(0.060, 1, "per_length"))
    return Robot(body, [Actuator.tca(tca, Routing.straight(x, 0.0)) for x in (4e-3, -4e-3)])


def test_inverse_with_a_fixed_input_is_a_forward_solve(planar_finger) -> None:  # type: ignore[no-untyped-def]
    target = planar_finger.solve([100.0, 25.0]).tip_position
    # the x-z plane has two coordinates and one variable: aim at a point on
    # the one-TCA curve (reachable), the other TCA held at ambient
    res = tip_position(planar_finger, target, fixed_inputs={1: 25.0})
    assert res.success and res.status == 0
    assert len(res.variables) == 1
    assert res.variables[0] == pytest.approx(100.0, abs=1e-3)
    assert res.solution.inputs[1] == 25.0
    # a forward solve at the found variable with the fixed input is the
    # inverse's tip (Newton tol 1e-10: tips agree to ~1e-12 m), within tol
    again = planar_finger.solve([res.variables[0], 25.0])
    assert np.linalg.norm(again.tip_position - target) <= 1e-7 + 1e-10
    # the other conventions of groups are the same problem
    for groups in ([0, None], [0]):
        same = tip_position(planar_finger, target, fixed_inputs={1: 25.0}, groups=groups)
        assert list(same.variables) == list(res.variables)


def test_off_plane_target_of_a_planar_finger_stalls_at_the_closest_point(planar_finger) -> None:  # type: ignore[no-untyped-def]
    in_plane = planar_finger.solve([100.0, 25.0]).tip_position
    target = in_plane + np.array([0.0, 2e-3, 0.0])
    res = tip_position(planar_finger, target, max_iter=500)
    # the error cannot fall below the 2 mm off the plane: the iteration ends
    # within a few Gauss-Newton steps (measured 4), not at max_iter
    assert not res.success
    assert res.status == 3
    assert res.nit <= 10
    assert "max_iter" not in res.message
    assert "closest tip point found" in res.message and "0.002 m from the target" in res.message
    # the closest point is the in-plane projection of the target: y = 0 by
    # symmetry, distance 2 mm to the inverse's tol
    assert abs(res.tip_position[1]) < 1e-12
    assert res.error == pytest.approx(2e-3, abs=1e-7)
    assert np.linalg.norm(res.tip_position - in_plane) < 1e-7
    # variables and solution are the closest point's
    again = planar_finger.solve(list(res.variables))
    assert np.linalg.norm(again.tip_position - res.tip_position) < 1e-9


def test_jacobian_with_a_fixed_input_has_columns_for_variables_only(planar_finger) -> None:  # type: ignore[no-untyped-def]
    sol = planar_finger.solve([90.0, 40.0])
    j, c = jacobian_and_compliance(sol, fixed_inputs={1: 40.0}, scheme="central")
    j_all, c_all = jacobian_and_compliance(sol, scheme="central")
    assert j.shape == (6, 1) and c.shape == (6, 6)
    # central differences of forward solves in the heated TCA's temperature
    # (h = 0.05 C: O(h^2) truncation ~1e-7 relative, Newton tol 1e-12 below it)
    h = 0.05
    plus = planar_finger.solve([90.0 + h, 40.0], tol=1e-12).tip_position
    minus = planar_finger.solve([90.0 - h, 40.0], tol=1e-12).tip_position
    fd = (plus - minus) / (2 * h)
    assert np.allclose(j[:3, 0], fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())
    # the same column as with one variable per actuator; C does not depend on the grouping
    assert np.allclose(j[:, 0], j_all[:, 0], rtol=1e-7, atol=1e-12)
    assert np.allclose(c, c_all, rtol=1e-7, atol=1e-12)
    # the fixed input must be the solution's own
    with pytest.raises(ValueError, match=r"fixed_inputs\[1\]"):
        jacobian_and_compliance(sol, fixed_inputs={1: 25.0})
