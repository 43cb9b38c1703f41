"""The TCA law (paper Section II, eqs 1-6) through the Python API.

Units: m, N, rad, degrees C. Sign convention: force > 0 is tension,
displacement > 0 is extension.

Numerical floor used in the tolerances below: the core solves for the
displacement with Brent's method to an absolute tolerance of 1e-15 * l
(about 5e-16 m for these TCAs) and for temperatures to 1e-10 C; the law
itself is evaluated with a handful of flops, so rounding adds a few ulp of
the displacement (|delta| <= 0.4 m, ulp ~ 5e-17 m).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tcarod import Material, Tca

T_REF = 25.0
T_MAX = 160.0
SETTINGS = settings(max_examples=60, deadline=None)


def fig5_tca(chirality: str = "extension") -> Tca:
    """The paper's three-thread Fig. 5 TCA (whole, unfolded)."""
    return Tca(0.497, 0.110, 2e-3, 300.0, chirality)


EXT = fig5_tca("extension")
CON = fig5_tca("contraction")

temperatures = st.floats(min_value=T_REF, max_value=T_MAX, allow_nan=False)
#: Both chiralities of the Fig. 5 TCA.
fig5_tcas = st.sampled_from([EXT, CON])


def stiffness(tca: Tca, displacement: float, temperature: float) -> float:
    """Local spring stiffness 1/f11 [N/m] at the given state."""
    return 1.0 / tca.f11(tca.pitch_angle(displacement), temperature)


# ---------------------------------------------------------------- analytic limits


@SETTINGS
@given(force=st.floats(min_value=1e-4, max_value=2.0))
def test_reference_temperature_tension_is_the_spring_law(force: float) -> None:
    # At t_ref the fibre has not expanded, so tau = 0 and eq (2) reduces to
    # delta = f11(alpha(delta)) F with alpha from eq (5).
    assert EXT.torque(T_REF) == 0.0
    delta = EXT.displacement(force, T_REF)
    assert delta > 0.0
    f11 = EXT.f11(EXT.pitch_angle(delta), T_REF)
    # delta is a root to 1e-15 * l ~ 5e-16 m; the residual's derivative is ~1,
    # so the identity holds to ~1e-15 m: 1e-13 m (or 1e-12 relative) is a
    # 100x margin.
    assert delta == pytest.approx(f11 * force, rel=1e-12, abs=1e-13)


@SETTINGS
@given(t1=temperatures, t2=temperatures, force=st.floats(min_value=-0.2, max_value=0.0))
def test_loaded_extension_tca_never_shortens_when_heated(t1: float, t2: float, force: float) -> None:
    lo, hi = min(t1, t2), max(t1, t2)
    # Exact comparison: the displacement is monotone in T and the solve error
    # (1e-15 m) is below the change over any distinct temperatures except
    # where both are clamped to exactly 0.
    d_lo, d_hi = EXT.displacement(force, lo), EXT.displacement(force, hi)
    assert d_hi >= d_lo - 1e-14


# ---------------------------------------------------------------- inverses


@SETTINGS
@given(temperature=temperatures, u=st.floats(min_value=1e-3, max_value=1.0), tca=fig5_tcas)
def test_force_inverts_displacement(temperature: float, u: float, tca: Tca) -> None:
    # Forces that keep the coils open (above the blocked force) and stay well
    # below the straight-fibre limit (F at 80% of the largest elongation).
    f_lo = tca.blocked_force(temperature)
    f_hi = tca.force(0.8 * tca.max_displacement, temperature)
    force = f_lo + u * (f_hi - f_lo)
    delta = tca.displacement(force, temperature)
    assert 0.0 < delta < tca.max_displacement
    back = tca.force(delta, temperature)
    # F = (delta - s f12 tau)/f11: an error e in delta gives k e in F with
    # k = 1/f11 the local stiffness; e <= ~1e-15 m (solve + rounding), so
    # k * 1e-13 m is a 100x margin (plus a few ulp of F itself).
    tol = stiffness(tca, delta, temperature) * 1e-13 + 8 * math.ulp(abs(force) + abs(f_lo))
    assert abs(back - force) <= tol


@SETTINGS
@given(temperature=temperatures, u=st.floats(min_value=1e-4, max_value=0.8), tca=fig5_tcas)
def test_displacement_inverts_force(temperature: float, u: float, tca: Tca) -> None:
    delta = u * tca.max_displacement
    force = tca.force(delta, temperature)
    assert force > tca.blocked_force(temperature)  # holding it open takes more than the blocked force
    # Brent tolerance 1e-15 * l (5e-16 m) plus rounding of a few ulp of delta:
    # 1e-13 m is a 100x margin.
    assert tca.displacement(force, temperature) == pytest.approx(delta, rel=0, abs=1e-13)


