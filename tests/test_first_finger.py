"""docs/first-finger.md runs as written: its ```python blocks are executed in
order in one namespace (as a reader runs them), interactive ones (``>>>``)
as doctests whose printed outputs are checked; its ```toml design file is
written where the page says to save it, and its ```sh commands run through
the ``tcarod`` command line. Everything runs in a scratch directory."""

from __future__ import annotations

import doctest
import re
import shlex
from pathlib import Path

import pytest
from test_readme import PYTHON_BLOCK  # noqa: E402  (tests/ is on sys.path under pytest)

from tcarod.cli import main

pytest.importorskip("matplotlib")  # the page draws the side view (the `plot` extra)
pytest.importorskip("pandas")  # and turns the batch into a DataFrame (the `pandas` extra)

ROOT = Path(__file__).resolve().parent.parent
PAGE = "docs/first-finger.md"
TEXT = (ROOT / PAGE).read_text(encoding="utf-8")
# Any fenced block, with its language: the page's blocks in reading order.
FENCED = re.compile(r"^```(\w+)\n(.*?)^```", flags=re.MULTILINE | re.DOTALL)
# The first line of a design-file block names the file: "# finger.toml: ...".
TOML_NAME = re.compile(r"^# (\S+\.toml)\b")


def test_page_is_linked_from_the_readme_and_the_site() -> None:
    assert "(docs/first-finger.md)" in (ROOT / "README.md").read_text(encoding="utf-8")
    assert "first-finger.md" in (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    # every python block of the page is one that the shared README pattern finds
    assert len(PYTHON_BLOCK.findall(TEXT)) == sum(1 for lang, _ in FENCED.findall(TEXT) if lang == "python")


def test_first_finger_page_runs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace: dict[str, object] = {"__name__": "__docs__"}
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    counts = {"python": 0, "toml": 0, "sh": 0}
    for i, (lang, block) in enumerate(FENCED.findall(TEXT)):
        counts[lang] = counts.get(lang, 0) + 1
        name = f"{PAGE}:block{i}"
        if lang == "python" and block.lstrip().startswith(">>>"):
            test = doctest.DocTestParser().get_doctest(block, namespace, name, PAGE, 0)
            test.globs = namespace  # names a block defines serve the next blocks
            result = runner.run(test, clear_globs=False)
            assert result.attempted > 0
            assert result.failed == 0, f"{name} failed (output above)"
        elif lang == "python":
            exec(compile(block, name, "exec"), namespace)
        elif lang == "toml":
            match = TOML_NAME.match(block)
            assert match, f"{name}: a design file's first line names it"
            (tmp_path / match.group(1)).write_text(block, encoding="utf-8")
        elif lang == "sh":
            for line in block.splitlines():
                argv = shlex.split(line)
                assert argv[0] == "tcarod", line
                assert main(argv[1:]) == 0, line
            out = capsys.readouterr().out
            # the CLI prints the 120 C / 25 C tip of the page's forward solve [mm]
            assert "tip position [mm]: -21.3962, 0.0000, 57.6255" in out
    assert counts["python"] >= 8 and counts["toml"] == 1 and counts["sh"] == 1
    # what the blocks wrote: the side view, the exports, the CLI's plot and shape
    for written in ("finger.png", "finger.json", "finger.csv", "tcarod-output/finger.png", "finger-shape.csv"):
        assert (tmp_path / written).stat().st_size > 0, written
