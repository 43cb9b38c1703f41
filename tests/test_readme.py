"""README.md's examples run: every ```python block is executed, so they cannot rot.

Blocks written as an interactive session (``>>>``) are run as doctests, so
their printed results are checked too; other blocks are executed and must not
raise. Both run in a scratch directory (the examples may write files).
"""

from __future__ import annotations

import doctest
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"^```python\n(.*?)^```", README, flags=re.MULTILINE | re.DOTALL)


def test_readme_has_python_examples() -> None:
    assert len(BLOCKS) >= 2
    assert any(b.lstrip().startswith(">>>") for b in BLOCKS)


@pytest.mark.parametrize("block", BLOCKS, ids=[f"block{i}" for i in range(len(BLOCKS))])
def test_readme_python_block_runs(block: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    if block.lstrip().startswith(">>>"):
        test = doctest.DocTestParser().get_doctest(block, {}, "README.md", "README.md", 0)
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        runner.run(test)
        result = runner.summarize(verbose=False)
        assert result.attempted > 0
        assert result.failed == 0, "README doctest failed (output above)"
    else:
        exec(compile(block, "README.md", "exec"), {"__name__": "__readme__"})


def test_quick_start_is_two_commands_and_ci_runs_the_second() -> None:
    quick = README.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    (block,) = re.findall(r"^```sh\n(.*?)^```", quick, flags=re.MULTILINE | re.DOTALL)
    commands = [line for line in block.splitlines() if line.strip()]
    assert len(commands) == 2
    install_and_run, test = commands
    assert "pip install" in install_and_run and "tcarod reproduce" in install_and_run
    for part in ("pip install -e '.[test]'", "cargo test", "python -m pytest", "mypy.stubtest"):
        assert part in test
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "README.md" in ci  # .ci/run takes the command from the README itself
    assert os.access(ROOT / ".ci" / "run", os.X_OK)
