"""Bad input: every constructor and solve rejects it with a clear error.

Contract (tcarod.tca module docstring):

* ``ValueError`` for numbers outside the law's domain -- NaN, inf,
  non-positive sizes, ``L >= l/2``, temperatures outside the material's range,
  loads that straighten the fibre, arrays that do not broadcast -- with a
  message naming the argument;
* ``TypeError`` for arguments that are not real numbers (or arrays of them):
  ``str``, ``None``, ``complex``, an array where a scalar is required. This is
  Python's own convention (``math.sqrt("x")`` is a TypeError,
  ``math.sqrt(-1.0)`` a ValueError), and it is what the compiled constructors
  do for any ``float`` parameter, so both layers agree;
* Python ints beyond the double range are real numbers: they saturate to
  +-inf and are rejected with ``ValueError`` like inf, not ``OverflowError``;
* no function returns NaN.
"""

from __future__ import annotations

import math
import warnings
from typing import Any, Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import tcarod
from tcarod import Material, Tca

NAN, INF = math.nan, math.inf
HUGE_INT = pytest.param(10**400, id="10**400")  # beyond the double range
TCA = Tca(0.497, 0.110, 2e-3, 300.0)
MATERIAL = Material.silver_coated_nylon()

MATERIAL_KW: dict[str, float] = {
    "youngs_modulus": 1.2e9,
    "shear_modulus": 2.2e8,
    "expansion": 1e-4,
    "youngs_modulus_slope": -1.3e6,
    "expansion_slope": 3.5e-6,
    "t_ref": 25.0,
    "t_min": 25.0,
    "t_max": 160.0,
}


# ---------------------------------------------------------------- named fields


@pytest.mark.parametrize("bad", [NAN, INF, -INF, 0.0, -1.0, HUGE_INT])
@pytest.mark.parametrize(
    ("index", "field"),
    [(0, "fibre_length"), (1, "coiled_length"), (2, "coil_diameter"), (3, "turns")],
)
def test_tca_rejects_non_finite_and_non_positive(index: int, field: str, bad: float) -> None:
    args: list[Any] = [0.497, 0.110, 2e-3, 300.0]
    args[index] = bad
    with pytest.raises(ValueError, match=field):
        Tca(*args)


@pytest.mark.parametrize("coiled", [0.497, 0.6, 0.25])  # L = l, L > l, L > l/2
def test_tca_rejects_coiled_length_not_below_fibre_length(coiled: float) -> None:
    with pytest.raises(ValueError, match="coiled_length"):
        Tca(0.497, coiled, 2e-3, 300.0)


def test_tca_rejects_unknown_chirality() -> None:
    with pytest.raises(ValueError, match="chirality"):
        Tca(0.497, 0.110, 2e-3, 300.0, "sideways")  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", [NAN, INF, 0.0, -0.1, math.pi / 6, 1.0])
def test_from_pitch_angle_rejects_bad_alpha0(bad: float) -> None:
    with pytest.raises(ValueError, match="alpha0"):
        Tca.from_pitch_angle(0.04, bad, 1.7e-3, 76.4)


@pytest.mark.parametrize(("index", "field"), [(0, "coiled_length"), (2, "coil_diameter"), (3, "turns")])
@pytest.mark.parametrize("bad", [NAN, -INF, 0.0, -2.0])
def test_from_pitch_angle_rejects_bad_sizes(index: int, field: str, bad: float) -> None:
    args: list[Any] = [0.04, math.radians(15), 1.7e-3, 76.4]
    args[index] = bad
    with pytest.raises(ValueError, match=field):
        Tca.from_pitch_angle(*args)


@pytest.mark.parametrize("bad", [NAN, INF, -INF])
@pytest.mark.parametrize("field", sorted(MATERIAL_KW))
def test_material_rejects_non_finite(field: str, bad: float) -> None:
    with pytest.raises(ValueError, match=field):
        Material(**{**MATERIAL_KW, field: bad})


