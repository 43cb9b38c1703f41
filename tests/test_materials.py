"""Body-material presets: values, sources, ``Body.from_material`` and its errors."""

from __future__ import annotations

import doctest
import re
from pathlib import Path

import pytest

import tcarod
from tcarod import Body, Section, body_material, body_materials
from tcarod import materials as materials_module
from tcarod.models.manipulators import ECOFLEX10_DENSITY_KG_PER_M3, ECOFLEX10_YOUNGS_MODULUS_PA

PSI = 6894.757293168
SECTION = Section.rectangle(12e-3, 12e-3)
EXPECTED = {
    "ecoflex-00-10",
    "ecoflex-00-30",
    "ecoflex-00-50",
    "dragon-skin-10",
    "dragon-skin-20",
    "dragon-skin-30",
    "sylgard-184",
}


def test_catalogue_lists_every_silicone_once_in_stiffness_order() -> None:
    cat = body_materials()
    assert set(cat) == EXPECTED
    assert all(m.name == name for name, m in cat.items())
    # Ecoflex < Dragon Skin < Sylgard, each family softest grade first
    moduli = [m.youngs_modulus_pa for m in cat.values()]
    assert moduli == sorted(moduli)


def test_values_follow_the_bulletins_and_the_papers() -> None:
    cat = body_materials()
    # bulletin 100 % moduli [psi] and specific gravities
    bulletin = {
        "ecoflex-00-10": (8.0, 1040.0),
        "ecoflex-00-30": (10.0, 1070.0),
        "ecoflex-00-50": (12.0, 1070.0),
        "dragon-skin-10": (22.0, 1070.0),
        "dragon-skin-20": (49.0, 1080.0),
        "dragon-skin-30": (86.0, 1080.0),
    }
    for name, (psi, rho) in bulletin.items():
        m = cat[name]
        assert m.modulus_100_pa == pytest.approx(psi * PSI, rel=1e-12), name
        assert m.density_kg_per_m3 == rho, name
    # neo-Hookean small-strain modulus through the 100 % point: E = (12/7) sigma_100
    for name in ("ecoflex-00-30", "ecoflex-00-50", "dragon-skin-10", "dragon-skin-20", "dragon-skin-30"):
        m = cat[name]
        assert m.modulus_100_pa is not None
        assert m.youngs_modulus_pa == pytest.approx(12.0 / 7.0 * m.modulus_100_pa, rel=1e-12), name
        assert "neo-Hookean" in m.modulus_basis and "100 %" in m.modulus_basis
    assert cat["ecoflex-00-30"].youngs_modulus_pa == pytest.approx(118.2e3, abs=0.1e3)
    # Ecoflex 00-10 is the paper's EcoFlex 10, the value of the fixtures (one number, not two)
    e10 = cat["ecoflex-00-10"]
    assert e10.youngs_modulus_pa == ECOFLEX10_YOUNGS_MODULUS_PA == 37.8e3
    assert e10.density_kg_per_m3 == ECOFLEX10_DENSITY_KG_PER_M3
    # Sylgard 184: Johnston et al. 2014, room-temperature cure; no 100 % modulus published
    s184 = cat["sylgard-184"]
    assert s184.youngs_modulus_pa == 1.32e6 and s184.modulus_100_pa is None and s184.density_kg_per_m3 == 1030.0
    for m in cat.values():
        assert m.poisson == 0.5
        assert m.shore_hardness and m.label


def test_every_material_names_its_sources() -> None:
    cat = body_materials()
    for name in ("ecoflex-00-30", "ecoflex-00-50"):
        assert "Ecoflex Series technical bulletin" in cat[name].sources
    for name in ("dragon-skin-10", "dragon-skin-20", "dragon-skin-30"):
        assert "Dragon Skin Series technical bulletin" in cat[name].sources
    assert "Pawlowski" in cat["ecoflex-00-10"].sources and "Section V" in cat["ecoflex-00-10"].sources
    assert "Johnston" in cat["sylgard-184"].sources and "SYLGARD 184" in cat["sylgard-184"].sources
    # the module docstring cites every source the catalogue names
    doc = materials_module.__doc__ or ""
    for cited in ("Ecoflex Series", "Dragon Skin", "Pawlowski", "Johnston", "SYLGARD 184", "nominal"):
        assert cited in doc, cited


