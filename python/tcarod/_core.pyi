"""Type stub of the Rust extension ``tcarod._core`` (hand-written; checked
against the compiled module by ``python -m mypy.stubtest tcarod._core``).

Units: lengths in m, forces in N (tension > 0), torques in N m, moduli in Pa,
temperatures in degrees C. Argument errors raise ``ValueError`` naming the
argument; wrong Python types raise ``TypeError``.
"""

from collections.abc import Callable, Sequence
from typing import Any, Final, Literal, final

import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure
from typing_extensions import Self, disjoint_base

_Chirality = Literal["extension", "contraction"]
_FloatArray = npt.NDArray[np.float64]

__version__: Final[str]

class ConvergenceError(RuntimeError):
    """A solve stopped without meeting its tolerance."""

    #: Best residual norm reached (dimensionless unless the solver says otherwise).
    residual: float
    #: Iterations performed.
    iterations: int
    #: IVPs integrated, failed attempts included.
    evaluations: int
    #: Why it stopped: "iteration_limit", "line_search", "singular_jacobian",
    #: "non_finite", "budget" (``max_evaluations`` or ``time_limit`` spent),
    #: "integration" or "other".
    reason: str

class UnstableEquilibriumError(RuntimeError):
    """``Robot.solve(..., stability="require")`` (or ``require_stable=True``)
    converged to an unstable equilibrium."""

    #: Stability margin of the equilibrium found [-] (< 0).
    margin: float
    #: The unstable equilibrium found.
    solution: Solution

class UnitsWarning(UserWarning):
    """Sizes that are valid SI numbers but look like millimetres."""

class UnstableEquilibriumWarning(UserWarning):
    """A solve handed back an unstable equilibrium (``stability="report"``,
    the default); ``stability="continue"`` moves to a stable one."""

_Policy = Literal["report", "require", "continue", "off"]

@final
class Material:
    """Temperature-dependent properties of a TCA's twisted fibre (linear in T).

    ``E_T(T) = youngs_modulus + youngs_modulus_slope (T - t_ref)`` [Pa], the
    same for ``G_T`` (``shear_modulus_slope`` defaults to constant ``G/E``), and
    ``rho(T) = expansion + expansion_slope (T - t_ref)`` [1/C] with fibre
    diameter ``d = d0 (1 + rho(T) (T - t_ref))``. Valid for
    ``t_min <= T <= t_max`` [C].
    """

    def __new__(
        cls,
        *,
        youngs_modulus: float,
        shear_modulus: float,
        expansion: float,
        youngs_modulus_slope: float = 0.0,
        shear_modulus_slope: float | None = None,
        expansion_slope: float = 0.0,
        t_ref: float = 25.0,
        t_min: float = 25.0,
        t_max: float = 160.0,
        name: str = "custom",
    ) -> Self: ...
    @staticmethod
    def silver_coated_nylon() -> Material:
        """The paper's silver-coated nylon 6,6 thread with the documented defaults."""
    @staticmethod
    def nylon66_measured_cte() -> Material:
        """The same thread with the measured radial CTE of oriented nylon 6,6 (Choy et al. 1984)."""
    @staticmethod
    def measured_radial_cte(temperature: float) -> float:
        """Measured radial CTE [1/K] of oriented nylon 6,6 at ``temperature`` [C] (-41..160 C)."""
    @staticmethod
    def measured_radial_cte_data() -> list[tuple[float, float]]:
        """The measured ``(T [C], alpha_r [1/K])`` points (Choy et al. 1984)."""
    def with_expansion_scale(self, factor: float) -> Material:
        """This material with ``rho(T)`` scaled by ``factor`` [-]."""
    def instantaneous_expansion(self, temperature: float) -> float:
        """Instantaneous expansion coefficient ``d'(T)/d(T)`` [1/C] at ``temperature`` [C]."""
    def __getnewargs_ex__(self) -> tuple[tuple[Any, ...], dict[str, Any]]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def t_ref(self) -> float:
        """Reference (ambient) temperature [C] at which ``d = d0``."""
    @property
    def t_min(self) -> float:
        """Lowest valid temperature [C]."""
    @property
    def t_max(self) -> float:
        """Highest valid temperature [C]."""
    @property
    def coefficients(self) -> tuple[float, float, float, float, float, float]:
        """``(E_ref [Pa], dE/dT [Pa/C], G_ref [Pa], dG/dT [Pa/C], rho_ref [1/C], drho/dT [1/C^2])``."""
    def youngs_modulus(self, temperature: float) -> float:
        """``E_T`` [Pa] at ``temperature`` [C]."""
    def shear_modulus(self, temperature: float) -> float:
        """``G_T`` [Pa] at ``temperature`` [C]."""
    def expansion(self, temperature: float) -> float:
        """``rho`` [1/C] at ``temperature`` [C]."""
    def diameter_ratio(self, temperature: float) -> float:
        """``d/d0`` [-] at ``temperature`` [C]."""

