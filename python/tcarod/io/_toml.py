"""The TOML side of design files: the reader, size and nesting limits checked
before parsing, and errors that name the file, the dotted key and its line
(:class:`DesignError`). Parsing and error location take linear time in the
file's size. The design itself (keys, building the robot, saving) is in
:mod:`tcarod.io.design`.
"""

from __future__ import annotations

import math
import sys
from typing import Any, Sequence

from .. import _validate as V
from .._optional import require

__all__ = ["MAX_ACTUATORS", "MAX_DESIGN_CHARS", "MAX_NESTING", "DesignError"]

#: Largest design file [characters] (a design is a few hundred).
MAX_DESIGN_CHARS = 1_000_000
#: Deepest nesting of arrays / inline tables, and most parts in a dotted key or header.
MAX_NESTING = 16
#: Most actuators in one design.
MAX_ACTUATORS = 1000
#: A length key (``..._m``) above this many metres looks like millimetres (a ``UnitsWarning``).
MILLIMETRE_LOOKING_M = 10.0


class DesignError(ValueError):
    """An invalid design file. ``key`` is the dotted key (``actuators[1].tca.turns``),
    ``line`` its 1-based line in the file (``None`` if unknown)."""

    def __init__(self, source: str, key: str, line: int | None, problem: str) -> None:
        where = f"{source}:{line}" if line is not None else source
        super().__init__(f"{where}: {key}: {problem}" if key else f"{where}: {problem}")
        self.source = source
        self.key = key
        self.line = line
        self.problem = problem


def _tomllib() -> Any:
    """The TOML reader: the standard ``tomllib`` (3.11+), else ``tomli`` (extra ``io``)."""
    if sys.version_info >= (3, 11):
        import tomllib

        return tomllib
    return require("tomli")  # type: ignore[unreachable,unused-ignore]  # Python < 3.11 only


# --------------------------------------------------------------------------
# Line lookup for semantic errors
# --------------------------------------------------------------------------


def _header_parts(line: str) -> tuple[bool, str] | None:
    """``(is_array, inner)`` if the stripped ``line`` is a table header, else ``None``."""
    if not line.startswith("["):
        return None
    arr = line.startswith("[[")
    inner_start = 2 if arr else 1
    close = line.find("]", inner_start)
    if close < 0:
        return None
    rest = line[close + (2 if arr else 1) :].strip()
    if rest and not rest.startswith("#"):
        return None  # e.g. a continuation line of a multi-line array
    if "=" in line[:close]:
        return None
    return arr, line[inner_start:close]


def _split_key(key: str) -> tuple[str, ...]:
    return tuple(p.strip().strip("\"'") for p in key.split("."))


def _key_lines(text: str) -> list[tuple[tuple[str, ...], int]]:
    """``(path, line)`` of every table header and key in ``text``; array-of-tables
    entries carry their index (``("actuators", "1", "tca", "turns")``).
    Linear in the size of ``text`` (no backtracking regular expressions; dotted
    keys are capped at :data:`MAX_NESTING` parts by :func:`_check_limits`)."""
    out: list[tuple[tuple[str, ...], int]] = []
    counts: dict[tuple[str, ...], int] = {}
    current: tuple[str, ...] = ()
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        header = _header_parts(line)
        if header is not None:
            arr, inner = header
            parts = _split_key(inner)
            if arr:
                counts[parts] = counts.get(parts, -1) + 1
                current = (*parts[:-1], parts[-1], str(counts[parts]))
            else:
                # sub-table of the latest array entry: [actuators.tca] -> actuators.<i>.tca
                resolved: list[str] = []
                for k, p in enumerate(parts):
                    resolved.append(p)
                    prefix = tuple(parts[: k + 1])
                    if prefix in counts:
                        resolved.append(str(counts[prefix]))
                current = tuple(resolved)
            out.append((current, n))
            continue
        eq = line.find("=")
        if eq > 0:
            out.append(((*current, *_split_key(line[:eq])), n))
    return out


def _check_limits(text: str, source: str) -> None:
    """Refuse, in one linear pass, files too large or nested too deep for the
    parser (``tomllib`` recurses per bracket level), naming the line."""
    if len(text) > MAX_DESIGN_CHARS:
        raise DesignError(source, "", None, f"file too large: {len(text)} characters, at most {MAX_DESIGN_CHARS}")
    depth = 0
    line = 1
    i = 0
    n = len(text)
    dots = 0  # dots in the key part of the current line (before '=' or in a header)
    in_value = False  # after '=' on this line
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            dots = 0
            in_value = depth > 0
            i += 1
        elif c == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif c in "\"'":
            triple = text.startswith(c * 3, i)
            if triple:
                j = text.find(c * 3, i + 3)
                while c == '"' and j > 0 and _escaped(text, j):
                    j = text.find(c * 3, j + 1)
                j = n if j < 0 else j + 3
                while j < n and text[j] == c:  # up to two quotes may close the string too
                    j += 1
            else:
                j = i + 1
                while j < n and text[j] != c and text[j] != "\n":
                    j += 2 if (c == '"' and text[j] == "\\") else 1
                j += 1
            line += text.count("\n", i, min(j, n))
            i = j
        else:
            if c in "[{":
                depth += 1
                if depth > MAX_NESTING:
                    raise DesignError(source, "", line, f"brackets nested deeper than {MAX_NESTING} levels")
            elif c in "]}":
                depth = max(0, depth - 1)
            elif c == "=":
                in_value = True
            elif c == "." and not in_value:
                dots += 1
                if dots >= MAX_NESTING:
                    raise DesignError(source, "", line, f"a dotted key or header of more than {MAX_NESTING} parts")
            i += 1


