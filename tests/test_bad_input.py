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
import re
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
    with pytest.raises(ValueError, match=r"^invalid temperature( \(element \d+\))? = \S+ C: allowed 25 <= T <= 160 C"):
        call(temperature)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: TCA.displacement(NAN, 50.0), r"^invalid force( \(element \d+\))? = \S+ N: allowed"),
        (lambda: TCA.displacement(INF, 50.0), r"^invalid force( \(element \d+\))? = \S+ N: allowed"),
        (
            lambda: TCA.force(-1e-3, 50.0),
            r"^invalid displacement( \(element \d+\))? = \S+ m: allowed",
        ),  # coils cannot close further
        (lambda: TCA.force(NAN, 50.0), r"^invalid displacement( \(element \d+\))? = \S+ m: allowed"),
        (
            lambda: TCA.force(0.5, 50.0),
            r"^invalid displacement( \(element \d+\))? = \S+ m: allowed",
        ),  # beyond the straight fibre
        (lambda: TCA.temperature(0.0, -1e-3), r"^invalid displacement( \(element \d+\))? = \S+ m: allowed"),
        (lambda: TCA.temperature(NAN, 1e-3), r"^invalid force( \(element \d+\))? = \S+ N: allowed"),
        (lambda: TCA.pitch_angle(INF), r"^invalid displacement( \(element \d+\))? = \S+ m: allowed"),
        (lambda: TCA.f11(NAN, 50.0), r"^invalid alpha = \S+ rad: allowed"),
        (lambda: TCA.f12(2.0, 50.0), r"^invalid alpha = \S+ rad: allowed"),
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
        (lambda: tcarod.Actuator.tendon(tcarod.Routing.straight(1e-3, 0.0)), NAN, "input >= 0 N (finite)"),
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


# ------------------------------------------- hostile lengths, ranges, units


class _LyingSequence:
    """Claims 2**62 items and yields a number at every index: NumPy and
    ``list()`` allocate by the claim before reading it."""

    def __len__(self) -> int:
        return 2**62

    def __getitem__(self, i: int) -> float:
        return 1.0


@pytest.mark.parametrize(
    "call",
    [
        lambda x: TCA.force(x, 60.0),
        lambda x: TCA.displacement(0.1, x),
        lambda x: TCA.temperature(x, 0.01),
        lambda x: TCA.onset_temperature(x),
        lambda x: TCA.free_stroke(x),
        lambda x: TCA.blocked_force(x),
        lambda x: TCA.force([x], 60.0),
    ],
    ids=["force", "displacement", "temperature", "onset_temperature", "free_stroke", "blocked_force", "nested"],
)
def test_a_sequence_claiming_a_huge_length_is_a_value_error(call: Callable[[object], object]) -> None:
    with pytest.raises(ValueError, match=r"at most 10000000 allowed|more values than memory holds"):
        call(_LyingSequence())


def _fig6() -> Any:
    from tcarod.batch import fig6_square_robot

    return fig6_square_robot(False)


def test_blocked_temperatures_refuse_a_sequence_claiming_a_huge_length() -> None:
    robot = _fig6()
    with pytest.raises(ValueError, match="point"):
        tcarod.blocked_temperature(robot, _LyingSequence(), [-1.0, 0.0, 0.0], 0.01)
    with pytest.raises(ValueError, match="normal"):
        tcarod.blocked_temperature_direct(robot, [0.0, 0.0, 0.04], _LyingSequence(), 0.01)


@pytest.mark.parametrize(
    ("name", "bad", "unit"),
    [
        ("fibre_length_m", 1e-300, "m"),
        ("fibre_length_m", 1e3, "m"),
        ("thread_radius_m", 1.7e308, "m"),
        ("thread_radius_m", 1e-9, "m"),
        ("density_kg_per_m3", 1e300, "kg/m^3"),
        ("specific_heat_j_per_kgk", 1e-300, "J/(kg K)"),
        ("heat_transfer_w_per_m2k", 1e200, "W/(m^2 K)"),
        ("resistance", 1e-300, "ohm"),
        ("resistance", 1e300, "ohm"),
    ],
)
def test_thermal_model_coefficients_outside_their_physical_range(name: str, bad: float, unit: str) -> None:
    from tcarod.models.thermal import RANGES, ThermalModel

    kwargs: dict[str, Any] = {"fibre_length_m": 0.3, "threads": 3, "resistance": 60.0, name: bad}
    lo, hi, _ = RANGES[name]
    expected = re.escape(f"invalid {name} = {bad:g} {unit}: allowed in [{lo:g}, {hi:g}] {unit} (a physical range")
    with pytest.raises(ValueError, match=expected):
        ThermalModel(**kwargs)


