"""The two integrations of :meth:`tcarod.models.thermal.ThermalModel.transient`:
exact exponentials for a constant resistance, fixed-step RK4 otherwise.
``model`` is the :class:`~tcarod.models.thermal.ThermalModel`, ``profile``
its :class:`~tcarod.models.thermal.VoltageProfile` (not imported here: the
thermal module imports this one)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


def exponential(
    model: Any,
    profile: Any,
    t_out: FloatArray,
    switches: list[float],
    temp0: float,
    strain: float,
    volts: FloatArray,
) -> tuple[FloatArray, FloatArray]:
    """Temperature [C] and power [W] at ``t_out`` with a constant
    resistance: exact exponentials between switches, vectorised over the samples."""
    t0 = float(profile.times_s[0])
    knot_times = np.asarray(profile.times_s)
    knot_volts = np.asarray(profile.voltages_v)
    tau = model.time_constant_s
    r = model.resistance_ohm(model.ambient_c, strain)
    ha = model.conductance_w_per_k
    knots = np.asarray([t0, *switches])
    with np.errstate(all="ignore"):  # overflow gives inf / NaN, refused below
        v_knot = knot_volts[np.maximum(np.searchsorted(knot_times, knots, side="right") - 1, 0)]
        tss = model.ambient_c + v_knot * v_knot / r / ha  # steady state of each interval [C]
        temps = np.empty_like(knots)  # temperature at each knot [C]
        temps[0] = temp0
        for j in range(1, knots.size):
            temps[j] = tss[j - 1] + (temps[j - 1] - tss[j - 1]) * math.exp(-(knots[j] - knots[j - 1]) / tau)
        k = np.searchsorted(knots, t_out, side="right") - 1
        out = tss[k] + (temps[k] - tss[k]) * np.exp(-(t_out - knots[k]) / tau)
        power = volts * volts / r
    return out, power


def rk4(
    model: Any,
    profile: Any,
    t_out: FloatArray,
    switches: list[float],
    temp0: float,
    strain: float,
    volts: FloatArray,
    steps: tuple[float | None, int],
) -> tuple[FloatArray, FloatArray]:
    """Temperature [C] and power [W] at ``t_out`` by fixed-step RK4,
    restarted at every voltage switch and output time, with steps of at most
    ``steps[0]`` [s] (default ``tau / 200``); at most ``steps[1]`` steps
    (``ValueError`` beyond)."""
    max_step_s, max_steps = steps
    t0 = float(profile.times_s[0])
    tau = model.time_constant_s
    h_max = tau / 200.0 if max_step_s is None else float(max_step_s)
    events = np.unique(np.concatenate([[t0], switches, t_out]))
    # counted in floating point: (b - a) / h_max may overflow to inf
    with np.errstate(over="ignore"):
        total = float(np.sum(np.maximum(1.0, np.diff(events) / h_max)))
    if not total <= max_steps:
        raise ValueError(
            f"invalid times_s / max_step_s: {total:.3g} RK4 steps needed, allowed at most "
            f"{max_steps} (fewer output times, a shorter span or a larger max_step_s)"
        )
    amb, ha, hc, r_of = model.ambient_c, model.conductance_w_per_k, model.heat_capacity_j_per_k, model._r

    def rate(v2: float, temp: float) -> float:
        # dT/dt [C/s] as rate_c_per_s, without re-reading its arguments on every
        # stage; a resistance that is not a finite float > 0 goes through the
        # checked path, whose ValueError names it
        r = r_of(temp, strain)
        if type(r) is not float or not 0.0 < r < math.inf:
            r = model.resistance_ohm(temp, strain)
        return float((v2 / r - ha * (temp - amb)) / hc)

    state = temp0
    values = {t0: temp0}
    for a, b in zip(events[:-1].tolist(), events[1:].tolist()):
        v = profile(a)  # constant on [a, b): switches are knots
        v2 = v * v
        n = max(1, math.ceil((b - a) / h_max))
        dt = (b - a) / n
        for _ in range(n):
            k1 = rate(v2, state)
            k2 = rate(v2, state + 0.5 * dt * k1)
            k3 = rate(v2, state + 0.5 * dt * k2)
            k4 = rate(v2, state + dt * k3)
            state += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
            if not math.isfinite(state):
                raise ValueError("the temperature overflows: voltages_v or initial_c far outside any physical range")
        values[b] = state
    out = np.array([values[float(t)] for t in t_out])
    power = np.array([model.power_w(v, float(tc), strain) for v, tc in zip(volts, out)])
    return out, power
