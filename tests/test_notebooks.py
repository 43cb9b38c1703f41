"""The notebook gallery (examples/*.ipynb) runs: each notebook is executed top to
bottom by nbclient on a real Jupyter kernel (ipykernel, this interpreter), must
finish without an error, and every cell that draws a figure must have produced
an image/png output -- what a reader of the notebook (or of the docs site,
which renders the same notebooks) sees.

Under ``make test`` (``TCAROD_TEST_ARTIFACTS`` set) each executed notebook is
also saved to ``$TCAROD_TEST_ARTIFACTS/notebooks/``, where the docs build of
the same run takes it (docs/_hooks.py) instead of executing it again.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

# jupyter_core warns (DeprecationWarning, an error under this suite's
# filterwarnings) unless the platformdirs layout is chosen explicitly.
os.environ.setdefault("JUPYTER_PLATFORM_DIRS", "1")

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
NOTEBOOKS = sorted(EXAMPLES.glob("*.ipynb"))
# A cell draws a figure if it calls pyplot, a .plot() method or a tcarod plot_* function.
FIGURE_CALL = re.compile(r"\bplt\.\w+\(|\.plot\(|\bplot_\w+\(")
# Generous per-cell limit: each notebook runs in well under 20 s on an idle
# core; this only stops a hung kernel.
CELL_TIMEOUT_S = 300


def test_gallery_has_the_six_notebooks() -> None:
    names = [p.stem for p in NOTEBOOKS]
    assert len(names) == 6, names
    for topic in ("quick_start", "fig6", "workspace", "voltage", "calibration", "dask"):
        assert any(topic in n for n in names), (topic, names)


def test_notebooks_are_stored_without_outputs() -> None:
    """Outputs are produced by running them (tests, docs build), never committed."""
    for path in NOTEBOOKS:
        book = nbformat.read(path, as_version=4)
        stale = [i for i, c in enumerate(book.cells) if c.cell_type == "code" and (c.outputs or c.execution_count)]
        assert not stale, f"{path.name}: cells {stale} carry outputs"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_and_shows_its_figures(path: Path, tmp_path: Path) -> None:
    book = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(
        book,
        kernel_name="python3",
        timeout=CELL_TIMEOUT_S,
        allow_errors=False,  # the first failing cell raises CellExecutionError
        resources={"metadata": {"path": str(tmp_path)}},  # files the notebook writes go here
    )
    client.execute()

    code = [c for c in book.cells if c.cell_type == "code"]
    assert all(c.execution_count for c in code), "a code cell did not run"
    errors = [o for c in code for o in c.outputs if o.output_type == "error"]
    assert not errors, errors
    figure_cells = [c for c in code if FIGURE_CALL.search(c.source)]
    assert figure_cells, f"{path.name} draws no figure"
    for cell in figure_cells:
        kinds = {k for o in cell.outputs for k in o.get("data", {})}
        assert "image/png" in kinds, f"{path.name}: figure cell shows no image ({sorted(kinds)}):\n{cell.source}"

    artifacts = os.environ.get("TCAROD_TEST_ARTIFACTS")
    if artifacts:
        executed = Path(artifacts) / "notebooks"
        executed.mkdir(parents=True, exist_ok=True)
        nbformat.write(book, executed / path.name)
