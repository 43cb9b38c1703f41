"""README.md's examples run, and so do the Python examples of the documentation
pages that carry code (getting started, beyond the paper): every ```python
block is executed, so they cannot rot.

Blocks written as an interactive session (``>>>``) are run as doctests, so
their printed results are checked too; other blocks are executed and must not
raise. Both run in a scratch directory (the examples may write files).
The README's quick start is checked to be the two commands CI relies on (the
second, ``make test``, with every tool the Makefile runs for it), and its
relative links to point at files that exist.
"""

from __future__ import annotations

import doctest
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
# Documentation pages whose ```python blocks are complete, runnable examples.
DOC_PAGES = ("README.md", "docs/getting-started.md", "docs/extensions.md")
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", flags=re.MULTILINE | re.DOTALL)


def _blocks() -> list[tuple[str, str]]:
    out = []
    for page in DOC_PAGES:
        text = (ROOT / page).read_text(encoding="utf-8")
        out += [(page, b) for b in PYTHON_BLOCK.findall(text)]
    return out


BLOCKS = _blocks()


def test_readme_has_a_checked_example() -> None:
    readme_blocks = [b for page, b in BLOCKS if page == "README.md"]
    assert len(readme_blocks) == 1  # one short example; the manual is on the docs site
    assert readme_blocks[0].lstrip().startswith(">>>")  # a doctest: its outputs are checked
    assert len(BLOCKS) >= 5


@pytest.mark.parametrize("page,block", BLOCKS, ids=[f"{p}:{i}" for i, (p, _) in enumerate(BLOCKS)])
def test_python_block_runs(page: str, block: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    if block.lstrip().startswith(">>>"):
        test = doctest.DocTestParser().get_doctest(block, {}, page, page, 0)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        runner.run(test)
        result = runner.summarize(verbose=False)
        assert result.attempted > 0
        assert result.failed == 0, f"{page} doctest failed (output above)"
    else:
        exec(compile(block, page, "exec"), {"__name__": "__docs__"})


def _make_target(makefile: str, target: str) -> str:
    """The recipe of a Makefile target, with the recipes of the targets it runs
    through ``$(MAKE) ... NAME`` or ``$(STEP) NAME $(MAKE) ... NAME`` inlined."""
    match = re.search(rf"^{target}:[^\n]*\n((?:\t[^\n]*\n)+)", makefile, flags=re.MULTILINE)
    assert match, f"no recipe for `{target}` in the Makefile"
    recipe = match.group(1)
    for sub in re.findall(r"\$\(MAKE\) --no-print-directory (\S+)", recipe):
        recipe += _make_target(makefile, sub)
    return recipe


def test_quick_start_is_two_commands_and_ci_runs_the_second() -> None:
    quick = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    (block,) = re.findall(r"^```sh\n(.*?)^```", quick, flags=re.MULTILINE | re.DOTALL)
    commands = [line for line in block.splitlines() if line.strip()]
    assert len(commands) == 2
    install_and_run, test = commands
    assert "pip install" in install_and_run and "tcarod reproduce" in install_and_run
    # the main job draws figures and fits Table I: it needs the optional extras
    assert "[all]" in install_and_run
    # the test line is a Makefile target; what it runs, with every step inlined
    assert test == "make test"
    recipe = _make_target((ROOT / "Makefile").read_text(encoding="utf-8"), "test")
    for part in (
        "pip install -e '.[test]'",
        "cargo fmt --check",
        "cargo clippy",
        "cargo test",
        "-m pytest",
        "-m mypy",
        "mypy.stubtest",
        "mkdocs build --strict",
    ):
        assert part in recipe, part
    # .ci/run takes the command from the README itself: the quick start's last line
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "README.md" in ci and "## Quick start" in ci and 'test_command="${lines[1]}"' in ci
    assert os.access(ROOT / ".ci" / "run", os.X_OK)


def test_readme_links_point_at_files() -> None:
    links = re.findall(r"\]\(([^)#]+)\)", README)
    local = [link for link in links if "://" not in link]
    assert local, "the README links into the docs"
    missing = [link for link in local if not (ROOT / link).exists()]
    assert not missing, missing
