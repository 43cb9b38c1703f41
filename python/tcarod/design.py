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

Unknown keys are errors (a typo must not be silently ignored).
"""

from __future__ import annotations

import math
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

from .rod import Actuator, Body, Robot, Routing, Section
from .tca import Material, Tca

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

__all__ = ["Design", "DesignError", "load_design", "loads_design", "save_design", "dumps_design"]


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

_HEADER = re.compile(r"^\s*(\[\[?)\s*([^\]]+?)\s*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"^\s*([A-Za-z0-9_\-\.\"' ]+?)\s*=")


def _key_lines(text: str) -> list[tuple[tuple[str, ...], int]]:
    """``(path, line)`` of every table header and key in ``text``; array-of-tables
    entries carry their index (``("actuators", "1", "tca", "turns")``)."""
    out: list[tuple[tuple[str, ...], int]] = []
    counts: dict[tuple[str, ...], int] = {}
    current: tuple[str, ...] = ()
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        m = _HEADER.match(line)
        if m and not _KEY.match(line):
            parts = tuple(p.strip().strip("\"'") for p in m.group(2).split("."))
            if m.group(1) == "[[":
                counts[parts] = counts.get(parts, -1) + 1
                current = (*parts[:-1], parts[-1], str(counts[parts]))
            else:
                # sub-table of the latest array entry: [actuators.tca] -> actuators.<i>.tca
                resolved: list[str] = []
                for k, p in enumerate(parts):
                    resolved.append(p)
                    arr = tuple(parts[: k + 1])
                    if arr in counts:
                        resolved.append(str(counts[arr]))
                current = tuple(resolved)
            out.append((current, n))
            continue
        km = _KEY.match(line)
        if km:
            key = tuple(p.strip().strip("\"'") for p in km.group(1).split("."))
            out.append(((*current, *key), n))
    return out


def _line_of(text: str, path: tuple[str, ...]) -> int | None:
    """Line of ``path`` or, failing that, of its longest present prefix."""
    entries = _key_lines(text)
    for k in range(len(path), 0, -1):
        for p, n in entries:
            if p == path[:k]:
                return n
    return None


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

    def error(self, path: tuple[str, ...], problem: str) -> DesignError:
        return DesignError(self.source, _dotted(path), _line_of(self.text, path), problem)

    def table(self, d: Any, path: tuple[str, ...]) -> dict[str, Any]:
        if not isinstance(d, dict):
            raise self.error(path, f"must be a table, got {type(d).__name__}")
        return d

    def check_keys(self, d: dict[str, Any], path: tuple[str, ...], allowed: Sequence[str]) -> None:
        for k in d:
            if k not in allowed:
                raise self.error((*path, k), f"unknown key (allowed: {', '.join(allowed)})")

    def number(self, d: dict[str, Any], key: str, path: tuple[str, ...], default: float | None = None,
               positive: bool = False) -> float:
        if key not in d:
            if default is None:
                raise self.error((*path, key), "missing")
            return default
        v = d[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.error((*path, key), f"must be a number, got {v!r}")
        x = float(v)
        if not math.isfinite(x):
            raise self.error((*path, key), f"must be finite, got {v!r}")
        if positive and x <= 0.0:
            raise self.error((*path, key), f"must be > 0, got {v!r}")
        return x

    def vector(self, d: dict[str, Any], key: str, path: tuple[str, ...]) -> list[float] | None:
        if key not in d:
            return None
        v = d[key]
        if not (isinstance(v, list) and len(v) == 3 and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)):
            raise self.error((*path, key), f"must be a list of 3 numbers, got {v!r}")
        if not all(math.isfinite(float(x)) for x in v):
            raise self.error((*path, key), f"must be finite, got {v!r}")
        return [float(x) for x in v]

    def string(self, d: dict[str, Any], key: str, path: tuple[str, ...], choices: Sequence[str], default: str | None = None) -> str:
        if key not in d:
            if default is None:
                raise self.error((*path, key), "missing")
            return default
        v = d[key]
        if v not in choices:
            raise self.error((*path, key), f"must be one of {', '.join(map(repr, choices))}, got {v!r}")
        return str(v)


_BODY_VECTORS = {
    "gravity_m_per_s2": "gravity",
    "nu_star": "nu_star",
    "omega_star_per_m": "omega_star",
    "distributed_force_n_per_m": "distributed_force",
    "distributed_moment_nm_per_m": "distributed_moment",
    "tip_force_n": "tip_force",
    "tip_moment_nm": "tip_moment",
}
_BODY_KEYS = ("length_m", "section", "youngs_modulus_pa", "poisson", "shear_modulus_pa", "density_kg_per_m3",
              "shear_coefficient", *_BODY_VECTORS)
_MATERIAL_KEYS = ("youngs_modulus_pa", "shear_modulus_pa", "expansion_per_c", "youngs_modulus_slope_pa_per_c",
                  "shear_modulus_slope_pa_per_c", "expansion_slope_per_c2", "t_ref_c", "t_min_c", "t_max_c", "name")


def _section(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    kind = r.string(t, "kind", path, ("circle", "rectangle", "custom"))
    if kind == "circle":
        r.check_keys(t, path, ("kind", "diameter_m"))
        return Section.circle(r.number(t, "diameter_m", path, positive=True))
    if kind == "rectangle":
        r.check_keys(t, path, ("kind", "width_m", "height_m"))
        return Section.rectangle(r.number(t, "width_m", path, positive=True), r.number(t, "height_m", path, positive=True))
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
        return Body(r.number(t, "length_m", path, positive=True), section,
                    r.number(t, "youngs_modulus_pa", path, positive=True), **kw)
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
    r.check_keys(t, path, ("coiled_length_m", "fibre_length_m", "alpha0_deg", "coil_diameter_m", "turns", "chirality", "material"))
    chir = r.string(t, "chirality", path, ("extension", "contraction"), default="extension")
    mat = _material(r, t.get("material", "silver_coated_nylon"), (*path, "material"))
    cl = r.number(t, "coiled_length_m", path, positive=True)
    dd = r.number(t, "coil_diameter_m", path, positive=True)
    nn = r.number(t, "turns", path, positive=True)
    if ("fibre_length_m" in t) == ("alpha0_deg" in t):
        raise r.error((*path, "fibre_length_m"), "give exactly one of fibre_length_m and alpha0_deg")
    try:
        if "alpha0_deg" in t:
            return Tca.from_pitch_angle(cl, math.radians(r.number(t, "alpha0_deg", path, positive=True)), dd, nn, chir, mat)  # type: ignore[arg-type]
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
    return Routing.helix(r.number(t, "radius_m", path), r.number(t, "rate_rad_per_m", path), r.number(t, "phase_rad", path, default=0.0))


def _actuator(r: _Reader, d: Any, path: tuple[str, ...]) -> Any:
    t = r.table(d, path)
    r.check_keys(t, path, ("routing", "s_start_m", "s_end_m", "length_ratio", "tca", "name"))
    if "tca" not in t:
        raise r.error((*path, "tca"), "missing (only TCA actuators can be described in a design file)")
    if "routing" not in t:
        raise r.error((*path, "routing"), "missing")
    routing = _routing(r, t["routing"], (*path, "routing"))
    tca = _tca(r, t["tca"], (*path, "tca"))
    s_end = r.number(t, "s_end_m", path, positive=True) if "s_end_m" in t else None
    lr = r.number(t, "length_ratio", path, positive=True) if "length_ratio" in t else None
    try:
        return Actuator.tca(tca, routing, r.number(t, "s_start_m", path, default=0.0), s_end, lr)
    except DesignError:
        raise
    except ValueError as exc:
        raise r.error(path, str(exc)) from None


def loads_design(text: str, source: str = "<string>") -> Design:
    """Parse a design from TOML ``text`` (``source`` names it in errors)."""
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        raise DesignError(source, "", int(m.group(1)) if m else None, f"TOML syntax error: {exc}") from None
    r = _Reader(text, source)
    r.check_keys(doc, (), ("body", "actuators", "temperatures_c"))
    if "body" not in doc:
        raise r.error(("body",), "missing [body] table")
    body = _body(r, doc["body"])
    acts_doc = doc.get("actuators", [])
    if not isinstance(acts_doc, list):
        raise r.error(("actuators",), "must be an array of tables ([[actuators]])")
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
            raise r.error(("temperatures_c",), f"must be a list of numbers [C], got {v!r}")
        if len(v) != len(acts):
            raise r.error(("temperatures_c",), f"expected {len(acts)} values (one per actuator), got {len(v)}")
        temps = [float(x) for x in v]
        for i, (a, x) in enumerate(zip(acts, temps)):
            lo, hi = a.input_bounds
            if not (lo <= x <= hi):
                raise r.error(("temperatures_c",), f"value {i} = {x} C is outside the material's range {lo:g}..{hi:g} C")
    return Design(robot, temps)


def load_design(path: str | os.PathLike[str]) -> Design:
    """Load a design file (TOML); raises :class:`DesignError` naming the key and line."""
    p = Path(path)
    return loads_design(p.read_text(encoding="utf-8"), str(p))


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


def _routing_doc(rt: Any) -> dict[str, Any]:
    r0, rp, _ = (list(map(float, v)) for v in rt.evaluate(0.0))
    if rt.kind == "helix":
        radius = math.hypot(r0[0], r0[1])
        phase = math.atan2(r0[1], r0[0])
        rate = (-rp[0] * math.sin(phase) + rp[1] * math.cos(phase)) / radius if radius > 0 else 0.0
        return {"kind": "helix", "radius_m": radius, "rate_rad_per_m": rate, "phase_rad": phase}
    return {"kind": "straight", "x_m": r0[0], "y_m": r0[1]}


def _section_doc(s: Any) -> dict[str, Any]:
    area, ix, iy, j = s.properties
    if s.kind == "circle":
        return {"kind": "circle", "diameter_m": math.sqrt(4.0 * area / math.pi)}
    if s.kind == "rectangle":
        # A = w h, Ix = w h^3 / 12, Iy = h w^3 / 12
        return {"kind": "rectangle", "width_m": math.sqrt(12.0 * iy / area), "height_m": math.sqrt(12.0 * ix / area)}
    return {"kind": "custom", "area_m2": area, "ix_m4": ix, "iy_m4": iy, "j_m4": j}


def dumps_design(robot: Any, temperatures_c: Sequence[float] | None = None) -> str:
    """TOML text of ``robot`` (TCA actuators only) and optional temperatures [C]."""
    import tomli_w

    b = robot.body
    kw = b.kwargs()
    body: dict[str, Any] = {
        "length_m": float(kw["length"]),
        "section": _section_doc(kw["section"]),
        "youngs_modulus_pa": float(kw["youngs_modulus"]),
        "shear_modulus_pa": float(kw["shear_modulus"]),
        "density_kg_per_m3": float(kw["density"]),
        "shear_coefficient": float(kw["shear_coefficient"]),
    }
    for key, arg in _BODY_VECTORS.items():
        v = [float(x) for x in kw[arg]]
        default = [0.0, 0.0, 1.0] if arg == "nu_star" else [0.0, 0.0, 0.0]
        if v != default:
            body[key] = v
    acts: list[dict[str, Any]] = []
    for i, a in enumerate(robot.actuators):
        tca = a.tca_model
        if tca is None:
            raise ValueError(f"actuators[{i}]: only TCA actuators can be saved in a design file, not {a.kind!r}")
        entry: dict[str, Any] = {"routing": _routing_doc(a.routing), "s_start_m": float(a.s_start)}
        if math.isfinite(a.s_end):
            entry["s_end_m"] = float(a.s_end)
        if a.length_ratio is not None:
            entry["length_ratio"] = float(a.length_ratio)
        entry["tca"] = {
            "coiled_length_m": float(tca.coiled_length),
            "fibre_length_m": float(tca.fibre_length),
            "coil_diameter_m": float(tca.coil_diameter),
            "turns": float(tca.turns),
            "chirality": tca.chirality,
            "material": _material_doc(tca.material),
        }
        acts.append(entry)
    doc: dict[str, Any] = {}
    if temperatures_c is not None:
        doc["temperatures_c"] = [float(t) for t in temperatures_c]
    doc["body"] = body
    doc["actuators"] = acts
    return "# tcarod robot design (SI units; see tcarod.design)\n" + tomli_w.dumps(doc)


def save_design(path: str | os.PathLike[str], robot: Any, temperatures_c: Sequence[float] | None = None) -> Path:
    """Write ``robot`` (and optional temperatures [C]) as a design file; return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(dumps_design(robot, temperatures_c), encoding="utf-8")
    return p
