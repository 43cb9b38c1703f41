"""MkDocs build hooks (mkdocs.yml `hooks:`), run by `mkdocs build`.

* on_config: the optional page ``table1.md`` (written separately) is listed in
  the nav only when it exists, so a strict build never points at a missing page.
* on_pre_build: figures and tables of the paper's experiments are generated
  from the installed tcarod (``tcarod reproduce NAME --out docs/figures``; the
  printed table goes to ``docs/figures/NAME.txt``), and the notebooks of
  ``examples/`` are copied to ``docs/gallery/`` for mkdocs-jupyter, which
  executes them (never from its cache: the outputs depend on the installed
  tcarod). Both folders are build outputs (.gitignore).
* on_post_build: if the Rust crate docs exist (``cargo doc --no-deps``, run by
  ``make docs``), they are copied to ``site/rust/``.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
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


def on_pre_build(config: Any) -> None:
    # mkdocs-jupyter caches executed notebooks by their source; the outputs
    # also depend on the installed tcarod, so every build executes afresh.
    shutil.rmtree(ROOT / ".cache" / "mkdocs-jupyter", ignore_errors=True)
    FIGURES.mkdir(exist_ok=True)
    for name in EXPERIMENTS:
        run = subprocess.run(
            [sys.executable, "-m", "tcarod", "reproduce", name, "--out", str(FIGURES)],
            capture_output=True,
            text=True,
            check=False,
        )
        if run.returncode != 0:
            raise RuntimeError(f"tcarod reproduce {name} failed:\n{run.stderr}")
        (FIGURES / f"{name}.txt").write_text(run.stdout, encoding="utf-8")
    if GALLERY.exists():
        shutil.rmtree(GALLERY)
    GALLERY.mkdir()
    for nb in sorted((ROOT / "examples").glob("*.ipynb")):
        shutil.copy2(nb, GALLERY / nb.name)


def on_post_build(config: Any) -> None:
    crate_docs = ROOT / "target" / "doc"
    if (crate_docs / "tcarod" / "index.html").is_file():
        shutil.copytree(crate_docs, Path(config["site_dir"]) / "rust", dirs_exist_ok=True)
