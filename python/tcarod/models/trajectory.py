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
    """Steady temperature [C] of each actuator under its voltage [V]."""
    models = _models(models)
    voltages_v = V.sequence("voltages_v", voltages_v, V.MAX_SEGMENTS)
    if len(models) != len(voltages_v):
        raise ValueError(f"voltages_v: expected {len(models)} values (one per thermal model), got {len(voltages_v)}")
    return [m.steady_temperature(v) for m, v in zip(models, voltages_v)]


def solve_with_voltages(
    robot: Any, models: Sequence[ThermalModel], voltages_v: Sequence[float], **solve_kwargs: Any
) -> Any:
    """Forward solution of ``robot`` with each actuator at the steady
    temperature of its voltage [V] (one :class:`ThermalModel` per actuator)."""
    _robot(robot)
    models = _models(models)
    if len(models) != len(robot.actuators):
        raise ValueError(f"models: expected {len(robot.actuators)} (one per actuator), got {len(models)}")
    return robot.solve(steady_temperatures(models, voltages_v), **solve_kwargs)


@dataclass(frozen=True, eq=False)
class ShapeTrajectory:
    """Quasi-static shapes along a heating transient: at each ``time_s`` [s],
    the actuator temperatures [C] (``(n_t, n_actuators)``), the tip position [m]
    (``(n_t, 3)``) and the forward solution."""

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
    """Temperatures from each actuator's voltage profile, then the quasi-static
    shape at every time (heating takes seconds, the body settles in far less),
    each solve warm-started from the previous one, without the stability
    verdict (``stability="off"``; ``Solution.stable`` computes it on demand).

    With constant or temperature-dependent resistance the temperature
    trajectories are computed first (:meth:`ThermalModel.transient`). If a
    resistance depends on strain, heating and mechanics are coupled: between
    output times the temperatures advance by RK4 with each TCA's strain
    (elongation / coiled length) frozen at the last solved shape.

    Raises ``ValueError`` naming the time [s] at which a temperature first
    exceeds ``t_max`` (the mechanics is not defined there).
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
