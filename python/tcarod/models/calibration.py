"""Calibration: fit a TCA's uncertain parameters to measured
displacement-temperature data (experiments of the paper's Fig. 5 kind), with
confidence intervals.

Fitted parameters (any subset; the others stay at their given values):

* ``youngs_modulus_slope_pa_per_c``: ``dE_T/dT`` [Pa/C] (``G_T`` follows with
  constant ``G/E``, as in :class:`tcarod.Material`'s default);
* ``expansion_scale``: a factor [-] on the expansion coefficient ``rho(T)``
  (both its reference value and its slope), i.e. on the fibre-diameter
  growth ``d/d0 - 1``;
* ``friction_mass_kg``: a friction-equivalent mass [kg] added to the dead
  weight, the same in every experiment;
* ``friction_ratio``: a friction-equivalent mass as a fraction [-] of each
  experiment's hanging mass (the paper's 2.5 g for 5 g and 5 g for 10 g are
  a ratio of 0.5).

One load alone hardly separates the modulus slope from the friction (both
enter only through ``f11 F``): fit data from two or more loads together
(pass lists of experiments and data), or fix the slope.

Model of one measurement: a TCA (or one folded half of it) carrying the
compressive force ``-(mass + friction) g x load_share`` at temperature ``T``
has elongation :meth:`Tca.displacement`. Fit by
``scipy.optimize.least_squares`` (trust-region reflective, finite-difference
Jacobian) on scaled parameters.

Confidence intervals (assumptions, check them before trusting the numbers):
measurement errors are independent, zero-mean, of one common variance and
only in the displacement (temperatures exact); the model is locally linear in
the parameters over the interval, so the covariance is
``s^2 (J^T J)^-1`` with ``s^2 = SSR / (n - p)`` and the interval is
``estimate +- t_{n-p, 0.975} x standard error``. Near the onset of extension
the model has a kink (coil contact), where the linearisation is poorest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Final, Sequence

import numpy as np
import numpy.typing as npt

from .. import _validate as V
from .._optional import require
from ..tca import Material, Tca
from .manipulators import GRAVITY_M_PER_S2

__all__ = ["PARAMETERS", "CalibrationResult", "TcaExperiment", "calibrate"]

FloatArray = npt.NDArray[np.float64]

#: Fittable parameter names, with the scale [unit] used inside the optimiser.
PARAMETERS: Final[dict[str, float]] = {
    "youngs_modulus_slope_pa_per_c": 1e6,
    "expansion_scale": 1.0,
    "friction_mass_kg": 1e-3,
    "friction_ratio": 0.1,
}


@dataclass(frozen=True)
class TcaExperiment:
    """What is known about a TCA experiment under a dead weight.

    The TCA's geometry [m, turns], the hanging mass [kg], the share of the
    weight one measured TCA carries (0.5 for each half of the paper's folded
    TCA) and ``g`` [m/s^2].

    Examples
    --------
    >>> from tcarod.models.calibration import TcaExperiment
    >>> half = TcaExperiment(0.2485, 0.055, 0.002, 150.0, 0.005, load_share=0.5)
    >>> params = {"youngs_modulus_slope_pa_per_c": -1.3e6, "expansion_scale": 1.0,
    ...           "friction_mass_kg": 0.0, "friction_ratio": 0.0}
    >>> d = half.predict(np.array([25.0, 150.0]), tcarod.Material.silver_coated_nylon(), params)
    >>> round(float(d[1] - d[0]) * 1e3, 2)          # displacement from 25 to 150 C [mm]
    14.24
    """

    fibre_length_m: float
    coiled_length_m: float
    coil_diameter_m: float
    turns: float
    mass_kg: float
    load_share: float = 1.0
    gravity_m_per_s2: float = GRAVITY_M_PER_S2
    chirality: str = "extension"

    def __post_init__(self) -> None:
        for name, unit in (
            ("fibre_length_m", "m"),
            ("coiled_length_m", "m"),
            ("coil_diameter_m", "m"),
            ("turns", ""),
            ("load_share", ""),
            ("gravity_m_per_s2", "m/s^2"),
        ):
            object.__setattr__(self, name, V.positive(name, getattr(self, name), unit))
        object.__setattr__(self, "mass_kg", V.real("mass_kg", self.mass_kg, lo=0.0, unit="kg"))
        if not isinstance(self.chirality, str):
            raise TypeError(f"chirality must be a str, not {type(self.chirality).__name__}")
        if self.chirality not in ("extension", "contraction"):
            raise ValueError(f"invalid chirality = {self.chirality!r}: need 'extension' or 'contraction'")

    def material(self, base: Material, youngs_modulus_slope_pa_per_c: float, expansion_scale: float) -> Material:
        """``base`` with its modulus slope replaced and its expansion scaled.

        Parameters
        ----------
        base : Material
            The base material.
        youngs_modulus_slope_pa_per_c : float
            Slope of the fibre's Young's modulus [Pa/C].
        expansion_scale : float
            Factor on the radial expansion [-].

        Returns
        -------
        Material
            The modified material.
        """
        e, _, g, _, rho, rho_slope = base.coefficients
        return Material(
            youngs_modulus=e,
            shear_modulus=g,
            expansion=rho * expansion_scale,
            youngs_modulus_slope=youngs_modulus_slope_pa_per_c,
            expansion_slope=rho_slope * expansion_scale,
            t_ref=base.t_ref,
            t_min=base.t_min,
            t_max=base.t_max,
            name=f"{base.name} (calibrated)",
        )

    def predict(self, temperatures_c: FloatArray, base: Material, params: dict[str, float]) -> FloatArray:
        """Displacement at ``temperatures_c`` for parameter values ``params``.

        Parameters
        ----------
        temperatures_c : numpy.ndarray
            Temperatures [C].
        base : Material
            The base material.
        params : dict of str to float
            A value for every name of :data:`PARAMETERS`.

        Returns
        -------
        numpy.ndarray
            Displacement [m] at each temperature.
        """
        mat = self.material(base, params["youngs_modulus_slope_pa_per_c"], params["expansion_scale"])
        tca = Tca(self.fibre_length_m, self.coiled_length_m, self.coil_diameter_m, self.turns, self.chirality, mat)  # type: ignore[arg-type]
        friction = params.get("friction_mass_kg", 0.0) + params.get("friction_ratio", 0.0) * self.mass_kg
        force = -(self.mass_kg + friction) * self.gravity_m_per_s2 * self.load_share
        return np.asarray(tca.displacement(force, temperatures_c), dtype=np.float64)


@dataclass(frozen=True, eq=False)
class CalibrationResult:
    """Fitted parameters with standard errors and confidence intervals.

    In the units of the parameter names.

    Examples
    --------
    >>> from tcarod.models.calibration import TcaExperiment, calibrate
    >>> half = TcaExperiment(0.2485, 0.055, 0.002, 150.0, 0.005, load_share=0.5)   # [m], [m], [m], turns, [kg]
    >>> base = tcarod.Material.silver_coated_nylon()
    >>> temps = np.linspace(30.0, 150.0, 9)                                          # [C]
    >>> truth = {"youngs_modulus_slope_pa_per_c": -1.56e6, "expansion_scale": 0.9,
    ...          "friction_mass_kg": 0.0, "friction_ratio": 0.0}
    >>> measured = half.predict(temps, base, truth)                                   # [m]
    >>> fit = calibrate(half, temps, measured, fit=("youngs_modulus_slope_pa_per_c", "expansion_scale"))
    >>> fit.names, round(float(fit.estimate[1]), 4), fit.success
    (('youngs_modulus_slope_pa_per_c', 'expansion_scale'), 0.9, True)
    """

    names: tuple[str, ...]
    estimate: FloatArray
    standard_error: FloatArray
    ci_low: FloatArray
    ci_high: FloatArray
    covariance: FloatArray
    residual_std_m: float
    n_points: int
    success: bool
    message: str

    def as_dict(self) -> dict[str, dict[str, float]]:
        """The estimates by name.

        Returns
        -------
        dict
            ``{name: {"estimate", "standard_error", "ci_low", "ci_high"}}``, in
            the parameter's unit.
        """
        return {
            n: {
                "estimate": float(self.estimate[k]),
                "standard_error": float(self.standard_error[k]),
                "ci_low": float(self.ci_low[k]),
                "ci_high": float(self.ci_high[k]),
            }
            for k, n in enumerate(self.names)
        }


def calibrate(
    experiment: TcaExperiment | Sequence[TcaExperiment],
    temperatures_c: Sequence[float] | FloatArray | Sequence[Sequence[float] | FloatArray],
    displacements_m: Sequence[float] | FloatArray | Sequence[Sequence[float] | FloatArray],
    fit: Sequence[str] = tuple(PARAMETERS),
    initial: dict[str, float] | None = None,
    base: Material | None = None,
    confidence: float = 0.95,
) -> CalibrationResult:
    """Fit a TCA's uncertain parameters to measured displacement against temperature.

    Needs scipy (the ``fit`` extra: ``pip install 'tcarod[fit]'``).

    Parameters
    ----------
    experiment : TcaExperiment or sequence of TcaExperiment
        What is known; several (e.g. two loads) are fitted together.
    temperatures_c, displacements_m : array_like or sequence of array_like
        Temperatures [C] and measured displacements [m], one array each per
        experiment.
    fit, initial : optional
        Names from :data:`PARAMETERS` to fit (default all); starting and fixed
        values (default: ``base``'s slope, expansion scale 1, no friction).
    base, confidence : optional
        Base material (default :meth:`Material.silver_coated_nylon`) and the
        confidence level of the intervals, in (0, 1) (default 0.95).

    Returns
    -------
    CalibrationResult
        Estimates, standard errors, intervals and the residual std [m].

    Raises
    ------
    ValueError
        Unknown names, mismatched data or fewer points than parameters + 1.
    ImportError
        scipy is missing.

    Examples
    --------
    >>> from tcarod.models.calibration import TcaExperiment, calibrate
    >>> half = TcaExperiment(0.2485, 0.055, 0.002, 150.0, 0.005, load_share=0.5)   # [m], [m], [m], turns, [kg]
    >>> base = tcarod.Material.silver_coated_nylon()
    >>> temps = np.linspace(30.0, 150.0, 9)                                          # [C]
    >>> truth = {"youngs_modulus_slope_pa_per_c": -1.56e6, "expansion_scale": 0.9,
    ...          "friction_mass_kg": 0.0, "friction_ratio": 0.0}
    >>> measured = half.predict(temps, base, truth)                                   # [m]
    >>> fit = calibrate(half, temps, measured, fit=("youngs_modulus_slope_pa_per_c", "expansion_scale"))
    >>> round(float(fit.estimate[0]) / 1e6, 3)    # youngs_modulus_slope_pa_per_c [MPa/C]
    -1.56
    """
    optimize = require("scipy.optimize")  # optional dependency: only calibration needs it
    stats = require("scipy.stats")

    mat = Material.silver_coated_nylon() if base is None else V.instance("base", base, Material, "a tcarod.Material")
    confidence = V.real("confidence", confidence, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
    exps, ts, ys = _data(experiment, temperatures_c, displacements_m)
    y = np.concatenate(ys)
    names = _fit_names(fit, y.size)
    values = _initial_values(initial, mat)
    scale = np.array([PARAMETERS[n] for n in names])
    x0 = np.array([values[n] for n in names]) / scale

    def params_of(x: FloatArray) -> dict[str, float]:
        d = dict(values)
        d.update({n: float(v) for n, v in zip(names, x * scale)})
        return d

    def residual(x: FloatArray) -> FloatArray:
        try:
            p_ = params_of(x)
            return np.concatenate([e.predict(tk, mat, p_) for e, tk in zip(exps, ts)]) - y
        except ValueError:  # e.g. a material with E_T <= 0 in range: far from the data
            return np.full_like(y, 1.0)

    # Unbounded: a bound at the start (friction 0) stalls the trust region,
    # and the linearised interval assumes an interior optimum anyway.
    sol: Any = optimize.least_squares(residual, x0, x_scale="jac", diff_step=1e-6)
    return _result(sol, names, scale, y.size, confidence, stats)


def _data(
    experiment: Any, temperatures_c: Any, displacements_m: Any
) -> tuple[list[TcaExperiment], list[FloatArray], list[FloatArray]]:
    """The experiments and one 1-D temperature [C] and displacement [m] array each, checked."""
    if isinstance(experiment, TcaExperiment):
        exps: list[TcaExperiment] = [experiment]
        ts = [V.real_array("temperatures_c", temperatures_c, max_size=100_000, unit="C")]
        ys = [V.real_array("displacements_m", displacements_m, max_size=100_000, unit="m")]
    else:
        exps = [
            V.instance("experiment", e, TcaExperiment, "a TcaExperiment or a sequence of them")
            for e in V.sequence("experiment", experiment, 1000)
        ]
        ts = [
            V.real_array(f"temperatures_c[{k}]", x, max_size=100_000, unit="C")
            for k, x in enumerate(V.sequence("temperatures_c", temperatures_c, 1000))
        ]
        ys = [
            V.real_array(f"displacements_m[{k}]", x, max_size=100_000, unit="m")
            for k, x in enumerate(V.sequence("displacements_m", displacements_m, 1000))
        ]
        if not (len(exps) == len(ts) == len(ys)) or not exps:
            raise ValueError(f"give one temperature and one displacement array per experiment ({len(exps)})")
    for k, (tk, yk) in enumerate(zip(ts, ys)):
        if tk.shape != yk.shape or tk.ndim != 1:
            raise ValueError(
                f"experiment {k}: temperatures_c {tk.shape} and displacements_m {yk.shape} must be 1-D of one length"
            )
    return exps, ts, ys


def _fit_names(fit: Sequence[str], n_points: int) -> tuple[str, ...]:
    """The names of the fitted parameters, checked against :data:`PARAMETERS` and the data size."""
    names = tuple(V.sequence("fit", fit, len(PARAMETERS) + 1))
    for n in names:
        if not isinstance(n, str):
            raise TypeError(f"fit must name parameters (str), not {type(n).__name__}")
    if len(set(names)) != len(names):
        raise ValueError(f"fit: repeated parameter names in {list(names)}")
    unknown = [n for n in names if n not in PARAMETERS]
    if unknown or not names:
        raise ValueError(f"fit: unknown parameter(s) {unknown}; choose from {list(PARAMETERS)}")
    p = len(names)
    if n_points < p + 1:
        raise ValueError(f"need at least {p + 1} data points to fit {p} parameters, got {n_points}")
    return names


def _initial_values(initial: dict[str, float] | None, mat: Material) -> dict[str, float]:
    """Every parameter's starting (or fixed) value: the defaults, overridden by ``initial``."""
    values: dict[str, float] = {
        "youngs_modulus_slope_pa_per_c": mat.coefficients[1],
        "expansion_scale": 1.0,
        "friction_mass_kg": 0.0,
        "friction_ratio": 0.0,
    }
    if initial is not None and not isinstance(initial, dict):
        raise TypeError(f"initial must be a dict of parameter values, not {type(initial).__name__}")
    for key, v in (initial or {}).items():
        if key not in PARAMETERS:
            raise ValueError(f"initial: unknown parameter {key!r}; choose from {list(PARAMETERS)}")
        values[key] = V.real(f"initial[{key!r}]", v)
    return values


def _result(
    sol: Any, names: tuple[str, ...], scale: FloatArray, n_points: int, confidence: float, stats: Any
) -> CalibrationResult:
    """Estimates, standard errors and ``confidence`` intervals from the linearised least-squares fit."""
    p = len(names)
    j = np.asarray(sol.jac, dtype=np.float64)
    dof = max(n_points - p, 1)
    ssr = float(np.sum(np.asarray(sol.fun) ** 2))
    s2 = ssr / dof
    jtj_inv = np.linalg.pinv(j.T @ j)
    cov_scaled = s2 * jtj_inv
    cov = np.asarray(cov_scaled * np.outer(scale, scale), dtype=np.float64)
    se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    est = np.asarray(sol.x, dtype=np.float64) * scale
    q = float(stats.t.ppf(0.5 + 0.5 * confidence, dof))
    if not (np.all(np.isfinite(est)) and np.all(np.isfinite(cov)) and math.isfinite(s2) and math.isfinite(q)):
        raise ValueError(
            "calibrate: the data do not determine the parameters (non-finite estimate or covariance); "
            "check temperatures_c [C] and displacements_m [m], or fit fewer parameters"
        )
    return CalibrationResult(
        names=names,
        estimate=est,
        standard_error=se,
        ci_low=est - q * se,
        ci_high=est + q * se,
        covariance=cov,
        residual_std_m=math.sqrt(s2),
        n_points=int(n_points),
        success=bool(sol.success),
        message=str(sol.message),
    )
