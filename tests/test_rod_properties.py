"""Properties of the forward kinetostatics that hold for every design,
checked through the Python API with hypothesis, and the solve's errors.

* global equilibrium: the wrench the body and its actuators transmit to the
  base equals the external loads (actuator forces are internal);
* the reference state: at 25 C, unloaded and weightless, the body keeps its
  reference shape, with zero elongation and tension;
* symmetries: mirroring the actuator layout mirrors the shape; rotating it
  about the axis rotates the shape; two equal TCAs opposite each other only
  stretch the body;
* failures raise ConvergenceError with ``residual`` and ``iterations``; bad
  input raises ValueError naming the field.

The same properties on seeded designs, the signs, interior anchors and coil
contact are the Rust tests in tests/integration/properties.rs (the Fig. 6
sweeps in tests/integration/solver.rs); here they are checked at the API
(hypothesis designs built from Python objects).

Frame: base at the origin, reference tangent +z. SI units, temperatures in C.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tcarod import Actuator, Body, ConvergenceError, Robot, Routing, Section, Solution, Tca
from tcarod.paper.fig6 import FIG6, manipulator_tca

FloatArray = npt.NDArray[np.float64]
G0 = 9.81
TCA40 = manipulator_tca(0.040)  # the paper's manipulator TCA for a 40 mm body

# Modest example counts: each example is a few shooting solves of ~ms each; the
# physics is also checked on 40 seeded designs per property in
# tests/integration/properties.rs.
SETTINGS = settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])


# ------------------------------------------------------------ random designs


def span_tca(s_start: float, s_end: float | None, length: float) -> Tca:
    """The paper's manipulator TCA cut to the span it is anchored over (a TCA
    may not be longer than its span: ``tca_fits_span`` in src/rod/robot.rs),
    twist per length kept."""
    span = (length if s_end is None else s_end) - s_start
    return Tca.from_pitch_angle(span, math.radians(15.0), 1.7e-3, 76.4 * span / 0.04)


@dataclass(frozen=True)
class ActuatorSpec:
    kind: str  # "tca" or "tendon"
    x: float  # [m], body frame
    y: float  # [m]
    s_start_frac: float  # of the body length
    s_end_frac: float | None  # None: the tip
    value: float  # temperature [C] or tension [N]


@dataclass(frozen=True)
class Design:
    length: float
    section: Section
    half_width: float  # [m], half extents for offsets
    half_height: float
    youngs_modulus: float
    density: float
    gravity: tuple[float, float, float]
    tip_force: tuple[float, float, float]
    tip_moment: tuple[float, float, float]
    distributed_moment: tuple[float, float, float]
    actuators: tuple[ActuatorSpec, ...]

    def body(self) -> Body:
        return Body(
            self.length,
            self.section,
            self.youngs_modulus,
            poisson=0.5,
            density=self.density,
            gravity=self.gravity,
            tip_force=self.tip_force,
            tip_moment=self.tip_moment,
            distributed_moment=self.distributed_moment,
        )

    def robot(self) -> Robot:
        acts = []
        for a in self.actuators:
            routing = Routing.straight(a.x, a.y)
            s0 = a.s_start_frac * self.length
            s1 = None if a.s_end_frac is None else a.s_end_frac * self.length
            if a.kind == "tca":
                acts.append(Actuator.tca(span_tca(s0, s1, self.length), routing, s0, s1))
            else:
                acts.append(Actuator.tendon(routing, s0, s1))
        return Robot(self.body(), acts)

    @property
    def inputs(self) -> list[float]:
        return [a.value for a in self.actuators]


def _unit(v: tuple[float, float, float]) -> FloatArray:
    a = np.asarray(v, dtype=np.float64)
    n = float(np.linalg.norm(a))
    return a / n if n > 1e-3 else np.array([0.0, 0.0, -1.0])


@st.composite
def designs(draw: st.DrawFn, nested: bool = False) -> Design:
    """A random body with 1-3 actuators (TCAs or tendons) at random offsets.
    ``nested=True``: random anchors. ``nested=False``: one actuator with a random
    span, or several that run base to tip or along consecutive disjoint pieces,
    so that no anchor inside the body is shared or passed by another actuator
    (see ``anchor_inside_the_body_with_other_strings_keeps_equilibrium`` in
    tests/integration/properties.rs)."""
    length = draw(st.floats(0.02, 0.06))
    if draw(st.booleans()):
        d = draw(st.floats(7e-3, 12e-3))
        section, hw, hh = Section.circle(d), d / 2 / math.sqrt(2), d / 2 / math.sqrt(2)
    else:
        w, h = draw(st.floats(7e-3, 12e-3)), draw(st.floats(7e-3, 12e-3))
        section, hw, hh = Section.rectangle(w, h), w / 2, h / 2
    e = draw(st.floats(3e4, 2e5))
    _, ix, iy, _ = section.properties
    ei = e * min(ix, iy)
    unit = st.floats(-1.0, 1.0)
    g_dir = _unit((draw(unit), draw(unit), draw(unit)))
    g = tuple(float(x) for x in g_dir * G0 * draw(st.sampled_from([0.0, 1.0])))
    # loads up to F L^2 / EI = 0.3 and M L / EI = 0.3 per component: large enough to bend
    # visibly, small enough for Newton from the straight guess
    f_scale, m_scale = 0.3 * ei / length**2, 0.3 * ei / length
    tip_force = tuple(draw(unit) * f_scale for _ in range(3))
    tip_moment = tuple(draw(unit) * m_scale for _ in range(3))
    dist_moment = tuple(draw(unit) * 0.1 * m_scale / length for _ in range(3))
    n_act = draw(st.integers(1, 3))
    acts = []
    single = (draw(st.floats(0.0, 0.4)), draw(st.one_of(st.none(), st.floats(0.7, 1.0))))
    disjoint = draw(st.booleans())
    for k in range(n_act):
        kind = draw(st.sampled_from(["tca", "tendon"]))
        x, y = draw(st.floats(-0.7, 0.7)) * hw, draw(st.floats(-0.7, 0.7)) * hh
        if nested:
            s0 = draw(st.floats(0.0, 0.4))
            s1 = draw(st.one_of(st.none(), st.floats(s0 + 0.3, 1.0)))
        elif n_act == 1:
            s0, s1 = single
        elif disjoint:  # consecutive pieces of the body, the last one to the tip
            s0, s1 = k / n_act, (None if k == n_act - 1 else (k + 1) / n_act)
        else:  # base to tip
            s0, s1 = 0.0, None
        # tendon tension up to tau r L / EI ~ 0.5 (bends ~30 degrees)
        # TCAs from 40 C: near 25 C a load that closes the coils makes Newton fail
        # (tca_pressed_into_coil_contact_converges in tests/integration/properties.rs)
        value = draw(st.floats(40.0, 120.0)) if kind == "tca" else draw(st.floats(0.0, 0.5 * ei / (length * 5e-3)))
        acts.append(ActuatorSpec(kind, x, y, s0, s1, value))
    # Self-weight: an upright column buckles at rho A g L^3 / EI = 7.84; keep the
    # weight parameter <= 2 (the Fig. 6 square has 2.1), clear of that.
    area = section.properties[0]
    density = min(draw(st.floats(0.0, 2000.0)), 2.0 * ei / (area * G0 * length**3))
    return Design(
        length,
        section,
        hw,
        hh,
        e,
        density,
        g,  # type: ignore[arg-type]
        tip_force,
        tip_moment,
        dist_moment,
        tuple(acts),  # type: ignore[arg-type]
    )


def _trapezoid(y: FloatArray, x: FloatArray) -> FloatArray:
    """Trapezoid rule along axis 0 on a non-uniform grid."""
    dx = np.diff(x)[:, None]
    return np.asarray(np.sum(0.5 * (y[1:] + y[:-1]) * dx, axis=0), dtype=np.float64)


# ------------------------------------------------------- global equilibrium


@SETTINGS
@given(design=designs())
def test_base_wrench_balances_external_loads(design: Design) -> None:
    robot = design.robot()
    sol = robot.solve(design.inputs)
    body = robot.body
    L = body.length
    f = body.distributed_load  # [N/m], world frame, constant along the body
    tip_f, tip_m = body.tip_force, body.tip_moment
    k_nu, k_om = (np.diag(k) for k in body.stiffness())
    # Solver tolerance 1e-10 on K_nu^-1 r_F and L K_omega^-1 r_M: force error
    # <= 1e-10 max K_nu, moment error <= 1e-10 max K_omega / L (+ force error x L).
    # RK4 truncation on this smooth problem is far smaller (~1e-12 relative).
    # Margin 100 on both.
    f_tol = 100 * 1e-10 * float(k_nu.max())
    want_f = tip_f + f * L
    np.testing.assert_allclose(sol.base_force, want_f, rtol=0.0, atol=f_tol)

    # base moment = tip moment + p(L) x F + int p x f ds + int l_e ds
    s, p = sol.s, sol.positions
    p_int = _trapezoid(p, s)
    # Trapezoid error <= sum h^3 / 12 max|p''| <= L h_max^2 / 12 max|p''|, and
    # |p''| = |R (omega x nu + nu')| ~ max|omega| max|nu| (nu' is a small strain rate,
    # covered by the factor 2).
    h_max = float(np.max(np.diff(s)))
    p2 = 2.0 * float(np.max(np.linalg.norm(sol.omega, axis=1))) * float(np.max(np.linalg.norm(sol.nu, axis=1)))
    trap_err = L * h_max**2 / 12.0 * p2 * float(np.linalg.norm(f))
    want_m = tip_m + np.cross(sol.tip_position, tip_f) + np.cross(p_int, f) + body.distributed_moment * L
    m_tol = 100 * 1e-10 * (float(k_om.max()) / L + float(k_nu.max()) * L) + 2.0 * trap_err
    np.testing.assert_allclose(sol.base_moment, want_m, rtol=0.0, atol=m_tol)


# -------------------------------------------------------- reference state


@SETTINGS
@given(design=designs(nested=True), precurvature=st.tuples(st.floats(-8.0, 8.0), st.floats(-8.0, 8.0)))
def test_reference_temperature_keeps_reference_shape(design: Design, precurvature: tuple[float, float]) -> None:
    # every actuator a TCA at 25 C; no load, no gravity; straight or pre-curved body
    omega_star = (precurvature[0], precurvature[1], 0.0)  # [1/m]
    body = Body(
        design.length,
        design.section,
        design.youngs_modulus,
        poisson=0.5,
        density=design.density,
        omega_star=omega_star,
        gravity=(0.0, 0.0, 0.0),  # weightless on purpose: said explicitly, so no UnitsWarning
    )
    acts = []
    for a in design.actuators:
        s0 = a.s_start_frac * design.length
        s1 = None if a.s_end_frac is None else a.s_end_frac * design.length
        acts.append(Actuator.tca(span_tca(s0, s1, design.length), Routing.straight(a.x, a.y), s0, s1))
    robot = Robot(body, acts)
    sol = robot.solve(robot.reference_inputs)
    assert robot.reference_inputs == [25.0] * len(acts)
    # The reference guess is the exact solution: zero residual, no Newton step.
    # The tolerances below are rounding of the reference configuration.
    assert sol.iterations == 0
    np.testing.assert_allclose(sol.omega, np.tile(omega_star, (len(sol.s), 1)), rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(sol.nu, np.tile([0.0, 0.0, 1.0], (len(sol.s), 1)), rtol=0.0, atol=1e-12)
    assert np.all(np.abs(sol.tensions) < 1e-12)
    assert np.all(np.abs(sol.elongations) < 1e-15)
    if precurvature == (0.0, 0.0):
        np.testing.assert_allclose(sol.positions[:, :2], 0.0, atol=1e-15)
        np.testing.assert_allclose(sol.positions[:, 2], sol.s, rtol=1e-14)
    np.testing.assert_allclose(sol.base_force, 0.0, atol=1e-15)


# ------------------------------------------------------------- symmetries


def _symmetric_robot(design: Design, xy: list[tuple[float, float]], gravity_z: float = 0.0) -> Robot:
    body = Body(
        design.length,
        design.section,
        design.youngs_modulus,
        poisson=0.5,
        density=design.density,
        gravity=(0.0, 0.0, gravity_z),
    )
    robot = design.robot()
    acts = []
    for a, (x, y) in zip(robot.actuators, xy):
        s_end = None if math.isinf(a.s_end) else a.s_end
        if a.kind == "tca":
            model = a.tca_model
            assert model is not None
            acts.append(Actuator.tca(model, Routing.straight(x, y), a.s_start, s_end))
        else:
            acts.append(Actuator.tendon(Routing.straight(x, y), a.s_start, s_end))
    return Robot(body, acts)


@SETTINGS
@given(design=designs(), upright=st.booleans())
def test_mirrored_layout_mirrors_shape(design: Design, upright: bool) -> None:
    # x -> -x for every actuator; sections are symmetric in x, gravity along z keeps the symmetry
    xy = [(a.x, a.y) for a in design.actuators]
    g = -G0 if upright else 0.0
    a = _symmetric_robot(design, xy, g).solve(design.inputs)
    b = _symmetric_robot(design, [(-x, y) for x, y in xy], g).solve(design.inputs)
    mirror = np.array([-1.0, 1.0, 1.0])
    # same equations mirrored; each solve meets its tolerance (strain 1e-10 ->
    # positions ~L * 1e-10 * (K ratio) ~1e-11 m); 1e-9 m leaves a margin of ~100
    np.testing.assert_allclose(b.positions, a.positions * mirror, rtol=0.0, atol=1e-9)
    # tensions: the same solve tolerance, relative (with a floor near zero tension)
    np.testing.assert_allclose(b.tensions, a.tensions, rtol=1e-7, atol=1e-12)


@SETTINGS
@given(design=designs(), angle=st.floats(-math.pi, math.pi), helix=st.booleans())
def test_rotated_layout_rotates_shape(design: Design, angle: float, helix: bool) -> None:
    # A circle (or square: I_x = I_y) is isotropic in bending, so the model is
    # invariant under rotation of the actuator layout about the axis (no gravity).
    # Offsets are up to 0.7 of each half-size, so |(x, y)| <= 0.99 max(half sizes):
    # sized by the larger half-size, every rotated layout stays inside the section
    # (routings outside it are rejected at construction).
    d = 2.0 * max(design.half_width, design.half_height)
    section = Section.circle(d * math.sqrt(2)) if design.section.kind == "circle" else Section.rectangle(d, d)
    body = Body(design.length, section, design.youngs_modulus, poisson=0.5)
    c, s = math.cos(angle), math.sin(angle)
    rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    def routing(x: float, y: float, turn: float) -> Routing:
        if helix:  # a helix starting at (x, y), turning once over the body
            return Routing.helix(math.hypot(x, y), 2.0 * math.pi / design.length, math.atan2(y, x) + turn)
        cc, ss = math.cos(turn), math.sin(turn)
        return Routing.straight(cc * x - ss * y, ss * x + cc * y)

    def robot(turn: float) -> Robot:
        acts = [Actuator.tendon(routing(a.x, a.y, turn), a.s_start_frac * design.length) for a in design.actuators]
        return Robot(body, acts)

    # tendons only (TCA forces would be identical, but a tendon's tension is the input)
    _, ix, _, _ = section.properties
    tension = 0.2 * design.youngs_modulus * ix / (design.length * 5e-3)
    inputs = [tension * (k + 1) / len(design.actuators) for k in range(len(design.actuators))]
    a = robot(0.0).solve(inputs)
    b = robot(angle).solve(inputs)
    # tolerance as for the mirror test; rotation entries (order 1) to 1e-7
    np.testing.assert_allclose(b.positions, a.positions @ rot.T, rtol=0.0, atol=1e-9)
    np.testing.assert_allclose(b.tip_rotation, rot @ a.tip_rotation @ rot.T, rtol=0.0, atol=1e-7)


@settings(max_examples=15, deadline=None)
@given(
    temperature=st.floats(25.0, 160.0),
    offset=st.floats(1e-3, 3.5e-3),
    angle=st.floats(-math.pi, math.pi),
    square=st.booleans(),
)
def test_opposite_equal_tcas_only_stretch(temperature: float, offset: float, angle: float, square: bool) -> None:
    # two identical TCAs at r and -r (opposite each other through the axis)
    section = Section.rectangle(10e-3, 10e-3) if square else Section.circle(9e-3)
    body = Body(0.04, section, 37.8e3, poisson=0.5)
    x, y = offset * math.cos(angle), offset * math.sin(angle)
    acts = [Actuator.tca(TCA40, Routing.straight(sx * x, sx * y)) for sx in (1.0, -1.0)]
    sol = Robot(body, acts).solve([temperature, temperature])
    # equal forces at opposite offsets: their moments cancel, no bending (to the
    # solver tolerance: curvature ~1e-10 / L = 2.5e-9 1/m; 1e-7 leaves margin)
    np.testing.assert_allclose(sol.omega[:, :2], 0.0, atol=1e-7)
    np.testing.assert_allclose(sol.positions[:, :2], 0.0, atol=1e-10)
    # equal by symmetry, to the solve tolerance relative to the tension
    assert sol.tensions[0] == pytest.approx(sol.tensions[1], rel=1e-8, abs=1e-15)
    if temperature > 26.0:
        # heated extension TCAs push (tension < 0): the body is stretched
        assert sol.tensions[0] < 0.0
        assert sol.tip_position[2] > 0.04


# ------------------------------------------------------- errors and input


def test_convergence_error_carries_residual_and_iterations() -> None:
    robot = FIG6.manipulators[1].robot(gravity=False)
    with pytest.raises(ConvergenceError) as info:
        robot.solve([160.0, 160.0], max_evaluations=1)  # cold at 160 C needs ~3 IVPs
    err = info.value
    assert err.evaluations >= 1
    # no full-grid residual within one IVP of the coarse grid's work: the
    # best residual is unknown, reported as infinite (never NaN, never 0)
    assert err.residual > 1e-10
    assert "did not converge" in str(err)


SQUARE = FIG6.manipulators[1].robot(gravity=False)
BODY = Body(0.04, Section.rectangle(10e-3, 10e-3), 37.8e3, poisson=0.5)


@pytest.mark.parametrize(
    ("call", "field"),
    [
        (lambda: SQUARE.solve([100.0]), "inputs"),  # one value for two actuators
        (lambda: SQUARE.solve([100.0, 100.0, 100.0]), "inputs"),
        (lambda: SQUARE.solve([170.0, 100.0]), r"inputs\[0\].*temperature"),
        (lambda: SQUARE.solve([100.0, 20.0]), r"inputs\[1\].*temperature"),
        (lambda: SQUARE.solve([math.nan, 100.0]), "temperature"),
        (lambda: SQUARE.sweep([[100.0, 100.0], [100.0]]), "inputs"),
        (lambda: SQUARE.solve([100.0, 100.0], steps=0), "steps"),
        (lambda: SQUARE.solve([100.0, 100.0], steps=10**400), "steps"),
        (lambda: SQUARE.solve([100.0, 100.0], tol=math.nan), "tol"),
        (lambda: SQUARE.solve([100.0, 100.0], max_iter=-1), "max_iter"),
        (lambda: SQUARE.solve(10**400), "inputs"),
        (lambda: BODY.replace(tip_force=(math.nan, 0.0, 0.0)), "tip_force"),
        (lambda: BODY.replace(tip_moment=(0.0, math.inf, 0.0)), "tip_moment"),
        (lambda: BODY.replace(gravity=(0.0, 0.0, 10**400)), "gravity"),
        (lambda: BODY.replace(distributed_force=(0.0, math.nan, 0.0)), "distributed_force"),
        (lambda: BODY.replace(density=-1.0), "density"),
        (lambda: BODY.replace(length=10**400), "length"),
        (lambda: Body(0.04, Section.circle(8e-3), math.nan), "youngs_modulus"),
        (lambda: Body(0.04, Section.circle(8e-3), 1e4, poisson=0.7), "poisson"),
        (lambda: Section.circle(10**400), "diameter"),
        (lambda: Section.circle(1e-200), "diameter"),  # I = d^4 pi / 64 underflows to 0
        (lambda: Section.rectangle(1e-2, -1.0), "height"),
        (lambda: Section.custom(1e-4, math.nan, 1e-9, 1e-9), "ix"),
        (lambda: Section.circle(8e-3).edge_distance(math.nan), "theta"),
        (lambda: Routing.straight(math.inf, 0.0), "x"),
        (lambda: Routing.helix(-1e-3, 10.0), "radius"),
        (lambda: Routing.helix(1e-3, 10**400), "rate"),
        (lambda: Routing.straight(0.0, 0.0).evaluate(math.nan), "s"),
        (lambda: Robot(BODY, [Actuator.tca(TCA40, Routing.straight(3e-3, 0.0), 0.0, 0.05)]), "s_end"),
        (lambda: Robot(BODY, [Actuator.tca(TCA40, Routing.straight(3e-3, 0.0), 0.02, 0.01)]), "s_end"),
        (lambda: Robot(BODY, [Actuator.tca(TCA40, Routing.straight(3e-3, 0.0), 0.02, 0.02)]), "s_end"),
        (lambda: Robot(BODY, [Actuator.tca(TCA40, Routing.straight(3e-3, 0.0), 0.04)]), "s_start"),
        (lambda: Actuator.tca(TCA40, Routing.straight(3e-3, 0.0), -0.01), "s_start"),
        (lambda: Actuator.tendon(Routing.straight(3e-3, 0.0), 0.0, math.nan), "s_end"),
        (lambda: Actuator.linear_tendon(0.0, Routing.straight(3e-3, 0.0)), "stiffness"),
        (lambda: Actuator.tendon(Routing.straight(3e-3, 0.0)).tension(0.0, -1.0), "tension"),
        (lambda: Actuator.tca(TCA40, Routing.straight(0.0, 0.0)).tension(math.nan, 100.0), "elongation"),
        (
            lambda: SQUARE.solve([100.0, 100.0], warm_start=FIG6.manipulators[0].robot(False).solve([100.0])),
            "warm_start",
        ),
    ],
)
def test_bad_input_raises_value_error_naming_the_field(call: Any, field: str) -> None:
    with pytest.raises(ValueError, match=field):
        call()


@pytest.mark.parametrize("bad", ["100", None])
def test_wrong_input_type_raises_type_error(bad: Any) -> None:
    with pytest.raises(TypeError):
        SQUARE.solve(bad)


def test_nested_inputs_are_a_shape_error() -> None:
    with pytest.raises(
        ValueError, match=r"^invalid inputs: expected shape \(2,\) \(one input per actuator\), got \(1, 1\)$"
    ):
        SQUARE.solve([[100.0]])


def test_solution_getters_are_finite() -> None:
    # no getter hands NaN (or inf) to Python
    sol: Solution = FIG6.manipulators[0].robot(True).solve([160.0])
    arrays = [n for n in dir(sol) if not n.startswith("_") and isinstance(getattr(sol, n), np.ndarray)]
    assert {"positions", "internal_force", "tensions", "tip_position", "base_moment"} <= set(arrays)
    for name in arrays:
        assert np.all(np.isfinite(getattr(sol, name))), name
    assert all(np.all(np.isfinite(p)) for p in sol.actuator_paths)
    assert math.isfinite(sol.residual)


# ------------------------------------------------------ physically possible geometry


def _coil_robot(section: Section, x: float, y: float = 0.0, **kw: Any) -> Robot:
    """A 40 mm body of ``section`` with the paper's 1.7 mm TCA at ``(x, y)`` [m]."""
    body = Body(0.04, section, 37.8e3, poisson=0.5)
    return Robot(body, [Actuator.tca(span_tca(0.0, None, 0.04), Routing.straight(x, y))], **kw)


