"""The Fig. 5 fixture (paper Section V-A) and its prediction."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from tcarod import Tca
from tcarod.paper import REGISTRY
from tcarod.paper._common import GRAVITY_M_PER_S2, onset_temperature_c
from tcarod.paper.fig5 import FIG5, Fig5Result, predict_fig5

RESULT = predict_fig5()


def test_fixture_matches_the_paper() -> None:
    # Section V-A, with l and L un-swapped (docs/choices.md, "l and L are swapped in Section V-A's text")
    three, four = FIG5.tcas
    assert (three.threads, three.coiled_length_m, three.fibre_length_m, three.coil_diameter_m, three.turns) == (
        3,
        0.110,
        0.497,
        2.0e-3,
        300.0,
    )
    assert (four.threads, four.coiled_length_m, four.fibre_length_m, four.coil_diameter_m, four.turns) == (
        4,
        0.110,
        0.471,
        2.13e-3,
        259.0,
    )
    assert [(w.mass_kg, w.friction_equivalent_kg) for w in FIG5.loads] == [(5e-3, 2.5e-3), (10e-3, 5e-3)]
    assert FIG5.temperatures_c == tuple(float(t) for t in range(25, 161, 5))
    assert len(FIG5.temperatures_c) == 28
    assert GRAVITY_M_PER_S2 == 9.81
    # The paper prints no numeric data for Fig. 5: recorded, not invented.
    assert FIG5.published_data is None
    assert "no numeric data" in FIG5.published_data_note


def test_load_sharing_half_tca_and_force() -> None:
    for case in FIG5.cases:
        whole = case.tca.build()
        half = case.half_tca()
        # Folding halves the coils and turns but keeps the pitch angle and the
        # fibre diameter (exact up to rounding of l/2, L/2: 1e-14 relative).
        assert half.alpha0 == pytest.approx(whole.alpha0, rel=1e-14)
        assert half.d0 == pytest.approx(whole.d0, rel=1e-14)
        assert half.n_coils == pytest.approx(whole.n_coils / 2, rel=1e-14)
        assert half.turns == whole.turns / 2
        assert half.coiled_length == pytest.approx(0.055, rel=1e-14)
        # Each half carries half the weight of (mass + friction equivalent), compressive.
        expected = -0.5 * (case.load.mass_kg + case.load.friction_equivalent_kg) * 9.81
        assert case.force_per_half_n == pytest.approx(expected, rel=1e-15)
        assert case.force_per_half_n < 0


def test_every_case_has_an_onset_in_range() -> None:
    assert len(RESULT.curves) == 4
    for c in RESULT.curves:
        assert c.onset_temperature_c is not None, c.case.label
        assert 25.0 < c.onset_temperature_c < 160.0
        half = c.case.half_tca()
        f = c.case.force_per_half_n
        # the coils really are closed just below the onset and open above it
        # (0.1 C is 1e9 times Brent's 1e-10 C temperature tolerance)
        assert half.displacement(f, c.onset_temperature_c - 0.1) == 0.0
        assert half.displacement(f, c.onset_temperature_c + 0.1) > 0.0


def test_heavier_load_starts_later_and_moves_less() -> None:
    by_tca: dict[str, list] = {}
    for c in RESULT.curves:
        by_tca.setdefault(c.case.tca.label, []).append(c)
    assert sorted(by_tca) == ["3 threads", "4 threads"]
    for light, heavy in by_tca.values():
        assert heavy.case.load.effective_mass_kg > light.case.load.effective_mass_kg
        assert heavy.onset_temperature_c > light.onset_temperature_c
        # never more displacement under the heavier load; strictly less once the
        # lighter one has moved (differences are ~1e-4 m, far above 1e-15 m)
        assert np.all(heavy.displacements_m <= light.displacements_m)
        moving = light.displacements_m > 0
        assert np.all(heavy.displacements_m[moving] < light.displacements_m[moving])


def test_curves_start_at_zero_and_rise() -> None:
    for c in RESULT.curves:
        d = c.displacements_m
        assert d[0] == 0.0  # 25 C: no expansion, compressive load, coils closed
        assert np.all(np.diff(d) >= 0.0)
        assert np.all(np.diff(d[d > 0]) > 0.0)


def test_final_displacement_is_positive_and_below_straight_fibre_limit() -> None:
    for c in RESULT.curves:
        assert c.final_temperature_c == 160.0
        d = c.displacement_at_final_temperature_m
        limit = c.straight_fibre_limit_m
        # the same quantity, computed by the same function: exact (rel=0)
        assert limit == pytest.approx(c.case.half_tca().max_displacement, rel=0)
        assert 0.0 < d < limit
        # millimetres to centimetres, as the paper's TCAs move (a loose sanity
        # bound: an error in units or load sharing would leave it)
        assert 1e-3 < d < 5e-2


def test_onset_helper_returns_none_outside_range() -> None:
    half = FIG5.cases[0].half_tca()
    assert onset_temperature_c(half, -50.0) is None  # never opens by 160 C
    assert onset_temperature_c(half, 0.01) is None  # open already at 25 C (tension)
    # inside the range it is the law's own onset: exact (abs=0)
    assert onset_temperature_c(half, -0.03) == pytest.approx(half.onset_temperature(-0.03), abs=0)


def test_registry_and_result_interface() -> None:
    assert "fig5" in REGISTRY
    result = REGISTRY["fig5"]()
    assert isinstance(result, Fig5Result)
    assert result.name == "fig5"
    table = result.table()
    assert "onset temperature [C]" in table and "displacement at 160 C [mm]" in table
    for c in result.curves:
        assert f"{c.onset_temperature_c:.1f}" in table
    doc = result.to_json()
    text = json.dumps(doc, allow_nan=False)  # valid JSON: no NaN anywhere
    assert json.loads(text)["temperature_c"] == list(FIG5.temperatures_c)
    case0 = doc["cases"][0]
    assert len(case0["displacement_m"]) == 28
    assert case0["displacement_m"][-1] == case0["displacement_at_final_temperature_m"]


def test_prediction_respects_the_material() -> None:
    # A fibre that expands twice as much must move more: the material argument is used.
    from tcarod import Material

    m = Material.silver_coated_nylon()
    e, es, g, gs, r, rs = m.coefficients
    more = Material(
        youngs_modulus=e,
        youngs_modulus_slope=es,
        shear_modulus=g,
        shear_modulus_slope=gs,
        expansion=2 * r,
        expansion_slope=2 * rs,
    )
    base = predict_fig5().curves[0].displacement_at_final_temperature_m
    boosted = predict_fig5(material=more).curves[0].displacement_at_final_temperature_m
    assert boosted > base


def test_whole_and_half_predictions_relate() -> None:
    # The onset condition f11(alpha0) F + f12(alpha0) tau = 0 does not depend
    # on the number of coils, so the half under F has the same onset as the
    # whole TCA under F (Brent's tolerance 1e-10 C; 1e-7 C margin).
    case = FIG5.cases[0]
    whole: Tca = case.tca.build()
    f = case.force_per_half_n
    assert case.half_tca().onset_temperature(f) == pytest.approx(whole.onset_temperature(f), abs=1e-7)
    assert math.isfinite(whole.onset_temperature(f))


def test_measured_cte_material_option() -> None:
    # the measured radial CTE of oriented nylon 6,6 (Choy et al. 1984; docs/table1.md) is about
    # half the default's d'/d: less untwisting, so every onset is later and the 160 C stroke smaller
    from tcarod.tca import Material

    default = FIG5.predict()
    measured = FIG5.predict(Material.nylon66_measured_cte())
    for a, b in zip(default.curves, measured.curves):
        assert a.onset_temperature_c is not None and b.onset_temperature_c is not None
        assert b.onset_temperature_c > a.onset_temperature_c, a.case.label
        # the free stroke scales roughly with d/d0 - 1 at 160 C: 3.7 % (measured) against 7.9 % (default)
        ratio = b.displacement_at_final_temperature_m / a.displacement_at_final_temperature_m
        # a band around that rough scaling, 3.7 / 7.9 = 0.47
        assert 0.4 < ratio < 0.55, (a.case.label, ratio)
