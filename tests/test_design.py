"""Robot design files (TOML): load, save, round trip, errors with key and line,
and the ``tcarod solve`` command."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tcarod.cli import main
from tcarod.io.design import DesignError, dumps_design, load_design, loads_design, save_design
from tcarod.paper.fig1b import FIG1B

ROOT = Path(__file__).resolve().parent.parent
DESIGNS = ROOT / "examples" / "designs"


@pytest.mark.parametrize("name", ["fig6_square.toml", "fig1b_three_tca.toml"])
def test_example_designs_load_and_solve(name: str) -> None:
    d = load_design(DESIGNS / name)
    assert d.temperatures_c is not None
    sol = d.solve()
    # converged: the default tolerance is 1e-10 (scaled residual)
    assert sol.residual < 1e-9
    # every example bends away from its heated +x TCA(s)
    assert sol.tip_position[0] < -1e-3


def test_fig1b_design_file_is_the_fixture() -> None:
    d = load_design(DESIGNS / "fig1b_three_tca.toml")
    temps = [120.0, 60.0, 25.0]
    a = d.solve(temps).tip_position
    b = FIG1B.robot().solve(temps).tip_position
    # the file's turns (114.6) and offsets are the fixture's to ~1e-15
    # relative; the shapes agree to far below a micrometre
    assert np.allclose(a, b, atol=1e-9)


@pytest.mark.parametrize("name", ["fig6_square.toml", "fig1b_three_tca.toml"])
def test_round_trip_gives_the_same_solution(name: str, tmp_path: Path) -> None:
    d = load_design(DESIGNS / name)
    path = save_design(tmp_path / "copy.toml", d.robot, d.temperatures_c)
    d2 = load_design(path)
    assert d2.temperatures_c == d.temperatures_c
    s1, s2 = d.solve(), d2.solve()
    # floats are written with repr (exact), geometry recovered from section
    # properties by one sqrt (1 ulp): identical to rounding
    assert np.allclose(s1.positions, s2.positions, rtol=0.0, atol=1e-12)
    # and saving again gives the same text
    assert dumps_design(d2.robot, d2.temperatures_c) == path.read_text(encoding="utf-8")


def test_round_trip_of_custom_material_helix_and_segments(tmp_path: Path) -> None:
    from tcarod import Actuator, Body, Material, Robot, Routing, Section, Tca

    mat = Material(youngs_modulus=1.5e9, shear_modulus=3e8, expansion=2e-4, youngs_modulus_slope=-1e6, name="mine")
    tca = Tca.from_pitch_angle(0.02, 0.25, 1.7e-3, 40.0, "extension", mat)
    body = Body(
        0.05,
        Section.custom(1e-4, 8e-10, 9e-10, 1.5e-9),
        40e3,
        poisson=0.45,
        density=1000.0,
        gravity=(0.0, 0.0, 0.0),
        tip_force=[0.0, 1e-3, 0.0],
    )
    acts = [
        Actuator.tca(tca, Routing.helix(3e-3, 20.0, 0.3), 0.01, 0.03),
        Actuator.tca(tca, Routing.straight(-3e-3, 0.0), 0.03),
    ]
    robot = Robot(body, acts)
    path = save_design(tmp_path / "r.toml", robot)
    d = load_design(path)
    temps = [90.0, 60.0]
    a, b = robot.solve(temps), d.solve(temps)
    # helix rate and phase come back through atan2/sin/cos: ~1e-16 relative
    assert np.allclose(a.positions, b.positions, rtol=0.0, atol=1e-12)


def test_syntax_error_names_the_line() -> None:
    text = '[body]\nlength_m = 0.04\nsection = { kind = "circle", diameter_m = }\n'
    with pytest.raises(DesignError) as e:
        loads_design(text, "bad.toml")
    assert e.value.line == 3
    assert "bad.toml:3" in str(e.value)


def _fig6_text() -> str:
    return (DESIGNS / "fig6_square.toml").read_text(encoding="utf-8")


@pytest.mark.parametrize(
    ("old", "new", "key", "line_text"),
    [
        (
            'turns = 38.2\nchirality = "extension"\nmaterial = "silver_coated_nylon"\n\n[[actuators]]',
            'turns = -38.2\nchirality = "extension"\nmaterial = "silver_coated_nylon"\n\n[[actuators]]',
            "actuators[0].tca.turns",
            "turns = -38.2",
        ),
        (
            "youngs_modulus_pa = 37.8e3",
            'youngs_modulus_pa = "soft"',
            "body.youngs_modulus_pa",
            'youngs_modulus_pa = "soft"',
        ),
        ("x_m = 0.003, y_m = -0.0025", "x_m = 0.003, z_m = -0.0025", "actuators[1].routing.z_m", "z_m = -0.0025"),
        (
            "temperatures_c = [100.0, 100.0]",
            "temperatures_c = [100.0, 200.0]",
            "temperatures_c",
            "temperatures_c = [100.0, 200.0]",
        ),
        ("density_kg_per_m3 = 1040.0", "densty_kg_per_m3 = 1040.0", "body.densty_kg_per_m3", "densty_kg_per_m3"),
    ],
    ids=["negative-turns", "string-modulus", "unknown-routing-key", "temperature-range", "typo"],
)
def test_semantic_errors_name_the_key_and_its_line(old: str, new: str, key: str, line_text: str) -> None:
    text = _fig6_text()
    assert text.count(old) == 1
    bad = text.replace(old, new)
    with pytest.raises(DesignError) as e:
        loads_design(bad, "d.toml")
    assert e.value.key == key
    assert e.value.line is not None
    assert line_text in bad.splitlines()[e.value.line - 1]
    assert f"d.toml:{e.value.line}: {key}:" in str(e.value)


def test_missing_key_points_at_its_table() -> None:
    bad = _fig6_text().replace("coil_diameter_m = 1.7e-3\n", "", 1)
    with pytest.raises(DesignError, match="coil_diameter_m: missing") as e:
        loads_design(bad, "d.toml")
    assert e.value.line is not None and bad.splitlines()[e.value.line - 1].strip() == "[actuators.tca]"


def test_cli_solve_prints_pose_and_writes_plot(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc = main(["solve", str(DESIGNS / "fig6_square.toml"), "--temperature", "120", "--out", str(tmp_path), "--json"])
    assert rc == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["temperature_c"] == [120.0, 120.0]
    assert len(doc["tip_position_m"]) == 3 and doc["tip_position_m"][0] < 0.0
    assert Path(doc["png_path"]).stat().st_size > 1000
    rc = main(["solve", str(DESIGNS / "fig6_square.toml"), "--out", str(tmp_path)])
    assert rc == 0
    assert "tip position [mm]" in capsys.readouterr().out


def test_cli_solve_reports_bad_files(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(_fig6_text().replace("turns = 38.2", "turns = 0", 1), encoding="utf-8")
    assert main(["solve", str(bad), "-T", "100"]) == 2
    err = capsys.readouterr().err
    assert "actuators[0].tca.turns" in err and "bad.toml:" in err
    assert main(["solve", str(DESIGNS / "fig6_square.toml"), "-T", "100", "90", "80"]) == 2


# ---------------------------------------------------------------------- limits
# Hostile files fail as DesignError (a ValueError) naming the line, in bounded
# time and memory.

FIG6_TEXT = (DESIGNS / "fig6_square.toml").read_text(encoding="utf-8")


def test_design_error_is_a_value_error() -> None:
    assert issubclass(DesignError, ValueError)


@pytest.mark.parametrize(
    "text",
    [
        "[body]\nlength_m = " + "[" * 1000 + "]" * 1000,  # tomllib alone raises RecursionError
        "[body]\nlength_m = " + "{a=" * 1000 + "1" + "}" * 1000,
    ],
)
def test_deep_nesting_is_a_design_error_naming_the_line(text: str) -> None:
    with pytest.raises(DesignError, match="nested deeper") as err:
        loads_design(text, "deep.toml")
    assert err.value.line == 2 and err.value.source == "deep.toml"


def test_long_dotted_header_is_a_design_error() -> None:
    # a 100k-part dotted header is located in linear time (a naive search takes tens of seconds)
    with pytest.raises(DesignError, match="dotted key") as err:
        loads_design("[" + ".".join(["a"] * 100_000) + "]\nx = 1\n")
    assert err.value.line == 1


def test_long_blank_run_error_names_its_line() -> None:
    # a 100k-character blank run: the line lookup stays linear (a naive one is quadratic)
    with pytest.raises(DesignError) as err:
        loads_design(FIG6_TEXT.replace("youngs_modulus_pa = 37.8e3", "youngs_modulus_pa =" + " " * 100_000 + "x"))
    assert err.value.line == 10


def test_too_large_file_is_a_design_error(tmp_path: Path) -> None:
    from tcarod.io.design import MAX_DESIGN_CHARS

    with pytest.raises(DesignError, match="too large"):
        loads_design("#" * (MAX_DESIGN_CHARS + 1))
    big = tmp_path / "big.toml"
    big.write_bytes(b"#" * (4 * MAX_DESIGN_CHARS + 1))
    with pytest.raises(DesignError, match="too large"):
        load_design(big)


def test_huge_integer_and_binary_file_are_design_errors(tmp_path: Path) -> None:
    with pytest.raises(DesignError, match="length_m: must be finite"):
        loads_design(FIG6_TEXT.replace("length_m = 0.040", "length_m = " + "9" * 400))
    raw = tmp_path / "raw.toml"
    raw.write_bytes(b"\xff\xfe[body]")
    with pytest.raises(DesignError, match="not UTF-8"):
        load_design(raw)


def test_wrong_argument_types_are_type_errors() -> None:
    with pytest.raises(TypeError, match="text"):
        loads_design(b"[body]")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="path"):
        load_design(None)  # type: ignore[arg-type]


# ------------------------------------------------------------------ round trip


def test_saved_file_is_written_the_way_it_was_written() -> None:
    text = dumps_design(load_design(DESIGNS / "fig6_square.toml").robot)
    # pitch-angle TCAs stay pitch-angle TCAs, poisson stays poisson, no rounding noise
    assert "alpha0_deg = 15.0" in text and "fibre_length_m" not in text
    assert "poisson = 0.5" in text and "shear_modulus_pa" not in text
    assert "y_m = -0.0025\n" in text and "width_m = 0.01\n" in text
    assert "99999" not in text and "00000000" not in text


def test_tendon_designs_round_trip() -> None:
    from tcarod import Actuator, Routing

    base = load_design(DESIGNS / "fig6_square.toml").robot
    robot = type(base)(
        base.body,
        [
            base.actuators[0],
            Actuator.tendon(Routing.helix(0.004, 10.0, 0.3), 0.0, 0.03),
            Actuator.linear_tendon(120.0, Routing.straight(-0.003, 0.0)),
        ],
    )
    text = dumps_design(robot)
    again = loads_design(text).robot
    assert [a.kind for a in again.actuators] == ["tca", "tension", "linear_tendon"]
    assert dumps_design(again) == text  # a fixed point: nothing drifts
    inputs = [80.0, 0.02, 0.001]  # C, N, m
    a, b = robot.solve(inputs), again.solve(inputs)
    # same design, same solver: identical to rounding of the saved decimals
    assert np.allclose(a.tip_position, b.tip_position, rtol=0.0, atol=1e-12)


def test_fibre_length_tca_is_saved_by_fibre_length() -> None:
    from tcarod import Robot, Tca

    base = load_design(DESIGNS / "fig6_square.toml").robot
    act = base.actuators[0]
    tca = Tca(0.180, 0.040, 1.7e-3, 76.4)  # alpha0 = asin(L/l) = 12.84 deg: not a round number
    from tcarod import Actuator

    robot = Robot(base.body, [Actuator.tca(tca, act.routing)])
    text = dumps_design(robot)
    assert "fibre_length_m = 0.18" in text and "alpha0_deg" not in text