@pytest.mark.parametrize("field", ["youngs_modulus", "shear_modulus"])
@pytest.mark.parametrize("bad", [0.0, -1e9])
def test_material_rejects_non_positive_moduli(field: str, bad: float) -> None:
    with pytest.raises(ValueError, match=field):
        Material(**{**MATERIAL_KW, field: bad})


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"t_max": 20.0}, "t_max"),  # t_max below t_min
        ({"t_ref": 200.0}, "t_ref"),  # reference outside the range
        ({"youngs_modulus_slope": -1e8}, "youngs_modulus_slope"),  # E_T < 0 at 160 C
        ({"expansion": -1.0}, "expansion"),  # d/d0 = 1 + rho dT < 0 at 160 C
    ],
)
def test_material_rejects_inconsistent_fields(changes: dict[str, float], field: str) -> None:
    with pytest.raises(ValueError, match=field):
        Material(**{**MATERIAL_KW, **changes})


@pytest.mark.parametrize("temperature", [24.9, 160.1, -300.0, NAN, INF, HUGE_INT])
@pytest.mark.parametrize(
    "call",
    [
        lambda t: TCA.displacement(0.0, t),
        lambda t: TCA.force(0.01, t),
        lambda t: TCA.free_stroke(t),
        lambda t: TCA.blocked_force(t),
        lambda t: TCA.torque(t),
        lambda t: TCA.f11(0.3, t),
        lambda t: MATERIAL.youngs_modulus(t),
    ],
    ids=["displacement", "force", "free_stroke", "blocked_force", "torque", "f11", "youngs_modulus"],
)
def test_solves_reject_out_of_range_temperatures(call: Callable[[float], object], temperature: float) -> None:
    with pytest.raises(ValueError, match=r"temperature \[C\]"):
        call(temperature)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: TCA.displacement(NAN, 50.0), r"force \[N\]"),
        (lambda: TCA.displacement(INF, 50.0), r"force \[N\]"),
        (lambda: TCA.force(-1e-3, 50.0), r"displacement \[m\]"),  # coils cannot close further
        (lambda: TCA.force(NAN, 50.0), r"displacement \[m\]"),
        (lambda: TCA.force(0.5, 50.0), r"displacement \[m\]"),  # beyond the straight fibre
        (lambda: TCA.temperature(0.0, -1e-3), r"displacement \[m\]"),
        (lambda: TCA.temperature(NAN, 1e-3), r"force \[N\]"),
        (lambda: TCA.pitch_angle(INF), r"displacement \[m\]"),
        (lambda: TCA.f11(NAN, 50.0), r"alpha \[rad\]"),
        (lambda: TCA.f12(2.0, 50.0), r"alpha \[rad\]"),
        (lambda: TCA.displacement(1e3, 50.0), "straightens the fibre"),
        (lambda: TCA.temperature(-100.0, 0.01), "no temperature"),  # no such state in range
        (lambda: TCA.onset_temperature(-100.0), "no temperature"),
        (lambda: TCA.displacement(np.zeros((2, 3)), np.zeros(4)), "cannot be broadcast"),
        (lambda: TCA.displacement([[0.0, 1.0], [2.0]], 50.0), "force"),  # ragged
    ],
)
def test_solves_reject_bad_values_naming_the_field(call: Callable[[], object], field: str) -> None:
    with pytest.raises(ValueError, match=field):
        call()


@pytest.mark.parametrize("bad", ["1.0", None, 1j, object(), b"x"])
def test_wrong_python_types_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match="fibre_length"):
        Tca(bad, 0.110, 2e-3, 300.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="force"):
        TCA.displacement(bad, 50.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="temperature"):
        TCA.torque(bad)  # type: ignore[arg-type]


# ---------------------------------------------------------------- fuzzing