@SETTINGS
@given(temperature=temperatures, force=st.floats(min_value=-0.3, max_value=0.5))
def test_temperature_inverts_displacement(temperature: float, force: float) -> None:
    delta = EXT.displacement(force, temperature)
    if delta == 0.0 and force > 0.0:
        # A tension so small that its elongation is below the solve tolerance
        # (1e-15 * l); nothing to invert.
        assert force * EXT.f11(EXT.alpha0, temperature) < 1e-14
        return
    if delta == 0.0:
        # Coils closed: the state is reached over a whole temperature range,
        # so only check that the onset lies at or above this temperature.
        assert EXT.onset_temperature(force) >= temperature - 1e-9
        return
    back = EXT.temperature(force, delta)
    # Brent stops within 1e-10 C; the displacement error (1e-15 m) divided by
    # the smallest d(delta)/dT in range (~5e-5 m/C at 25 C) adds 2e-11 C:
    # 1e-7 C is a 500x margin.
    assert back == pytest.approx(temperature, rel=0, abs=1e-7)


# ---------------------------------------------------------------- vectorised API


def test_scalars_in_floats_out() -> None:
    for out in (
        EXT.displacement(-0.01, 80.0),
        EXT.force(0.001, 80.0),
        EXT.temperature(-0.01, 0.001),
        EXT.onset_temperature(-0.01),
        EXT.free_stroke(80.0),
        EXT.blocked_force(80.0),
        EXT.displacement(np.float64(-0.01), np.array(80.0)),  # 0-d arrays count as scalars
    ):
        assert type(out) is float


def test_broadcasting_shapes_and_values() -> None:
    forces = np.array([[-0.05], [0.0], [0.05]])  # (3, 1)
    temps = np.array([25.0, 60.0, 100.0, 160.0])  # (4,)
    disp = EXT.displacement(forces, temps)
    assert isinstance(disp, np.ndarray)
    assert disp.shape == (3, 4)
    assert disp.dtype == np.float64
    for i in range(3):
        for j in range(4):
            # elementwise the same solve as the scalar call: identical bits
            assert disp[i, j] == EXT.displacement(float(forces[i, 0]), float(temps[j]))
    # lists broadcast too; a scalar against an array gives the array's shape
    assert EXT.force([0.001, 0.002], 80.0).shape == (2,)  # type: ignore[union-attr]
    assert EXT.free_stroke([[40.0, 50.0]]).shape == (1, 2)  # type: ignore[union-attr]
    temps_back = EXT.temperature(-0.01, np.array([0.001, 0.002, 0.004]))
    assert isinstance(temps_back, np.ndarray) and temps_back.shape == (3,)
    assert np.all(np.diff(temps_back) > 0)  # more stroke needs more heat
    empty = EXT.displacement(np.zeros(0), 50.0)
    assert isinstance(empty, np.ndarray) and empty.shape == (0,)


def test_array_error_names_the_failing_element() -> None:
    with pytest.raises(ValueError, match=r"^invalid temperature \(element 2\) = 170 C: allowed 25 <= T <= 160 C"):
        EXT.displacement(0.0, [30.0, 40.0, 170.0])


def test_material_preset_reproduces_documented_values() -> None:
    m = Material.silver_coated_nylon()
    assert (m.t_ref, m.t_min, m.t_max) == (25.0, 25.0, 160.0)
    # docs/choices.md, "Material (silver-coated nylon 6,6)": E_T(25 C) = 1.198e9 Pa,
    # G_T(25 C) = 2.218e8 Pa, slope -1.3e6 Pa/C (Sun & Zhao's T-RO 2022 code);
    # the preset's own numbers, so rounding only (1e-12)
    assert m.youngs_modulus(25.0) == pytest.approx(1.198e9, rel=1e-12)
    assert m.shear_modulus(25.0) == pytest.approx(2.218e8, rel=1e-12)
    assert m.youngs_modulus(160.0) == pytest.approx(1.198e9 - 1.3e6 * 135, rel=1e-12)
    # d/d0 fit 3.542e-6 T^2 - 6.705e-5 T + 1.00169 normalised to 25 C (exact identity,
    # so only rounding: 1e-12)
    q = lambda t: 3.542e-6 * t * t - 6.705e-5 * t + 1.00169  # noqa: E731
    for t in (25.0, 90.0, 160.0):
        assert m.diameter_ratio(t) == pytest.approx(q(t) / q(25.0), rel=1e-12)
