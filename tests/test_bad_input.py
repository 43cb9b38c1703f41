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


# ------------------------------------------------- issue 12: binding boundary
#
# Rod, inverse and batch bindings: every index and size from Python is
# validated before the core sees it. ValueError names the argument and the
# allowed range; TypeError for bytes, str, complex (incl. NumPy complex),
# None and objects of the wrong class; never PanicException, OverflowError,
# MemoryError or a hang.


from tcarod import (  # noqa: E402
    Actuator,
    Body,
    Robot,
    Routing,
    Section,
    blocked_force,
    blocked_temperature,
    tip_position,
)
from tcarod import _core  # noqa: E402
from tcarod.batch import fig6_square_robot, solve_batch  # noqa: E402

SQUARE = fig6_square_robot()
SQUARE_NG = fig6_square_robot(gravity=False)


class _LyingLength:
    """A sequence claiming 2**62 items (once a `capacity overflow` panic)."""

    def __len__(self) -> int:
        return 2**62

    def __getitem__(self, k: int) -> float:
        if k < 3:
            return 25.0
        raise IndexError(k)


@pytest.mark.parametrize(
    "bad",
    [
        b"ab",
        bytearray(b"ab"),
        "ab",
        None,
        1j,
        np.complex128(25.0),
        [25.0, 1j],
        [25.0, np.complex64(25.0)],
        [25.0, "25"],
        [25.0, None],
        object(),
    ],
)
def test_solve_inputs_of_the_wrong_type_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError):
        SQUARE.solve(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize("name", ["steps", "max_iter"])
@pytest.mark.parametrize("bad", [-1, 0, 10**30, -(10**30), 100_001])
def test_solve_counts_out_of_range_name_the_argument_and_range(name: str, bad: int) -> None:
    with pytest.raises(ValueError, match=rf"{name} = .*allowed 1 <= {name} <= 100000"):
        SQUARE.solve([30.0, 30.0], **{name: bad})  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", [3.5, "3", b"3", None.__class__, 1j, True])
def test_solve_counts_of_the_wrong_type_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match="steps"):
        SQUARE.solve([30.0, 30.0], steps=bad)  # type: ignore[arg-type]


def test_wrong_length_vectors_name_the_argument() -> None:
    with pytest.raises(ValueError, match="tip_force: expected 3 values, got 2"):
        Body(0.04, Section.circle(0.01), 1e5, tip_force=[0.0, 0.0])
    with pytest.raises(TypeError, match="gravity"):
        Body(0.04, Section.circle(0.01), 1e5, gravity=b"abc")
    with pytest.raises(ValueError, match=r"inputs.*expected 2 values"):
        SQUARE.solve([30.0])
    with pytest.raises(ValueError, match=r"start: expected 1 values, got 2"):
        tip_position(SQUARE, [0.0, 0.0, 0.04], start=[30.0, 30.0], groups=[0, 0])
    with pytest.raises(ValueError, match="target"):
        _core.tip_inverse(SQUARE, [0.0, 0.0])


def test_a_lying_len_never_panics() -> None:
    with pytest.raises(ValueError, match="inputs"):
        SQUARE.solve(_LyingLength())  # 3 items for 2 actuators
    # the items are read one by one, whatever __len__ says: 3 items, a valid force
    body = Body(0.04, Section.circle(0.01), 1e5, tip_force=_LyingLength())
    assert body.tip_force.tolist() == [25.0, 25.0, 25.0]


@pytest.mark.parametrize("groups", [[0, -1], [0, 10**20], [0, 2], [0], [0, 0, 0]])
def test_bad_groups_are_value_errors_naming_groups(groups: list[int]) -> None:
    with pytest.raises(ValueError, match="groups"):
        tip_position(SQUARE, [0.0, 0.0, 0.04], groups=groups)
    with pytest.raises(ValueError, match="groups"):
        _core.tip_inverse(SQUARE, [0.0, 0.0, 0.04], groups=groups)


@pytest.mark.parametrize("bad", [[0.5, 0.5], ["0", "0"], [None, 0], b"\x00\x00"])
def test_groups_of_the_wrong_type_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match="groups"):
        _core.tip_inverse(SQUARE, [0.0, 0.0, 0.04], groups=bad)


def test_blocked_temperature_with_a_solution_of_a_different_robot() -> None:
    # issue 12's shortest PanicException reproducer
    other = Robot(SQUARE_NG.body, [Actuator.tendon(Routing.straight(0.003, 0.0))]).solve([0.01])
    tip = SQUARE_NG.solve([25.0, 25.0]).tip_position
    with pytest.raises(ValueError, match="start: a Solution of a different robot"):
        blocked_temperature(SQUARE_NG, tip, [-1, 0, 0], 1e-3, other, groups=[0, 0])


