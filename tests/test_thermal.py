"""Electro-thermal model of a Joule-heated TCA (``tcarod.models.thermal``: a
lumped heat balance with the coefficients of Sun & Zhao's code, see
docs/choices.md "Beyond the paper"), and voltage-driven shapes."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tcarod.paper.fig1b import FIG1B
from tcarod.models.thermal import LinearResistance, ThermalModel, VoltageProfile
from tcarod.models.trajectory import quasi_static_trajectory, solve_with_voltages
from tcarod.plotting import plot_shape_trajectory, plot_step_response, save_trajectory_frames

L_FIBRE = FIG1B.tca().fibre_length  # ~0.232 m
MODEL = ThermalModel(fibre_length_m=L_FIBRE, threads=3, resistance=60.0)


def test_lumped_parameters_and_time_constant() -> None:
    r = 0.1e-3
    m = 1127.0 * 3 * math.pi * r * r * L_FIBRE
    a = 3 * 2 * math.pi * r * L_FIBRE
    # closed forms: rounding only
    assert MODEL.mass_kg == pytest.approx(m, rel=1e-14)
    assert MODEL.area_m2 == pytest.approx(a, rel=1e-14)
    # tau = m c_p / (h A) = density c_p r / (2 h): independent of l and threads
    assert MODEL.time_constant_s == pytest.approx(1127.0 * 2000.0 * r / (2 * 23.0), rel=1e-12)
    assert MODEL.time_constant_s == pytest.approx(4.9, abs=0.01)
    assert replace(MODEL, threads=4, fibre_length_m=0.5).time_constant_s == pytest.approx(
        MODEL.time_constant_s, rel=1e-12
    )


def test_resistance_is_required_and_checked() -> None:
    with pytest.raises(TypeError):
        ThermalModel(fibre_length_m=0.2, threads=3)  # type: ignore[call-arg]
    # None is a wrong type, so TypeError (the package's bad-input contract), naming the argument
    with pytest.raises(TypeError, match="resistance"):
        ThermalModel(fibre_length_m=0.2, threads=3, resistance=None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="resistance"):
        ThermalModel(fibre_length_m=0.2, threads=3, resistance=-1.0)


def test_steady_state_is_analytic_and_inverse() -> None:
    v = 2.0
    expected = 25.0 + v * v / (60.0 * MODEL.conductance_w_per_k)
    # the steady state in closed form, and its inverse: rounding only
    assert MODEL.steady_temperature(v) == pytest.approx(expected, rel=1e-14)
    assert MODEL.steady_voltage(expected) == pytest.approx(v, rel=1e-12)
    with pytest.raises(ValueError, match="t_max"):
        MODEL.steady_voltage(170.0)
    with pytest.raises(ValueError, match="t_max"):
        MODEL.steady_temperature(50.0)


def test_step_response_reaches_63_percent_at_tau() -> None:
    tau = MODEL.time_constant_s
    tss = MODEL.steady_temperature(2.0)
    traj = MODEL.transient(VoltageProfile.step(2.0), [0.0, tau, 10 * tau])
    assert traj.method.startswith("analytic")
    rise = (traj.temperature_c - 25.0) / (tss - 25.0)
    assert rise[0] == 0.0
    # the analytic solution is these exponentials: rounding only
    assert rise[1] == pytest.approx(1 - math.exp(-1), rel=1e-12)
    assert rise[2] == pytest.approx(1 - math.exp(-10), rel=1e-12)
    assert traj.exceeds_t_max_at_s is None


def _energy_residual(model: ThermalModel, profile: VoltageProfile, t_end: float) -> tuple[float, float]:
    t = np.linspace(0.0, t_end, 20001)
    traj = model.transient(profile, t)
    # power on each interval with the voltage of that interval (the voltage
    # jumps at switches; sampling it at a switch would cost |dP| dt / 2)
    v_mid = np.array([profile(0.5 * (a + b)) for a, b in zip(t[:-1], t[1:])])
    r = np.array([model.resistance_ohm(float(x)) for x in traj.temperature_c])
    p_left, p_right = v_mid**2 / r[:-1], v_mid**2 / r[1:]
    e_in = float(np.sum(0.5 * (p_left + p_right) * np.diff(t)))
    q = model.conductance_w_per_k * (traj.temperature_c - model.ambient_c)
    e_loss = float(np.sum(0.5 * (q[:-1] + q[1:]) * np.diff(t)))  # trapezoid (numpy < 2 has no np.trapezoid)
    e_stored = model.heat_capacity_j_per_k * (traj.temperature_c[-1] - traj.temperature_c[0])
    return float(e_in - e_loss - e_stored), float(e_in)


@pytest.mark.parametrize(
    "resistance",
    [60.0, LinearResistance(60.0, alpha_per_c=-1e-3), lambda t, e: 50.0 + 0.1 * (t - 25.0)],
    ids=["constant", "linear", "callable"],
)
def test_energy_balance(resistance: object) -> None:
    model = replace(MODEL, resistance=resistance)
    profile = VoltageProfile((0.0, 6.0, 9.0), (8.0, 2.0, 5.0))
    resid, e_in = _energy_residual(model, profile, 15.0)
    # electrical energy = stored + convected; the trapezoid rule on 20001
    # samples errs by O(dt^2) = O(1e-7) relative: 1e-6 of the input is safe
    assert abs(resid) < 1e-6 * e_in


def test_numeric_integrator_matches_analytic_for_constant_resistance() -> None:
    # a callable constant resistance takes the RK4 path: it must agree with the
    # exponentials to RK4's O(dt^4) (tau/200 steps: ~1e-10 relative)
    profile = VoltageProfile((0.0, 4.0), (2.0, 0.7))
    t = np.linspace(0.0, 12.0, 25)
    exact = MODEL.transient(profile, t).temperature_c
    numeric = replace(MODEL, resistance=lambda T, e: 60.0).transient(profile, t)
    assert numeric.method.startswith("numeric")
    assert np.max(np.abs(numeric.temperature_c - exact)) < 1e-7


def test_transient_reports_exceeding_t_max() -> None:
    traj = MODEL.transient(VoltageProfile.step(12.0), np.linspace(0, 20, 201))
    assert traj.exceeds_t_max_at_s is not None and 0.0 < traj.exceeds_t_max_at_s < 20.0
    assert traj.temperature_c[-1] > 160.0  # not clipped


@settings(max_examples=30, deadline=None)
@given(st.floats(min_value=20.0, max_value=200.0), st.floats(min_value=-2e-3, max_value=2e-3))
def test_steady_voltage_inverts_steady_temperature_for_linear_resistance(r0: float, alpha: float) -> None:
    model = replace(MODEL, resistance=LinearResistance(r0, alpha_per_c=alpha))
    for t in (40.0, 100.0, 155.0):
        v = model.steady_voltage(t)
        # bisection to 2^-200 of the bracket: round-off level
        assert model.steady_temperature(v) == pytest.approx(t, abs=1e-9)


def test_voltages_drive_the_robot_and_trajectory_ends_at_steady_shape(tmp_path: Path) -> None:
    robot = FIG1B.robot()
    models = [MODEL] * 3
    volts = [MODEL.steady_voltage(120.0), 0.0, MODEL.steady_voltage(60.0)]
    steady = solve_with_voltages(robot, models, volts)
    # the voltages are steady_voltage of these temperatures, exact to round-off: 1e-9 C
    assert np.allclose(steady.inputs, [120.0, 25.0, 60.0], atol=1e-9)
    profiles = [VoltageProfile.step(v) for v in volts]
    t = np.linspace(0.0, 12 * MODEL.time_constant_s, 25)
    traj = quasi_static_trajectory(robot, models, profiles, t)
    assert traj.tip_positions_m.shape == (25, 3)
    # starts straight (ambient), ends at the steady shape: after 12 tau the
    # temperatures are within 6e-6 of the rise (~1e-3 C), and the tip moves
    # ~0.3 mm/C, so 1e-6 m
    assert np.allclose(traj.tip_positions_m[0], [0, 0, robot.solve([25.0] * 3).tip_position[2]], atol=1e-9)
    assert np.linalg.norm(traj.tip_positions_m[-1] - steady.tip_position) < 1e-5
    # the tip moves monotonically away from the heated TCA 0 (at +x)
    assert np.all(np.diff(traj.tip_positions_m[:, 0]) <= 1e-12)
    fig = plot_shape_trajectory(traj)
    fig.savefig(tmp_path / "traj.png")
    plot_step_response(MODEL, 2.0).savefig(tmp_path / "step.png")
    assert (tmp_path / "traj.png").stat().st_size > 1000
    frames = save_trajectory_frames(traj, tmp_path / "frames", every=12)
    assert [p.name for p in frames] == ["frame_0000.png", "frame_0012.png", "frame_0024.png"]


def test_strain_dependent_resistance_couples_heating_and_shape() -> None:
    robot = FIG1B.robot()
    base = [MODEL] * 3
    coupled = [replace(MODEL, resistance=LinearResistance(60.0, strain_coefficient=2.0))] + [MODEL] * 2
    volts = [MODEL.steady_voltage(110.0), 0.0, 0.0]
    profiles = [VoltageProfile.step(v) for v in volts]
    t = np.linspace(0.0, 15.0, 16)
    a = quasi_static_trajectory(robot, base, profiles, t)
    b = quasi_static_trajectory(robot, coupled, profiles, t)
    # the heated TCA lengthens, its resistance rises, it draws less power:
    # cooler than with constant resistance (a visible difference, > 0.1 C)
    assert b.temperatures_c[-1, 0] < a.temperatures_c[-1, 0] - 0.1


# ------------------------------------------------------------------ bad input


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_power_rejects_non_finite_voltage_and_temperature(bad: float) -> None:
    with pytest.raises(ValueError, match="voltage_v"):
        MODEL.power_w(bad, 60.0)
    with pytest.raises(ValueError, match="temperature_c"):
        MODEL.power_w(1.0, bad)


def test_power_overflow_is_a_value_error_not_inf() -> None:
    with pytest.raises(ValueError, match="voltage_v"):
        MODEL.power_w(1e200, 60.0)  # V^2 overflows the double range


@pytest.mark.parametrize("bad", [math.inf, -math.inf, math.nan, 1e300])
def test_transient_rejects_unphysical_initial_temperature(bad: float) -> None:
    with pytest.raises(ValueError, match="initial_c"):
        MODEL.transient(VoltageProfile.step(1.0), [0.0, 1.0], initial_c=bad)


def test_profile_starting_at_minus_1e300_returns_promptly() -> None:
    # 1e300 s of RK4 steps would never end: the step count is capped, with a documented ValueError
    profile = VoltageProfile((-1e300, 0.0), (0.0, 1.0))
    model_t = ThermalModel(0.3, 3, LinearResistance(60.0, 0.002))
    with pytest.raises(ValueError, match="RK4 steps"):
        model_t.transient(profile, [0.0, 1.0])
    # constant resistance: exact exponentials, no steps to count; the result is finite
    out = MODEL.transient(profile, [0.0, 1.0])
    assert np.all(np.isfinite(out.temperature_c))


def test_tiny_heat_transfer_is_a_value_error_not_zero_division() -> None:
    with pytest.raises(
        ValueError,
        match=r"heat_transfer_w_per_m2k = 4.940656458e-324 W/\(m\^2 K\): allowed in \[0.001, 100000\] W/\(m\^2 K\)",
    ):
        ThermalModel(0.3, 3, 60.0, heat_transfer_w_per_m2k=5e-324)


@pytest.mark.parametrize(
    ("kwargs", "exc", "name"),
    [
        ({"fibre_length_m": "0.3"}, TypeError, "fibre_length_m"),
        ({"fibre_length_m": None}, TypeError, "fibre_length_m"),
        ({"threads": 2.5}, TypeError, "threads"),
        ({"threads": 10**400}, ValueError, "threads"),
        ({"threads": -1}, ValueError, "threads"),
        ({"ambient_c": 1j}, TypeError, "ambient_c"),
        ({"resistance": "60"}, TypeError, "resistance"),
    ],
)
def test_model_arguments_wrong_type_or_range_name_the_argument(kwargs: dict[str, Any], exc: type, name: str) -> None:
    args: dict[str, Any] = {"fibre_length_m": 0.3, "threads": 3, "resistance": 60.0, **kwargs}
    with pytest.raises(exc, match=name):
        ThermalModel(**args)


def test_transient_wrong_types_are_type_errors() -> None:
    with pytest.raises(TypeError, match="profile"):
        MODEL.transient(None, [0.0, 1.0])  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="times_s"):
        MODEL.transient(VoltageProfile.step(1.0), "0 1")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="voltage_v"):
        VoltageProfile.step("3")  # type: ignore[arg-type]
