"""Robot designs as TOML files: load, validate (errors name the key and its
line), build the robot, save.

Format (SI units; every key says its unit; optional keys in brackets)::

    temperatures_c = [100.0, 100.0]     # [optional] one per actuator [C]

    [body]
    length_m = 0.040
    section = { kind = "rectangle", width_m = 0.010, height_m = 0.010 }
    #   or { kind = "circle", diameter_m = ... }
    #   or { kind = "custom", area_m2 = ..., ix_m4 = ..., iy_m4 = ..., j_m4 = ... }
    youngs_modulus_pa = 37.8e3
    poisson = 0.5                       # [optional] or shear_modulus_pa (not both); default 0.5
    density_kg_per_m3 = 1040.0          # [optional] default 0
    gravity_m_per_s2 = [0.0, 0.0, -9.81]  # [optional] world frame; default none
    # [optional] shear_coefficient, nu_star, omega_star_per_m, distributed_force_n_per_m,
    #            distributed_moment_nm_per_m, tip_force_n, tip_moment_nm

    [[actuators]]                       # one table per actuator, in input order
    routing = { kind = "straight", x_m = 0.003, y_m = 0.0025 }
    #   or { kind = "helix", radius_m = ..., rate_rad_per_m = ..., phase_rad = 0.0 }
    s_start_m = 0.0                     # [optional] default 0 (the base)
    s_end_m = 0.040                     # [optional] default: the tip
    # [optional] length_ratio
    [actuators.tca]
    coiled_length_m = 0.040
    alpha0_deg = 15.0                   # or fibre_length_m (not both)
    coil_diameter_m = 1.7e-3
    turns = 76.4
    chirality = "extension"             # [optional] or "contraction"
    material = "silver_coated_nylon"    # [optional] the default; or a table:
    # [actuators.tca.material]
    # youngs_modulus_pa, shear_modulus_pa, expansion_per_c, [youngs_modulus_slope_pa_per_c,
    # shear_modulus_slope_pa_per_c, expansion_slope_per_c2, t_ref_c, t_min_c, t_max_c, name]

    [[actuators]]                       # a tendon instead of a TCA (input: tension [N])
    routing = { kind = "straight", x_m = -0.003, y_m = 0.0 }
    tendon = { kind = "tension" }       # or { kind = "linear", stiffness_n_per_m = ... }
                                        #   (input: length pulled in at the base [m])

Unknown keys are errors (a typo must not be silently ignored).

Limits (``DesignError`` beyond, naming file and line): at most
:data:`MAX_DESIGN_CHARS` characters, brackets/braces nested at most
:data:`MAX_NESTING` deep, dotted keys and headers of at most
:data:`MAX_NESTING` parts, at most :data:`MAX_ACTUATORS` actuators.
Parsing and error location take linear time in the file's size.

Saving writes the design the way it is usually written: ``alpha0_deg`` for a
TCA whose pitch angle is a round number of degrees (otherwise
``fibre_length_m``), ``poisson`` when it is a round number (otherwise
``shear_modulus_pa``), and derived lengths rounded to the shortest decimal
within a few ulps of the stored value (``0.0025``, not
``0.0024999999999999988``).
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

from . import _validate as V
from .rod import Actuator, Body, Robot, Routing, Section
from .tca import Material, Tca

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = [
    "MAX_ACTUATORS",
    "MAX_DESIGN_CHARS",
    "MAX_NESTING",
    "Design",
    "DesignError",
    "load_design",
    "loads_design",
    "save_design",
    "dumps_design",
]

#: Largest design file [characters] (a design is a few hundred).
MAX_DESIGN_CHARS = 1_000_000
#: Deepest nesting of arrays / inline tables, and most parts in a dotted key or header.
MAX_NESTING = 16
#: Most actuators in one design.
MAX_ACTUATORS = 1000


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


@dataclass(frozen=True, eq=False)
class Design:
    """A robot and, optionally, the temperatures [C] it is designed for."""

    robot: Any
    temperatures_c: list[float] | None = None

    def solve(self, temperatures_c: Sequence[float] | None = None, **kwargs: Any) -> Any:
        """Forward solution at ``temperatures_c`` [C] (default: the design's)."""
        temps = self.temperatures_c if temperatures_c is None else [float(t) for t in temperatures_c]
        if temps is None:
            raise ValueError("temperatures_c: the design gives none; pass one per actuator [C]")
        return self.robot.solve(temps, **kwargs)


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
        return x

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


_BODY_VECTORS = {
    "gravity_m_per_s2": "gravity",
    "nu_star": "nu_star",
    "omega_star_per_m": "omega_star",
    "distributed_force_n_per_m": "distributed_force",
    "distributed_moment_nm_per_m": "distributed_moment",
    "tip_force_n": "tip_force",
    "tip_moment_nm": "tip_moment",
}
_BODY_KEYS = (
    "length_m",
    "section",
    "youngs_modulus_pa",
    "poisson",
    "shear_modulus_pa",
    "density_kg_per_m3",
    "shear_coefficient",
    *_BODY_VECTORS,
)
_MATERIAL_KEYS = (
    "youngs_modulus_pa",
    "shear_modulus_pa",
    "expansion_per_c",
    "youngs_modulus_slope_pa_per_c",
    "shear_modulus_slope_pa_per_c",
    "expansion_slope_per_c2",
    "t_ref_c",
    "t_min_c",
    "t_max_c",
    "name",
)


def _section(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    kind = r.string(t, "kind", path, ("circle", "rectangle", "custom"))
    if kind == "circle":
        r.check_keys(t, path, ("kind", "diameter_m"))
        return Section.circle(r.number(t, "diameter_m", path, positive=True))
    if kind == "rectangle":
        r.check_keys(t, path, ("kind", "width_m", "height_m"))
        return Section.rectangle(
            r.number(t, "width_m", path, positive=True), r.number(t, "height_m", path, positive=True)
        )
    keys = ("area_m2", "ix_m4", "iy_m4", "j_m4")
    r.check_keys(t, path, ("kind", *keys))
    return Section.custom(*(r.number(t, k, path, positive=True) for k in keys))


def _body(r: _Reader, d: Any) -> Any:
    path = ("body",)
    t = r.table(d, path)
    r.check_keys(t, path, _BODY_KEYS)
    kw: dict[str, Any] = {}
    if "poisson" in t and "shear_modulus_pa" in t:
        raise r.error((*path, "shear_modulus_pa"), "give poisson or shear_modulus_pa, not both")
    if "shear_modulus_pa" in t:
        kw["shear_modulus"] = r.number(t, "shear_modulus_pa", path, positive=True)
    else:
        kw["poisson"] = r.number(t, "poisson", path, default=0.5)
    kw["density"] = r.number(t, "density_kg_per_m3", path, default=0.0)
    kw["shear_coefficient"] = r.number(t, "shear_coefficient", path, default=1.0, positive=True)
    for key, arg in _BODY_VECTORS.items():
        v = r.vector(t, key, path)
        if v is not None:
            kw[arg] = v
    if "section" not in t:
        raise r.error((*path, "section"), "missing")
    section = _section(r, t["section"], (*path, "section"))
    try:
        return Body(
            r.number(t, "length_m", path, positive=True),
            section,
            r.number(t, "youngs_modulus_pa", path, positive=True),
            **kw,
        )
    except DesignError:
        raise
    except ValueError as exc:
        raise r.error(path, str(exc)) from None


def _material(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    if d == "silver_coated_nylon":
        return Material.silver_coated_nylon()
    if isinstance(d, str):
        raise r.error(path, f"unknown preset {d!r} (presets: 'silver_coated_nylon'; or give a table)")
    t = r.table(d, path)
    r.check_keys(t, path, _MATERIAL_KEYS)
    e = r.number(t, "youngs_modulus_pa", path, positive=True)
    kw: dict[str, Any] = {
        "youngs_modulus": e,
        "shear_modulus": r.number(t, "shear_modulus_pa", path, positive=True),
        "expansion": r.number(t, "expansion_per_c", path),
        "youngs_modulus_slope": r.number(t, "youngs_modulus_slope_pa_per_c", path, default=0.0),
        "expansion_slope": r.number(t, "expansion_slope_per_c2", path, default=0.0),
        "t_ref": r.number(t, "t_ref_c", path, default=25.0),
        "t_min": r.number(t, "t_min_c", path, default=25.0),
        "t_max": r.number(t, "t_max_c", path, default=160.0),
    }
    if "shear_modulus_slope_pa_per_c" in t:
        kw["shear_modulus_slope"] = r.number(t, "shear_modulus_slope_pa_per_c", path)
    if "name" in t:
        if not isinstance(t["name"], str):
            raise r.error((*path, "name"), "must be a string")
        kw["name"] = t["name"]
    try:
        return Material(**kw)
    except DesignError:
        raise
    except ValueError as exc:
        raise r.error(path, str(exc)) from None


def _tca(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    r.check_keys(
        t,
        path,
        ("coiled_length_m", "fibre_length_m", "alpha0_deg", "coil_diameter_m", "turns", "chirality", "material"),
    )
    chir = r.string(t, "chirality", path, ("extension", "contraction"), default="extension")
    mat = _material(r, t.get("material", "silver_coated_nylon"), (*path, "material"))
    cl = r.number(t, "coiled_length_m", path, positive=True)
    dd = r.number(t, "coil_diameter_m", path, positive=True)
    nn = r.number(t, "turns", path, positive=True)
    if ("fibre_length_m" in t) == ("alpha0_deg" in t):
        raise r.error((*path, "fibre_length_m"), "give exactly one of fibre_length_m and alpha0_deg")
    try:
        if "alpha0_deg" in t:
            return Tca.from_pitch_angle(
                cl,
                math.radians(r.number(t, "alpha0_deg", path, positive=True)),
                dd,
                nn,
                chir,  # type: ignore[arg-type]
                mat,
            )
        return Tca(r.number(t, "fibre_length_m", path, positive=True), cl, dd, nn, chir, mat)  # type: ignore[arg-type]
    except DesignError:
        raise
    except ValueError as exc:
        raise r.error(path, str(exc)) from None


def _routing(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    kind = r.string(t, "kind", path, ("straight", "helix"))
    if kind == "straight":
        r.check_keys(t, path, ("kind", "x_m", "y_m"))
        return Routing.straight(r.number(t, "x_m", path), r.number(t, "y_m", path))
    r.check_keys(t, path, ("kind", "radius_m", "rate_rad_per_m", "phase_rad"))
    return Routing.helix(
        r.number(t, "radius_m", path), r.number(t, "rate_rad_per_m", path), r.number(t, "phase_rad", path, default=0.0)
    )


def _actuator(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    r.check_keys(t, path, ("routing", "s_start_m", "s_end_m", "length_ratio", "tca", "tendon", "name"))
    if ("tca" in t) == ("tendon" in t):
        raise r.error((*path, "tca"), "give exactly one of tca and tendon")
    if "routing" not in t:
        raise r.error((*path, "routing"), "missing")
    routing = _routing(r, t["routing"], (*path, "routing"))
    s_end = r.number(t, "s_end_m", path, positive=True) if "s_end_m" in t else None
    lr = r.number(t, "length_ratio", path, positive=True) if "length_ratio" in t else None
    s_start = r.number(t, "s_start_m", path, default=0.0)
    try:
        if "tendon" in t:
            tp = (*path, "tendon")
            td = r.table(t["tendon"], tp)
            kind = r.string(td, "kind", tp, ("tension", "linear"))
            if kind == "tension":
                r.check_keys(td, tp, ("kind",))
                return Actuator.tendon(routing, s_start, s_end, lr)
            r.check_keys(td, tp, ("kind", "stiffness_n_per_m"))
            return Actuator.linear_tendon(
                r.number(td, "stiffness_n_per_m", tp, positive=True), routing, s_start, s_end, lr
            )
        tca = _tca(r, t["tca"], (*path, "tca"))
        return Actuator.tca(tca, routing, s_start, s_end, lr)
    except DesignError:
        raise
    except ValueError as exc:
        raise r.error(path, str(exc)) from None


def loads_design(text: str, source: str = "<string>") -> Design:
    """Parse a design from TOML ``text`` (``source`` names it in errors)."""
    if not isinstance(text, str):
        raise TypeError(f"text must be a str (TOML), not {type(text).__name__}")
    if not isinstance(source, str):
        raise TypeError(f"source must be a str, not {type(source).__name__}")
    _check_limits(text, source)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise DesignError(source, "", int(m.group(1)) if m else None, f"TOML syntax error: {exc}") from None
    except RecursionError:  # pragma: no cover - _check_limits caps the nesting first
        raise DesignError(source, "", None, f"nested deeper than {MAX_NESTING} levels") from None
    r = _Reader(text, source)
    r.check_keys(doc, (), ("body", "actuators", "temperatures_c"))
    if "body" not in doc:
        raise r.error(("body",), "missing [body] table")
    body = _body(r, doc["body"])
    acts_doc = doc.get("actuators", [])
    if not isinstance(acts_doc, list):
        raise r.error(("actuators",), "must be an array of tables ([[actuators]])")
    if len(acts_doc) > MAX_ACTUATORS:
        raise r.error(("actuators",), f"{len(acts_doc)} actuators, at most {MAX_ACTUATORS} allowed")
    acts = [_actuator(r, a, ("actuators", str(i))) for i, a in enumerate(acts_doc)]
    try:
        robot = Robot(body, acts)
    except DesignError:
        raise
    except ValueError as exc:
        m = re.search(r"actuators\[(\d+)\]\.(s_start|s_end)", str(exc))
        path = ("actuators", m.group(1), f"{m.group(2)}_m") if m else ("actuators",)
        raise r.error(path, str(exc)) from None
    temps: list[float] | None = None
    if "temperatures_c" in doc:
        v = doc["temperatures_c"]
        if not (isinstance(v, list) and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)):
            raise r.error(("temperatures_c",), f"must be a list of numbers [C], got {_short(v)}")
        if len(v) != len(acts):
            raise r.error(("temperatures_c",), f"expected {len(acts)} values (one per actuator), got {len(v)}")
        temps = [_float(x) for x in v]
        for i, (a, x) in enumerate(zip(acts, temps)):
            lo, hi = a.input_bounds
            if not (lo <= x <= hi):
                raise r.error(
                    ("temperatures_c",), f"value {i} = {x} C is outside the material's range {lo:g}..{hi:g} C"
                )
    return Design(robot, temps)


def load_design(path: str | os.PathLike[str]) -> Design:
    """Load a design file (TOML); raises :class:`DesignError` naming the key and line."""
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
    p = Path(path)
    # refuse a huge file before reading it (4 bytes per character at most in UTF-8)
    if p.is_file() and p.stat().st_size > 4 * MAX_DESIGN_CHARS:
        raise DesignError(str(p), "", None, f"file too large: {p.stat().st_size} bytes")
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise DesignError(str(p), "", None, f"not UTF-8 text: {exc.reason} at byte {exc.start}") from None
    except ValueError as exc:  # e.g. an embedded NUL in the path
        raise DesignError(str(p), "", None, f"invalid path: {exc}") from None
    return loads_design(text, str(p))


# --------------------------------------------------------------------------
# Saving
# --------------------------------------------------------------------------


def _material_doc(m: Any) -> Any:
    ref = Material.silver_coated_nylon()
    if m.coefficients == ref.coefficients and (m.t_ref, m.t_min, m.t_max) == (ref.t_ref, ref.t_min, ref.t_max):
        return "silver_coated_nylon"
    e, es, g, gs, rho, rs = m.coefficients
    return {
        "name": m.name,
        "youngs_modulus_pa": e,
        "youngs_modulus_slope_pa_per_c": es,
        "shear_modulus_pa": g,
        "shear_modulus_slope_pa_per_c": gs,
        "expansion_per_c": rho,
        "expansion_slope_per_c2": rs,
        "t_ref_c": m.t_ref,
        "t_min_c": m.t_min,
        "t_max_c": m.t_max,
    }


def _clean(x: float) -> float:
    """The shortest decimal within 4 ulps of ``x`` (derived values such as a
    width recomputed from the section's area carry rounding noise:
    ``0.0024999999999999988`` -> ``0.0025``); ``x`` itself if none is."""
    x = float(x)
    if x == 0.0 or not math.isfinite(x):
        return 0.0 if x == 0.0 else x
    tol = 4.0 * math.ulp(x)
    for digits in range(1, 18):
        c = float(f"{x:.{digits}g}")
        if abs(c - x) <= tol:
            return c
    return x


def _routing_doc(rt: Any) -> dict[str, Any]:
    r0, rp, _ = (list(map(float, v)) for v in rt.evaluate(0.0))
    if rt.kind == "helix":
        radius = math.hypot(r0[0], r0[1])
        phase = math.atan2(r0[1], r0[0])
        rate = (-rp[0] * math.sin(phase) + rp[1] * math.cos(phase)) / radius if radius > 0 else 0.0
        return {"kind": "helix", "radius_m": _clean(radius), "rate_rad_per_m": _clean(rate), "phase_rad": _clean(phase)}
    return {"kind": "straight", "x_m": _clean(r0[0]), "y_m": _clean(r0[1])}


def _section_doc(s: Any) -> dict[str, Any]:
    area, ix, iy, j = s.properties
    if s.kind == "circle":
        return {"kind": "circle", "diameter_m": _clean(math.sqrt(4.0 * area / math.pi))}
    if s.kind == "rectangle":
        # A = w h, Ix = w h^3 / 12, Iy = h w^3 / 12
        return {
            "kind": "rectangle",
            "width_m": _clean(math.sqrt(12.0 * iy / area)),
            "height_m": _clean(math.sqrt(12.0 * ix / area)),
        }
    return {"kind": "custom", "area_m2": area, "ix_m4": ix, "iy_m4": iy, "j_m4": j}


def _round_degrees(alpha0_rad: float) -> float | None:
    """``alpha0`` [deg] if it is a round number (at most 6 significant digits
    after removing rounding noise), else ``None``."""
    deg = _clean(math.degrees(alpha0_rad))
    return deg if len(f"{deg:.17g}".rstrip("0").replace(".", "").replace("-", "").lstrip("0")) <= 6 else None


def _tca_doc(tca: Any) -> dict[str, Any]:
    """A TCA as written: by pitch angle when that rebuilds the same fibre length."""
    doc: dict[str, Any] = {"coiled_length_m": float(tca.coiled_length)}
    deg = _round_degrees(float(tca.alpha0))
    rebuilt = None
    if deg is not None:
        try:
            rebuilt = Tca.from_pitch_angle(
                float(tca.coiled_length),
                math.radians(deg),
                float(tca.coil_diameter),
                float(tca.turns),
                tca.chirality,
                tca.material,
            )
        except ValueError:
            rebuilt = None
    if rebuilt is not None and abs(float(rebuilt.fibre_length) - float(tca.fibre_length)) <= 4.0 * math.ulp(
        float(tca.fibre_length)
    ):
        doc["alpha0_deg"] = deg
    else:
        doc["fibre_length_m"] = float(tca.fibre_length)
    doc.update(
        {
            "coil_diameter_m": float(tca.coil_diameter),
            "turns": float(tca.turns),
            "chirality": tca.chirality,
            "material": _material_doc(tca.material),
        }
    )
    return doc


def _actuator_doc(i: int, a: Any) -> dict[str, Any]:
    entry: dict[str, Any] = {"routing": _routing_doc(a.routing), "s_start_m": float(a.s_start)}
    if math.isfinite(a.s_end):
        entry["s_end_m"] = float(a.s_end)
    if a.length_ratio is not None:
        entry["length_ratio"] = float(a.length_ratio)
    if a.kind == "tca":
        entry["tca"] = _tca_doc(a.tca_model)
    elif a.kind == "tension":
        entry["tendon"] = {"kind": "tension"}
    elif a.kind == "linear_tendon":
        # tension k (pull + elongation): k = tension at unit elongation and no pull
        entry["tendon"] = {"kind": "linear", "stiffness_n_per_m": float(a.tension(1.0, 0.0))}
    else:  # pragma: no cover - every kind of Actuator is listed above
        raise ValueError(f"actuators[{i}]: cannot save an actuator of kind {a.kind!r}")
    return entry


def dumps_design(robot: Any, temperatures_c: Sequence[float] | None = None) -> str:
    """TOML text of ``robot`` and optional inputs (temperatures [C] for TCAs)."""
    import tomli_w

    V.instance("robot", robot, Robot, "a tcarod.Robot")
    b = robot.body
    kw = b.kwargs()
    e_b, g_b = float(kw["youngs_modulus"]), float(kw["shear_modulus"])
    body: dict[str, Any] = {
        "length_m": float(kw["length"]),
        "section": _section_doc(kw["section"]),
        "youngs_modulus_pa": e_b,
    }
    poisson = _clean(e_b / (2.0 * g_b) - 1.0)
    if (
        len(f"{poisson:.17g}".rstrip("0")) <= 8
        and Body(float(kw["length"]), kw["section"], e_b, poisson=poisson).shear_modulus == g_b
    ):
        body["poisson"] = poisson
    else:
        body["shear_modulus_pa"] = g_b
    body["density_kg_per_m3"] = float(kw["density"])
    body["shear_coefficient"] = float(kw["shear_coefficient"])
    for key, arg in _BODY_VECTORS.items():
        v = [float(x) for x in kw[arg]]
        default = [0.0, 0.0, 1.0] if arg == "nu_star" else [0.0, 0.0, 0.0]
        if v != default:
            body[key] = v
    acts = [_actuator_doc(i, a) for i, a in enumerate(robot.actuators)]
    doc: dict[str, Any] = {}
    if temperatures_c is not None:
        doc["temperatures_c"] = V.vector("temperatures_c", temperatures_c, len(acts), "C")
    doc["body"] = body
    doc["actuators"] = acts
    return "# tcarod robot design (SI units; see tcarod.design)\n" + tomli_w.dumps(doc)


def save_design(path: str | os.PathLike[str], robot: Any, temperatures_c: Sequence[float] | None = None) -> Path:
    """Write ``robot`` (and optional temperatures [C]) as a design file; return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(dumps_design(robot, temperatures_c), encoding="utf-8")
    return p
