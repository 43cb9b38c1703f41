"""The command line, ``tcarod reproduce``: run as a user would, in a subprocess."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

import tcarod
from tcarod import cli
from tcarod.paper import REGISTRY, ExperimentResult
from tcarod.paper.fig5 import FIG5

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "tcarod.cli", *args],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_reproduce_fig5_json(tmp_path: Path) -> None:
    out = tmp_path / "pngs"
    proc = run("reproduce", "fig5", "--json", "--out", str(out), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)  # stdout is JSON and nothing else
    assert doc["tcarod_version"] == tcarod.__version__
    assert list(doc["experiments"]) == ["fig5"]
    fig5 = doc["experiments"]["fig5"]
    assert fig5["temperature_c"] == list(FIG5.temperatures_c)
    assert fig5["published_data"] is None
    assert fig5["gravity_m_per_s2"] == 9.81
    assert len(fig5["cases"]) == 4
    for case in fig5["cases"]:
        for key in (
            "label",
            "threads",
            "fibre_length_m",
            "coiled_length_m",
            "coil_diameter_m",
            "turns",
            "mass_kg",
            "friction_equivalent_kg",
            "force_per_half_n",
            "displacement_m",
            "onset_temperature_c",
            "final_temperature_c",
            "displacement_at_final_temperature_m",
            "straight_fibre_limit_m",
        ):
            assert key in case, key
        assert len(case["displacement_m"]) == len(fig5["temperature_c"])
        assert 25.0 < case["onset_temperature_c"] < 160.0
        assert 0.0 < case["displacement_at_final_temperature_m"] < case["straight_fibre_limit_m"]
    png = Path(fig5["png_path"])
    assert png == out / "fig5.png"
    data = png.read_bytes()
    assert data.startswith(PNG_MAGIC) and len(data) > 10_000  # a real plot, not an empty canvas


def test_reproduce_all_prints_table_and_writes_default_png(tmp_path: Path) -> None:
    # Under `make test` the run happens in $TCAROD_TEST_ARTIFACTS/reproduce,
    # whose figures and tables the docs build of the same run then shows
    # (docs/_hooks.py) instead of running every experiment again.
    artifacts = os.environ.get("TCAROD_TEST_ARTIFACTS")
    cwd = Path(artifacts) / "reproduce" if artifacts else tmp_path
    cwd.mkdir(parents=True, exist_ok=True)
    proc = run("reproduce", cwd=cwd)  # no name: every registered experiment
    assert proc.returncode == 0, proc.stderr
    assert "onset temperature [C]" in proc.stdout
    assert "displacement at 160 C [mm]" in proc.stdout
    for c in FIG5.predict().curves:
        assert f"{c.onset_temperature_c:.1f}" in proc.stdout
    for name in REGISTRY:
        png = cwd / "tcarod-output" / f"{name}.png"
        assert png.read_bytes().startswith(PNG_MAGIC)
        table = (cwd / "tcarod-output" / f"{name}.txt").read_text(encoding="utf-8")
        assert table.strip() and table.strip() in proc.stdout  # the printed table, as a file


def test_version(tmp_path: Path) -> None:
    proc = run("--version", cwd=tmp_path)
    assert proc.returncode == 0
    assert proc.stdout.strip() == f"tcarod {tcarod.__version__}"


def test_console_script_is_installed(tmp_path: Path) -> None:
    # pyproject declares `tcarod = "tcarod.cli:main"`; pip writes it into the
    # install scheme's scripts directory (beside python in a venv or pyenv,
    # /usr/local/bin for a Debian system python).
    candidates = [Path(sysconfig.get_path("scripts")) / "tcarod", Path(sys.executable).parent / "tcarod"]
    found = [c for c in candidates if c.exists()]
    assert found, f"none of {candidates} exists: is the package installed (pip install -e .)?"
    proc = subprocess.run([str(found[0]), "--version"], capture_output=True, text=True, timeout=60, check=False)
    assert proc.returncode == 0 and tcarod.__version__ in proc.stdout


@pytest.mark.parametrize(
    "args",
    [
        [],  # no command
        ["reproduce", "fig99"],  # unknown experiment
        ["reproduce", "--bogus"],
        ["frobnicate"],
        ["reproduce", "fig5", "--out"],  # option without its value
    ],
    ids=["no-command", "unknown-experiment", "unknown-option", "unknown-command", "missing-value"],
)
def test_bad_arguments_exit_2(tmp_path: Path, args: list[str]) -> None:
    proc = run(*args, cwd=tmp_path)
    assert proc.returncode == 2
    assert proc.stderr.strip()
    assert "Traceback" not in proc.stderr
    assert proc.stdout == ""


def test_unwritable_output_exits_2_with_one_line(tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    proc = run("reproduce", "fig5", "--out", str(blocker / "sub"), cwd=tmp_path)
    assert proc.returncode == 2
    assert len(proc.stderr.strip().splitlines()) == 1
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize(
    "exc",
    [
        ValueError("invalid temperature = 200 C:\n allowed 25 <= T <= 160 C"),
        tcarod.ConvergenceError("did not converge"),
    ],
    ids=["ValueError", "ConvergenceError"],
)
def test_model_errors_exit_2_with_one_line(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path, exc: Exception
) -> None:
    def failing() -> ExperimentResult:
        raise exc

    monkeypatch.setitem(REGISTRY, "broken", failing)
    status = cli.main(["reproduce", "broken", "--out", str(tmp_path)])
    captured = capsys.readouterr()
    assert status == 2
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and type(exc).__name__ in lines[0]
    assert captured.out == ""


# ---------------------------------------------------------------- tcarod solve: several designs

DESIGNS = Path(__file__).resolve().parent.parent / "examples" / "designs"
TWO = [str(DESIGNS / "fig6_square.toml"), str(DESIGNS / "fig1b_three_tca.toml")]


def test_solve_accepts_several_designs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["solve", *TWO, "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [Path(d["design"]).name for d in doc["designs"]] == ["fig6_square.toml", "fig1b_three_tca.toml"]
    assert len(doc["designs"][1]["tensions_n"]) == 3  # the 3-TCA design has three actuators
    assert (tmp_path / "fig6_square.png").read_bytes()[:8] == PNG_MAGIC
    assert (tmp_path / "fig1b_three_tca.png").read_bytes()[:8] == PNG_MAGIC


def test_missing_optional_package_is_one_line_naming_the_extra(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib -> ImportError
    assert cli.main(["solve", TWO[0], "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "tcarod[plot]" in err and "Traceback" not in err


def test_closed_pipe_ends_quietly(tmp_path: Path) -> None:
    # `tcarod ... --json | head`: the reader goes away before the output is written
    proc = subprocess.Popen(
        [sys.executable, "-m", "tcarod.cli", "solve", *TWO, *TWO, "--out", str(tmp_path), "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        cwd=tmp_path,
    )
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()
    err = proc.stderr.read().decode()
    proc.stderr.close()
    assert proc.wait(timeout=120) == 1
    assert "BrokenPipeError" not in err and "Traceback" not in err


# ---------------------------------------------------------------- tcarod solve: shapes and stability

FIG6 = TWO[0]


def _tall_finger(tmp_path: Path) -> Path:
    """The Fig. 6 square stretched to 90 mm at 25 C: Newton finds it upright,
    an unstable equilibrium (past its self-weight buckling length)."""
    text = Path(FIG6).read_text(encoding="utf-8")
    text = text.replace("length_m = 0.040\n", "length_m = 0.090\n")
    text = text.replace("coiled_length_m = 0.040", "coiled_length_m = 0.090")
    text = text.replace("temperatures_c = [100.0, 100.0]", "temperatures_c = [25.0, 25.0]")
    path = tmp_path / "tallfinger.toml"
    path.write_text(text, encoding="utf-8")
    return path


def test_solve_json_is_solution_to_dict(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from tcarod.io.design import load_design

    assert cli.main(["solve", FIG6, "-T", "60", "25", "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    want = load_design(FIG6).solve([60.0, 25.0]).to_dict()
    assert {k: doc[k] for k in want} == want  # the same solve, bit for bit
    assert doc["stable"] is True and doc["stability_margin"] > 0
    assert doc["stability_policy"] == "report" and doc["continued_route"] is None
    assert doc["temperature_c"] == [60.0, 25.0] and doc["output_paths"] == []


def test_solve_writes_every_output_format(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("meshio", reason="meshio (the `export` extra) is not installed")
    outs = [str(tmp_path / "shape" / f"finger.{s}") for s in ("json", "csv", "vtu", "vtk")]
    args = ["solve", FIG6, "--out", str(tmp_path), "--json"]
    for o in outs:
        args += ["--output", o]
    assert cli.main(args) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["output_paths"] == outs
    saved = json.loads(Path(outs[0]).read_text(encoding="utf-8"))
    assert saved == {k: doc[k] for k in saved}  # the file is to_dict(); the CLI adds its own keys
    assert len(Path(outs[1]).read_text(encoding="utf-8").splitlines()) == doc["nodes"] + 1
    assert Path(outs[2]).read_bytes().startswith(b"<?xml")
    assert Path(outs[3]).read_bytes().startswith(b"# vtk DataFile")


def test_several_designs_need_a_design_placeholder_in_output(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert cli.main(["solve", *TWO, "--out", str(tmp_path), "--output", str(tmp_path / "a.csv")]) == 2
    assert "{design}" in capsys.readouterr().err
    pattern = str(tmp_path / "{design}.csv")
    assert cli.main(["solve", *TWO, "--out", str(tmp_path), "--output", pattern]) == 0
    assert (tmp_path / "fig6_square.csv").is_file() and (tmp_path / "fig1b_three_tca.csv").is_file()


def test_unknown_output_suffix_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["solve", FIG6, "--out", str(tmp_path), "--output", str(tmp_path / "a.txt")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and ".csv" in err and not (tmp_path / "fig6_square.png").exists()


def test_unstable_design_warns_in_cli_words_and_exits_0(tmp_path: Path) -> None:
    proc = run("solve", str(_tall_finger(tmp_path)), "--json", "--out", str(tmp_path), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    doc = json.loads(proc.stdout)
    assert doc["stable"] is False and doc["stability_margin"] < 0
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tcarod: warning: ")
    assert "--stability continue" in lines[0] and "stability=" not in lines[0]
    assert ".py" not in proc.stderr  # no source file or line of the package


def test_require_on_an_unstable_design_exits_3(tmp_path: Path) -> None:
    proc = run("solve", str(_tall_finger(tmp_path)), "--json", "--stability", "require", cwd=tmp_path)
    assert proc.returncode == cli.EXIT_UNSTABLE == 3
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("tcarod: error: ") and "unstable" in lines[0]
    assert "--stability continue" in lines[0] and "Traceback" not in proc.stderr
    assert not (tmp_path / "tcarod-output" / "tallfinger.png").exists()


def test_continue_moves_an_unstable_design_to_a_stable_shape(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    design = str(_tall_finger(tmp_path))
    assert cli.main(["solve", design, "--stability", "continue", "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["stable"] is True and doc["stability_margin"] > 0
    assert doc["stability_policy"] == "continue" and doc["continued_route"]
    # the upright tip stands at 90 mm; the stable shape has bent over, far from it
    assert doc["tip_position_m"][2] < 0.08


def test_stability_off_gives_no_verdict(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["solve", FIG6, "--stability", "off", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "not computed (--stability off)" in out
    assert cli.main(["solve", FIG6, "--stability", "off", "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["stable"] is None and doc["stability_margin"] is None


def test_bad_stability_choice_exits_2(tmp_path: Path) -> None:
    proc = run("solve", FIG6, "--stability", "maybe", cwd=tmp_path)
    assert proc.returncode == 2 and "--stability" in proc.stderr and proc.stdout == ""
