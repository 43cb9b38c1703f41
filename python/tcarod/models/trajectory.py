"""Robots driven by voltages: each actuator at the steady temperature of its
voltage, and quasi-static shapes along a heating transient (the temperatures
from :mod:`tcarod.models.thermal`, each shape by :meth:`Robot.solve`).

Units: SI (s, V, m); temperatures in degrees C.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from .. import _validate as V
from .thermal import FloatArray, LinearResistance, ThermalModel, VoltageProfile

__all__ = ["ShapeTrajectory", "quasi_static_trajectory", "solve_with_voltages", "steady_temperatures"]


def steady_temperatures(models: Sequence[ThermalModel], voltages_v: Sequence[float]) -> list[float]:
    """Steady temperature [C] of each actuator under its voltage [V].

    Parameters
    ----------
    models : sequence of ThermalModel
        One electro-thermal model per actuator.
    voltages_v : sequence of float
        One voltage per actuator [V].

    Returns
    -------
    list of float
        Steady temperatures [C].

    Raises
    ------
    ValueError
        Lengths that differ, or a voltage whose steady state exceeds ``t_max``.

    Examples
    --------
    >>> from tcarod.models.thermal import ThermalModel
    >>> from tcarod.models.trajectory import steady_temperatures
    >>> heater = ThermalModel(fibre_length_m=0.155, threads=3, resistance=60.0)     # [m], [ohm]
    >>> cold, warm = steady_temperatures((heater, heater), (0.0, 1.0))     # [C] at 0 V and 1 V
    >>> round(cold, 1), round(warm, 1)
    (25.0, 27.5)
    """
    models = _models(models)
    voltages_v = V.sequence("voltages_v", voltages_v, V.MAX_SEGMENTS)
    if len(models) != len(voltages_v):
        raise ValueError(f"voltages_v: expected {len(models)} values (one per thermal model), got {len(voltages_v)}")
    return [m.steady_temperature(v) for m, v in zip(models, voltages_v)]


def solve_with_voltages(
    robot: Any, models: Sequence[ThermalModel], voltages_v: Sequence[float], **solve_kwargs: Any
) -> Any:
    """Forward solution with each actuator at the steady temperature of its voltage.

    Parameters
    ----------
    robot : Robot
        The robot.
    models : sequence of ThermalModel
        One electro-thermal model per actuator.
    voltages_v : sequence of float
        One voltage per actuator [V].
    **solve_kwargs
        Keywords of ``Robot.solve``.

    Returns
    -------
    Solution
        The shape at the steady temperatures.

    Raises
    ------
    ValueError
        One model per actuator is needed; a steady state above ``t_max``.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> robot = fig6_square_robot()
    >>> heater = ThermalModel(fibre_length_m=0.155, threads=3, resistance=60.0)     # [m], [ohm]
    >>> from tcarod.models.trajectory import solve_with_voltages
    >>> sol = solve_with_voltages(robot, [heater, heater], [5.0, 5.0], steps=20)
    >>> tuple(sol.inputs.round(1).tolist())     # steady temperatures [C]
    (87.0, 87.0)
    """
    _robot(robot)
    models = _models(models)
    if len(models) != len(robot.actuators):
        raise ValueError(f"models: expected {len(robot.actuators)} (one per actuator), got {len(models)}")
    return robot.solve(steady_temperatures(models, voltages_v), **solve_kwargs)


@dataclass(frozen=True, eq=False)
class ShapeTrajectory:
    """Quasi-static shapes along a heating transient.

    Made by :func:`quasi_static_trajectory`.

    Attributes
    ----------
    time_s : numpy.ndarray
        Output times [s], shape ``(n_t,)``.
    temperatures_c : numpy.ndarray
        Actuator temperatures [C], shape ``(n_t, n_actuators)``.
    tip_positions_m : numpy.ndarray
        Tip positions [m], shape ``(n_t, 3)``.
    solutions : list of Solution
        The forward solution at each time.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> robot = fig6_square_robot()
    >>> heater = ThermalModel(fibre_length_m=0.155, threads=3, resistance=60.0)     # [m], [ohm]
    >>> from tcarod.models.trajectory import quasi_static_trajectory
    >>> traj = quasi_static_trajectory(robot, [heater, heater], [VoltageProfile.step(5.0)] * 2, [0.0, 5.0, 60.0], steps=20)
    >>> traj.temperatures_c[:, 0].round(1).tolist()       # [C], heating toward 87.0 C
    [25.0, 64.7, 87.0]
    """

    time_s: FloatArray
    temperatures_c: FloatArray
    tip_positions_m: FloatArray
    solutions: list[Any]


def quasi_static_trajectory(
    robot: Any,
    models: Sequence[ThermalModel],
    profiles: Sequence[VoltageProfile],
    times_s: Sequence[float] | FloatArray,
    steps: int = 100,
) -> ShapeTrajectory:
    """Quasi-static shapes of a robot driven by voltage profiles.

    Temperatures from each actuator's voltage profile, then the shape at
    every time (heating takes seconds, the body settles in far less), each
    solve warm-started from the previous one, without the stability verdict
    (``Solution.stable`` computes it on demand). With constant or
    temperature-dependent resistance the temperature trajectories are
    computed first (:meth:`ThermalModel.transient`). If a resistance depends
    on strain, heating and mechanics are coupled: between output times the
    temperatures advance by RK4 with each TCA's strain (elongation / coiled
    length) frozen at the last solved shape.

    Parameters
    ----------
    robot : Robot
        The robot.
    models : sequence of ThermalModel
        One electro-thermal model per actuator.
    profiles : sequence of VoltageProfile
        One voltage profile per actuator [V against s].
    times_s : sequence of float
        Output times [s], increasing.
    steps : int, optional
        RK4 steps per solve (default 100).

    Returns
    -------
    ShapeTrajectory
        Temperatures [C], tip positions [m] and solutions at the times.

    Raises
    ------
    ValueError
        Naming the time [s] at which a temperature first exceeds ``t_max``
        (the mechanics is not defined there), or mismatched lengths.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> robot = fig6_square_robot()
    >>> heater = ThermalModel(fibre_length_m=0.155, threads=3, resistance=60.0)     # [m], [ohm]
    >>> from tcarod.models.trajectory import quasi_static_trajectory
    >>> traj = quasi_static_trajectory(robot, [heater, heater], [VoltageProfile.step(5.0)] * 2, [0.0, 60.0], steps=20)
    >>> round(float(traj.tip_positions_m[-1, 2]) * 1e3, 1)    # tip height [mm] after 60 s
    39.9
    """
    _robot(robot)
    models = _models(models)
    profiles = [
        V.instance("profiles", p, VoltageProfile, "a sequence of VoltageProfile")
        for p in V.sequence("profiles", profiles, V.MAX_SEGMENTS)
    ]
    steps = V.integer("steps", steps, 1, 100_000)
    n = len(robot.actuators)
    if len(models) != n or len(profiles) != n:
        raise ValueError(
            f"models and profiles: expected {n} each (one per actuator), got {len(models)} and {len(profiles)}"
        )
    t = V.real_array("times_s", times_s, ndim=1, max_size=10_000, unit="s")
    coupled = any(not _temperature_only(m) for m in models)
    temps = np.empty((t.size, n))
    if not coupled:
        for i, (m, p) in enumerate(zip(models, profiles)):
            temps[:, i] = m.transient(p, t).temperature_c
    over = (
        np.nonzero(np.any(temps > np.array([m.t_max_c for m in models]), axis=1))[0]
        if not coupled
        else np.array([], int)
    )
    if over.size:
        raise ValueError(f"the temperature exceeds t_max at t = {t[over[0]]:.3f} s: lower the voltage")
    return _trajectory(robot, models, profiles, t, temps, coupled, steps)


def _trajectory(
    robot: Any,
    models: list[ThermalModel],
    profiles: list[VoltageProfile],
    t: FloatArray,
    temps: FloatArray,
    coupled: bool,
    steps: int,
) -> ShapeTrajectory:
    """The solves of :func:`quasi_static_trajectory` at the times ``t`` [s]:
    ``temps`` [C] as computed, or advanced here between times when coupled."""
    coiled = [_coiled_length(a) for a in robot.actuators]
    sols: list[Any] = []
    tips = np.empty((t.size, 3))
    state = [m.ambient_c for m in models]
    for k in range(t.size):
        if coupled:
            if k == 0:
                state = [m.transient(p, t[:1]).temperature_c[0] for m, p in zip(models, profiles)]
            else:
                strains = [float(e) / c for e, c in zip(sols[-1].elongations, coiled)]
                state = [
                    float(
                        m.transient(_shifted(p, t[k - 1]), [t[k - 1], t[k]], initial_c=s0, strain=e).temperature_c[-1]
                    )
                    for m, p, s0, e in zip(models, profiles, state, strains)
                ]
            for m, s0 in zip(models, state):
                if s0 > m.t_max_c:
                    raise ValueError(f"the temperature exceeds t_max at t = {t[k]:.3f} s: lower the voltage")
            temps[k] = state
        warm = sols[-1] if sols else None
        sol = robot.solve([float(x) for x in temps[k]], steps=steps, warm_start=warm, stability="off")
        sols.append(sol)
        tips[k] = np.asarray(sol.tip_position, dtype=np.float64)
    return ShapeTrajectory(t, temps, tips, sols)


def _robot(robot: Any) -> Any:
    from ..rod import Robot

    return V.instance("robot", robot, Robot, "a tcarod.Robot")


def _models(models: Any) -> list[ThermalModel]:
    return [
        V.instance("models", m, ThermalModel, "a sequence of ThermalModel")
        for m in V.sequence("models", models, V.MAX_SEGMENTS)
    ]


def _temperature_only(m: ThermalModel) -> bool:
    r = m.resistance
    return isinstance(r, (int, float)) or (isinstance(r, LinearResistance) and r.strain_coefficient == 0.0)


def _coiled_length(actuator: Any) -> float:
    tca = actuator.tca_model
    return float(tca.coiled_length) if tca is not None else 1.0


def _shifted(p: VoltageProfile, start: float) -> VoltageProfile:
    """The profile restricted to ``t >= start`` (a new first knot at ``start``)."""
    times = [start] + [s for s in p.times_s if s > start]
    return VoltageProfile(tuple(times), tuple(p(s) for s in times))
