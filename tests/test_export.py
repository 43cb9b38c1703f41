"""Shapes out: ``Solution.to_dict`` / ``to_json`` / ``to_csv`` / ``to_vtk`` and
``tcarod.io.write_shape`` (python/tcarod/io/results.py)."""

from __future__ import annotations

import csv
import json
import doctest
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import tcarod
from tcarod import _core
from tcarod.batch import fig6_square_robot
from tcarod.io import results, write_shape
from tcarod.io.design import loads_design
from tcarod._optional import MissingDependencyError

ROBOT = fig6_square_robot()
SOL = ROBOT.solve([60.0, 25.0])  # bends toward one leg: every strain component non-trivial

#: Solution attribute -> key of to_dict().
ARRAYS = {
    "s": "arc_length_m",
    "positions": "positions_m",
    "rotations": "rotations",
    "nu": "nu",
    "omega": "omega_per_m",
    "internal_force": "internal_force_n",
    "internal_moment": "internal_moment_nm",
    "tip_position": "tip_position_m",
    "tip_rotation": "tip_rotation",
    "base_force": "base_force_n",
    "base_moment": "base_moment_nm",
    "inputs": "inputs",
    "tensions": "tensions_n",
    "elongations": "elongations_m",
    "elongation_profile": "elongation_profile_m",
    "continuation_steps": "continuation_steps",
}


def test_json_round_trip_gives_the_solutions_arrays_bit_for_bit() -> None:
    # json writes floats with repr (the shortest text that reads back to the same
    # double), so equality is exact: no tolerance
    doc = json.loads(SOL.to_json())
    for attr, key in ARRAYS.items():
        got = np.array(doc[key], dtype=float)
        want = np.asarray(getattr(SOL, attr))
        assert got.shape == want.shape, key
        assert np.array_equal(got, want), key
    for got, want in zip(doc["actuator_paths_m"], SOL.actuator_paths):
        assert np.array_equal(np.array(got), want)
    assert len(doc["actuator_paths_m"]) == len(SOL.actuator_paths) == 2


def test_to_dict_is_the_json_document_and_solution_json() -> None:
    doc = SOL.to_dict()
    assert json.loads(SOL.to_json()) == doc
    assert results.solution_json(SOL) == doc
    assert doc["nodes"] == len(SOL.s) == SOL.steps + 1
    assert doc["format"] == results.SOLUTION_FORMAT
    assert doc["tcarod_version"] == tcarod.__version__
    assert (doc["iterations"], doc["evaluations"], doc["steps"]) == (SOL.iterations, SOL.evaluations, SOL.steps)
    assert doc["residual"] == SOL.residual and doc["floor"] == SOL.floor
    assert doc["status"] == SOL.status and doc["message"] == SOL.message


def test_every_key_is_documented_with_its_shape_or_unit() -> None:
    documented = set(re.findall(r"^``(\w+)`` {2,}", results.__doc__ or "", re.M))
    assert set(SOL.to_dict()) == documented


def test_inputs_carry_their_units() -> None:
    doc = SOL.to_dict()
    assert doc["input_names"] == ["temperature", "temperature"]
    assert doc["input_units"] == ["C", "C"]
    tendon = loads_design(
        """
[body]
length_m = 0.05
section = { kind = "circle", diameter_m = 0.01 }
youngs_modulus_pa = 1e6
[[actuators]]
routing = { kind = "straight", x_m = 0.003, y_m = 0.0 }
tendon = { kind = "tension" }
"""
    ).robot.solve([0.01])
    assert tendon.to_dict()["input_units"] == ["N"]
    assert tendon.to_dict()["input_names"] == ["tension"]


def test_stability_is_included_when_known_computed_on_request_or_left_out() -> None:
    known = SOL.to_dict()
    assert known["stable"] is True and known["stability_margin"] == SOL.stability_margin > 0
    cold = ROBOT.solve([60.0, 25.0], stability="off")
    assert cold._verdict is None
    assert cold.to_dict()["stable"] is None and cold.to_dict()["stability_margin"] is None
    assert cold._verdict is None  # to_dict() with the default computes nothing
    asked = cold.to_dict(stability=True)
    assert asked["stable"] is True and asked["stability_margin"] == SOL.stability_margin
    assert SOL.to_dict(stability=False)["stable"] is None
    with pytest.raises(TypeError):
        SOL.to_dict(stability="yes")  # type: ignore[arg-type]


def test_json_indent_and_file(tmp_path: Path) -> None:
    one_line = SOL.to_json(indent=None)
    assert "\n" not in one_line and json.loads(one_line) == SOL.to_dict()
    path = tmp_path / "deep" / "finger.json"
    text = SOL.to_json(path)
    assert json.loads(path.read_text(encoding="utf-8")) == json.loads(text)
    with pytest.raises(ValueError, match="indent"):
        SOL.to_json(indent=-1)