@pytest.mark.parametrize("bad", [0, -1, 10**30, 10_001])
def test_increments_out_of_range(bad: int) -> None:
    start = SQUARE_NG.solve([25.0, 25.0])
    with pytest.raises(ValueError, match=r"increments = .*allowed 1 <= increments <= 10000"):
        blocked_temperature(SQUARE_NG, start.tip_position, [-1, 0, 0], 1e-3, start, groups=[0, 0], increments=bad)


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"chunk_size": 0}, "chunk_size"),
        ({"chunk_size": -5}, "chunk_size"),
        ({"chunk_size": 10**40}, "chunk_size"),
        ({"threads": -1}, "threads"),
        ({"threads": 10**6}, "threads"),
        ({"steps": 10**9}, "steps"),
        ({"max_iter": -(2**70)}, "max_iter"),
    ],
)
def test_batch_counts_out_of_range(kw: dict[str, int], match: str) -> None:
    q = np.array([[30.0, 30.0]])
    with pytest.raises(ValueError, match=match):
        _core.solve_batch(SQUARE, q, **kw)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=match):
        solve_batch(SQUARE, q, **kw)  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", [[["30", "30"]], [[30.0, 1j]], np.array([[30.0, 30.0]], dtype=complex), b"ab"])
def test_batch_inputs_of_the_wrong_type_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match="inputs"):
        solve_batch(SQUARE, bad)


def test_wrong_classes_are_type_errors() -> None:
    with pytest.raises(TypeError, match=r"actuators\[0\]"):
        Robot(SQUARE.body, [1])  # type: ignore[list-item]
    with pytest.raises(TypeError):
        Robot(SQUARE.body, 5)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        blocked_force(SQUARE.body, [0, 0, 0.04], [-1, 0, 0], 60.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        SQUARE.solve([30.0, 30.0], warm_start=SQUARE)  # type: ignore[arg-type]


# ---------------------------------------------------- issue 14: geometric sanity


def test_routing_outside_the_section_is_a_value_error() -> None:
    body = Body(0.04, Section.circle(0.014), 1e5)
    tca = SQUARE.actuators[0].tca_model
    assert tca is not None
    with pytest.raises(ValueError, match=r"actuators\[0\]\.routing.*outside the section"):
        Robot(body, [Actuator.tca(tca, Routing.straight(0.020, 0.0))])
    with pytest.raises(ValueError, match=r"actuators\[1\]\.routing"):
        Robot(body, [Actuator.tendon(Routing.straight(0.005, 0.0)), Actuator.tendon(Routing.helix(0.0071, 10.0))])


def test_a_tca_longer_than_its_span_is_a_value_error() -> None:
    body = Body(0.030, Section.circle(0.014), 1e5)
    tca70 = Tca.from_pitch_angle(0.070, math.radians(15.0), 1.7e-3, 76.4)
    with pytest.raises(ValueError, match=r"actuators\[0\]\.tca.*coiled_length 0.07 m exceeds its anchored span"):
        Robot(body, [Actuator.tca(tca70, Routing.straight(0.003, 0.0))])


def test_sizes_that_look_like_millimetres_warn() -> None:
    with pytest.warns(tcarod.UnitsWarning, match="millimetres"):
        Body(40.0, Section.rectangle(10.0, 10.0), 37.8e3)
    with pytest.warns(tcarod.UnitsWarning, match="coil_diameter"):
        Tca(0.497, 0.110, 1.7, 300.0)
    assert issubclass(tcarod.UnitsWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Body(0.04, Section.rectangle(0.01, 0.01), 37.8e3)  # metres: silent


def test_ambient_below_the_preset_range_points_to_a_custom_material() -> None:
    with pytest.raises(
        ValueError, match=r"inputs\[0\].*25 <= T <= 160.*Material\(\.\.\., t_ref=<ambient>, t_min=<ambient>\)"
    ):
        SQUARE.solve([20.0, 20.0])
    cold = Material(youngs_modulus=1.2e9, shear_modulus=2.2e8, expansion=1.1e-4, t_ref=20.0, t_min=20.0, t_max=160.0)
    tca = Tca.from_pitch_angle(0.04, math.radians(15.0), 1.7e-3, 76.4, material=cold)
    robot = Robot(SQUARE.body, [Actuator.tca(tca, Routing.straight(0.003, 0.0))])
    assert robot.reference_inputs == [20.0]
    assert robot.solve([20.0]).success