@disjoint_base
class Tca:
    """A twisted-and-coiled actuator (paper Section II); see ``tcarod.Tca``."""

    def __new__(
        cls,
        fibre_length: float,
        coiled_length: float,
        coil_diameter: float,
        turns: float,
        chirality: _Chirality = "extension",
        material: Material | None = None,
    ) -> Self: ...
    def __getnewargs_ex__(self) -> tuple[tuple[Any, ...], dict[str, Any]]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    @classmethod
    def from_pitch_angle(
        cls,
        coiled_length: float,
        alpha0: float,
        coil_diameter: float,
        turns: float,
        chirality: _Chirality = "extension",
        material: Material | None = None,
    ) -> Self:
        """Build from coiled length ``L`` [m] and pitch angle ``alpha0`` [rad]: ``l = L / sin(alpha0)``."""
    def segment(self, fraction: float) -> Self:
        """The fraction ``fraction`` (0 < fraction <= 1) of this TCA as a segment in series:
        ``l``, ``L`` and ``N`` scaled by ``fraction``; same ``D``, ``alpha0``, ``d0``, material."""
    @property
    def fibre_length(self) -> float:
        """Twisted-fibre length ``l`` [m]."""
    @property
    def coiled_length(self) -> float:
        """Coiled length ``L`` [m]."""
    @property
    def coil_diameter(self) -> float:
        """Coil outer diameter ``D`` [m]."""
    @property
    def turns(self) -> float:
        """Inserted turns ``N`` [-]."""
    @property
    def chirality(self) -> _Chirality: ...
    @property
    def material(self) -> Material: ...
    @property
    def alpha0(self) -> float:
        """Initial pitch angle ``asin(L/l)`` [rad]."""
    @property
    def n_coils(self) -> float:
        """Number of coils ``2 cos(alpha0) l / (pi D)`` [-]."""
    @property
    def phi0(self) -> float:
        """Initial twist ``2 pi N`` [rad]."""
    @property
    def d0(self) -> float:
        """Fibre diameter at the reference temperature, ``2 D L / l`` [m]."""
    @property
    def max_displacement(self) -> float:
        """Straight-fibre limit of the elongation, ``l (1 - sin alpha0)`` [m]."""
    def pitch_angle(self, displacement: float) -> float:
        """Pitch angle [rad] at elongation ``displacement`` [m], eq (5)."""
    def f11(self, alpha: float, temperature: float) -> float:
        """``f11`` [m/N] of eq (3) at pitch angle ``alpha`` [rad] and ``temperature`` [C]."""
    def f12(self, alpha: float, temperature: float) -> float:
        """``f12`` [1/N] of eq (4) at pitch angle ``alpha`` [rad] and ``temperature`` [C]."""
    def torque(self, temperature: float) -> float:
        """Untwisting torque ``tau`` [N m] of eq (1) at ``temperature`` [C]."""
    def fibre_diameter(self, temperature: float) -> float:
        """Fibre diameter ``d`` [m] at ``temperature`` [C]."""
    def _displacement_flat(self, force: _FloatArray, temperature: _FloatArray) -> _FloatArray: ...
    def _force_flat(self, displacement: _FloatArray, temperature: _FloatArray) -> _FloatArray: ...
    def _temperature_flat(self, force: _FloatArray, displacement: _FloatArray) -> _FloatArray: ...

# ---------------------------------------------------------------------------
# Forward kinetostatics (src/python/rod.rs; paper Section III, eqs 7-33).
# World frame: base at the origin, reference tangent +z. Vectors given to or
# returned by these classes are length-3 world-frame vectors unless noted;
# body-frame offsets (routing) span the cross-section (x, y). Actuator forces
# are tensions [N] (negative: the actuator pushes). No getter returns NaN.
# ---------------------------------------------------------------------------

_Vec3 = Sequence[float] | _FloatArray