def test_thermal_model_tiny_callable_resistance_gives_value_errors_not_zero_division() -> None:
    from tcarod.models.thermal import ThermalModel, VoltageProfile

    model = ThermalModel(0.3, 3, lambda t, e: 1e-300)
    with pytest.raises(ValueError, match="t_max"):
        model.steady_temperature(3.0)
    # the transient stays finite and says it left the material's range
    out = model.transient(VoltageProfile.step(3.0), [0.0, 1.0])
    assert np.all(np.isfinite(out.temperature_c))
    assert out.exceeds_t_max_at_s == 1.0


def test_thermal_transient_of_a_million_samples_is_vectorised_and_finite() -> None:
    import time

    from tcarod.models.thermal import MAX_TRANSIENT_SAMPLES, ThermalModel, VoltageProfile

    model = ThermalModel(0.3, 3, 60.0)
    times = np.linspace(0.0, 30.0, MAX_TRANSIENT_SAMPLES)
    t0 = time.perf_counter()
    out = model.transient(VoltageProfile((0.0, 10.0), (1.0, 0.5)), times)
    assert time.perf_counter() - t0 < 8.0  # about 0.1 s; far below the fuzz time limit even on a loaded machine
    assert out.temperature_c.shape == times.shape
    assert np.all(np.isfinite(out.temperature_c)) and np.all(np.isfinite(out.power_w))
    # the same samples one by one (the exact exponential), at a few points
    few = model.transient(VoltageProfile((0.0, 10.0), (1.0, 0.5)), times[::250_000])
    np.testing.assert_allclose(out.temperature_c[::250_000], few.temperature_c, rtol=1e-12)
    np.testing.assert_allclose(out.voltage_v[[0, -1]], [1.0, 0.5])
    with pytest.raises(
        ValueError, match=rf"times_s: {MAX_TRANSIENT_SAMPLES + 1} values, at most {MAX_TRANSIENT_SAMPLES}"
    ):
        model.transient(VoltageProfile.step(1.0), np.linspace(0.0, 30.0, MAX_TRANSIENT_SAMPLES + 1))


def test_thermal_transient_rk4_steps_are_capped() -> None:
    from tcarod.models.thermal import MAX_TRANSIENT_RK4_STEPS, LinearResistance, ThermalModel, VoltageProfile

    model = ThermalModel(0.3, 3, LinearResistance(60.0, 0.002))
    with pytest.raises(ValueError, match=rf"times_s / max_step_s: .* allowed at most {MAX_TRANSIENT_RK4_STEPS}"):
        model.transient(VoltageProfile.step(1.0), np.linspace(0.0, 30.0, 2 * MAX_TRANSIENT_RK4_STEPS))


def test_iter_batches_reads_numpy_integer_arguments_as_integers() -> None:
    from tcarod.batch import iter_batches

    robot = _fig6()
    rows = np.full((3, 2), 30.0)
    blocks = list(iter_batches(robot, rows, threads=np.uint8(5), chunk_size=np.uint8(2), block_chunks=np.int64(1)))
    assert [len(b) for b in blocks] == [2, 1]
    assert all(bool(np.all(b.converged)) for b in blocks)
    with pytest.raises(ValueError, match=r"invalid threads = -1: allowed an integer in 0\.\.1024"):
        list(iter_batches(robot, rows, threads=np.int64(-1)))
    with pytest.raises(ValueError, match="invalid chunk_size = 0"):
        list(iter_batches(robot, rows, chunk_size=0))
    with pytest.raises(TypeError, match="threads must be an integer"):
        list(iter_batches(robot, rows, threads=2.0))


@pytest.mark.parametrize(
    ("rotation", "what"),
    [
        (-np.eye(3), "determinant"),
        (np.diag([1.0, 1.0, -1.0]), "determinant"),
        (2.0 * np.eye(3), "orthogonal"),
        (np.full((3, 3), np.nan), "finite"),
    ],
    ids=["minus-identity", "reflection", "scaled", "nan"],
)
def test_tip_position_refuses_an_improper_target_rotation(rotation: Any, what: str) -> None:
    robot = _fig6()
    with pytest.raises(ValueError, match=rf"invalid target_rotation.*{what}"):
        tcarod.tip_position(robot, [0.0, 0.0, 0.04], target_rotation=rotation)


