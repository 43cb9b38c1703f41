"""Fig. 8 (blocked-tip force) and Table I (grip temperatures) fixtures, and
the Table I parameter study (tcarod.studies)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from tcarod.experiments import REGISTRY
from tcarod.experiments.fig8 import FIG8, Fig8Result
from tcarod.experiments.table1 import TABLE1, Table1Result
from tcarod.studies import (
    PARAMETERS,
    identify_table1,
    perturbed_finger,
    table1_grip_temperatures,
    table1_sensitivity,
)


@pytest.fixture(scope="module")
def fig8() -> Fig8Result:
    return FIG8.predict()


@pytest.fixture(scope="module")
def table1() -> Table1Result:
    return TABLE1.predict()  # without the (slower) study


def test_registered() -> None:
    assert "fig8" in REGISTRY and "table1" in REGISTRY


def test_fig8_force_is_zero_while_slack_then_rises(fig8: Fig8Result) -> None:
    t, f = fig8.temperatures_c, fig8.forces_n
    assert t[0] == 25.0 and t[-1] == 160.0 and np.allclose(np.diff(t), 5.0)
    assert np.all(f[t < 55.0] == 0.0)
    # at 55 C the tip is exactly at the wire: the mixed solve's force is ~0
    # (Newton tolerance 1e-10 in scaled units: ~1e-9 N here)
    assert abs(fig8.force_at(55.0)) < 1e-8
    above = f[t > 55.0]
    assert np.all(above > 0.0) and np.all(np.diff(above) > 0.0)
    # the block point is the free tip at 55 C, bent toward -x by the TCA at +x
    assert fig8.block_point_m[0] < 0.0
    with pytest.raises(ValueError):
        fig8.force_at(57.0)


def test_fig8_cross_checked_by_incremental_eq43(fig8: Fig8Result) -> None:
    assert len(fig8.cross_checks) >= 3
    for c in fig8.cross_checks:
        # both methods close the same equations (tip gap 1e-9 L): agreement << 1e-6 C
        assert abs(c.difference_c) < 1e-6, c
        assert c.force_n == pytest.approx(fig8.force_at(c.temperature_c), rel=1e-12)


def test_fig8_json_table_plot(fig8: Fig8Result, tmp_path: Path) -> None:
    doc = json.loads(json.dumps(fig8.to_json(), allow_nan=False))
    assert doc["published_data"] is None
    assert doc["published_rms_n"] == pytest.approx(0.74e-3)
    assert doc["taut_temperature_c"] == 55.0
    assert len(doc["force_n"]) == len(doc["temperature_c"]) == 28
    assert "55 C" in doc["blocking"] and "-x" in doc["blocking"]
    text = fig8.table()
    assert "force [mN]" in text and "0.74 mN" in text
    png = fig8.plot(tmp_path / "fig8.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_table1_rows(table1: Table1Result) -> None:
    rows = table1.rows
    assert [r.mass_kg for r in rows] == [1e-3, 2e-3, 3e-3]
    assert [r.experiment_c for r in rows] == [95.0, 120.0, 135.0]
    assert [r.paper_prediction_c for r in rows] == [93.7, 114.8, 136.3]
    t = [r.predicted_c for r in rows]
    assert 25.0 < t[0] < t[1] < t[2] < 160.0
    for r in rows:
        # eq 43 (incremental) and the direct mixed solve agree (both to tip gap 1e-9 L)
        assert r.direct_c == pytest.approx(r.predicted_c, abs=1e-6)
        assert r.error_vs_experiment_c == r.predicted_c - r.experiment_c
        assert r.error_vs_paper_c == r.predicted_c - r.paper_prediction_c
        assert r.grasp.force_per_finger_n == pytest.approx(r.mass_kg * 9.81 / 2.2, rel=1e-15)


def test_table1_json_table_plot(table1: Table1Result, tmp_path: Path) -> None:
    doc = json.loads(json.dumps(table1.to_json(), allow_nan=False))
    assert doc["study"] is None
    assert [r["experiment_c"] for r in doc["rows"]] == [95.0, 120.0, 135.0]
    text = table1.table()
    assert "93.7" in text and "tcarod-exp [C]" in text
    png = table1.plot(tmp_path / "table1.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sensitivity_ranking_and_signs() -> None:
    sens = table1_sensitivity()
    assert len(sens) == len(PARAMETERS)
    ranks = [s.mean_abs_elasticity for s in sens]
    assert ranks == sorted(ranks, reverse=True)
    by_key = {s.parameter.key: s for s in sens}
    # more radial expansion -> more untwisting torque -> the force is reached sooner
    assert all(e < 0.0 for e in by_key["rho(T)"].elasticity)
    # a larger offset gives the TCA more lever arm: lower grip temperature
    assert all(e < 0.0 for e in by_key["tca_offset"].elasticity)
    # the central difference brackets the default: T(-10 %) > T > T(+10 %) for rho(T)
    s = by_key["rho(T)"]
    assert all(m > b > p for m, b, p in zip(s.minus_c, s.base_c, s.plus_c))


def test_identification_recovers_a_known_scale() -> None:
    # synthetic target: the model itself with rho(T) halved; the fit must find 0.5
    target = table1_grip_temperatures({"rho(T)": 0.5})
    ident = identify_table1(("rho(T)",), target_c=target)
    # least_squares xtol 1e-10 on log scale; the model is smooth in the scale
    assert ident.scales[0] == pytest.approx(0.5, rel=1e-4)
    assert ident.rms_c < 1e-3
    assert ident.values()["rho(T)"] == pytest.approx(0.5 * PARAMETERS[3].default, rel=1e-4)


def test_perturbed_finger_rejects_unknown_parameters() -> None:
    with pytest.raises(ValueError, match="unknown"):
        perturbed_finger({"youngs": 1.1})
    with pytest.raises(ValueError, match="scale"):
        perturbed_finger({"E_B": -1.0})
    with pytest.raises(ValueError, match="keys"):
        identify_table1(("rho", "E_B", "G_T"))