# Each entry: a callable and valid arguments; "s" marks a scalar-only
# argument, "a" an argument that also takes arrays.
ENTRY_POINTS: dict[str, tuple[Callable[..., Any], list[Any], str]] = {
    "Tca": (Tca, [0.497, 0.110, 2e-3, 300.0], "ssss"),
    "Tca.from_pitch_angle": (Tca.from_pitch_angle, [0.04, 0.26, 1.7e-3, 76.4], "ssss"),
    "Material": (
        lambda *a: Material(**dict(zip(MATERIAL_KW, a))),
        list(MATERIAL_KW.values()),
        "s" * len(MATERIAL_KW),
    ),
    "Tca.displacement": (TCA.displacement, [-0.03, 100.0], "aa"),
    "Tca.force": (TCA.force, [0.005, 100.0], "aa"),
    "Tca.temperature": (TCA.temperature, [-0.03, 0.005], "aa"),
    "Tca.onset_temperature": (TCA.onset_temperature, [-0.03], "a"),
    "Tca.free_stroke": (TCA.free_stroke, [100.0], "a"),
    "Tca.blocked_force": (TCA.blocked_force, [100.0], "a"),
    "Tca.pitch_angle": (TCA.pitch_angle, [0.005], "s"),
    "Tca.f11": (TCA.f11, [0.3, 100.0], "ss"),
    "Tca.f12": (TCA.f12, [0.3, 100.0], "ss"),
    "Tca.torque": (TCA.torque, [100.0], "s"),
    "Tca.fibre_diameter": (TCA.fibre_diameter, [100.0], "s"),
    "Material.youngs_modulus": (MATERIAL.youngs_modulus, [100.0], "s"),
    "Material.shear_modulus": (MATERIAL.shear_modulus, [100.0], "s"),
    "Material.expansion": (MATERIAL.expansion, [100.0], "s"),
    "Material.diameter_ratio": (MATERIAL.diameter_ratio, [100.0], "s"),
}

real_scalars = st.one_of(
    st.sampled_from([NAN, INF, -INF, 0.0, -0.0, 10**400, -(10**400), 1e308, -1e308, 5e-324]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(min_value=-(10**320), max_value=10**320),
    st.booleans(),
)
real_arrays = st.one_of(
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=4).map(np.array),
    st.lists(st.floats(min_value=-1e3, max_value=1e3), min_size=1, max_size=6).map(
        lambda v: np.array(v).reshape(-1, 1) if len(v) % 2 else np.array(v).reshape(2, -1)
    ),
    st.lists(st.integers(min_value=-(10**400), max_value=10**400), max_size=3),  # object arrays
    st.just([[1.0, 2.0], [3.0]]),  # ragged
)
wrong_types = st.one_of(
    st.text(max_size=5),
    st.none(),
    st.complex_numbers(allow_nan=False, max_magnitude=1e3),
    st.sampled_from([object(), b"1.0", bytearray(b"2"), {1.0}, (1.0, "x")]),
    st.dictionaries(st.text(max_size=2), st.floats(), max_size=2),
    st.lists(st.text(max_size=2), min_size=1, max_size=3),
)


def _is_real_scalar(v: object) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, np.ndarray)


def _is_real_array(v: object) -> bool:
    if isinstance(v, np.ndarray):
        return v.dtype.kind in "biuf" or (v.dtype.kind == "O" and all(_is_real_scalar(x) for x in v.ravel()))
    if isinstance(v, list):
        try:
            return _is_real_array(np.asarray(v))
        except ValueError:  # ragged: a ValueError is expected, never a TypeError
            return True
    return False


def _assert_no_nan(out: object) -> None:
    if isinstance(out, Tca):
        values = [
            out.fibre_length,
            out.coiled_length,
            out.coil_diameter,
            out.turns,
            out.alpha0,
            out.n_coils,
            out.phi0,
            out.d0,
        ]
        assert not any(math.isnan(v) for v in values), out
    elif isinstance(out, Material):
        assert not any(math.isnan(v) for v in out.coefficients), out
    else:
        arr = np.asarray(out, dtype=np.float64)
        assert not np.isnan(arr).any(), out