def test_from_material_builds_the_preset_body() -> None:
    body = Body.from_material("ecoflex-00-30", 0.060, SECTION, gravity=(0.0, 0.0, -9.81))
    m = body_material("ecoflex-00-30")
    assert body.youngs_modulus == m.youngs_modulus_pa
    assert body.density == m.density_kg_per_m3
    assert body.shear_modulus == pytest.approx(m.youngs_modulus_pa / 3.0)  # nu = 0.5
    assert body.length == 0.060 and body.section == SECTION
    assert body.gravity.tolist() == [0.0, 0.0, -9.81]
    # the same body as typed out by hand, and through the record
    by_hand = Body(0.060, SECTION, m.youngs_modulus_pa, poisson=0.5, density=1070.0, gravity=(0.0, 0.0, -9.81))
    assert body == by_hand
    assert m.body(0.060, SECTION, gravity=(0.0, 0.0, -9.81)) == body


def test_from_material_accepts_trade_names_and_an_identified_modulus() -> None:
    up = (0.0, 0.0, -9.81)  # [m/s^2]
    a = Body.from_material("Dragon Skin 10", 0.05, SECTION, gravity=up)
    assert (
        a
        == Body.from_material("dragon_skin_10", 0.05, SECTION, gravity=up)
        == Body.from_material("dragon-skin-10", 0.05, SECTION, gravity=up)
    )
    identified = Body.from_material("ecoflex-00-30", 0.06, SECTION, youngs_modulus=70e3, gravity=up)
    assert identified.youngs_modulus == 70e3 and identified.density == 1070.0
    g = Body.from_material("ecoflex-00-30", 0.06, SECTION, shear_modulus=20e3, gravity=up)
    assert g.shear_modulus == 20e3


def test_unknown_material_lists_the_known_ones() -> None:
    with pytest.raises(ValueError, match="ecoflex-00-30") as info:
        Body.from_material("ecoflex-00-99", 0.06, SECTION)
    for name in EXPECTED:
        assert name in str(info.value)
    assert "name" in str(info.value)
    with pytest.raises(ValueError, match="dragon-skin-20"):
        body_material("silicone")


def test_from_material_bad_arguments() -> None:
    with pytest.raises(TypeError):
        Body.from_material(30, 0.06, SECTION)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        body_material(None)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="length"):
        Body.from_material("ecoflex-00-30", -0.06, SECTION)
    with pytest.raises(TypeError, match="length"):
        Body.from_material("ecoflex-00-30", 0.06, SECTION, length=0.1)  # type: ignore[misc]
    with pytest.raises(TypeError):
        Body.from_material("ecoflex-00-30", 0.06, SECTION, colour="blue")


def test_top_level_exports_and_docstring_examples() -> None:
    assert tcarod.body_materials is body_materials and "BodyMaterial" in tcarod.__all__
    result = doctest.testmod(materials_module, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


def test_docs_table_matches_the_catalogue() -> None:
    """The table of docs/model.md shows the catalogue's values (in kPa and kg/m^3)."""
    page = (Path(__file__).resolve().parent.parent / "docs" / "model.md").read_text(encoding="utf-8")
    rows = {m.group(1): m for m in re.finditer(r"^\| `([a-z0-9-]+)` \| [^|]+ \| ([0-9.]+) \| ([0-9]+) \|", page, re.M)}
    assert set(rows) == EXPECTED
    for name, m in body_materials().items():
        assert float(rows[name].group(2)) == pytest.approx(m.youngs_modulus_pa / 1e3, abs=0.05), name
        assert float(rows[name].group(3)) == m.density_kg_per_m3, name