def test_blocked_temperature_direct_without_actuators_says_so() -> None:
    bare = tcarod.Robot(_fig6().body, [])
    for guess in (None, 60.0):
        with pytest.raises(ValueError, match="no actuator to heat"):
            tcarod.blocked_temperature_direct(bare, [0.0, 0.0, 0.04], [-1.0, 0.0, 0.0], 0.01, guess)


@pytest.mark.parametrize(
    ("normal", "match"),
    [([2**1100, 0, 0], "normal"), ([0.0, 0.0, 0.0], "non-zero"), ([math.nan, 0.0, 0.0], "normal")],
)
def test_grasp_refuses_a_bad_normal(normal: list[float], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        tcarod.grasp_temperature(1e-3, normal=normal)


def test_a_huge_but_finite_block_normal_is_the_unit_normal() -> None:
    robot = _fig6()
    tip = [float(x) for x in robot.solve([25.0, 25.0]).tip_position]
    unit = tcarod.blocked_force(robot, tip, [-1.0, 0.0, 0.0], [40.0, 40.0])
    huge = tcarod.blocked_force(robot, tip, [-1e300, 0.0, 0.0], [40.0, 40.0])
    assert huge.force == pytest.approx(unit.force, rel=1e-12)


@pytest.mark.parametrize("modulus", [70.0, 2e12])
def test_a_youngs_modulus_outside_1kpa_to_1tpa_warns(modulus: float) -> None:
    with pytest.warns(tcarod.UnitsWarning, match=rf"youngs_modulus = {modulus:.0f} Pa is outside 1 kPa\.\.1 TPa"):
        tcarod.Body(0.04, tcarod.Section.rectangle(0.01, 0.01), modulus)


def test_a_silicone_modulus_does_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tcarod.Body(0.04, tcarod.Section.rectangle(0.01, 0.01), 5e4)


def test_kelvin_looking_temperatures_warn() -> None:
    from tcarod.models.thermal import ThermalModel

    with pytest.warns(tcarod.UnitsWarning, match="temperature = 330 C.*did you give Kelvin"):
        with pytest.raises(ValueError, match="temperature"):
            TCA.free_stroke(330.0)
    with pytest.warns(tcarod.UnitsWarning, match="ambient_c = 298.15 C.*Kelvin"):
        ThermalModel(0.3, 3, 60.0, ambient_c=298.15, t_max_c=433.15)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        TCA.free_stroke([25.0, 160.0])


def test_design_values_that_look_like_another_unit_warn() -> None:
    from pathlib import Path

    from tcarod.io.design import DesignError, loads_design

    text = (Path(__file__).resolve().parents[1] / "examples" / "designs" / "fig6_square.toml").read_text(
        encoding="utf-8"
    )
    assert "length_m = 0.040" in text
    with pytest.warns(tcarod.UnitsWarning) as record:
        loads_design(text.replace("length_m = 0.040", "length_m = 40", 1))
    messages = [str(w.message) for w in record]
    assert any(re.search(r":8: body\.length_m = 40: keys ending in _m are in metres", m) for m in messages), messages
    hot = text.replace("temperatures_c = [100.0, 100.0]", "temperatures_c = [300.0, 300.0]")
    assert hot != text
    with pytest.warns(tcarod.UnitsWarning, match="temperatures_c = 300.*did you give Kelvin"):
        with pytest.raises(DesignError, match="temperatures_c"):
            loads_design(hot)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        loads_design(text)


def test_a_tca_temperature_in_kelvin_is_named_as_such() -> None:
    from tcarod.batch import fig6_square_robot

    robot = fig6_square_robot()
    # 373.15 K is 100 C, inside the material's range once read as kelvin
    with pytest.raises(ValueError, match=r"inputs\[0\].*373\.15.*Celsius: 373\.15 K is 100\.00 C"):
        robot.solve([373.15, 373.15])
    # beyond the range either way: the range, the material and what to change
    with pytest.raises(ValueError, match=r"allowed 25 <= T <= 160 C, .*silver-coated nylon.*lower the temperature\)$"):
        robot.solve([170.0, 25.0])


# ------------------------------------- one message format, from Rust and Python


def _fig6() -> tcarod.Robot:
    from tcarod.batch import fig6_square_robot

    return fig6_square_robot()


def _robot_12mm(offset: float = 3e-3, **kw: Any) -> tcarod.Robot:
    """A 40 mm EcoFlex-like body of 12 mm diameter with one 1.7 mm TCA at
    ``offset`` [m] along body x."""
    body = tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3, gravity=(0.0, 0.0, -9.81), density=1040.0)
    tca = Tca.from_pitch_angle(0.04, math.radians(15.0), 1.7e-3, 76.4)
    return tcarod.Robot(body, [tcarod.Actuator.tca(tca, tcarod.Routing.straight(offset, 0.0))], **kw)


