"""Hypothesis strategies for fuzzing tcarod's public Python API.

Every drawn call is a :class:`Call`: an entry-point name, positional and
keyword arguments made of plain, picklable data. Objects the call needs
(a robot, a solution, a thermal model) appear as :class:`Fix` tokens, which
the harness resolves in the process that runs the call, so the same draws
serve the in-process quick profile and the subprocess long profile.

The values mix mostly-valid numbers (near the model's working range, so the
solver is actually reached) with edge values (NaN, +-inf, 0, -0, subnormals,
1e300, ints beyond the double range, negative or huge counts) and wrong types
(None, str, bytes, complex, NumPy complex, bool, containers, an object whose
``__len__`` claims 2**62 items).
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np
from hypothesis import strategies as st

from .primitives import (
    argv_strategy,
    design_text_strategy,
    Fix,
    Call,
    bad_type,
    num,
    fnum,
    flen,
    fint,
    fvec,
    maybe,
    fix,
    this,
    call,
    TEMP,
    TEMPS2,
    ROBOTS,
    GROUPS,
    FIXED_INPUTS,
    VEC3_POS,
    VEC3_NORMAL,
    SOLVE_KW,
    MATERIAL_KW,
    INPUT_ROWS,
)


#: Chirality arguments of the TCA constructors, valid and not.
CHIRALITY = st.sampled_from(["extension", "contraction", "sideways", None, 1])


def _tca_rod_entries(reg: Callable[..., None]) -> None:
    """The TCA law and the geometry."""
    # TCA law
    coil = (fnum(1e-4, 5e-3), fnum(1.0, 500.0))  # coil diameter [m] and turns, alike for both constructors
    reg("Tca", 1, fnum(0.05, 1.0), fnum(0.01, 0.2), *coil, chirality=CHIRALITY, material=fix("MAT"))
    reg("Tca.from_pitch_angle", 1, fnum(0.01, 0.2), fnum(0.05, 1.0), *coil, chirality=CHIRALITY)
    arr_or = lambda lo, hi: st.one_of(fnum(lo, hi), fvec(3, lo, hi))  # noqa: E731
    reg("Tca.displacement", 1, this("TCA"), arr_or(-0.5, 0.5), arr_or(25.0, 160.0))
    reg("Tca.force", 1, this("TCA"), arr_or(-0.01, 0.05), arr_or(25.0, 160.0))
    reg("Tca.temperature", 1, this("TCA"), arr_or(-0.5, 0.0), arr_or(0.0, 0.05))
    reg("Tca.onset_temperature", 1, this("TCA"), arr_or(-0.5, 0.0))
    reg("Tca.free_stroke", 1, this("TCA"), arr_or(25.0, 160.0))
    reg("Tca.blocked_force", 1, this("TCA"), arr_or(25.0, 160.0))
    reg("Tca.segment", 1, this("TCA"), fnum(0.0, 1.0))
    reg("Tca.pitch_angle", 1, this("TCA"), fnum(-0.01, 0.05))
    reg("Tca.f11", 1, this("TCA"), fnum(0.05, 1.0), TEMP)
    reg("Tca.torque", 1, this("TCA"), TEMP)
    reg("Material", 1, **MATERIAL_KW)
    reg("Material.youngs_modulus", 1, this("MAT"), TEMP)
    reg("Material.diameter_ratio", 1, this("MAT"), TEMP)
    # geometry
    reg("Section.circle", 1, flen(1e-3, 0.05))
    reg("Section.rectangle", 1, flen(1e-3, 0.05), flen(1e-3, 0.05))
    reg("Section.custom", 1, fnum(1e-6, 1e-3), fnum(1e-12, 1e-8), fnum(1e-12, 1e-8), fnum(1e-12, 1e-8))
    reg("Section.edge_distance", 1, this("SQ", "CIRC"), fnum(-7.0, 7.0))
    reg("Routing.straight", 1, flen(-0.01, 0.01), flen(-0.01, 0.01))
    reg("Routing.helix", 1, flen(0.0, 0.01), fnum(-100.0, 100.0), phase=fnum(-7.0, 7.0))
    reg("Routing.evaluate", 1, this("HELIX", "ROUTE"), fnum(0.0, 0.05))
    reg(
        "Body",
        2,
        flen(0.01, 0.2),
        fix("SQ", "CIRC"),
        fnum(1e3, 1e6),
        poisson=fnum(0.0, 0.5),
        density=fnum(0.0, 2000.0),
        gravity=fvec(3, -10.0, 10.0),
        tip_force=fvec(3, -0.1, 0.1),
        omega_star=fvec(3, -10.0, 10.0),
        shear_coefficient=fnum(0.5, 1.0),
    )
    reg(
        "Actuator.tca",
        1,
        fix("TCA"),
        fix("ROUTE", "HELIX", "ROUTE_MM"),
        flen(0.0, 0.04),
        maybe(flen(0.0, 0.04)),
        maybe(fnum(0.5, 1.0)),
    )
    reg("Actuator.tendon", 1, fix("ROUTE", "ROUTE_MM"), flen(0.0, 0.04), maybe(flen(0.0, 0.04)))
    reg("Actuator.linear_tendon", 1, fnum(0.0, 1e3), fix("ROUTE"), fnum(0.0, 0.04), maybe(fnum(0.0, 0.04)))
    reg(
        "Robot",
        2,
        fix("BODY", "BODY_CIRC"),
        st.one_of(st.lists(fix("ACT", "ACT2", "ACT_OUT", "ACT_MM"), max_size=4), bad_type),
        spacer_disks=st.one_of(st.booleans(), st.booleans(), bad_type),
    )


def _forward_entries(reg: Callable[..., None]) -> None:
    """The forward solve."""
    reg(
        "Robot.solve",
        8,
        this("R", "RNG"),
        st.one_of(TEMPS2, TEMP),
        warm_start=maybe(fix("SOL", "SOL_OTHER")),
        **SOLVE_KW,
    )
    reg("Robot.sweep", 15, this("R", "RNG"), INPUT_ROWS, **SOLVE_KW)
    reg("circle_radius", 1, VEC3_POS, VEC3_POS, VEC3_POS)
    reg("inner_edge_radius", 1, fix("SOL", "SOL_OTHER"))


def _inverse_entries(reg: Callable[..., None]) -> None:
    """The inverse problems (tip, blocked tip, J and C, grasp) and batches."""
    # inverse
    near_tip = st.one_of(st.just(Fix("TIP")), fvec(3, -0.03, 0.05))
    reg(
        "tip_position",
        40,
        ROBOTS,
        near_tip,
        groups=GROUPS,
        fixed_inputs=maybe(FIXED_INPUTS),
        max_iter=fint(1, 20),
        tol=fnum(1e-9, 1e-5),
        start=maybe(TEMPS2),
        steps=fint(2, 120),
    )
    reg(
        "blocked_force",
        15,
        ROBOTS,
        near_tip,
        VEC3_NORMAL,
        st.one_of(TEMPS2, TEMP),
        groups=GROUPS,
        fixed_inputs=maybe(FIXED_INPUTS),
        steps=fint(2, 120),
    )
    reg(
        "blocked_temperature",
        40,
        fix("RNG"),
        near_tip,
        VEC3_NORMAL,
        fnum(1e-4, 0.05),
        start=maybe(fix("SOL0", "SOL_OTHER")),
        groups=GROUPS,
        fixed_inputs=maybe(FIXED_INPUTS),
        increments=fint(1, 12),
        steps=fint(2, 120),
    )
    reg(
        "blocked_temperature_direct",
        30,
        fix("RNG"),
        near_tip,
        VEC3_NORMAL,
        fnum(1e-4, 0.05),
        guess=maybe(TEMP),
        groups=GROUPS,
        fixed_inputs=maybe(FIXED_INPUTS),
        steps=fint(2, 120),
    )
    reg(
        "jacobian_and_compliance",
        10,
        fix("SOL", "SOL_OTHER"),
        groups=GROUPS,
        fixed_inputs=maybe(FIXED_INPUTS),
        scheme=st.sampled_from(["forward", "central", "sideways", None]),
    )
    reg(
        "grasp_temperature",
        40,
        fnum(1e-4, 3e-3),
        finger=fix("FINGER"),
        mu=fnum(0.1, 2.0),
        fingers=fint(1, 4),
        gravity=fnum(1.0, 20.0),
        method=st.sampled_from(["incremental", "direct", "x"]),
        increments=fint(1, 12),
        fixed_inputs=maybe(FIXED_INPUTS),
    )
    reg(
        "solve_batch",
        15,
        ROBOTS,
        INPUT_ROWS,
        chunk_size=fint(1, 64),
        threads=fint(0, 2),
        steps=fint(2, 120),
        max_iter=fint(1, 60),
        wrenches=maybe(st.one_of(fvec(6, -0.01, 0.01).map(lambda v: [v]), bad_type)),
    )


def _thermal_entries(reg: Callable[..., None]) -> None:
    """The thermal models and trajectories."""
    # thermal
    res = st.one_of(fnum(1.0, 100.0), st.just(Fix("LINRES")))
    reg(
        "ThermalModel",
        1,
        fnum(0.01, 1.0),
        fint(1, 8),
        res,
        thread_radius_m=fnum(1e-5, 1e-3),
        heat_transfer_w_per_m2k=fnum(1.0, 100.0),
        density_kg_per_m3=fnum(100.0, 2000.0),
        specific_heat_j_per_kgk=fnum(100.0, 3000.0),
        ambient_c=fnum(0.0, 40.0),
        t_max_c=fnum(60.0, 200.0),
    )
    reg("LinearResistance", 1, fnum(1.0, 100.0), fnum(-0.01, 0.01), fnum(0.0, 40.0), fnum(-1.0, 1.0))
    reg(
        "VoltageProfile",
        1,
        st.one_of(st.lists(fnum(-10.0, 100.0), max_size=4), bad_type),
        st.one_of(st.lists(fnum(0.0, 10.0), max_size=4), bad_type),
    )
    reg("VoltageProfile.step", 1, fnum(0.0, 10.0), at_s=fnum(0.0, 10.0))
    reg("ThermalModel.power_w", 1, this("MODEL", "MODEL_T"), fnum(0.0, 10.0), TEMP)
    reg("ThermalModel.steady_temperature", 1, this("MODEL", "MODEL_T"), fnum(0.0, 10.0))
    reg("ThermalModel.steady_voltage", 1, this("MODEL", "MODEL_T"), TEMP)
    profile = st.one_of(
        st.just(Fix("PROFILE")),
        st.just(Fix("PROFILE_EARLY")),
        st.builds(lambda t, v: Fix("PROFILE_AT", (t, v)), fnum(-1e300, 10.0), fnum(0.0, 10.0)),
        bad_type,
    )
    times = st.one_of(
        st.lists(num(0.0, 30.0), min_size=1, max_size=6).map(sorted),
        fvec(3, 0.0, 30.0),
        st.just([0.0, 1e300]),
        bad_type,
    )
    reg(
        "ThermalModel.transient",
        3,
        this("MODEL", "MODEL_T"),
        profile,
        times,
        initial_c=maybe(fnum(0.0, 160.0)),
        max_step_s=maybe(fnum(1e-3, 1.0)),
    )
    reg("steady_temperatures", 1, st.lists(fix("MODEL", "MODEL_T"), max_size=3), st.lists(fnum(0.0, 10.0), max_size=3))
    reg("solve_with_voltages", 6, fix("RNG"), st.lists(fix("MODEL"), max_size=3), st.lists(fnum(0.0, 3.0), max_size=3))
    reg(
        "quasi_static_trajectory",
        25,
        fix("RNG"),
        st.lists(fix("MODEL", "MODEL_T"), min_size=2, max_size=2),
        st.lists(profile, min_size=2, max_size=2),
        st.lists(num(0.0, 20.0), min_size=1, max_size=3).map(sorted),
        steps=fint(2, 100),
    )


def _model_io_entries(reg: Callable[..., None]) -> None:
    """Segmented robots, workspace, calibration, design files and the CLI."""
    # segmented, workspace, calibration
    seg = st.one_of(fint(1, 6), st.lists(fnum(0.0, 1.0), max_size=4), st.just([0.25, 0.75]))
    reg("segment_bounds", 1, seg, fnum(0.0, 0.02), fnum(0.02, 0.05))
    reg("segmented_actuators", 1, fix("TCA"), fix("ROUTE"), seg, fnum(0.0, 0.02), fnum(0.02, 0.05))
    reg("snake_grid", 1, st.one_of(st.lists(st.lists(fnum(25.0, 160.0), max_size=4), max_size=3), bad_type))
    reg(
        "workspace_map",
        30,
        fix("RNG"),
        st.one_of(st.lists(fnum(25.0, 160.0), max_size=3), bad_type, st.just(np.linspace(25.0, 160.0, 400))),
        steps=fint(2, 80),
    )
    reg("solve_rows", 15, fix("RNG"), INPUT_ROWS, steps=fint(2, 80))
    reg(
        "TcaExperiment",
        1,
        fnum(0.1, 1.0),
        fnum(0.01, 0.2),
        fnum(1e-4, 5e-3),
        fnum(1.0, 500.0),
        fnum(0.0, 0.02),
        load_share=fnum(0.1, 1.0),
        chirality=CHIRALITY,
    )
    reg(
        "calibrate",
        60,
        fix("EXP"),
        st.lists(fnum(25.0, 160.0), min_size=0, max_size=6),
        st.lists(fnum(0.0, 0.02), min_size=0, max_size=6),
        fit=st.one_of(
            st.just(["expansion_scale"]),
            st.lists(
                st.sampled_from(
                    ["expansion_scale", "friction_mass_kg", "friction_ratio", "youngs_modulus_slope_pa_per_c", "x"]
                ),
                max_size=3,
            ),
            bad_type,
        ),
        confidence=fnum(0.5, 0.99),
    )
    # design files and CLI
    reg("loads_design", 2, st.one_of(design_text_strategy(), design_text_strategy(), st.text(max_size=200), bad_type))
    reg(
        "load_design",
        2,
        st.one_of(
            st.sampled_from(
                [
                    Fix("DESIGN_PATH"),
                    Fix("BAD_DESIGN_PATH"),
                    Fix("MISSING_PATH"),
                    Fix("OUT_DIR"),
                    Fix("BIG_PATH"),
                    Fix("BINARY_PATH"),
                    "",
                    "\0",
                ]
            ),
            bad_type,
        ),
    )
    reg("dumps_design", 2, fix("R", "ROBOT_TENDON"), maybe(TEMPS2))
    reg("cli.main", 20, argv_strategy())


def _entries() -> dict[str, tuple[st.SearchStrategy[Call], float]]:
    """``{entry: (strategy, relative cost)}``; the cost sets how often the
    quick profile draws it (cheap ones more)."""
    E: dict[str, tuple[st.SearchStrategy[Call], float]] = {}

    def reg(entry: str, cost: float, *args: Any, **kwargs: Any) -> None:
        E[entry] = (call(entry, *args, **kwargs), cost)

    for part in (_tca_rod_entries, _forward_entries, _inverse_entries, _thermal_entries, _model_io_entries):
        part(reg)
    return E


ENTRIES: dict[str, tuple[st.SearchStrategy[Call], float]] = _entries()

#: Entry points whose arguments include file paths: OSError is in their contract.
FILE_ENTRIES = frozenset({"load_design", "cli.main"})


def any_call(weights: Callable[[str, float], float] | None = None) -> st.SearchStrategy[Call]:
    """A call of any entry point; entry ``e`` of cost ``c`` drawn with weight
    ``weights(e, c)`` (default: every entry point equally often)."""
    names = sorted(ENTRIES)
    w = np.array([1.0 if weights is None else max(weights(n, ENTRIES[n][1]), 1e-6) for n in names])
    slots = np.maximum(1, np.round(1000.0 * w / w.sum())).astype(int)  # ~1000 slots, each entry at least one
    table = [n for n, k in zip(names, slots) for _ in range(k)]
    return st.sampled_from(table).flatmap(lambda n: ENTRIES[n][0])


def _more_entries() -> None:
    """The parameter studies and the brute-force baselines (few draws: each
    valid call runs many forward solves)."""
    keys = st.sampled_from(["rho", "E_B", "rho(T)", "coil_diameter", "nope", 1])
    scales = st.one_of(st.none(), st.dictionaries(keys, fnum(0.5, 2.0), max_size=2), bad_type)
    tip = st.one_of(st.just(Fix("TIP")), fvec(3, -0.03, 0.05))  # the fixture's tip [m] or a point near it
    ENTRIES["perturbed_finger"] = (call("perturbed_finger", scales), 2)
    ENTRIES["table1_grip_temperatures"] = (
        call("table1_grip_temperatures", scales, st.one_of(st.lists(fnum(1e-4, 3e-3), max_size=2), bad_type)),
        1000,
    )
    ENTRIES["brute_force_blocked_temperature"] = (
        call(
            "brute_force_blocked_temperature",
            fix("RNG"),
            tip,
            VEC3_NORMAL,
            fnum(1e-4, 0.05),
            groups=GROUPS,
            xatol=fnum(1e-3, 1.0),
            steps=fint(2, 60),
        ),
        1000,
    )
    ENTRIES["brute_force_tip_position"] = (
        call(
            "brute_force_tip_position",
            fix("RNG"),
            tip,
            start=maybe(TEMPS2),
            groups=GROUPS,
            xatol=fnum(1e-2, 1.0),
            max_solves=fint(1, 40),
            steps=fint(2, 60),
            simplex_size_c=fnum(0.1, 20.0),
        ),
        1000,
    )


_more_entries()
