"""Quick fuzz profile (issue 12): every public entry point, in process.

Each entry point gets a fixed, derandomised budget of hypothesis examples
from :mod:`fuzz.strategies` (more for cheap calls, a few for a workspace map
or a calibration; about a minute in all), and every outcome must be inside
the contract (:mod:`fuzz.harness`): a finite result, ``ValueError``
(``DesignError``), ``TypeError``, ``ConvergenceError``, ``OSError`` for file
paths, or an exit status from the CLI. A panic, a NaN/inf result, another
exception type or a call over the time limit fails the test with the call
that did it. The long profile (>= 100,000 calls, each in a worker
subprocess) is ``benches/fuzz_long.py``.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, example, given, settings

from fuzz.harness import ALLOWED, classify
from fuzz.strategies import ENTRIES, Call, EvilLen, Fix, Opaque

#: In-process time limit per call [s]: far above any valid call here (the
#: slowest, a calibration or a 3x3 workspace map, takes well under 1 s).
TIME_LIMIT_S = 10.0
#: Examples per entry point: ~150 / relative cost, between 3 and 100.
BUDGET = {name: max(3, min(100, int(150 / cost))) for name, (_, cost) in ENTRIES.items()}

_API = "api helper's files"
_CPLX = f"{_API} (bindings): a NumPy complex scalar is accepted as a float, its imaginary part dropped (want TypeError)"
C = np.complex128(0.01 + 1j)  # a complex length [m] / angle / temperature: a wrong type

#: Entry points with known violations in files this suite's owner does not
#: own, each with one reproducer (run first as an explicit example, so the
#: strict xfail fails every time whatever the random draws; a fix shows up as
#: XPASS and the mark must go).
KNOWN: dict[str, tuple[str, Call]] = {
    "Tca": (_CPLX, Call("Tca", (C * 50, 0.110, 2e-3, 300.0))),
    "Tca.from_pitch_angle": (_CPLX, Call("Tca.from_pitch_angle", (C, 0.26, 1.7e-3, 76.4))),
    "Tca.segment": (_CPLX, Call("Tca.segment", (Fix("TCA"), np.complex128(0.5 + 1j)))),
    "Tca.pitch_angle": (_CPLX, Call("Tca.pitch_angle", (Fix("TCA"), C))),
    "Tca.f11": (_CPLX, Call("Tca.f11", (Fix("TCA"), np.complex128(0.3 + 1j), 60.0))),
    "Tca.torque": (_CPLX, Call("Tca.torque", (Fix("TCA"), np.complex128(60 + 1j)))),
    "Material": (_CPLX, Call("Material", (), {"youngs_modulus": np.complex128(1e9 + 1j), "shear_modulus": 2e8,
                                               "expansion": 1e-4})),
    "Material.youngs_modulus": (_CPLX, Call("Material.youngs_modulus", (Fix("MAT"), np.complex128(60 + 1j)))),
    "Material.diameter_ratio": (_CPLX, Call("Material.diameter_ratio", (Fix("MAT"), np.complex128(60 + 1j)))),
    "Section.circle": (_CPLX, Call("Section.circle", (C,))),
    "Section.rectangle": (_CPLX, Call("Section.rectangle", (C, 0.01))),
    "Section.custom": (_CPLX, Call("Section.custom", (np.complex128(1e-4 + 1j), 1e-9, 1e-9, 1e-9))),
    "Section.edge_distance": (_CPLX, Call("Section.edge_distance", (Fix("SQ"), np.complex128(0.3 + 1j)))),
    "Routing.straight": (_CPLX, Call("Routing.straight", (C, 0.0))),
    "Routing.helix": (_CPLX, Call("Routing.helix", (C, 10.0))),
    "Routing.evaluate": (_CPLX, Call("Routing.evaluate", (Fix("HELIX"), C))),
    "Body": (_CPLX, Call("Body", (np.complex128(0.04 + 1j), Fix("SQ"), 3.78e4))),
    "Actuator.tca": (_CPLX, Call("Actuator.tca", (Fix("TCA"), Fix("ROUTE"), np.complex128(0.0 + 1j)))),
    "Actuator.tendon": (_CPLX, Call("Actuator.tendon", (Fix("ROUTE"), np.complex128(0.0 + 1j)))),
    "Actuator.linear_tendon": (_CPLX, Call("Actuator.linear_tendon", (np.complex128(10 + 1j), Fix("ROUTE")))),
    "Robot": (f"{_API} (bindings): Robot(body, <__len__ = 2**62>) -> PanicException 'capacity overflow'",
              Call("Robot", (Fix("BODY"), EvilLen()))),
    "Robot.solve": (f"{_API} (bindings): solve(<__len__ = 2**62>) -> PanicException 'capacity overflow'",
                    Call("Robot.solve", (Fix("R"), EvilLen()))),
    "Robot.sweep": (f"{_API} (bindings): sweep(<__len__ = 2**62>) -> PanicException 'capacity overflow'",
                    Call("Robot.sweep", (Fix("R"), EvilLen()))),
    "tip_position": (f"{_API} inverse.py: max_iter=-1 -> OverflowError (want ValueError naming max_iter)",
                     Call("tip_position", (Fix("RNG"), Fix("TIP")), {"max_iter": -1})),
    "blocked_temperature": (f"{_API}: start = a Solution of another robot -> PanicException 'index out of bounds'",
                            Call("blocked_temperature", (Fix("RNG"), Fix("TIP"), [-1.0, 0.0, 0.0], 1e-3),
                                 {"start": Fix("SOL_OTHER"), "groups": [0, 0]})),
    "blocked_temperature_direct": (f"{_API} inverse.py: robot='' -> AttributeError (want TypeError)",
                                   Call("blocked_temperature_direct", ("", Fix("TIP"), [-1.0, 0.0, 0.0], 1e-3))),
    "blocked_force": (f"{_API} inverse.py: force=-10**400 -> OverflowError (an int beyond the double range is inf: ValueError)",
                      Call("blocked_force", (Fix("RNG"), [0.0, 0.0, 0.04], [-1.0, 0.0, 0.0], -(10**400)))),
    "grasp_temperature": ("grasp.py (fidelity helper's): finger=b'ab' -> AttributeError (want TypeError)",
                          Call("grasp_temperature", (1e-3,), {"finger": b"ab"})),
    "circle_radius": (f"{_API} rod.py: circle_radius(None, ...) -> NaN (None is not a point: TypeError)",
                      Call("circle_radius", (None, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]))),
    "inner_edge_radius": (f"{_API} rod.py: inner_edge_radius(None) -> AttributeError (want TypeError)",
                          Call("inner_edge_radius", (None,))),
    "solve_batch": (f"{_API} batch.py: chunk_size=-1 -> OverflowError (want ValueError naming chunk_size)",
                    Call("solve_batch", (Fix("R"), [[60.0, 60.0]]), {"chunk_size": -1})),
}


def _param(name: str) -> object:
    if name in KNOWN and not os.environ.get("TCAROD_FUZZ_NO_XFAIL"):
        return pytest.param(name, marks=pytest.mark.xfail(strict=True, reason=KNOWN[name][0]))
    return name


@pytest.mark.parametrize("entry", [_param(n) for n in sorted(ENTRIES)])
def test_fuzz_entry_point_keeps_the_contract(entry: str) -> None:
    strategy, _ = ENTRIES[entry]

    def body(call: Call) -> None:
        outcome, detail = classify(call, timeout=TIME_LIMIT_S)
        assert outcome in ALLOWED, f"contract violation {outcome}: {call!r} -> {detail}"

    run = given(strategy)(body)
    if entry in KNOWN:
        run = example(KNOWN[entry][1])(run)
    settings(
        max_examples=BUDGET[entry],
        deadline=None,
        database=None,
        derandomize=True,
        phases=[Phase.explicit, Phase.generate],  # no shrinking: report the call as drawn
        suppress_health_check=list(HealthCheck),
    )(run)()


def test_classifier_flags_violations() -> None:
    """The classifier itself: a NaN result and a foreign exception are violations."""
    from fuzz import harness

    assert harness.nonfinite(float("nan")) is not None
    assert harness.nonfinite([1.0, {"a": float("inf")}]) is not None
    assert harness.nonfinite((1.0, 2)) is None
    assert harness._exception_class(KeyError("x"), "Tca") == "other:KeyError"
    assert harness._exception_class(OSError("x"), "Tca") == "other:OSError"  # no file path there
    assert harness._exception_class(OSError("x"), "load_design") == "OSError"
    assert classify(Call("Section.circle", (0.01,)))[0] == "ok"
    assert classify(Call("Section.circle", ("x",)))[0] == "TypeError"
    assert classify(Call("Section.circle", (float("nan"),)))[0] == "ValueError"
