"""Voltage to temperature: a lumped electro-thermal model of a Joule-heated TCA.
Robots driven by voltages (steady states, quasi-static shape trajectories) are in :mod:`tcarod.models.trajectory`;
the plots in :mod:`tcarod.plotting`.

Model (``thermal_model.m`` of the code released with Sun & Zhao, IEEE T-RO 38(2), 2022; see ``docs/choices.md``,
Sources)::

    m c_p dT/dt = V^2 / R - h A (T - T_amb)

* ``m = density x threads x pi r^2 l`` [kg]: the threads' volume (``r`` the thread radius, 0.1 mm for the paper's
  0.2 mm Shieldex thread; ``l`` the twisted-fibre length);
* ``A = threads x 2 pi r l`` [m^2]: the threads' lateral surface;
* ``density = 1127 kg/m^3``, ``c_p = 2000 J/(kg K)``, ``h = 23 W/(m^2 K)``.

The time constant ``m c_p / (h A) = density c_p r / (2 h)`` does not depend on the length or the number of
threads: 4.90 s with these coefficients, not the "about 3-4 s" quoted with them. (The source code computes its
mass as ``density^2 V / 1000``, 1.127 times the threads' mass, from *one* fibre of radius ``r_t`` with three
fibres' surface; its time constant is about ``18400 r_t`` s/m, 3-4 s for ``r_t`` = 0.16-0.22 mm.) This module
follows the coefficients as stated; pass your own to change them.

Resistance is a **required** input, with no default: a TCA's resistance depends on the thread, the number of
threads, the twist and the coiling, and changes with temperature and strain (the paper's refs [24], [25] use that
change for self-sensing). Measure it, or take the linear resistance of the thread from its datasheet (Shieldex
publishes ohms per metre for its silver-coated nylon threads) times the fibre length divided by the number of
threads in parallel. Give it as a constant [ohm], a :class:`LinearResistance` ``R0 (1 + alpha_R (T - T_ref) +
k_strain strain)``, or any callable ``R(temperature_c, strain) -> ohm``. Constant resistance and
piecewise-constant voltage give exact exponentials; otherwise a fixed-step RK4 integrates.

Temperatures are never clipped: a steady state above the material's ``t_max`` raises ``ValueError``; a transient
that exceeds it is reported (:attr:`TemperatureTrajectory.exceeds_t_max_at_s`).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from typing import Any, Callable, Final, Sequence, Union

import numpy as np
import numpy.typing as npt

from .. import _validate as V
from ._thermal_transient import exponential, rk4

__all__ = [
    "DENSITY_KG_PER_M3",
    "HEAT_TRANSFER_W_PER_M2K",
    "SPECIFIC_HEAT_J_PER_KGK",
    "THREAD_RADIUS_M",
    "LinearResistance",
    "TemperatureTrajectory",
    "ThermalModel",
    "VoltageProfile",
]

FloatArray = npt.NDArray[np.float64]

#: Fibre density [kg/m^3] (thermal_model.m).
DENSITY_KG_PER_M3: Final[float] = 1127.0
#: Specific heat [J/(kg K)] (thermal_model.m: between silver 2400... and nylon 1700).
SPECIFIC_HEAT_J_PER_KGK: Final[float] = 2000.0
#: Convective heat-transfer coefficient [W/(m^2 K)] (thermal_model.m, "used 23 for dynamics").
HEAT_TRANSFER_W_PER_M2K: Final[float] = 23.0
#: Radius [m] of the paper's 0.2 mm silver-coated nylon thread.
THREAD_RADIUS_M: Final[float] = 0.1e-3

#: Physical ranges of the model's coefficients, ``(lo, hi, unit)``: every
#: value inside keeps the lumped parameters and the results finite numbers
#: (``ValueError`` outside, naming the argument, its unit and the range).
RANGES: Final[dict[str, tuple[float, float, str]]] = {
    "fibre_length_m": (1e-4, 100.0, "m"),
    "thread_radius_m": (1e-6, 1e-2, "m"),
    "density_kg_per_m3": (1.0, 1e5, "kg/m^3"),
    "specific_heat_j_per_kgk": (1.0, 1e5, "J/(kg K)"),
    "heat_transfer_w_per_m2k": (1e-3, 1e5, "W/(m^2 K)"),
    "resistance": (1e-6, 1e9, "ohm"),
}
#: Most output times of :meth:`ThermalModel.transient` (``ValueError`` beyond).
MAX_TRANSIENT_SAMPLES: Final[int] = 1_000_000
#: Most RK4 steps of :meth:`ThermalModel.transient` with a resistance that
#: depends on temperature or strain (about 4 s of Python per 100,000 steps).
MAX_TRANSIENT_RK4_STEPS: Final[int] = 100_000


class _Required:
    """The default of a required :class:`ThermalModel` field: a missing
    argument is reported with its meaning and unit, not only its name."""

    def __repr__(self) -> str:
        return "<required>"


_REQUIRED: Any = _Required()

#: What each required argument of :class:`ThermalModel` is, with its unit.
_REQUIRED_ARGS: Final[dict[str, str]] = {
    "fibre_length_m": "the twisted-fibre length l [m] (Tca.fibre_length)",
    "threads": "the number of threads twisted together [-] (an integer 1..10,000)",
    "resistance": "the TCA's electrical resistance [ohm]: a number, a LinearResistance or a callable R(T, strain)",
}


def _in_range(name: str, value: object) -> float:
    lo, hi, unit = RANGES[name]
    return V.real(name, value, lo=lo, hi=hi, unit=unit, reason="a physical range: the results stay finite")


@dataclass(frozen=True)
class LinearResistance:
    """``R = r0_ohm (1 + alpha_per_c (T - t_ref_c) + strain_coefficient strain)`` [ohm].

    ``strain`` is the TCA's elongation over its coiled length [-]. All coefficients are the user's (measured); none
    has a default value in the literature that would fit every TCA.

    Examples
    --------
    >>> from tcarod.models.thermal import LinearResistance
    >>> LinearResistance(10.0, alpha_per_c=0.001)(125.0)   # 10 ohm at 25 C, at 125 C [ohm]
    11.0
    """

    r0_ohm: float
    alpha_per_c: float = 0.0
    t_ref_c: float = 25.0
    strain_coefficient: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "r0_ohm", V.positive("r0_ohm", self.r0_ohm, "ohm"))
        for name in ("alpha_per_c", "t_ref_c", "strain_coefficient"):
            object.__setattr__(self, name, V.real(name, getattr(self, name)))

    def __call__(self, temperature_c: float, strain: float = 0.0) -> float:
        t = V.real("temperature_c", temperature_c, unit="C")
        e = V.real("strain", strain)
        return self.r0_ohm * (1.0 + self.alpha_per_c * (t - self.t_ref_c) + self.strain_coefficient * e)

    @property
    def is_constant(self) -> bool:
        """Whether the resistance is constant.

        Returns
        -------
        bool
            ``True`` if neither temperature [C] nor strain [-] changes it."""
        return self.alpha_per_c == 0.0 and self.strain_coefficient == 0.0


Resistance = Union[float, LinearResistance, Callable[[float, float], float]]


@dataclass(frozen=True)
class VoltageProfile:
    """Piecewise-constant voltage [V] over time [s].

    ``voltages_v[k]`` [V] from ``times_s[k]`` [s] until ``times_s[k+1]`` (the last holds on); ``times_s[0]`` starts.

    Examples
    --------
    >>> from tcarod.models.thermal import VoltageProfile
    >>> p = VoltageProfile.step(2.0, at_s=1.0)          # 2 V from 1 s on
    >>> p(0.5), p(3.0)                                  # [V] at 0.5 s and 3 s
    (0.0, 2.0)
    """

    times_s: tuple[float, ...]
    voltages_v: tuple[float, ...]

    def __post_init__(self) -> None:
        t = V.real_array("times_s", self.times_s, ndim=1, max_size=V.MAX_PROFILE_KNOTS, unit="s")
        v = V.real_array("voltages_v", self.voltages_v, ndim=1, max_size=V.MAX_PROFILE_KNOTS, unit="V")
        if t.size == 0 or t.shape != v.shape:
            raise ValueError(
                f"times_s and voltages_v must be non-empty sequences of the same length, got {t.size} and {v.size}"
            )
        if np.any(np.diff(t) <= 0.0):
            raise ValueError(f"times_s [s] must increase strictly, got {list(self.times_s)[:10]}")
        object.__setattr__(self, "times_s", tuple(float(x) for x in t))
        object.__setattr__(self, "voltages_v", tuple(float(x) for x in v))

    @classmethod
    def step(cls, voltage_v: float, at_s: float = 0.0) -> VoltageProfile:
        """0 V until ``at_s`` [s], then ``voltage_v`` [V] (from t = 0 if ``at_s`` = 0)."""
        v = V.real("voltage_v", voltage_v, unit="V")
        at = V.real("at_s", at_s, lo=0.0, unit="s")
        if at == 0.0:
            return cls((0.0,), (v,))
        return cls((0.0, at), (0.0, v))

    def __call__(self, t_s: float) -> float:
        t = V.real("t_s", t_s, unit="s")
        k = int(np.searchsorted(np.asarray(self.times_s), t, side="right")) - 1
        return float(self.voltages_v[max(k, 0)])


@dataclass(frozen=True, eq=False)
class TemperatureTrajectory:
    """Temperature [C] of one TCA at ``time_s`` [s], with the voltage [V] and Joule power [W].

    What :meth:`ThermalModel.transient` returns: one value of each array per output time.

    Examples
    --------
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> tca = ThermalModel(fibre_length_m=0.15, threads=2, resistance=20.0)   # [m], [-], [ohm]
    >>> tr = tca.transient(VoltageProfile.step(5.0), [0.0, 5.0, 30.0])        # 5 V [V], times [s]
    >>> tr.temperature_c.round(1), tr.exceeds_t_max_at_s                      # [C], [s]
    (array([ 25. , 209.4, 312.7]), 5.0)
    """

    time_s: FloatArray
    temperature_c: FloatArray
    voltage_v: FloatArray
    power_w: FloatArray
    t_max_c: float
    method: str

    @property
    def exceeds_t_max_at_s(self) -> float | None:
        """First sample time [s] above the material's ``t_max`` [C].

        Returns
        -------
        float or None
            The time [s], or ``None`` if the temperature stays within ``t_max_c``."""
        over = np.nonzero(self.temperature_c > self.t_max_c)[0]
        return None if over.size == 0 else float(self.time_s[over[0]])


@dataclass(frozen=True)
class ThermalModel:
    """Lumped electro-thermal model of one Joule-heated TCA (see the module docstring).

    ``fibre_length_m``: twisted-fibre length ``l`` [m] (``Tca.fibre_length``); ``threads``: number of threads
    twisted together; ``resistance``: [ohm], required (see the module docstring). Temperatures in C, times in s. A
    missing required argument raises ``TypeError`` naming it, its meaning and its unit.

    Coefficients and a constant ``resistance`` within :data:`RANGES`, ``threads`` 1..10,000, ``ambient_c``
    -273.15..1e6 C (``ValueError`` outside, naming the argument, its unit and the range); an ``ambient_c`` above
    273 C warns with ``tcarod.UnitsWarning`` (Kelvin given as Celsius?).

    Examples
    --------
    >>> from tcarod.models.thermal import ThermalModel
    >>> tca = ThermalModel(fibre_length_m=0.15, threads=2, resistance=20.0)   # [m], [-], [ohm]
    >>> round(tca.time_constant_s, 2), round(tca.steady_temperature(3.0), 1)  # [s], [C] at 3 V
    (4.9, 128.8)
    """

    fibre_length_m: float = _REQUIRED
    threads: int = _REQUIRED
    resistance: Resistance = _REQUIRED
    thread_radius_m: float = THREAD_RADIUS_M
    density_kg_per_m3: float = DENSITY_KG_PER_M3
    specific_heat_j_per_kgk: float = SPECIFIC_HEAT_J_PER_KGK
    heat_transfer_w_per_m2k: float = HEAT_TRANSFER_W_PER_M2K
    ambient_c: float = 25.0
    t_max_c: float = 160.0
    _r: Callable[[float, float], float] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        missing = [name for name in _REQUIRED_ARGS if getattr(self, name) is _REQUIRED]
        if missing:
            what = "; ".join(f"{name}: {_REQUIRED_ARGS[name]}" for name in missing)
            plural = "s" if len(missing) > 1 else ""
            raise TypeError(f"ThermalModel() missing {len(missing)} required argument{plural}: {what}")
        for name in (
            "fibre_length_m",
            "thread_radius_m",
            "density_kg_per_m3",
            "specific_heat_j_per_kgk",
            "heat_transfer_w_per_m2k",
        ):
            object.__setattr__(self, name, _in_range(name, getattr(self, name)))
        object.__setattr__(self, "threads", V.integer("threads", self.threads, 1, 10_000))
        amb = V.real("ambient_c", self.ambient_c, lo=-273.15, hi=1e6, unit="C")
        tmax = V.real("t_max_c", self.t_max_c, lo=amb, lo_open=True, hi=1e6, unit="C")
        V.warn_if_kelvin("ambient_c", amb, stacklevel=5)
        object.__setattr__(self, "ambient_c", amb)
        object.__setattr__(self, "t_max_c", tmax)
        # derived quantities must be usable numbers (tiny or huge coefficients underflow/overflow)
        for name in ("heat_capacity_j_per_k", "conductance_w_per_k", "time_constant_s"):
            x = getattr(self, name)
            if not (math.isfinite(x) and x > 0.0):
                raise ValueError(
                    f"invalid thermal coefficients: {name} = {x:g} is not a finite number > 0 "
                    "(fibre_length_m, thread_radius_m, density_kg_per_m3, specific_heat_j_per_kgk, "
                    "heat_transfer_w_per_m2k out of any physical range)"
                )
        r: Any = self.resistance
        if r is None:
            raise TypeError(
                "resistance [ohm] is required: give an ohm value, a LinearResistance or a callable R(T, strain)"
            )
        if isinstance(r, bool):
            raise TypeError("resistance must be a number [ohm], a LinearResistance or a callable, not bool")
        if isinstance(r, (numbers.Real, np.number)):
            const = _in_range("resistance", r)
            fn: Callable[[float, float], float] = lambda t, e: const  # noqa: E731
        elif callable(r):
            fn = r
        else:
            raise TypeError(
                f"resistance must be a number [ohm], a LinearResistance or a callable, not {type(r).__name__}"
            )
        object.__setattr__(self, "_r", fn)

    # -- lumped parameters ---------------------------------------------------
    @property
    def mass_kg(self) -> float:
        """Threads' mass ``density x threads x pi r^2 l`` [kg].

        Returns
        -------
        float
            The mass [kg]."""
        return self.density_kg_per_m3 * self.threads * math.pi * self.thread_radius_m**2 * self.fibre_length_m

    @property
    def area_m2(self) -> float:
        """Cooled surface ``threads x 2 pi r l`` [m^2].

        Returns
        -------
        float
            The lateral surface [m^2]."""
        return self.threads * 2.0 * math.pi * self.thread_radius_m * self.fibre_length_m

    @property
    def heat_capacity_j_per_k(self) -> float:
        """Heat capacity ``m c_p`` [J/K].

        Returns
        -------
        float
            The heat capacity [J/K]."""
        return self.mass_kg * self.specific_heat_j_per_kgk

    @property
    def conductance_w_per_k(self) -> float:
        """Convective conductance ``h A`` [W/K].

        Returns
        -------
        float
            The conductance [W/K]."""
        return self.heat_transfer_w_per_m2k * self.area_m2

    @property
    def time_constant_s(self) -> float:
        """Time constant ``tau = m c_p / (h A)`` [s].

        Returns
        -------
        float
            With constant resistance the response is ``1 - exp(-t/tau)`` [s]."""
        ha = self.conductance_w_per_k
        return self.heat_capacity_j_per_k / ha if ha > 0.0 else math.inf

    @property
    def constant_resistance(self) -> bool:
        """Whether the resistance is constant.

        Returns
        -------
        bool
            ``True`` if it depends on neither temperature [C] nor strain [-]."""
        r: Any = self.resistance
        return (isinstance(r, (numbers.Real, np.number)) and not callable(r)) or (
            isinstance(r, LinearResistance) and r.is_constant
        )

    def resistance_ohm(self, temperature_c: float, strain: float = 0.0) -> float:
        """Resistance [ohm] at ``temperature_c`` [C] and ``strain`` [-]; ``ValueError`` if not > 0."""
        t = V.real("temperature_c", temperature_c, unit="C")
        e = V.real("strain", strain)
        value = self._r(t, e)
        try:
            r = V.real("resistance", value, unit="ohm")
        except ValueError:
            r = math.nan
        if not (math.isfinite(r) and r > 0.0):
            raise ValueError(f"resistance = {value!r} ohm at {t} C, strain {e}: need a finite value > 0")
        return r

    def power_w(self, voltage_v: float, temperature_c: float, strain: float = 0.0) -> float:
        """Joule power ``V^2 / R`` [W]; ``ValueError`` if it overflows."""
        v = V.real("voltage_v", voltage_v, unit="V")
        p = v * v / self.resistance_ohm(temperature_c, strain)
        if not math.isfinite(p):
            raise ValueError(f"invalid voltage_v = {v:g} V: the Joule power V^2/R overflows")
        return p

    def rate_c_per_s(self, voltage_v: float, temperature_c: float, strain: float = 0.0) -> float:
        """``dT/dt`` [C/s] of the model."""
        t = V.real("temperature_c", temperature_c, unit="C")
        q = self.power_w(voltage_v, t, strain) - self.conductance_w_per_k * (t - self.ambient_c)
        rate = q / self.heat_capacity_j_per_k
        if not math.isfinite(rate):
            raise ValueError(f"dT/dt overflows at voltage_v = {voltage_v} V, temperature_c = {t:g} C")
        return rate

    # -- steady state ----------------------------------------------------------
    def steady_temperature(self, voltage_v: float, strain: float = 0.0) -> float:
        """Steady temperature [C] under ``voltage_v`` [V].

        ``T_amb + V^2 / (R h A)`` (solved for ``T`` if ``R`` depends on it). ``ValueError`` above ``t_max_c``."""
        v = V.real("voltage_v", voltage_v, unit="V")
        strain = V.real("strain", strain)
        ha = self.conductance_w_per_k

        def g(t: float) -> float:
            return t - self.ambient_c - v * v / self.resistance_ohm(t, strain) / ha

        if self.constant_resistance:
            t = self.ambient_c + v * v / self.resistance_ohm(self.ambient_c, strain) / ha
        else:
            # bracket on [T_amb, t_max]: g(T_amb) <= 0; if g(t_max) < 0 the root lies above t_max
            lo, hi = self.ambient_c, self.t_max_c
            if g(hi) < 0.0:
                t = math.inf
            else:
                for _ in range(200):
                    mid = 0.5 * (lo + hi)
                    if g(mid) < 0.0:
                        lo = mid
                    else:
                        hi = mid
                t = 0.5 * (lo + hi)
        if not t <= self.t_max_c:  # also NaN / inf from an overflowing V^2
            raise ValueError(
                f"voltage {v:g} V gives a steady temperature above t_max = {self.t_max_c:g} C"
                + ("" if math.isinf(t) else f" ({t:.1f} C)")
            )
        return t

    def steady_voltage(self, temperature_c: float, strain: float = 0.0) -> float:
        """Voltage [V] that holds ``temperature_c`` [C] in steady state.

        ``sqrt((T - T_amb) h A R(T))``. ``ValueError`` outside ``[T_amb, t_max]``."""
        t = V.real("temperature_c", temperature_c, unit="C")
        if not self.ambient_c <= t <= self.t_max_c:
            raise ValueError(
                f"invalid temperature_c = {t:g} C: a steady state needs "
                f"ambient {self.ambient_c:g} <= T <= t_max {self.t_max_c:g} C"
            )
        v = math.sqrt((t - self.ambient_c) * self.conductance_w_per_k * self.resistance_ohm(t, strain))
        if not math.isfinite(v):
            raise ValueError(f"the steady voltage for temperature_c = {t:g} C overflows")
        return v

    # -- transient ---------------------------------------------------------------
    def transient(
        self,
        profile: VoltageProfile,
        times_s: Sequence[float] | FloatArray,
        initial_c: float | None = None,
        strain: float = 0.0,
        max_step_s: float | None = None,
    ) -> TemperatureTrajectory:
        """Temperature [C] at ``times_s`` [s] under a voltage ``profile`` [V].

        ``times_s`` increase from ``profile.times_s[0]``; the TCA starts from ``initial_c`` [C] (default ambient).
        Exact exponentials for a constant resistance; otherwise RK4 with steps of at most ``max_step_s`` (default
        ``tau / 200``), restarted at every voltage switch.

        Bounded work: at most ``MAX_TRANSIENT_SAMPLES`` (1,000,000) output times, evaluated vectorised with a
        constant resistance (about 0.1 s per million); with a resistance that depends on temperature or strain, at
        most ``MAX_TRANSIENT_RK4_STEPS`` (100,000) RK4 steps, every output time taking at least one (``ValueError``
        beyond either, naming the argument and the bound); ``initial_c`` within [-273.15, 1e6] C."""
        V.instance("profile", profile, VoltageProfile, "a VoltageProfile")
        t_out = V.real_array("times_s", times_s, ndim=1, max_size=MAX_TRANSIENT_SAMPLES, unit="s")
        if t_out.size == 0 or np.any(np.diff(t_out) < 0.0) or t_out[0] < profile.times_s[0]:
            raise ValueError(
                "times_s [s] must be a non-empty increasing sequence starting at or after the profile's start"
            )
        t0 = float(profile.times_s[0])
        temp0 = self.ambient_c if initial_c is None else V.real("initial_c", initial_c, lo=-273.15, hi=1e6, unit="C")
        strain = V.real("strain", strain)
        if max_step_s is not None:
            max_step_s = V.positive("max_step_s", max_step_s, "s")
        # span of the integration: ranges beyond the double's resolution are refused, not looped over
        if not math.isfinite(float(t_out[-1]) - t0):
            raise ValueError("times_s [s]: the span from the profile's start overflows")
        # integration knots: voltage switches, plus the output times
        switches = [s for s in profile.times_s if t0 < s < t_out[-1]]
        # the profile's voltage at every output time (piecewise constant, the last one holds on)
        volts = np.asarray(profile.voltages_v)[np.maximum(np.searchsorted(profile.times_s, t_out, "right") - 1, 0)]
        if self.constant_resistance:
            method = "analytic (exponential)"
            out, power = exponential(self, profile, t_out, switches, temp0, strain, volts)
        else:
            method = "numeric (RK4)"
            steps = (max_step_s, MAX_TRANSIENT_RK4_STEPS)
            out, power = rk4(self, profile, t_out, switches, temp0, strain, volts, steps)
        if not np.all(np.isfinite(out)):
            raise ValueError("the temperature overflows: voltages_v or initial_c far outside any physical range")
        if not np.all(np.isfinite(power)):
            raise ValueError("the Joule power V^2/R overflows: voltages_v far outside any physical range")
        return TemperatureTrajectory(t_out, out, volts, power, self.t_max_c, method)