CSV_HEAD = (
    ["s_m", "x_m", "y_m", "z_m"]
    + [f"r{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
    + ["nu_1", "nu_2", "nu_3", "omega_1_per_m", "omega_2_per_m", "omega_3_per_m"]
    + ["force_x_n", "force_y_n", "force_z_n", "moment_x_nm", "moment_y_nm", "moment_z_nm"]
    + ["elongation_0_m", "elongation_1_m"]
)


def test_csv_has_one_row_per_node_and_columns_named_with_units(tmp_path: Path) -> None:
    path = tmp_path / "finger.csv"
    text = SOL.to_csv(path)
    assert path.read_text(encoding="utf-8") == text
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    assert rows[0] == CSV_HEAD
    assert len(rows) - 1 == len(SOL.s)
    # every column is a unit-suffixed quantity or a dimensionless one (rotation, nu)
    assert all(re.search(r"_(m|n|nm|per_m)$", c) or re.fullmatch(r"r\d\d|nu_\d", c) for c in rows[0])
    table = np.array(rows[1:], dtype=float)
    n = len(SOL.s)
    # numbers written with repr read back to the same doubles: exact
    assert np.array_equal(table[:, 0], SOL.s)
    assert np.array_equal(table[:, 1:4], SOL.positions)
    assert np.array_equal(table[:, 4:13], SOL.rotations.reshape(n, 9))
    assert np.array_equal(table[:, 13:16], SOL.nu)
    assert np.array_equal(table[:, 16:19], SOL.omega)
    assert np.array_equal(table[:, 19:22], SOL.internal_force)
    assert np.array_equal(table[:, 22:25], SOL.internal_moment)
    assert np.array_equal(table[:, 25:], SOL.elongation_profile)


@pytest.mark.parametrize("suffix", [".vtu", ".vtk"])
def test_vtk_reads_back_with_meshio(tmp_path: Path, suffix: str) -> None:
    meshio = pytest.importorskip("meshio", reason="meshio (the `export` extra) is not installed")
    path = SOL.to_vtk(tmp_path / f"finger{suffix}")
    assert path == tmp_path / f"finger{suffix}"
    mesh = meshio.read(path)
    n = len(SOL.s)
    # binary float64 in both formats: the values come back exactly
    assert np.array_equal(mesh.points, SOL.positions)
    (block,) = mesh.cells
    assert block.type == "line" and block.data.tolist() == [[k, k + 1] for k in range(n - 1)]
    pd = mesh.point_data
    assert np.array_equal(pd["arc_length_m"].ravel(), SOL.s)
    assert np.array_equal(pd["d3"], SOL.rotations[:, :, 2])
    assert np.array_equal(pd["nu"], SOL.nu)
    assert np.array_equal(pd["internal_moment_nm"], SOL.internal_moment)
    assert np.array_equal(np.column_stack([pd["elongation_0_m"], pd["elongation_1_m"]]), SOL.elongation_profile)
    assert "elongation_2_m" not in pd


def test_vtk_without_meshio_names_the_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    for name in [m for m in sys.modules if m == "meshio" or m.startswith("meshio.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "meshio", None)  # import meshio -> ImportError
    with pytest.raises(MissingDependencyError, match=re.escape("pip install 'tcarod[export]'")) as info:
        SOL.to_vtk(tmp_path / "finger.vtu")
    assert isinstance(info.value, ImportError)
    assert not (tmp_path / "finger.vtu").exists()


@pytest.mark.parametrize("suffix", [".json", ".csv", ".vtu", ".vtk"])
def test_write_shape_picks_the_format_by_suffix(tmp_path: Path, suffix: str) -> None:
    if suffix in (".vtu", ".vtk"):
        pytest.importorskip("meshio", reason="meshio (the `export` extra) is not installed")
    path = write_shape(SOL, tmp_path / f"finger{suffix.upper()}")  # suffixes in any case
    data = path.read_bytes()
    if suffix == ".json":
        assert json.loads(data) == SOL.to_dict()
    elif suffix == ".csv":
        assert data.decode() == SOL.to_csv()
    elif suffix == ".vtu":
        assert data.startswith(b"<?xml") and b"UnstructuredGrid" in data
    else:
        assert data.startswith(b"# vtk DataFile")


def test_write_shape_rejects_unknown_suffixes_and_non_paths(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"path: suffix '\.txt'"):
        write_shape(SOL, tmp_path / "finger.txt")
    with pytest.raises(TypeError, match="path"):
        write_shape(SOL, 3)
    with pytest.raises(ValueError, match=r"\.vtu or \.vtk"):
        results.write_vtk(SOL, tmp_path / "finger.csv")


def test_no_exporter_without_the_package_is_a_clear_error() -> None:
    # the package registered the exporter at import: the bindings hold it
    assert SOL.to_dict() == results.export("to_dict", SOL)
    with pytest.raises(TypeError, match="callable"):
        _core._register_exporter(42)


def test_the_export_page_examples_run() -> None:
    # the >>> blocks of docs/export.md, as a reader would type them
    page = Path(__file__).resolve().parents[1] / "docs" / "export.md"
    blocks = re.findall(r"```python\n(>>>.*?)```", page.read_text(encoding="utf-8"), re.S)
    assert blocks
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
    for i, block in enumerate(blocks):
        runner.run(doctest.DocTestParser().get_doctest(block, {}, f"export.md:{i}", str(page), 0))
    assert runner.failures == 0, "docs/export.md doctest failed (output above)"
