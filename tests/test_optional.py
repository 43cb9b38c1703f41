"""Optional dependencies: the core needs NumPy only, and a feature whose extra is
missing fails with one line naming the extra to install.

A missing package is simulated by ``sys.modules[name] = None``, which makes
``import name`` raise ImportError exactly as if the package were absent
(monkeypatch restores the real entries afterwards). The NumPy-only check runs in
a subprocess, so that no module already imported by other tests can hide an
import of an optional package.
"""

from __future__ import annotations

import importlib
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from tcarod._optional import EXTRAS, MissingDependencyError, require

ROOT = Path(__file__).resolve().parent.parent

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - CI runs 3.11
    import tomli as tomllib

PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
OPTIONAL = ("matplotlib", "scipy", "tqdm", "dask", "distributed", "pandas")


def _hide(monkeypatch: pytest.MonkeyPatch, top: str) -> None:
    """Make ``import top`` (and its submodules) fail as if ``top`` were not installed."""
    for name in [m for m in sys.modules if m == top or m.startswith(top + ".")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, top, None)


@pytest.mark.parametrize("module", OPTIONAL)
def test_require_names_the_extra_in_one_line(module: str, monkeypatch: pytest.MonkeyPatch) -> None:
    _hide(monkeypatch, module)
    with pytest.raises(MissingDependencyError) as info:
        require(module)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(f"{module} is needed")
    assert f"pip install 'tcarod[{EXTRAS[module]}]'" in message
    # an ImportError subclass, so `except ImportError` in user code still works
    assert isinstance(info.value, ImportError)


def test_require_returns_the_module_when_present() -> None:
    assert require("numpy") is np
    assert require("numpy.linalg") is importlib.import_module("numpy.linalg")


def test_every_extra_named_by_require_is_declared_in_pyproject() -> None:
    extras = PYPROJECT["project"]["optional-dependencies"]
    for module, extra in EXTRAS.items():
        assert extra in extras, f"{module} -> tcarod[{extra}] is not an extra of pyproject.toml"
        # the extra installs the package it is named for (dask's scheduler
        # `distributed` comes from dask[distributed])
        dist = {"distributed": "dask", "tomli_w": "tomli-w"}.get(module, module)
        assert any(req.lower().startswith(dist) for req in extras[extra]), (extra, extras[extra])
    # `all` pulls every feature extra
    (all_req,) = extras["all"]
    assert all(extra in all_req for extra in set(EXTRAS.values()))


def test_core_dependencies_are_numpy_only() -> None:
    names = {
        req.split(";")[0].split(">")[0].split("=")[0].strip().lower() for req in PYPROJECT["project"]["dependencies"]
    }
    assert names == {"numpy"}


def test_plotting_without_matplotlib_names_the_plot_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    _hide(monkeypatch, "matplotlib")
    _hide(monkeypatch, "mpl_toolkits")
    monkeypatch.delitem(sys.modules, "tcarod.plotting", raising=False)
    with pytest.raises(MissingDependencyError, match=r"pip install 'tcarod\[plot\]'"):
        importlib.import_module("tcarod.plotting")


def test_calibration_without_scipy_names_the_fit_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    from tcarod.models.calibration import TcaExperiment, calibrate

    _hide(monkeypatch, "scipy")
    half = TcaExperiment(0.497 / 2, 0.110 / 2, 2e-3, 150.0, mass_kg=10e-3, load_share=0.5)
    t = np.linspace(40.0, 160.0, 8)
    with pytest.raises(MissingDependencyError, match=r"pip install 'tcarod\[fit\]'"):
        calibrate(half, t, np.zeros_like(t), fit=("expansion_scale",))


def test_progress_bar_without_tqdm_names_the_progress_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    from tcarod.batch import fig6_square_robot, solve_batch

    _hide(monkeypatch, "tqdm")
    with pytest.raises(MissingDependencyError, match=r"pip install 'tcarod\[progress\]'"):
        solve_batch(fig6_square_robot(), [[60.0, 60.0]], progress=True)


def test_core_works_with_numpy_only() -> None:
    """import tcarod, a solve, a batch and a design file with every optional
    package blocked (a fresh interpreter, so nothing is imported already)."""
    script = textwrap.dedent(
        f"""
        import sys
        for name in {OPTIONAL!r}:
            sys.modules[name] = None  # import name -> ImportError
        import tcarod, tcarod.batch, tcarod.io.design, tcarod.cli, tcarod.inverse
        from tcarod.batch import fig6_square_robot, solve_batch
        robot = fig6_square_robot()
        sol = robot.solve([100.0, 100.0])
        assert sol.tip_position[0] < 0.0  # bends away from the heated TCA
        res = solve_batch(robot, [[60.0, 60.0], [100.0, 100.0]])
        assert res.converged.all()
        loaded = [m for m in {OPTIONAL!r} if sys.modules.get(m) is not None]
        assert not loaded, loaded
        print("ok")
        """
    )
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
