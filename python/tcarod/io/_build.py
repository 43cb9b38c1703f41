"""From the parsed TOML of a design file to tcarod objects: section, body,
material, TCA, routing and actuator tables, each key checked (unknown keys are
errors) with :class:`~tcarod.io._toml.DesignError` naming the key and line."""

from __future__ import annotations

import math
from typing import Any

from ..rod import Actuator, Body, Routing, Section
from ..tca import Material, Tca
from ._toml import DesignError, _Reader

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
            alpha0 = math.radians(r.number(t, "alpha0_deg", path, positive=True))
            return Tca.from_pitch_angle(cl, alpha0, dd, nn, chir, mat)  # type: ignore[arg-type]
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
