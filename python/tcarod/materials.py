"""Body materials: nominal properties of common casting silicones.

``tcarod.Material`` is the TCA's fibre; the soft body's material is given to
:class:`tcarod.Body` as Young's modulus [Pa], Poisson ratio [-] and density
[kg/m^3]. This module lists catalogued silicones (Ecoflex 00-10, 00-30,
00-50, Dragon Skin 10, 20, 30, Sylgard 184) whose values
:meth:`tcarod.Body.from_material` uses::

    body = tcarod.Body.from_material("ecoflex-00-30", 0.060, tcarod.Section.rectangle(12e-3, 12e-3))

The catalogue is defined once, in the core (``src/python/rod/body.rs``);
:func:`body_materials` presents it as :class:`BodyMaterial` records.

Which modulus: the model needs the small-strain (initial) Young's modulus.
The manufacturers' technical bulletins give Shore hardness, specific gravity
and the *100 % modulus* (stress at 100 % elongation), a secant modulus at
large strain. For Ecoflex 00-30, 00-50 and Dragon Skin 10, 20, 30 the
small-strain modulus is the incompressible neo-Hookean one through that
point, ``E = (12/7) x 100 % modulus``. Ecoflex 00-10 takes the modulus the
paper (Pawlowski et al. 2019, Section V) uses for its EcoFlex 10 bodies,
37.8 kPa, the value of the paper's fixtures; Sylgard 184 the tensile modulus
measured by Johnston et al. 2014 for room-temperature cure. Poisson ratio
0.5 (silicone rubber is nearly incompressible); density is the bulletins'
specific gravity.

Sources:

* Smooth-On, *Ecoflex Series* technical bulletin; Smooth-On, *Dragon Skin
  Series* technical bulletin (specific gravity, Shore hardness, 100 % modulus).
* M. Pawlowski, J. Sun, J. Xu, Y. Liu, J. Zhao, "Modeling of Soft Robots
  Actuated by Twisted-and-Coiled Actuators", IEEE/ASME Trans. Mechatronics
  24(1), 2019, Section V (EcoFlex 10: 37.8 kPa, 1040 kg/m^3).
* I. D. Johnston, D. K. McCluskey, C. K. L. Tan, M. C. Tracey, "Mechanical
  characterization of bulk Sylgard 184 for microfluidics and
  microengineering", J. Micromech. Microeng. 24, 035017, 2014 (1.32 MPa
  cured at 25 C, up to 2.97 MPa cured at 200 C).
* Dow, *SYLGARD 184 Silicone Elastomer* technical data sheet (specific
  gravity, Shore A hardness).

These are nominal values. Silicone moduli vary by tens of percent with the
mixing ratio, degassing, cure temperature and time, and age (published small-
strain moduli of one grade span a factor of two or more), so a modulus
identified from a test of your own samples (a cantilever under its weight, a
tensile test at small strain) should replace the preset's:
``Body.from_material(name, length, section, youngs_modulus=E_identified)``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

from . import _core
from .rod import Body, Section

__all__ = ["BodyMaterial", "body_material", "body_materials"]


@dataclass(frozen=True)
class BodyMaterial:
    """One catalogued silicone: nominal properties with their sources, SI units.

    A row of the core's catalogue (``tcarod.Body.materials()``).

    Attributes
    ----------
    name : str
        Key for :meth:`tcarod.Body.from_material`, e.g. ``"ecoflex-00-30"``.
    label : str
        Trade name, e.g. ``"Ecoflex 00-30"``.
    youngs_modulus_pa : float
        Small-strain (initial) Young's modulus [Pa], the value the model uses.
    modulus_basis : str
        Which modulus ``youngs_modulus_pa`` is and how it was obtained.
    modulus_100_pa : float or None
        The technical bulletin's 100 % modulus (stress at 100 % elongation)
        [Pa]; ``None`` where the manufacturer publishes none.
    shore_hardness : str
        Shore hardness (``"00-30"``: Shore 00 scale, ``"10A"``: Shore A).
    poisson : float
        Poisson ratio [-].
    density_kg_per_m3 : float
        Density [kg/m^3] (specific gravity x 1000).
    sources : str
        The publications and technical bulletins the values come from.

    Examples
    --------
    >>> from tcarod import body_material
    >>> m = body_material("Dragon Skin 10")
    >>> m.label, m.shore_hardness, round(m.youngs_modulus_pa / 1e3)   # [kPa]
    ('Dragon Skin 10', '10A', 260)
    """

    name: str
    label: str
    youngs_modulus_pa: float
    modulus_basis: str
    modulus_100_pa: Optional[float]
    shore_hardness: str
    poisson: float
    density_kg_per_m3: float
    sources: str

    def body(self, length_m: float, section: Section, **kwargs: Any) -> Body:
        """A :class:`tcarod.Body` of this material.

        See :meth:`tcarod.Body.from_material`.

        Parameters
        ----------
        length_m : float
            Length of the centre line [m].
        section : Section
            Cross-section (sizes in m).
        **kwargs
            Other keywords of :class:`tcarod.Body` (``gravity`` [m/s^2], ...);
            ``youngs_modulus`` [Pa] replaces the nominal modulus.

        Returns
        -------
        Body
            The body, with this material's modulus [Pa], Poisson ratio [-]
            and density [kg/m^3] unless replaced.

        Examples
        --------
        >>> from tcarod import Section, body_material
        >>> ecoflex = body_material("ecoflex-00-30")
        >>> body = ecoflex.body(0.060, Section.circle(0.012), youngs_modulus=70e3, gravity=(0, 0, -9.81))
        >>> body.youngs_modulus, body.density        # [Pa], [kg/m^3]
        (70000.0, 1070.0)
        """
        return Body.from_material(self.name, length_m, section, **kwargs)


def _record(row: dict[str, Any]) -> BodyMaterial:
    return BodyMaterial(
        name=row["name"],
        label=row["label"],
        youngs_modulus_pa=float(row["youngs_modulus"]),
        modulus_basis=row["modulus_basis"],
        modulus_100_pa=None if row["modulus_100"] is None else float(row["modulus_100"]),
        shore_hardness=row["shore_hardness"],
        poisson=float(row["poisson"]),
        density_kg_per_m3=float(row["density"]),
        sources=row["sources"],
    )


def body_materials() -> dict[str, BodyMaterial]:
    """The catalogued silicones by name, softest Ecoflex first.

    Returns
    -------
    dict of str to BodyMaterial
        Nominal values with their sources; see the module docstring for which
        modulus each is.

    Examples
    --------
    >>> from tcarod import body_materials
    >>> m = body_materials()["ecoflex-00-30"]
    >>> round(m.youngs_modulus_pa / 1e3, 1), m.density_kg_per_m3, m.poisson  # [kPa], [kg/m^3], [-]
    (118.2, 1070.0, 0.5)
    >>> list(body_materials())
    ['ecoflex-00-10', 'ecoflex-00-30', 'ecoflex-00-50', 'dragon-skin-10', 'dragon-skin-20', 'dragon-skin-30', 'sylgard-184']
    """
    return {row["name"]: _record(row) for row in _core.Body.materials()}


def body_material(name: str) -> BodyMaterial:
    """The catalogued silicone ``name`` (case, spaces and underscores ignored).

    Parameters
    ----------
    name : str
        A key of :func:`body_materials`, e.g. ``"Dragon Skin 10"`` or ``"dragon-skin-10"``.

    Returns
    -------
    BodyMaterial
        Its nominal modulus [Pa], Poisson ratio [-], density [kg/m^3] and
        sources.

    Raises
    ------
    TypeError
        If ``name`` is not a str.
    ValueError
        If ``name`` is not catalogued (the message lists the known names).

    Examples
    --------
    >>> from tcarod import body_material
    >>> body_material("ecoflex_00_10").youngs_modulus_pa     # [Pa], the paper's EcoFlex 10
    37800.0
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, not {type(name).__name__}")
    catalogue = body_materials()
    key = name.strip().lower().replace(" ", "-").replace("_", "-")
    if key not in catalogue:
        raise ValueError(f"invalid name: {name!r} is not a catalogued body material; known: {', '.join(catalogue)}")
    return catalogue[key]
