"""Forward kinetostatics against closed-form solutions (paper Section III).

* a pure tip moment bends the rod into a circular arc of curvature M/(EI);
* a small tip load deflects it by Euler-Bernoulli plus Timoshenko shear,
  F L^3/(3 E I) + F L/(k G A);
* a large dead tip load perpendicular to the rod gives the inextensible
  elastica of Bisshopp & Drucker (1945), computed here independently with
  scipy's elliptic integrals;
* a straight tendon of constant tension (the Rucker & Webster tendon model
  that the TCA model reduces to) gives an arc of curvature tau r/(EI) less the
  axial shortening tau/(EA); helical routings that degenerate to a straight
  path give the same answer as that path.

Frame: base at the origin, reference tangent +z. SI units.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from tcarod import Actuator, Body, Robot, Routing, Section, Solution, inner_edge_radius

FloatArray = npt.NDArray[np.float64]

LENGTH = 0.04  # [m], the paper's manipulators
DIAMETER = 8e-3  # [m], Fig. 6 circle
E_B = 37.8e3  # [Pa], EcoFlex 10
AREA = math.pi * DIAMETER**2 / 4.0
I_SECTION = math.pi * DIAMETER**4 / 64.0
EI = E_B * I_SECTION


def weightless_body(**kw: object) -> Body:
    return Body(LENGTH, Section.circle(DIAMETER), E_B, poisson=0.5, **kw)  # type: ignore[arg-type]


# ------------------------------------------------------------- pure moment


@pytest.mark.parametrize("axis", [0, 1])
@pytest.mark.parametrize("curvature", [2.0, 25.0])  # [1/m]: tip angle 0.08 and 1.0 rad
def test_pure_tip_moment_gives_circular_arc(axis: int, curvature: float) -> None:
    moment = np.zeros(3)
    moment[axis] = curvature * EI
    sol = Robot(weightless_body(tip_moment=moment)).solve([])
    k, L = curvature, LENGTH
    # A moment about world +y turns the tangent (+z) toward +x; about +x, toward -y.
    bend = np.array([1.0, 0.0, 0.0]) if axis == 1 else np.array([0.0, -1.0, 0.0])
    want = bend * (1.0 - math.cos(k * L)) / k + np.array([0.0, 0.0, math.sin(k * L) / k])
    # Solver tolerance 1e-10 on L * (curvature error) -> curvature error <= 2.5e-9 1/m,
    # tip error <= L^2 * 2.5e-9 ~ 4e-12 m; RK4 (100 steps) integrates an arc of
    # constant curvature to ~(kh)^5 ~ 1e-12 m. 1e-10 m leaves a margin of 10.
    np.testing.assert_allclose(sol.tip_position, want, rtol=0.0, atol=1e-10)
    # curvature along the whole body, to the solver tolerance (2.5e-9 1/m, margin 4)
    np.testing.assert_allclose(sol.omega[:, axis], k, rtol=0.0, atol=1e-8)
    # pure moment: no internal force, so no axial or shear strain
    np.testing.assert_allclose(sol.nu, np.tile([0.0, 0.0, 1.0], (len(sol.s), 1)), rtol=0.0, atol=1e-10)


def test_inner_edge_radius_of_an_arc_is_centre_radius_less_half_width() -> None:
    # The paper's bending radius (circle through base, middle and tip of the
    # concave edge): for an arc of radius 1/k the inner edge is an arc of
    # radius 1/k - d/2 exactly.
    k = 10.0
    sol = Robot(weightless_body(tip_moment=(0.0, k * EI, 0.0))).solve([])
    # the three edge points lie on an exact circle up to the arc error (1e-10 m)
    assert inner_edge_radius(sol) == pytest.approx(1.0 / k - DIAMETER / 2.0, rel=1e-8)


# ------------------------------------------------- small load, Timoshenko


@pytest.mark.parametrize("shear_coefficient", [1.0, 0.5])
def test_small_tip_load_matches_euler_bernoulli_plus_shear(shear_coefficient: float) -> None:
    body = weightless_body(shear_coefficient=shear_coefficient)
    g_b = body.shear_modulus
    force = 1e-4 * EI / LENGTH**2  # F L^2 / EI = 1e-4: tip angle ~5e-5 rad
    sol = Robot(body.replace(tip_force=(force, 0.0, 0.0))).solve([])
    bending = force * LENGTH**3 / (3.0 * EI)
    shear = force * LENGTH / (shear_coefficient * g_b * AREA)
    # Linear theory neglects terms of relative order (F L^2 / EI)^2 = 1e-8; the
    # solver tolerance contributes ~1e-9 relative. The shear term is 2-4 % of
    # the total here, so 1e-6 relative separates it from Euler-Bernoulli alone
    # by four orders of magnitude.
    assert sol.tip_position[0] == pytest.approx(bending + shear, rel=1e-6)
    assert abs(sol.tip_position[0] - bending) > 0.01 * bending
    assert abs(sol.tip_position[1]) < 1e-15


# ------------------------------------------------ large load, the elastica


def elastica(alpha: float) -> tuple[float, float, float]:
    """Bisshopp & Drucker (1945): inextensible cantilever of length L under a
    dead end load P perpendicular to its straight shape, ``alpha = P L^2 / EI``.

    Returns ``(theta0 [rad], x/L, y/L)``: tip slope, tip coordinate along the
    original axis, tip deflection along the load. With
    ``k^2 = (1 + sin theta0) / 2`` and ``sin phi1 = 1 / (sqrt(2) k)``:
    ``sqrt(alpha) = K(k) - F(phi1, k)``,
    ``y/L = 1 - 2 (E(k) - E(phi1, k)) / sqrt(alpha)`` and
    ``x/L = sqrt(2 sin(theta0) / alpha)`` (from ``EI theta'^2 / 2 = P (sin theta0 - sin theta)``).
    scipy's elliptic integrals take the parameter ``m = k^2``.
    """

    def mismatch(k: float) -> float:
        phi1 = math.asin(1.0 / (math.sqrt(2.0) * k))
        return float(ellipk(k * k) - ellipkinc(phi1, k * k)) - math.sqrt(alpha)

    k = brentq(mismatch, 1.0 / math.sqrt(2.0) + 1e-15, 1.0 - 1e-15, xtol=1e-15, rtol=1e-15)
    phi1 = math.asin(1.0 / (math.sqrt(2.0) * k))
    theta0 = math.asin(2.0 * k * k - 1.0)
    y = 1.0 - 2.0 / math.sqrt(alpha) * float(ellipe(k * k) - ellipeinc(phi1, k * k))
    x = math.sqrt(2.0 * math.sin(theta0) / alpha)
    return theta0, x, y


# Bisshopp & Drucker's table, to the 4 digits it is usually quoted with
# (alpha = P L^2 / EI: x/L, y/L), e.g. alpha = 1: horizontal shortening
# (L - x)/L = 0.0564, vertical deflection 0.3017.
PUBLISHED = {1.0: (0.9436, 0.3017), 2.0: (0.8394, 0.4935), 10.0: (0.4450, 0.8106)}


@pytest.mark.parametrize("alpha", sorted(PUBLISHED))
def test_elliptic_reference_reproduces_published_table(alpha: float) -> None:
    _, x, y = elastica(alpha)
    # 4 published digits: rounding leaves at most 5e-5
    assert x == pytest.approx(PUBLISHED[alpha][0], abs=5e-5)
    assert y == pytest.approx(PUBLISHED[alpha][1], abs=5e-5)


def _loaded_tips(area_factor: float, alphas: list[float]) -> dict[float, FloatArray]:
    """Tip positions / L of a rod with ``area_factor`` times the area (same I,
    hence same EI, but EA and GA scaled) under dead tip loads ``alpha EI/L^2``
    along +x, reached by load continuation (each solve warm-started from the
    previous load)."""
    section = Section.custom(AREA * area_factor, I_SECTION, I_SECTION, 2.0 * I_SECTION)
    previous: Solution | None = None
    tips: dict[float, FloatArray] = {}
    for alpha in alphas:
        body = Body(LENGTH, section, E_B, poisson=0.5, tip_force=(alpha * EI / LENGTH**2, 0.0, 0.0))
        previous = Robot(body).solve([], steps=100, warm_start=previous)
        tips[alpha] = previous.tip_position / LENGTH
    return tips


def test_large_tip_load_matches_bisshopp_drucker_elastica() -> None:
    """The rod made inextensible and unshearable by Section.custom with a
    larger area (same I) converges, as the area grows, to the elastica.

    Directly with a very large area (x1000) the shooting solver does not
    converge (see ``test_stiff_section_large_load_converges_from_straight``),
    so the inextensible limit is reached by Richardson extrapolation in the
    axial/shear compliance 1/area_factor: the tip's deviation from the
    elastica is a smooth function c1/f + c2/f^2 + ... of 1/f (f = area
    factor), and three areas f = 2, 4, 8 eliminate c1 and c2.
    """
    alphas = [round(0.25 * j, 2) for j in range(1, 41)]  # 0.25 .. 10 in steps of 0.25
    runs = [_loaded_tips(f, alphas) for f in (2.0, 4.0, 8.0)]
    for alpha in (1.0, 2.0, 5.0, 10.0):
        theta0, x, y = elastica(alpha)
        t2, t4, t8 = (r[alpha] for r in runs)
        # compliance matters at f = 2: the tip differs from the elastica by 0.3-2 % of L
        assert abs(t2[0] - y) > 1e-3
        r24, r48 = 2.0 * t4 - t2, 2.0 * t8 - t4  # eliminate c1
        limit = (4.0 * r48 - r24) / 3.0  # eliminate c2
        # 4 digits: |error| < 5e-5 L. The c3/f^3 remainder is ~(2 %)^3 / 64 ~ 1e-7,
        # RK4 (100 steps) and the solver tolerance ~1e-9.
        assert limit[0] == pytest.approx(y, abs=5e-5), (alpha, limit, y)
        assert limit[2] == pytest.approx(x, abs=5e-5), (alpha, limit, x)
        assert abs(limit[1]) < 1e-12


# The tip force residual is scaled by L^2/EI (src/shooting.rs residual_scales),
# so the line search sees force errors of axially stiff sections.
@pytest.mark.parametrize(("area_factor", "alpha"), [(1.0, 10.0), (100.0, 1.0)])
def test_stiff_section_large_load_converges_from_straight(area_factor: float, alpha: float) -> None:
    section = Section.custom(AREA * area_factor, I_SECTION, I_SECTION, 2.0 * I_SECTION)
    body = Body(LENGTH, section, E_B, poisson=0.5, tip_force=(alpha * EI / LENGTH**2, 0.0, 0.0))
    sol = Robot(body).solve([])
    _, _, y = elastica(alpha)
    # Shear and axial compliance only add deflection along the load, and by at
    # most the largest shear plus axial strain, P/(k G A) + P/(E A), integrated
    # over the length (|d(p - p_inextensible)/ds| <= those strains).
    p_load = alpha * EI / LENGTH**2
    bound = p_load / (E_B / 3.0 * AREA * area_factor) + p_load / (E_B * AREA * area_factor)
    excess = sol.tip_position[0] / LENGTH - y
    assert -1e-6 < excess < bound, (excess, bound)


# ------------------------------------------------ tendon of constant tension


@pytest.mark.parametrize("offset", [(3e-3, 0.0), (0.0, -2e-3), (1.5e-3, 2e-3)])
def test_straight_tendon_gives_arc_less_axial_shortening(offset: tuple[float, float]) -> None:
    tau = 0.05  # [N]
    body = weightless_body()
    r = np.array([offset[0], offset[1], 0.0])
    sol = Robot(body, [Actuator.tendon(Routing.straight(*offset))]).solve([tau])
    ea = E_B * AREA
    radius = float(np.linalg.norm(r))
    k = tau * radius / EI  # the tendon's moment / EI; it bends the body toward the tendon
    stretch = 1.0 - tau / ea  # compressed by the tension
    toward = r / radius
    L = LENGTH
    want = toward * stretch * (1.0 - math.cos(k * L)) / k + np.array([0.0, 0.0, stretch * math.sin(k * L) / k])
    # exact arc under this model (Rucker & Webster 2011); RK4 + solver tolerance ~1e-12 m
    np.testing.assert_allclose(sol.tip_position, want, rtol=0.0, atol=1e-11)
    assert sol.tensions[0] == tau
    # the tendon path is the centre line offset by R r: shorter than the body
    assert sol.elongations[0] < 0.0


def test_helix_of_zero_radius_is_a_centred_tendon() -> None:
    # r = 0 whatever the rate: the tendon runs on the centre line and only
    # compresses the straight rod by tau/(EA).
    tau = 0.2
    sol = Robot(weightless_body(), [Actuator.tendon(Routing.helix(0.0, 300.0, 0.7))]).solve([tau])
    ea = E_B * AREA
    want = np.array([0.0, 0.0, LENGTH * (1.0 - tau / ea)])
    # x, y exactly zero (nothing bends it); z to the solver tolerance 1e-10 on the
    # axial strain: L * 1e-10 = 4e-12 m (margin 5)
    np.testing.assert_allclose(sol.tip_position, want, rtol=0.0, atol=2e-11)
    assert sol.tip_position[0] == 0.0 and sol.tip_position[1] == 0.0
    # tau / EA = 0.1: strain tolerance 1e-10 is 1e-9 relative (margin 10)
    assert sol.elongations[0] == pytest.approx(-LENGTH * tau / ea, rel=1e-8)


def test_helix_of_zero_rate_equals_straight_routing() -> None:
    # rate 0: r = radius (cos phase, sin phase, 0) for all s, r' = r'' = 0, the same path
    # as a straight routing at that offset -- through the helix code path (r', r'' terms).
    radius, phase = 2.5e-3, 2.0
    tau = 0.03
    body = weightless_body()
    helix = Robot(body, [Actuator.tendon(Routing.helix(radius, 0.0, phase))]).solve([tau])
    straight = Robot(
        body, [Actuator.tendon(Routing.straight(radius * math.cos(phase), radius * math.sin(phase)))]
    ).solve([tau])
    np.testing.assert_allclose(helix.positions, straight.positions, rtol=0.0, atol=1e-14)  # identical arithmetic


@pytest.mark.parametrize("turns", [1.0, -1.0, 2.0])
def test_helical_tendon_small_tension_matches_linear_theory(turns: float) -> None:
    """A helical tendon ``r = a (cos(w s), sin(w s), 0)`` with ``w = 2 pi turns / L``
    under a small tension. Cutting the body at ``s``, the tendon's force
    ``tau t_a`` with ``t_a = (e3 + r') / sqrt(1 + (a w)^2)`` acts at ``r``, so to
    first order in ``tau`` the body carries the moment ``-r x tau t_a``:
    a bending curvature ``tau a / (EI c)`` toward the tendon (``c = sqrt(1 + (a w)^2)``)
    and a twist ``u_z = -tau a^2 w / (GJ c)``. The bending direction turns with
    the tendon, so the tip moves sideways by
    ``int_0^L (L - s) kappa (cos(w s), sin(w s)) ds = (0, kappa L^2 / (2 pi turns))``.
    This checks the helix's ``r'`` terms (tangent, twisting moment) independently.
    """
    a, tau = 3e-3, 1e-4  # [m], [N]: kappa L ~ 2e-3, twist over L ~ 1e-3 rad
    w = 2.0 * math.pi * turns / LENGTH
    body = weightless_body()
    sol = Robot(body, [Actuator.tendon(Routing.helix(a, w))]).solve([tau])
    c = math.sqrt(1.0 + (a * w) ** 2)
    kappa = tau * a / (EI * c)
    gj = body.shear_modulus * 2.0 * I_SECTION  # J = 2 I for a circle
    y_lin = kappa * LENGTH**2 / (2.0 * math.pi * turns)
    # neglected terms are of relative order kappa L and (twist angle): ~2e-3; 5e-3 leaves margin 2.5
    assert sol.tip_position[1] == pytest.approx(y_lin, rel=5e-3)
    assert abs(sol.tip_position[0]) < 5e-3 * abs(y_lin)
    np.testing.assert_allclose(sol.omega[:, 2], -tau * a * a * w / (gj * c), rtol=5e-3)