@pytest.mark.parametrize(
    ("call", "name", "value", "allowed", "reason"),
    [
        pytest.param(
            lambda: _fig6().solve([170.0, 25.0]),
            "inputs[0] (temperature)",
            "170 C",
            "25 <= T <= 160 C",
            "the valid range of the TCA's material silver-coated nylon",
            id="tca-temperature-above",
        ),
        pytest.param(
            lambda: _fig6().solve([25.0, 20.0]),
            "inputs[1] (temperature)",
            "20 C",
            "25 <= T <= 160 C",
            "t_min=<ambient>",
            id="tca-temperature-below",
        ),
        pytest.param(
            lambda: tcarod.Routing.straight(math.inf, 0.0),
            "x",
            "inf m",
            "a finite number",
            "",
            id="routing-offset",
        ),
        pytest.param(
            lambda: tcarod.Section.circle(-12e-3),
            "diameter",
            "-0.012 m",
            "finite and > 0",
            "",
            id="section-diameter",
        ),
        pytest.param(
            lambda: tcarod.Body(0.04, tcarod.Section.circle(12e-3), -5.0),
            "youngs_modulus E_B",
            "-5 Pa",
            "finite and > 0",
            "",
            id="modulus",
        ),
        pytest.param(
            lambda: Tca(0.497, 0.110, 0.0, 300.0),
            "coil_diameter D",
            "0 m",
            "finite and > 0",
            "",
            id="coil-diameter",
        ),
        pytest.param(
            lambda: tcarod.Robot(
                tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3),
                [tcarod.Actuator.tendon(tcarod.Routing.straight(3e-3, 0.0), s_end=60.0)],
            ),
            "actuators[0].s_end",
            "60 m",
            "s_start = 0 m < s_end <= body length 0.04 m",
            "millimetres? lengths are in metres: 60 mm is 0.06 m",
            id="anchor-in-mm",
        ),
        pytest.param(
            lambda: tcarod.Actuator.tendon(tcarod.Routing.straight(3e-3, 0.0), length_ratio=0.0),
            "length_ratio",
            "0",
            "finite and > 0",
            "",
            id="dimensionless",
        ),
    ],
)
def test_every_core_error_reads_name_value_unit_range(
    call: Callable[[], object], name: str, value: str, allowed: str, reason: str
) -> None:
    """``invalid NAME = VALUE UNIT: allowed RANGE (reason)``: the value as a
    person writes it, its unit after it (not in the name), no Rust type or
    function names and no Rust float formatting (``4.000000e0``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tcarod.UnitsWarning)
        with pytest.raises(ValueError) as info:
            call()
    msg = str(info.value)
    assert msg.startswith(f"invalid {name} = {value}"), msg
    assert f"allowed {allowed}" in msg, msg
    assert reason in msg, msg
    assert "::" not in msg and not re.search(r"\de[+-]?0\b|\.0{6}", msg), msg
    assert "[" not in msg.split(" = ")[0].replace("[0]", "").replace("[1]", ""), msg


def test_a_temperature_above_the_range_names_the_material() -> None:
    robot = _robot_12mm()
    with pytest.raises(ValueError) as info:
        robot.solve([170.0])
    msg = str(info.value)
    assert msg.startswith("invalid inputs[0] (temperature) = 170 C: allowed 25 <= T <= 160 C"), msg
    assert "silver-coated nylon" in msg and "lower the temperature" in msg, msg


@pytest.mark.parametrize(
    ("inputs", "shape"),
    [
        (np.array([[170.0], [25.0]]), "(2, 1)"),
        ([[100.0], [25.0]], "(2, 1)"),
        (np.ones((1, 2)), "(1, 2)"),
        (np.ones((2, 2, 1)), "(2, 2, 1)"),
    ],
    ids=["array-2x1", "list-2x1", "array-1x2", "array-3d"],
)
def test_a_two_dimensional_input_names_the_expected_shape(inputs: Any, shape: str) -> None:
    robot = _fig6()
    with pytest.raises(ValueError) as info:
        robot.solve(inputs)
    msg = str(info.value)
    assert msg == f"invalid inputs: expected shape (2,) (one input per actuator), got {shape}", msg
    assert "0-dimensional" not in msg


def test_the_wrong_number_of_inputs_names_the_shape() -> None:
    robot = _fig6()
    with pytest.raises(
        ValueError, match=r"invalid inputs: expected 2 values \(shape \(2,\), one input per actuator\), got 3"
    ):
        robot.solve([50.0, 50.0, 50.0])


def test_an_offset_in_millimetres_warns_and_its_error_asks_about_millimetres() -> None:
    with pytest.warns(tcarod.UnitsWarning, match=r"millimetres\? lengths are in metres: 4 mm is 0\.004 m"):
        routing = tcarod.Routing.straight(4, 0)
    body = tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3)
    with pytest.raises(ValueError) as info:
        tcarod.Robot(body, [tcarod.Actuator.tendon(routing)])
    msg = str(info.value)
    assert "at offset (4 m, 0 m)" in msg, msg
    assert "millimetres? lengths are in metres: 4 mm is 0.004 m" in msg, msg
    assert "e0" not in msg and "Routing::" not in msg and "Rust" not in msg, msg


@pytest.mark.parametrize(
    ("make", "what"),
    [
        (lambda: tcarod.Routing.straight(0.0, 5.0), "offset 5 m"),
        (lambda: tcarod.Routing.helix(1.7, 10.0), "radius 1.7 m"),
        (lambda: tcarod.Actuator.tendon(tcarod.Routing.straight(3e-3, 0.0), 0.0, 60.0), "s_end = 60 m"),
        (lambda: tcarod.Body(60.0, tcarod.Section.circle(12e-3), 37.8e3), "length = 60 m"),
        (lambda: Tca(497.0, 110.0, 2e-3, 300.0), "fibre_length = 497 m"),
        (lambda: Tca.from_pitch_angle(0.04, 0.26, 1.7, 76.4), "coil_diameter = 1.7 m"),
    ],
    ids=["offset", "helix-radius", "anchor", "body-length", "fibre-length", "coil-diameter"],
)
def test_lengths_that_look_like_millimetres_warn(make: Callable[[], object], what: str) -> None:
    with pytest.warns(tcarod.UnitsWarning, match=re.escape(what)):
        make()


def test_metre_sizes_of_a_soft_robot_do_not_warn() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tcarod.Routing.straight(6e-3, -2e-3)
        tcarod.Routing.helix(4e-3, 50.0)
        tcarod.Actuator.tendon(tcarod.Routing.straight(3e-3, 0.0), 0.01, 0.04)
        _robot_12mm()


def test_a_density_without_gravity_warns_once_per_body() -> None:
    with pytest.warns(tcarod.UnitsWarning, match=r"density = 1040 kg/m\^3 but no gravity.*weightless") as record:
        body = tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3, density=1040.0)
    assert len([w for w in record if "weightless" in str(w.message)]) == 1
    # building robots on it and solving them adds no warning: it was said where gravity was left out
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        robot = tcarod.Robot(body, [tcarod.Actuator.tendon(tcarod.Routing.straight(3e-3, 0.0))])
        robot.solve([0.01])
        # an explicit gravity, zero included, says the weight is meant (or not)
        tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3, density=1040.0, gravity=(0.0, 0.0, 0.0))
        tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3, density=1040.0, gravity=(0.0, 0.0, -9.81))
        tcarod.Body(0.04, tcarod.Section.circle(12e-3), 37.8e3)
        body.replace(tip_force=(0.0, 0.0, 0.0))  # replace passes the body's gravity on


def test_a_thermal_model_without_threads_names_the_argument_and_its_unit() -> None:
    from tcarod.models.thermal import ThermalModel

    with pytest.raises(TypeError) as info:
        ThermalModel(fibre_length_m=0.497, resistance=60.0)  # type: ignore[call-arg]
    msg = str(info.value)
    assert "missing 1 required argument: threads" in msg and "[-]" in msg, msg
    assert "positional" not in msg
    with pytest.raises(TypeError, match=r"fibre_length_m: the twisted-fibre length l \[m\].*resistance.*\[ohm\]"):
        ThermalModel(threads=3)  # type: ignore[call-arg]


def test_python_checks_write_the_same_format() -> None:
    """``_validate.real`` (Python) and ``error::Error::param`` (Rust) agree."""
    from tcarod import _validate as V

    with pytest.raises(ValueError) as info:
        V.real("fibre_length_m", 4000.0, lo=1e-4, hi=100.0, unit="m", reason="a physical range")
    assert str(info.value) == (
        "invalid fibre_length_m = 4000 m: allowed in [0.0001, 100] m (a physical range)"
        " (millimetres? lengths are in metres: 4000 mm is 4 m)"
    )
    with pytest.raises(ValueError, match=r"^invalid ratio = 0\.3: allowed <= 0\.2$"):
        V.real("ratio", 0.1 + 0.2, hi=0.2, unit="-")
