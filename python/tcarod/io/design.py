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

Unknown keys are errors (a typo must not be silently ignored). Values that
are valid but look like another unit warn with ``tcarod.UnitsWarning``,
naming file, line and key: a key ending in ``_m`` above 10 (metres, not
millimetres), a ``temperatures_c`` entry above 273 (Celsius, not Kelvin).

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
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

from .. import _validate as V
from ..rod import Body, Robot
from ..tca import Material, Tca

from ._build import _BODY_VECTORS, _actuator, _body
from .._optional import require
from ._toml import (
    MAX_ACTUATORS,
    MAX_DESIGN_CHARS,
    MAX_NESTING,
    DesignError,
    _check_limits,
    _float,
    _Reader,
    _short,
    _tomllib,
)


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


def loads_design(text: str, source: str = "<string>") -> Design:
    """Parse a design from TOML ``text`` (``source`` names it in errors)."""
    if not isinstance(text, str):
        raise TypeError(f"text must be a str (TOML), not {type(text).__name__}")
    if not isinstance(source, str):
        raise TypeError(f"source must be a str, not {type(source).__name__}")
    _check_limits(text, source)
    toml = _tomllib()
    try:
        doc = toml.loads(text)
    except toml.TOMLDecodeError as exc:
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
        hot = [x for x in temps if math.isfinite(x) and x > V.KELVIN_LOOKING_C]
        if hot:
            r.warn_units(
                ("temperatures_c",),
                f"= {hot[0]:g}: temperatures are in degrees Celsius; did you give Kelvin? (25 C is 298.15 K)",
            )
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
    tomli_w = require("tomli_w")
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
        # a weightless body with a density says so: zero gravity is written
        # (read back without it, the density would warn of a missing gravity)
        weightless = arg == "gravity" and float(kw["density"]) > 0.0
        if v != default or weightless:
            body[key] = v
    acts = [_actuator_doc(i, a) for i, a in enumerate(robot.actuators)]
    doc: dict[str, Any] = {}
    if temperatures_c is not None:
        doc["temperatures_c"] = V.vector("temperatures_c", temperatures_c, len(acts), "C")
    doc["body"] = body
    doc["actuators"] = acts
    toml_text: str = tomli_w.dumps(doc)
    return "# tcarod robot design (SI units; see tcarod.io.design)\n" + toml_text


def save_design(path: str | os.PathLike[str], robot: Any, temperatures_c: Sequence[float] | None = None) -> Path:
    """Write ``robot`` (and optional temperatures [C]) as a design file; return the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(dumps_design(robot, temperatures_c), encoding="utf-8")
    return p