@pytest.mark.parametrize("offset", [5.5e-3, 6e-3])
def test_a_coil_sticking_out_of_a_circular_body_is_rejected(offset: float) -> None:
    """A 1.7 mm coil (outer radius 0.85 mm) at 5.5 or 6 mm in a 12 mm body
    reaches 6.35 or 6.85 mm from the axis: outside the silicone."""
    reach = (offset + 0.85e-3) * 1e3
    with pytest.raises(ValueError) as info:
        _coil_robot(Section.circle(12e-3), offset)
    msg = str(info.value)
    assert msg.startswith("invalid actuators[0].routing: the TCA's coil (outer radius 0.85 mm)"), msg
    assert f"reaches {reach:g} mm from the axis, outside the 6 mm radius body section" in msg, msg
    assert "move it inward, or pass spacer_disks=True" in msg, msg
    # on spacer disks outside the body it is a valid robot, and it solves
    robot = _coil_robot(Section.circle(12e-3), offset, spacer_disks=True)
    assert robot.spacer_disks and robot.solve([60.0]).success


def test_a_coil_inside_the_body_is_accepted() -> None:
    # 5 mm + 0.85 mm = 5.85 mm < 6 mm; the paper's square leg at (3, 2.5) mm reaches (3.85, 3.35) mm < 5 mm
    assert _coil_robot(Section.circle(12e-3), 5e-3).solve([60.0]).success
    assert _coil_robot(Section.rectangle(10e-3, 10e-3), 3e-3, 2.5e-3).solve([60.0]).success


