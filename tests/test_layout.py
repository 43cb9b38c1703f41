"""The Python package's layout (README, "Development"): imports run one way,
cli -> paper / models -> API -> _core, and no file or function is too long.

The import graph is read from the source with ``ast`` (nothing is imported):
every ``import`` and ``from ... import`` of a tcarod module counts, at module
level, inside functions (deferred imports) and under ``if TYPE_CHECKING``
alike, so that a cycle cannot hide behind a lazy import.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "tcarod"

#: The API over the core: thin wrappers, nothing built on top of them.
API = ("tcarod.tca", "tcarod.rod", "tcarod.inverse", "tcarod.batch", "tcarod._validate", "tcarod._optional")
#: Layers the API and the models must never reach, even lazily.
ABOVE_MODELS = ("tcarod.paper", "tcarod.plotting", "tcarod.cli", "tcarod.io")

MAX_FILE_LINES = 500  # the project's size rule: no source file over 500 lines
MAX_FUNCTION_LINES = 80  # the project's size rule: no function over 80 lines


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


#: Every module: the .py sources and the compiled core (read from its stub).
MODULES: dict[str, Path] = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}
#: The compiled core is one module at run time; its hand-written stub is a package
#: (``_core/__init__.pyi`` re-exporting one private stub per part of the bindings).
CORE_STUBS = sorted((PACKAGE / "_core").glob("*.pyi"))
MODULES["tcarod._core"] = PACKAGE / "_core" / "__init__.pyi"
#: The hand-written Python (the stub mirrors the Rust bindings and is checked by stubtest instead).
SOURCES = sorted(m for m, p in MODULES.items() if p.suffix == ".py")
#: Every file the size limits apply to: the Python sources and every stub.
FILES = [MODULES[m] for m in SOURCES] + sorted(PACKAGE.rglob("*.pyi"))


def _resolve(module: str, path: Path, node: ast.ImportFrom) -> str:
    """The absolute module name ``from <node.module> import ...`` refers to."""
    if node.level == 0:
        return node.module or ""
    package = module.split(".") if path.stem == "__init__" else module.split(".")[:-1]
    base = package[: len(package) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(module: str) -> set[str]:
    """tcarod modules imported anywhere in ``module``'s source (parent packages
    that Python imports implicitly are not counted). The core's imports are
    those of all its stubs (imports between the stubs stay inside the module)."""
    paths = CORE_STUBS if module == "tcarod._core" else [MODULES[module]]
    found: set[str] = set()
    for path in paths:
        found.update(_imports_of_file(_module_name(path), path))
    return {m for m in found if m in MODULES and m != module}


def _imports_of_file(module: str, path: Path) -> set[str]:
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            target = _resolve(module, path, node)
            for a in node.names:  # `from pkg import submodule` imports the submodule
                sub = f"{target}.{a.name}"
                found.add(sub if sub in MODULES else target)
    return found


GRAPH: dict[str, set[str]] = {m: _imports(m) for m in MODULES}


def _reachable(start: str) -> set[str]:
    seen: set[str] = set()
    stack = [start]
    while stack:
        for nxt in GRAPH[stack.pop()]:
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def _cycle() -> list[str] | None:
    """One import cycle as a list of modules, or ``None`` (depth-first search)."""
    state: dict[str, int] = {}  # 1: on the stack, 2: done
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for n in sorted(GRAPH[m]):
            if state.get(n) == 1:
                return stack[stack.index(n) :] + [n]
            if n not in state and (found := visit(n)) is not None:
                return found
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(GRAPH):
        if m not in state and (found := visit(m)) is not None:
            return found
    return None


def test_the_graph_sees_the_known_arrows() -> None:
    # guards the parser itself: a graph that lost its edges would pass every test below
    assert "tcarod._core" in GRAPH["tcarod.rod"]
    assert "tcarod.paper" in GRAPH["tcarod.cli"]
    assert "tcarod.plotting" in GRAPH["tcarod.paper.fig5"]  # deferred import inside plot()
    assert "tcarod.models.manipulators" in GRAPH["tcarod.paper.fig6"]


def test_no_import_cycle() -> None:
    assert _cycle() is None, " -> ".join(_cycle() or [])


def test_a_cycle_would_be_found() -> None:
    saved = GRAPH["tcarod._core"]
    GRAPH["tcarod._core"] = {"tcarod.rod"}  # a fake back edge: rod -> _core -> rod
    try:
        assert _cycle() is not None
    finally:
        GRAPH["tcarod._core"] = saved


@pytest.mark.parametrize("module", API)
def test_api_does_not_import_models_paper_plotting_io_or_cli(module: str) -> None:
    bad = sorted(m for m in _reachable(module) if m.startswith((*ABOVE_MODELS, "tcarod.models")))
    assert not bad, f"{module} reaches {bad}"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.startswith("tcarod.models")))
def test_models_do_not_import_paper_plotting_io_or_cli(module: str) -> None:
    bad = sorted(m for m in _reachable(module) if m.startswith(ABOVE_MODELS))
    assert not bad, f"{module} reaches {bad}"


def test_plotting_does_not_import_the_paper() -> None:
    # the paper's results call plotting from plot(path); the reverse arrow would be a cycle
    bad = sorted(
        m for m in MODULES if m.startswith("tcarod.plotting") for n in GRAPH[m] if n.startswith("tcarod.paper")
    )
    assert not bad


def _file_id(path: Path) -> str:
    return str(path.relative_to(PACKAGE))


def test_the_stubs_are_counted() -> None:
    # the stub package exists and its parts are in the size checks below
    assert MODULES["tcarod._core"].is_file() and len(CORE_STUBS) > 1
    assert set(CORE_STUBS) <= set(FILES)


@pytest.mark.parametrize("path", FILES, ids=_file_id)
def test_no_file_over_500_lines(path: Path) -> None:
    n = path.read_text(encoding="utf-8").count("\n")
    assert n <= MAX_FILE_LINES, f"{path}: {n} lines"


def _code_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    """Lines of a function without its docstring: the size rule is about
    code, and a numpydoc docstring (Parameters, Returns, Raises, Examples)
    is not a reason to split a function."""
    assert node.end_lineno is not None
    lines = node.end_lineno - node.lineno + 1
    first = node.body[0] if node.body else None
    if (
        isinstance(first, ast.Expr)
        and isinstance(first.value, ast.Constant)
        and isinstance(first.value.value, str)
        and first.end_lineno is not None
    ):
        lines -= first.end_lineno - first.lineno + 1
    return lines


@pytest.mark.parametrize("path", FILES, ids=_file_id)
def test_no_function_over_80_lines(path: Path) -> None:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    long = [
        f"{node.name} ({_code_lines(node)} lines of code, line {node.lineno})"
        for node in ast.walk(tree)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and _code_lines(node) > MAX_FUNCTION_LINES
    ]
    assert not long, f"{path}: {long}"


def test_stub_only_bases_declare_only_runtime_members() -> None:
    # stubtest checks a stub class by its own names and the run-time class's names,
    # so a member declared only in a @type_check_only base (python/tcarod/_core/
    # _inverse.pyi: _Outcome) and missing at run time would pass it unseen
    from tcarod import _core

    classes = {
        node.name: node
        for path in CORE_STUBS
        for node in ast.parse(path.read_text(encoding="utf-8")).body
        if isinstance(node, ast.ClassDef)
    }
    stub_only = {n for n, c in classes.items() if any("type_check_only" in ast.unparse(d) for d in c.decorator_list)}
    checked = []
    for name, cls in classes.items():
        for base in (ast.unparse(b) for b in cls.bases if ast.unparse(b) in stub_only):
            for member in (f.name for f in classes[base].body if isinstance(f, ast.FunctionDef)):
                assert hasattr(getattr(_core, name), member), f"{name}.{member} (from {base}) is not at run time"
                checked.append(f"{name}.{member}")
    assert len(checked) >= 16  # InverseResult and BlockedResult, 8 members each
