"""Calibration of TCA parameters from displacement-temperature data
(``tcarod.models.calibration``, SciPy least squares), on synthetic data from
the model itself: exact data recovers the truth, noisy data within a stated
multiple of the standard error, and the interval narrows with more data."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from tcarod import Material
from tcarod.models.calibration import TcaExperiment, calibrate

# one folded half of the paper's 3-thread Fig. 5 TCA under a 10 g weight
EXP = TcaExperiment(0.5 * 0.497, 0.5 * 0.110, 2e-3, 150.0, mass_kg=10e-3, load_share=0.5)
TRUE = {"youngs_modulus_slope_pa_per_c": -1.0e6, "expansion_scale": 1.15, "friction_mass_kg": 4e-3}
BASE = Material.silver_coated_nylon()


def _data(n: int, noise_m: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(25.0, 160.0, n)
    y = EXP.predict(t, BASE, TRUE) + np.random.default_rng(seed).normal(0.0, noise_m, n)
    return t, y


def test_exact_data_recovers_the_parameters() -> None:
    t, y = _data(28, 0.0, 0)
    r = calibrate(
        EXP, t, y, fit=("expansion_scale", "friction_mass_kg"), initial={"youngs_modulus_slope_pa_per_c": -1e6}
    )
    # noise-free: the optimum is the truth up to the solver's tolerances
    # (least_squares' ftol/xtol 1e-8 relative)
    assert r.estimate[0] == pytest.approx(1.15, rel=1e-5)
    assert r.estimate[1] == pytest.approx(4e-3, rel=1e-3)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_noisy_data_recovery_within_stated_multiple_of_standard_error(seed: int) -> None:
    t, y = _data(28, 0.05e-3, seed)  # 28 points, 0.05 mm noise
    r = calibrate(
        EXP, t, y, fit=("expansion_scale", "friction_mass_kg"), initial={"youngs_modulus_slope_pa_per_c": -1e6}
    )
    assert r.success
    truth = np.array([TRUE["expansion_scale"], TRUE["friction_mass_kg"]])
    z = np.abs(r.estimate - truth) / r.standard_error
    # A correct linearised SE gives |z| ~ N(0,1); over 20 seeds at this size
    # the largest measured |z| is 1.9. 4 standard errors leaves room for the
    # kink at the onset of extension, where the model is not linear.
    assert np.all(z < 4.0), z
    # the noise estimate matches the noise put in (n - p = 26 dof: +-30 %)
    assert 0.035e-3 < r.residual_std_m < 0.065e-3


def test_more_data_narrows_the_interval() -> None:
    widths = []
    for n in (8, 55):
        t, y = _data(n, 0.05e-3, 7)
        r = calibrate(
            EXP, t, y, fit=("expansion_scale", "friction_mass_kg"), initial={"youngs_modulus_slope_pa_per_c": -1e6}
        )
        widths.append(r.ci_high - r.ci_low)
    # ~1/sqrt(n): 55 points vs 8 should be ~2.6x narrower; require 1.5x
    assert np.all(widths[1] * 1.5 < widths[0])


def test_bad_input_is_rejected() -> None:
    with pytest.raises(ValueError, match="unknown"):
        calibrate(EXP, [30.0, 60.0, 90.0], [0.0, 1e-3, 2e-3], fit=("modulus",))
    with pytest.raises(ValueError, match="at least"):
        calibrate(EXP, [30.0, 60.0], [0.0, 1e-3])


def test_two_loads_fit_modulus_slope_expansion_and_friction_ratio() -> None:
    # Fig. 5's two loads (5 g, 10 g) with friction half the hanging mass:
    # fitting them together separates the modulus slope from the friction.
    exps = [TcaExperiment(0.5 * 0.497, 0.5 * 0.110, 2e-3, 150.0, mass_kg=m, load_share=0.5) for m in (5e-3, 10e-3)]
    true = {"youngs_modulus_slope_pa_per_c": -1.3e6, "expansion_scale": 1.15, "friction_ratio": 0.5}
    t = np.linspace(25.0, 160.0, 28)
    rng = np.random.default_rng(11)
    ys = [e.predict(t, BASE, true) + rng.normal(0.0, 0.02e-3, t.size) for e in exps]
    r = calibrate(exps, [t, t], ys, fit=tuple(true))
    z = np.abs(r.estimate - np.array(list(true.values()))) / r.standard_error
    # over 20 seeds at this size and noise the largest measured |z| is 2.3;
    # 4 SE as above
    assert np.all(z < 4.0), z
    # the expansion is pinned to about 1 % (CI half-width), the slope only to
    # about +-1 MPa/C: the modulus enters only through f11 F, F is small
    assert r.ci_high[1] - r.ci_low[1] < 0.02
    assert r.ci_high[0] - r.ci_low[0] > 0.5e6


def test_wrong_types_are_type_errors_naming_the_argument() -> None:
    with pytest.raises(TypeError, match="temperatures_c"):
        calibrate(EXP, ["30", "60", "90"], [0.0, 1e-3, 2e-3])
    with pytest.raises(TypeError, match="fit"):
        calibrate(EXP, [30.0, 60.0, 90.0], [0.0, 1e-3, 2e-3], fit=None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="displacements_m"):
        calibrate(EXP, [30.0, 60.0, 90.0], [0.0, float("nan"), 2e-3])
    with pytest.raises(ValueError, match="confidence"):
        calibrate(EXP, [30.0, 60.0, 90.0], [0.0, 1e-3, 2e-3], confidence=1.5)
    with pytest.raises(TypeError, match="mass_kg"):
        replace(EXP, mass_kg="5 g")