def test_a_coil_is_checked_against_the_rectangle_along_each_axis() -> None:
    # a 10 mm x 4 mm strip: along x there is room (3 + 0.85 < 5), along y
    # the coil at y = 1.5 mm reaches 2.35 mm > 2 mm although its distance
    # from the axis (3.35 mm) is well inside the half-width
    strip = Section.rectangle(10e-3, 4e-3)
    assert _coil_robot(strip, 3e-3, 1e-3).solve([60.0]).success
    with pytest.raises(ValueError, match=r"reaches 3\.85 mm from the axis along x and 2\.35 mm along y.*rectangular"):
        _coil_robot(strip, 3e-3, 1.5e-3)
    assert _coil_robot(strip, 3e-3, 1.5e-3, spacer_disks=True).spacer_disks


def test_a_tendon_is_a_line_and_may_run_on_the_edge() -> None:
    body = Body(0.04, Section.circle(12e-3), 37.8e3, poisson=0.5)
    assert Robot(body, [Actuator.tendon(Routing.straight(6e-3, 0.0))]).solve([0.01]).success


def test_the_paper_robots_keep_their_coils_inside_the_body() -> None:
    """Fig. 6 circle (8 mm, TCA at 3 mm: 3.85 mm < 4 mm) and square (10 mm,
    legs at (3, +-2.5) mm): built without spacer disks, so the check passed."""
    for m in FIG6.manipulators:
        assert not m.robot(False).spacer_disks