@final
class Section:
    """Cross-section of a body: ``Section.circle``, ``Section.rectangle`` or ``Section.custom``."""

    @staticmethod
    def circle(diameter: float) -> Section:
        """Solid circle of ``diameter`` [m]."""
    @staticmethod
    def rectangle(width: float, height: float) -> Section:
        """Solid rectangle: ``width`` [m] along body x, ``height`` [m] along body y."""
    @staticmethod
    def custom(area: float, ix: float, iy: float, j: float) -> Section:
        """User-given area [m^2], second moments about body x and y [m^4], torsion constant [m^4]."""
    @property
    def properties(self) -> tuple[float, float, float, float]:
        """``(area [m^2], ix [m^4], iy [m^4], j [m^4])``."""
    def edge_distance(self, theta: float) -> float:
        """Distance [m] from the centre line to the edge in body-frame direction angle ``theta`` [rad]
        (a custom section is treated as the circle of its area)."""
    @property
    def kind(self) -> Literal["circle", "rectangle", "custom"]: ...
    @property
    def parameters(self) -> dict[str, float]:
        """Constructor keywords exactly as given (sizes [m], area [m^2], moments [m^4])."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class Routing:
    """Body-frame path of an actuator: ``Routing.straight`` or ``Routing.helix``."""

    @staticmethod
    def straight(x: float, y: float) -> Routing:
        """Parallel to the centre line at body-frame offset ``(x, y)`` [m]."""
    @staticmethod
    def helix(radius: float, rate: float, phase: float = 0.0) -> Routing:
        """``r(s) = radius (cos(rate s + phase), sin(rate s + phase), 0)``: ``radius`` [m],
        ``rate`` [rad/m] (positive: right-handed about +z), ``phase`` [rad]."""
    def evaluate(self, s: float) -> tuple[_FloatArray, _FloatArray, _FloatArray]:
        """``(r [m], r' [-], r'' [1/m])`` at arc length ``s`` [m], body frame, length 3 each."""
    @property
    def kind(self) -> Literal["straight", "helix"]: ...
    @property
    def parameters(self) -> dict[str, float]:
        """Constructor keywords exactly as given (``x``, ``y`` [m] or ``radius`` [m], ``rate`` [rad/m], ``phase`` [rad])."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@final
class Body:
    """The soft body (a Cosserat rod): geometry, material, reference strains, loads.

    ``poisson`` (default 0.5) or ``shear_modulus`` [Pa] sets ``G_B``;
    ``density`` [kg/m^3]; ``shear_coefficient`` ``k`` in ``K_nu = diag(k G A, k G A, E A)``;
    ``nu_star`` [-] and ``omega_star`` [1/m] are the body-frame reference strains
    (default ``(0, 0, 1)`` and zero; non-zero ``omega_star``: pre-curved);
    ``gravity`` [m/s^2], ``distributed_force`` [N/m], ``distributed_moment``
    [N m/m], ``tip_force`` [N], ``tip_moment`` [N m] in the world frame.
    """

    def __new__(
        cls,
        length: float,
        section: Section,
        youngs_modulus: float,
        *,
        poisson: float | None = None,
        shear_modulus: float | None = None,
        density: float = 0.0,
        shear_coefficient: float = 1.0,
        nu_star: _Vec3 | None = None,
        omega_star: _Vec3 | None = None,
        gravity: _Vec3 | None = None,
        distributed_force: _Vec3 | None = None,
        distributed_moment: _Vec3 | None = None,
        tip_force: _Vec3 | None = None,
        tip_moment: _Vec3 | None = None,
    ) -> Self: ...
    def __getnewargs_ex__(self) -> tuple[tuple[Any, ...], dict[str, Any]]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    @property
    def shear_coefficient(self) -> float:
        """Shear coefficient [-] (Timoshenko)."""
    @property
    def distributed_force(self) -> _FloatArray:
        """Distributed force [N/m] besides gravity (world frame), shape ``(3,)``."""
    def replace(self, **changes: Any) -> Body:
        """A copy with some fields replaced (same keywords as the constructor)."""
    def kwargs(self) -> dict[str, Any]:
        """Constructor keywords of this body (``shear_modulus`` rather than ``poisson``)."""
    @property
    def length(self) -> float:
        """Length of the centre line [m]."""
    @property
    def section(self) -> Section: ...
    @property
    def youngs_modulus(self) -> float:
        """``E_B`` [Pa]."""
    @property
    def shear_modulus(self) -> float:
        """``G_B`` [Pa]."""
    @property
    def density(self) -> float:
        """``psi`` [kg/m^3]."""
    @property
    def nu_star(self) -> _FloatArray:
        """Reference linear strain [-], body frame."""
    @property
    def omega_star(self) -> _FloatArray:
        """Reference angular strain [1/m], body frame."""
    @property
    def gravity(self) -> _FloatArray:
        """Gravitational acceleration [m/s^2], world frame."""
    @property
    def tip_force(self) -> _FloatArray:
        """Tip force [N], world frame."""
    @property
    def tip_moment(self) -> _FloatArray:
        """Tip moment [N m], world frame."""
    @property
    def distributed_load(self) -> _FloatArray:
        """Total distributed force ``psi A g + f`` [N/m], world frame."""
    @property
    def distributed_moment(self) -> _FloatArray:
        """Distributed moment [N m/m], world frame."""
    def stiffness(self) -> tuple[_FloatArray, _FloatArray]:
        """``(K_nu [N], K_omega [N m^2])``, diagonal 3x3 matrices."""

@final
class Actuator:
    """A string-like actuator: ``Actuator.tca`` (input: temperature [C]),
    ``Actuator.tendon`` (input: tension [N]) or ``Actuator.linear_tendon``
    (input: length pulled in at the base [m]). It runs from arc length
    ``s_start`` [m] to ``s_end`` [m] (``None``: the tip); ``length_ratio`` is
    the paper's ``L_i`` (``None``: the reference configuration is unstrained)."""

    @staticmethod
    def tca(
        tca: Tca,
        routing: Routing,
        s_start: float = 0.0,
        s_end: float | None = None,
        length_ratio: float | None = None,
        *,
        pretension_n: float | None = None,
    ) -> Actuator:
        """``pretension_n`` [N]: tension at the reference temperature in the
        undeformed body (makes contraction TCAs act); sets ``length_ratio``."""
    @staticmethod
    def tendon(
        routing: Routing,
        s_start: float = 0.0,
        s_end: float | None = None,
        length_ratio: float | None = None,
    ) -> Actuator: ...
    @staticmethod
    def linear_tendon(
        stiffness: float,
        routing: Routing,
        s_start: float = 0.0,
        s_end: float | None = None,
        length_ratio: float | None = None,
    ) -> Actuator:
        """``stiffness`` [N/m]: tension ``k (pull + elongation)``, zero when slack."""
    @property
    def kind(self) -> Literal["tca", "tension", "linear_tendon"]: ...
    @property
    def input_name(self) -> str:
        """Name and unit of the input, e.g. ``"temperature [C]"``."""
    @property
    def input_bounds(self) -> tuple[float, float]:
        """``(lowest, highest)`` valid input."""
    @property
    def reference_input(self) -> float:
        """Input of the passive (reference) state."""
    @property
    def routing(self) -> Routing: ...
    @property
    def s_start(self) -> float:
        """Proximal anchor [m]."""
    @property
    def s_end(self) -> float:
        """Distal anchor [m]; ``inf`` means the tip."""
    @property
    def length_ratio(self) -> float | None: ...
    @property
    def tca_model(self) -> Tca | None:
        """The TCA, for TCA actuators."""
    def tension(self, elongation: float, input: float) -> float:
        """Tension [N] at total elongation ``elongation`` [m] and ``input``."""
    @property
    def pretension_n(self) -> float | None:
        """Pre-tension [N] at the reference temperature, or ``None``."""
    @property
    def stiffness(self) -> float | None:
        """Tendon stiffness [N/m] of a linear tendon, else ``None``."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

@disjoint_base
class Robot:
    """A body with its embedded actuators (see ``tcarod.Robot``)."""

    def __new__(cls, body: Body, actuators: Sequence[Actuator] = (), *, spacer_disks: bool = False) -> Self: ...
    def __getnewargs_ex__(self) -> tuple[tuple[Any, ...], dict[str, Any]]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    @property
    def spacer_disks(self) -> bool:
        """``True`` if the actuators run through spacer disks outside the section."""
    @property
    def body(self) -> Body: ...
    @property
    def actuators(self) -> list[Actuator]: ...
    @property
    def reference_inputs(self) -> list[float]:
        """Passive inputs (25 C for TCAs, zero for tendons)."""
    def solve(
        self,
        inputs: float | Sequence[float] | _FloatArray,
        *,
        steps: int = 100,
        tol: float = 1e-10,
        max_iter: int = 50,
        warm_start: Solution | None = None,
        stability: _Policy = "report",
        require_stable: bool = False,
        max_evaluations: int = 20000,
        time_limit: float | None = None,
    ) -> Solution:
        """Forward kinetostatics for one input per actuator (temperature [C] for TCAs);
        ``steps`` RK4 steps over the body; ``max_evaluations`` IVPs and
        ``time_limit`` seconds bound the whole solve (continuation included).
        ``stability``: ``"report"`` (the verdict comes with the solution, one
        tangent IVP; an unstable one warns ``UnstableEquilibriumWarning``),
        ``"require"`` (raise ``UnstableEquilibriumError``), ``"continue"`` (move
        to a stable equilibrium at the same inputs; ``Solution.continued``) or
        ``"off"`` (no verdict, hot loops); ``require_stable=True`` is
        ``"require"``. Raises ``ValueError`` on bad input and
        ``ConvergenceError`` if Newton fails (``reason == "budget"`` when the
        budget ran out)."""
    def sweep(
        self,
        inputs: Sequence[Sequence[float] | _FloatArray] | _FloatArray,
        *,
        steps: int = 100,
        tol: float = 1e-10,
        max_iter: int = 50,
        stability: _Policy = "report",
    ) -> list[Solution]:
        """Solve along rows of ``inputs`` (shape ``(k, n_actuators)``), each
        warm-started from the previous; ``stability`` as for ``solve`` (one
        warning names the unstable rows; ``"continue"`` follows the physical
        robot's quasi-static path)."""

@final
class Solution:
    """A converged forward solution at ``n`` nodes; NumPy arrays, SI units,
    world frame unless noted."""

    @property
    def robot(self) -> Robot: ...
    @property
    def s(self) -> _FloatArray:
        """Arc length of each node [m], shape ``(n,)``."""
    @property
    def positions(self) -> _FloatArray:
        """Centre-line positions [m], shape ``(n, 3)``."""
    @property
    def rotations(self) -> _FloatArray:
        """Rotation matrices (body to world), shape ``(n, 3, 3)``."""
    @property
    def nu(self) -> _FloatArray:
        """Linear strain [-], body frame, shape ``(n, 3)``."""
    @property
    def omega(self) -> _FloatArray:
        """Angular strain [1/m], body frame, shape ``(n, 3)``."""
    @property
    def internal_force(self) -> _FloatArray:
        """Internal force ``n`` [N], shape ``(n, 3)``."""
    @property
    def internal_moment(self) -> _FloatArray:
        """Internal moment ``m`` [N m], shape ``(n, 3)``."""
    @property
    def elongation_profile(self) -> _FloatArray:
        """Elongation of each actuator up to each node [m], shape ``(n, n_actuators)``."""
    @property
    def actuator_paths(self) -> list[_FloatArray]:
        """Path ``p + R r_i`` [m] of each actuator over its span, ``(k_i, 3)`` each."""
    @property
    def tensions(self) -> _FloatArray:
        """Actuator tensions [N] (negative: pushes), shape ``(n_actuators,)``."""
    @property
    def elongations(self) -> _FloatArray:
        """Actuator total elongations [m], shape ``(n_actuators,)``."""
    @property
    def inputs(self) -> _FloatArray:
        """Inputs solved for (temperature [C] for TCAs)."""
    @property
    def base_force(self) -> _FloatArray:
        """Force [N] transmitted to the base by body and actuators (the reaction is its negative)."""
    @property
    def base_moment(self) -> _FloatArray:
        """Moment [N m] about the origin transmitted to the base."""
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m], shape ``(3,)``."""
    @property
    def tip_rotation(self) -> _FloatArray:
        """Tip rotation, shape ``(3, 3)``."""
    @property
    def iterations(self) -> int:
        """Newton iterations used (including any fallback continuation)."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated."""
    @property
    def residual(self) -> float:
        """Final residual (max-norm, dimensionless strain units)."""
    @property
    def floor(self) -> float:
        """Estimated rounding floor of the dimensionless residual at the solution [-];
        a ``tol`` below it converges to it (``status == 1``)."""
    @property
    def continuation_steps(self) -> _FloatArray:
        """Homotopy parameters in (0, 1], ending at 1, of the continuation path
        taken when the direct Newton solve failed; empty if it did not."""
    @property
    def unknowns(self) -> _FloatArray:
        """Scaled shooting unknowns ``[nu(0), L omega(0), delta_i / L]``."""
    def plot(self, **kwargs: Any) -> Figure:
        """3-D plot of the shape with the actuators; see ``tcarod.plotting.plot_solution``."""
    @property
    def success(self) -> bool:
        """Always ``True`` (a failed solve raises ``ConvergenceError``)."""
    @property
    def status(self) -> int:
        """``0``: converged to ``tol``; ``1``: ``tol`` lies below the estimated
        rounding floor and the residual reached the floor (``floor``). Both are
        successes (as in ``scipy.optimize.least_squares``)."""
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int:
        """Newton iterations (``iterations``)."""
    @property
    def nfev(self) -> int:
        """IVPs integrated (``evaluations``)."""
    @property
    def steps(self) -> int:
        """RK4 steps over the body."""
    @property
    def stable(self) -> bool:
        """True if the equilibrium is stable (strict local energy minimum);
        computed by the solve (``stability="report"``, the default) or on
        first access (one tangent IVP, GIL released), and cached. A
        ``BlockedResult.solution`` carries the verdict with its tip held."""
    @property
    def stability_margin(self) -> float:
        """Smallest eigenvalue of the dimensionless tip stiffness [-], ``> 0``
        iff ``stable``; computed and cached with ``stable``."""
    @property
    def continued(self) -> Continuation | None:
        """How ``stability="continue"`` reached this equilibrium from an
        unstable one, or None."""
    def __reduce__(self) -> tuple[Any, ...]: ...

@final
class Continuation:
    """Route of a ``stability="continue"`` solve from the unstable
    equilibrium Newton found first to the stable one handed back."""

    @property
    def route(self) -> str: ...
    @property
    def unstable(self) -> Solution: ...
    @property
    def margin(self) -> float:
        """Stability margin of the unstable equilibrium [-] (< 0)."""
    @property
    def candidates(self) -> int: ...
    @property
    def evaluations(self) -> int: ...
    def __eq__(self, value: object, /) -> bool: ...

def _restore_section(kind: str, values: Sequence[float]) -> Section: ...
def _restore_routing(kind: str, values: Sequence[float]) -> Routing: ...
def _restore_actuator(
    kind: str,
    tca: Tca | None,
    stiffness: float | None,
    routing: Routing,
    s_start: float,
    s_end: float | None,
    length_ratio: float | None,
    pretension_n: float | None,
) -> Actuator: ...
def _register_plotter(plotter: Callable[..., Any]) -> None:
    """Register the function ``Solution.plot`` calls (the package does it at import)."""

def _restore_solution(
    robot: Robot,
    inputs: Sequence[float],
    unknowns: Sequence[float],
    tip_force: Sequence[float],
    tip_moment: Sequence[float],
    steps: int,
    iterations: int,
    evaluations: int,
    jacobian: tuple[int, int, Sequence[float]] | None,
    outcome: tuple[int, float, Sequence[float]] | None = None,
    blocked: Sequence[Sequence[float]] | None = None,
) -> Solution: ...
def _restore_inverse_result(
    solution: Solution,
    variables: Sequence[float],
    error: float,
    iterations: int,
    reached: bool,
    at_bound: Sequence[bool],
    evaluations: int,
    max_iter: int,
) -> InverseResult: ...
def _restore_blocked_result(
    solution: Solution, force: float, variables: Sequence[float], iterations: int, evaluations: int
) -> BlockedResult: ...
def _experiment_robot(name: Literal["fig6_circle", "fig6_square"], gravity: bool) -> Robot:
    """The Rust fixture ``name`` of ``src/experiments.rs`` (for tests; not public API)."""

# ---------------------------------------------------------------------------
# Inverse kinetostatics (src/python/inverse.rs; paper Section IV, eqs 34-43).
# `Robot` and `Solution` are the rod classes stubbed above. Tip poses are
# `[dp (m); dtheta (rad)]` in the world frame; tip wrenches `[F (N); M (N m)]`.
# `groups[i]` is the actuation variable driving actuator `i` (the two legs of
# a U-shaped TCA share one temperature: `groups=[0, 0]`); default: one
# variable per actuator.
# ---------------------------------------------------------------------------

@final
class InverseResult:
    """Result of :func:`tip_inverse`: the final (or closest reachable) configuration."""

    @property
    def solution(self) -> Solution:
        """Forward solution at :attr:`variables`."""
    @property
    def variables(self) -> list[float]:
        """Actuation variables (temperatures [C] for TCAs), one per group."""
    @property
    def error(self) -> float:
        """Remaining tip error [m] (plus weighted angle if an orientation was asked)."""
    @property
    def iterations(self) -> int:
        """Jacobian evaluations (outer iterations)."""
    @property
    def reached(self) -> bool:
        """Whether the target was reached to ``tol``."""
    @property
    def at_bound(self) -> list[bool]:
        """Per variable: resting on a bound of its input range at the end."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated in total."""
    @property
    def max_iter(self) -> int:
        """The iteration budget of the solve."""
    @property
    def success(self) -> bool: ...
    @property
    def status(self) -> int:
        """0 reached, 1 unreachable (at the bounds), 2 out of budget, 3 stalled."""
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int: ...
    @property
    def nfev(self) -> int: ...
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m] of ``solution``, shape ``(3,)``."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class BlockedResult:
    """A blocked-tip solution: contact ``force`` [N] at actuation ``variables``."""

    @property
    def solution(self) -> Solution:
        """Forward solution with the contact force applied at the tip."""
    @property
    def force(self) -> float:
        """Contact force [N] with which the tip presses along the block normal."""
    @property
    def variables(self) -> list[float]:
        """Actuation variables (temperatures [C] for TCAs)."""
    @property
    def iterations(self) -> int:
        """Increments (incremental method) or Newton iterations (direct solves)."""
    @property
    def evaluations(self) -> int:
        """IVPs integrated."""
    @property
    def success(self) -> bool: ...
    @property
    def status(self) -> int: ...
    @property
    def message(self) -> str: ...
    @property
    def nit(self) -> int: ...
    @property
    def nfev(self) -> int: ...
    @property
    def tip_position(self) -> _FloatArray:
        """Tip position [m] of ``solution``, shape ``(3,)``."""
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

