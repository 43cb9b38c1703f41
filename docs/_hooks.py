"""MkDocs build hooks (mkdocs.yml `hooks:`), run by `mkdocs build`.

* on_config: the optional page ``table1.md`` (written separately) is listed in
  the nav only when it exists, so a strict build never points at a missing page.
* on_pre_build: the figures and tables of the paper's experiments
  (``tcarod reproduce``: ``NAME.png`` and the printed table ``NAME.txt``) go to
  ``docs/figures/``, and the notebooks of ``examples/``, executed, go to
  ``docs/gallery/``, which mkdocs-jupyter renders without executing them
  again. Both come from the installed tcarod. Under ``make test``
  (``TCAROD_TEST_ARTIFACTS`` set) the tests of the same run have already
  drawn the figures and executed the notebooks; the hook takes their outputs
  (a notebook only if its code cells are those of ``examples/``) and makes
  only what is missing. Both folders are build outputs (.gitignore).
* on_post_build: if the Rust crate docs exist (``cargo doc --no-deps``, run by
  ``make docs``), they are copied to ``site/rust/``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
FIGURES = DOCS / "figures"
GALLERY = DOCS / "gallery"
#: The experiments shown on docs/experiments.md, by their `tcarod reproduce` name.
EXPERIMENTS = ("fig5", "fig6", "fig8", "table1", "fig1b")


def _drop_missing(nav: list[Any]) -> list[Any]:
    out: list[Any] = []
    for item in nav:
        if isinstance(item, dict):
            ((title, target),) = item.items()
            if isinstance(target, list):
                out.append({title: _drop_missing(target)})
            elif target == "table1.md" and not (DOCS / target).is_file():
                continue
            else:
                out.append(item)
        else:
            out.append(item)
    return out


def on_config(config: Any) -> Any:
    config["nav"] = _drop_missing(config["nav"])
    return config


def _artifacts() -> Path | None:
    path = os.environ.get("TCAROD_TEST_ARTIFACTS")
    return Path(path) if path else None


def _figures() -> None:
    """docs/figures/NAME.png and NAME.txt for every experiment on the site."""
    FIGURES.mkdir(exist_ok=True)
    artifacts = _artifacts()
    made = artifacts / "reproduce" / "tcarod-output" if artifacts else None
    missing = []
    for name in EXPERIMENTS:
        files = [made / f"{name}{ext}" for ext in (".png", ".txt")] if made else []
        if files and all(f.is_file() for f in files):
            for f in files:
                shutil.copy2(f, FIGURES / f.name)
        else:
            missing.append(name)
    if missing:
        run = subprocess.run(
            [sys.executable, "-m", "tcarod", "reproduce", *missing, "--out", str(FIGURES)],
            capture_output=True,
            text=True,
            check=False,
        )
        if run.returncode != 0:
            raise RuntimeError(f"tcarod reproduce {' '.join(missing)} failed:\n{run.stderr}")


def _code(book: Any) -> list[str]:
    return [c.source for c in book.cells if c.cell_type == "code"]


def _gallery() -> None:
    """docs/gallery/NAME.ipynb: every notebook of examples/, executed."""
    import nbclient
    import nbformat

    if GALLERY.exists():
        shutil.rmtree(GALLERY)
    GALLERY.mkdir()
    artifacts = _artifacts()
    for path in sorted((ROOT / "examples").glob("*.ipynb")):
        source = nbformat.read(path, as_version=4)
        executed = artifacts / "notebooks" / path.name if artifacts else None
        if executed is not None and executed.is_file():
            book = nbformat.read(executed, as_version=4)
            if _code(book) == _code(source):
                nbformat.write(book, GALLERY / path.name)
                continue
        with tempfile.TemporaryDirectory() as cwd:  # files the notebook writes go here
            nbclient.NotebookClient(
                source, kernel_name="python3", timeout=300, resources={"metadata": {"path": cwd}}
            ).execute()
        nbformat.write(source, GALLERY / path.name)


def on_pre_build(config: Any) -> None:
    # jupyter_core warns unless the platformdirs layout is chosen explicitly.
    os.environ.setdefault("JUPYTER_PLATFORM_DIRS", "1")
    _figures()
    _gallery()


def on_post_build(config: Any) -> None:
    crate_docs = ROOT / "target" / "doc"
    if (crate_docs / "tcarod" / "index.html").is_file():
        shutil.copytree(crate_docs, Path(config["site_dir"]) / "rust", dirs_exist_ok=True)