def _escaped(text: str, j: int) -> bool:
    """True if ``text[j]`` is preceded by an odd number of backslashes."""
    k = j - 1
    while k >= 0 and text[k] == "\\":
        k -= 1
    return (j - 1 - k) % 2 == 1


def _dotted(path: tuple[str, ...]) -> str:
    s = ""
    for p in path:
        if p.isdigit():
            s += f"[{p}]"
        else:
            s += ("." if s else "") + p
    return s


class _Reader:
    """Typed access to the parsed document with key-and-line errors."""

    def __init__(self, text: str, source: str) -> None:
        self.text = text
        self.source = source
        self._lines: dict[tuple[str, ...], int] | None = None

    def line_of(self, path: tuple[str, ...]) -> int | None:
        """Line of ``path`` or, failing that, of its longest present prefix
        (one linear scan of the text, done once)."""
        if self._lines is None:
            self._lines = {}
            for p, n in _key_lines(self.text):
                self._lines.setdefault(p, n)
        for k in range(len(path), 0, -1):
            if path[:k] in self._lines:
                return self._lines[path[:k]]
        return None

    def error(self, path: tuple[str, ...], problem: str) -> DesignError:
        return DesignError(self.source, _dotted(path), self.line_of(path), problem)

    def table(self, d: Any, path: tuple[str, ...]) -> dict[str, Any]:
        if not isinstance(d, dict):
            raise self.error(path, f"must be a table, got {type(d).__name__}")
        return d

    def check_keys(self, d: dict[str, Any], path: tuple[str, ...], allowed: Sequence[str]) -> None:
        for k in d:
            if k not in allowed:
                raise self.error((*path, k), f"unknown key (allowed: {', '.join(allowed)})")

    def number(
        self, d: dict[str, Any], key: str, path: tuple[str, ...], default: float | None = None, positive: bool = False
    ) -> float:
        if key not in d:
            if default is None:
                raise self.error((*path, key), "missing")
            return default
        v = d[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.error((*path, key), f"must be a number, got {_short(v)}")
        x = _float(v)
        if not math.isfinite(x):
            raise self.error((*path, key), f"must be finite, got {_short(v)}")
        if positive and x <= 0.0:
            raise self.error((*path, key), f"must be > 0, got {v!r}")
        if key.endswith("_m") and not key.endswith("_per_m") and abs(x) > MILLIMETRE_LOOKING_M:
            self.warn_units(
                (*path, key),
                f"= {x:g}: keys ending in _m are in metres (SI); did you give millimetres? (40 mm is 0.040)",
            )
        return x

    def warn_units(self, path: tuple[str, ...], message: str) -> None:
        """``tcarod.UnitsWarning`` naming the file, the line and the dotted key."""
        line = self.line_of(path)
        where = f"{self.source}:{line}" if line is not None else self.source
        V.warn_units(f"{where}: {_dotted(path)} {message}", stacklevel=4)

    def vector(self, d: dict[str, Any], key: str, path: tuple[str, ...]) -> list[float] | None:
        if key not in d:
            return None
        v = d[key]
        if not (
            isinstance(v, list)
            and len(v) == 3
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)
        ):
            raise self.error((*path, key), f"must be a list of 3 numbers, got {_short(v)}")
        if not all(math.isfinite(_float(x)) for x in v):
            raise self.error((*path, key), f"must be finite, got {_short(v)}")
        return [_float(x) for x in v]

    def string(
        self, d: dict[str, Any], key: str, path: tuple[str, ...], choices: Sequence[str], default: str | None = None
    ) -> str:
        if key not in d:
            if default is None:
                raise self.error((*path, key), "missing")
            return default
        v = d[key]
        if not isinstance(v, str) or v not in choices:
            raise self.error((*path, key), f"must be one of {', '.join(map(repr, choices))}, got {_short(v)}")
        return str(v)


def _float(v: int | float) -> float:
    """``float(v)``; TOML integers beyond the double range become +-inf (refused as not finite)."""
    try:
        return float(v)
    except OverflowError:
        return math.inf if v > 0 else -math.inf


def _short(v: Any) -> str:
    """``repr(v)`` cut to 60 characters (messages stay one readable line)."""
    try:
        r = repr(v)
    except ValueError:  # an integer too long to print (sys.int_info.str_digits_check_threshold)
        r = f"a {type(v).__name__} too long to print"
    return r if len(r) <= 60 else r[:57] + "..."