def sensitivities(
    solution: Solution,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    scheme: Literal["forward", "central", "exact"] = "forward",
) -> tuple[_FloatArray, _FloatArray]:
    """``(J, C)`` at ``solution`` (eqs 41-42): ``J`` is ``6 x n_vars`` [m or rad per C],
    ``C`` is ``6 x 6`` [m or rad per N or N m]."""

def tip_inverse(
    robot: Robot,
    target: Sequence[float] | _FloatArray,
    *,
    start: Sequence[float] | _FloatArray | None = None,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    target_rotation: Sequence[Sequence[float]] | _FloatArray | None = None,
    orientation_weight: float = 0.01,
    tol: float = 1e-7,
    max_iter: int = 50,
    damping: float = 1e-6,
    steps: int = 100,
) -> InverseResult:
    """Iterate the local inverse to put the tip at ``target`` [m]; unreachable
    targets end at the closest configuration with ``reached=False``."""

def blocked_force(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    variables: Sequence[float] | _FloatArray,
    *,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    warm_start: BlockedResult | None = None,
) -> BlockedResult:
    """Contact force [N] with the tip held on the plane through ``point`` [m]
    with unit ``normal`` (the direction the tip presses in), at ``variables``."""

def blocked_temperature(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    force: float,
    start: Solution,
    *,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    increments: int = 10,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """The paper's incremental method (eq 43, ``dx = 0``): the single actuation
    variable at which the blocked tip presses with ``force`` [N]."""

def blocked_temperature_direct(
    robot: Robot,
    point: Sequence[float] | _FloatArray,
    normal: Sequence[float] | _FloatArray,
    force: float,
    guess: float,
    *,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> BlockedResult:
    """Direct mixed solve: the actuation variable is a shooting unknown, the
    contact ``force`` [N] is given (check of :func:`blocked_temperature`)."""

# --- batch solves and bench timings (src/python/batch.rs; see tcarod.batch) ---

def grasp_temperature(
    robot: Robot,
    normal: Sequence[float] | _FloatArray,
    mass: float,
    mu: float,
    fingers: int,
    *,
    gravity: float = 9.81,
    groups: Sequence[int] | npt.NDArray[np.integer] | None = None,
    contact: Sequence[float] | _FloatArray | None = None,
    method: Literal["incremental", "direct"] = "incremental",
    increments: int = 8,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> tuple[BlockedResult, tuple[float, float, float]]:
    """Grasp temperature (eq 44): the actuation variable at which ``fingers``
    fingers with friction ``mu`` hold ``mass`` [kg], ``mu n F(T) = m g``, each
    tip blocked where it rests at the ``contact`` inputs (default: the
    reference inputs), pressing along ``normal``; ``method``: eq 43 in
    ``increments`` steps or a direct solve. Returns (the blocked result of
    one finger, the block point [m])."""

def solve_batch(
    robot: Robot,
    inputs: _FloatArray,
    wrenches: _FloatArray | None = None,
    *,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
    chunk_size: int = 256,
    threads: int = 0,
    warm: bool = True,
) -> tuple[_FloatArray, _FloatArray, _FloatArray, npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.bool_]]:
    """Solve every row of ``inputs`` ``(n, n_actuators)`` in parallel; returns
    ``(tip_positions (n, 3) [m], tip_rotations (n, 3, 3), tensions (n, n_actuators) [N],
    iterations, evaluations, converged)``."""

def default_threads() -> int:
    """Worker threads ``solve_batch`` uses for ``threads=0``."""

def bench_rows() -> list[tuple[str, str, float]]:
    """Rows of the performance table: ``(name, description, target [s])``."""

def bench_time(name: str, repeats: int = 7, min_time: float = 0.05) -> list[float]:
    """Seconds per operation of row ``name``, one value per run (timed in Rust)."""

# --- stability and branch following (src/python/stability.rs; see tcarod.models.stability) ---

@final
class Stability:
    """Stability verdict of one equilibrium (see ``tcarod.models.stability``)."""

    @property
    def stable(self) -> bool: ...
    @property
    def margin(self) -> float:
        """Smallest eigenvalue of the dimensionless tip stiffness [-]: > 0 iff stable."""
    @property
    def conjugate_point(self) -> float | None:
        """Arc length [m] of the first conjugate point, or None."""
    @property
    def s(self) -> _FloatArray: ...
    @property
    def determinant(self) -> _FloatArray:
        """Till and Rucker's ``det(Y(s) Y(0)^-1)`` [-] at the nodes."""
    @property
    def min_stiffness(self) -> _FloatArray: ...
    @property
    def mode(self) -> _FloatArray:
        """Softest tip mode ``(dp / L, dtheta)``, shape ``(6,)``."""
    @property
    def evaluations(self) -> int: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

@final
class Branch:
    """A followed branch or a stable sweep (see ``tcarod.models.stability.follow_branch``)."""

    @property
    def parameter(self) -> _FloatArray: ...
    @property
    def tip_positions(self) -> _FloatArray:
        """Tip positions [m], shape ``(k, 3)``."""
    @property
    def stable(self) -> npt.NDArray[np.bool_]: ...
    @property
    def margin(self) -> _FloatArray: ...
    @property
    def solutions(self) -> list[Solution]: ...
    @property
    def events(self) -> list[tuple[str, float, _FloatArray]]:
        """``(kind, parameter, tip position [m])``, kind ``"fold"`` or ``"bifurcation"``."""
    @property
    def folds(self) -> _FloatArray: ...
    @property
    def bifurcations(self) -> _FloatArray: ...
    @property
    def jumps(self) -> list[tuple[float, Solution, Solution]]:
        """Stable sweeps: ``(parameter, before, after)``."""
    @property
    def evaluations(self) -> int: ...
    def __len__(self) -> int: ...
    def __reduce__(self) -> tuple[Any, ...]: ...
    def __eq__(self, value: object, /) -> bool: ...

def _restore_stability(
    stable: bool,
    margin: float,
    conjugate_point: float | None,
    s: Sequence[float],
    determinant: Sequence[float],
    min_stiffness: Sequence[float],
    evaluations: int,
    mode: Sequence[float],
) -> Stability: ...
def _restore_branch(
    points: Sequence[tuple[float, Sequence[float], bool, float]],
    solutions: Sequence[Solution],
    events: Sequence[tuple[str, float, Sequence[float]]],
    jumps: Sequence[tuple[float, Solution, Solution]],
    evaluations: int,
) -> Branch: ...
def stability(robot: Robot, solution: Solution, *, blocked: Sequence[Sequence[float]] | None = None) -> Stability:
    """Stability of ``solution``; ``blocked``: world directions of held tip translation."""

def follow_branch(
    robot: Robot,
    *,
    parameter: str,
    start: float,
    end: float,
    actuators: Sequence[int] | None = None,
    inputs: float | Sequence[float] | None = None,
    step: float = 0.02,
    max_step: float = 0.1,
    max_points: int = 500,
    stable_only: bool = False,
    warm_start: Solution | None = None,
    steps: int = 100,
    tol: float = 1e-10,
    max_iter: int = 50,
) -> Branch:
    """Pseudo-arclength continuation in ``parameter`` (``"inputs"``,
    ``"gravity_scale"``, ``"tip_load_scale"``) from ``start`` to ``end``."""

# The paper's fixtures, defined once in the core (src/experiments.rs).

_Manipulator = Literal["square", "fig6_circle", "fig6_square", "fig8", "table1_finger"]
_TurnsReading = Literal["per_tca", "per_leg", "per_length"]

def fixture_constants() -> dict[str, Any]:
    """The paper's constants by name, SI units (temperatures in C)."""

def fixture_manipulator(
    name: _Manipulator,
    *,
    length: float | None = None,
    gravity: Sequence[float] | _FloatArray | None = None,
    material: Material | None = None,
    youngs_modulus: float | None = None,
    tca_offset: float | None = None,
    coil_diameter: float | None = None,
    turns_reading: _TurnsReading = "per_tca",
) -> Robot:
    """The paper's manipulator ``name`` with any of its parameters replaced."""

def fixture_leg_turns(length: float, legs: int, reading: _TurnsReading = "per_tca") -> float:
    """Turns [-] of one leg of a manipulator TCA of coiled length ``length`` [m]."""

def fixture_fig5_tca(threads: Literal[3, 4]) -> Tca:
    """The whole Fig. 5 TCA of 3 or 4 threads."""

def fixture_fig5_half_tca(threads: Literal[3, 4]) -> Tca:
    """One folded half of the Fig. 5 TCA: ``Tca.segment(0.5)`` of the whole."""

def fixture_tendon_robot(name: Literal["steel", "soft"]) -> Robot:
    """The issue-10 tendon robots: ``"steel"`` (on spacer disks) or ``"soft"``."""