@settings(max_examples=400, deadline=None)
@given(
    entry=st.sampled_from(sorted(ENTRY_POINTS)),
    data=st.data(),
)
def test_fuzz_only_value_or_type_errors_and_never_nan(entry: str, data: st.DataObject) -> None:
    fn, valid, kinds = ENTRY_POINTS[entry]
    args = list(valid)
    # Replace one or more arguments with bad values.
    positions = data.draw(
        st.lists(st.integers(0, len(args) - 1), min_size=1, max_size=len(args), unique=True), label="positions"
    )
    for i in positions:
        args[i] = data.draw(st.one_of(real_scalars, real_arrays, wrong_types), label=f"arg{i}")
    try:
        with warnings.catch_warnings():
            # valid sizes that look like mm warn (tcarod.UnitsWarning): not an error
            warnings.simplefilter("ignore", tcarod.UnitsWarning)
            out = fn(*args)
    except TypeError as exc:
        # Allowed only if some replaced argument is not a real number of the
        # kind that position takes (a scalar for "s", scalar or array for "a").
        def acceptable(i: int) -> bool:
            v = args[i]
            return _is_real_scalar(v) or (kinds[i] == "a" and _is_real_array(v))

        assert not all(acceptable(i) for i in positions), f"TypeError for real-number input: {exc}"
    except ValueError as exc:
        assert str(exc)  # has a message
        assert "nan" not in type(exc).__name__.lower()
    else:
        _assert_no_nan(out)


def test_tiny_and_huge_but_valid_geometry_never_returns_nan() -> None:
    # Finite inputs that pass the range checks but over/underflow inside the
    # law (d0^4 = 0 for a 1e-300 m fibre) are refused when the TCA is built,
    # naming the geometry -- never a NaN later.
    with pytest.raises(ValueError, match="TCA geometry"):
        Tca(1e-300, 1e-301, 1e-300, 1e-300)
    with pytest.raises(ValueError):
        Tca(0.497, 0.110, 2e-3, 300.0, material=Material(youngs_modulus=1e9, shear_modulus=1e8, expansion=1e300))


@pytest.mark.parametrize(
    ("make", "bad", "allowed"),
    [
        (lambda: tcarod.Actuator.tendon(tcarod.Routing.straight(1e-3, 0.0)), NAN, "input >= 0 (finite)"),
        (lambda: tcarod.Actuator.linear_tendon(100.0, tcarod.Routing.straight(1e-3, 0.0)), INF, "a finite input"),
    ],
    ids=["tendon", "linear_tendon"],
)
def test_an_unbounded_input_range_is_stated_without_the_double_maximum(
    make: Callable[[], tcarod.Actuator], bad: float, allowed: str
) -> None:
    """A law whose input has no upper bound says "finite", not f64::MAX's 309 digits."""
    body = tcarod.Body(0.1, tcarod.Section.circle(10e-3), 1e6)
    robot = tcarod.Robot(body, [make()])
    with pytest.raises(ValueError, match=r"invalid inputs\[0\]") as info:
        robot.solve([bad])
    assert allowed in str(info.value)
    assert "179769" not in str(info.value)


def test_an_offset_outside_the_section_points_to_spacer_disks() -> None:
    """The steel tendon robot's tendons (``tcarod::experiments::steel_tendon_robot``: 15.06 mm off a rod of
    1 mm radius) need spacer disks: the error says so."""
    body = tcarod.Body(0.5, tcarod.Section.circle(2e-3), 200e9, shear_modulus=80e9)
    tendon = tcarod.Actuator.tendon(tcarod.Routing.straight(15.06e-3, 0.0))
    with pytest.raises(ValueError, match=r"actuators\[0\]\.routing.*spacer_disks=True"):
        tcarod.Robot(body, [tendon])
    assert tcarod.Robot(body, [tendon], spacer_disks=True).solve([15.0]).success
