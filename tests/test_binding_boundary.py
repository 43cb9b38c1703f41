"""Bad input at the binding boundary: every index and size that comes from
Python is validated before the core sees it, and geometry that cannot be
built (routings outside the section, TCAs longer than their span,
millimetres passed as metres) is refused or warned about. The TCA law's own
bad-input contract is tests/test_bad_input.py."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import tcarod
from tcarod import (
    Actuator,
    Material,
    Body,
    Robot,
    Routing,
    Section,
    Tca,
    blocked_force,
    blocked_temperature,
    tip_position,
)
from tcarod import _core
from tcarod.batch import fig6_square_robot, solve_batch

NAN, INF = math.nan, math.inf

# ------------------------------------------------------------ binding boundary
#
# Rod, inverse and batch bindings: every index and size from Python is
# validated before the core sees it. ValueError names the argument and the
# allowed range; TypeError for bytes, str, complex (incl. NumPy complex),
# None and objects of the wrong class; never PanicException, OverflowError,
# MemoryError or a hang.


SQUARE = fig6_square_robot()
SQUARE_NG = fig6_square_robot(gravity=False)


class _LyingLength:
    """A sequence claiming 2**62 items: trusting ``__len__`` to size a buffer
    would panic with ``capacity overflow``."""

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
        _core.tip_position(SQUARE, [0.0, 0.0])


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
        _core.tip_position(SQUARE, [0.0, 0.0, 0.04], groups=groups)


@pytest.mark.parametrize("bad", [[0.5, 0.5], ["0", "0"], [None, 0], b"\x00\x00"])
def test_groups_of_the_wrong_type_are_type_errors(bad: object) -> None:
    with pytest.raises(TypeError, match="groups"):
        _core.tip_position(SQUARE, [0.0, 0.0, 0.04], groups=bad)


def test_blocked_temperature_with_a_solution_of_a_different_robot() -> None:
    # a start Solution of another robot (other unknowns): a ValueError naming
    # `start`, never a PanicException from the core
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


# ------------------------------------------------------------ geometric sanity


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
