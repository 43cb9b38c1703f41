"""Rod classes of ``tcarod._core`` (src/python/rod/)."""

from collections.abc import Sequence
from typing import Any, Literal, final

from typing_extensions import Self, disjoint_base

from ._common import _FloatArray, _Policy, _Vec3
from ._solution import Solution
from ._tca import Tca

# ---------------------------------------------------------------------------
# Forward kinetostatics (src/python/rod/; paper Section III, eqs 7-33).
# World frame: base at the origin, reference tangent +z. Vectors given to or
# returned by these classes are length-3 world-frame vectors unless noted;
# body-frame offsets (routing) span the cross-section (x, y). Actuator forces
# are tensions [N] (negative: the actuator pushes). No getter returns NaN.
# ---------------------------------------------------------------------------

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
        """Parallel to the centre line at body-frame offset ``(x, y)`` [m].

        An offset above 1 m looks like millimetres and warns with ``UnitsWarning``."""
    @staticmethod
    def helix(radius: float, rate: float, phase: float = 0.0) -> Routing:
        """Helix of ``radius`` [m] turning at ``rate`` [rad/m] from angle ``phase`` [rad].

        ``r(s) = radius (cos(rate s + phase), sin(rate s + phase), 0)``; a
        positive ``rate`` turns right-handed about +z; a radius above 1 m
        warns with ``UnitsWarning``."""
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
    A ``density`` without a ``gravity`` argument warns with ``UnitsWarning``
    (the body would be weightless; pass ``gravity``, zero if that is meant).
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
    @staticmethod
    def from_material(name: str, length: float, section: Section, **kwargs: Any) -> Body:
        """A body of a catalogued silicone: ``Body.from_material(name, length, section, **kwargs)``.

        ``name`` is a ``name`` of :meth:`Body.materials`, e.g.
        ``"ecoflex-00-30"`` (case, spaces and underscores ignored); ``length``
        [m]; ``section`` a ``Section``. The preset gives
        ``youngs_modulus`` [Pa], ``poisson`` [-] and ``density`` [kg/m^3];
        ``kwargs`` are the constructor's other keywords and may replace a
        preset value (e.g. ``youngs_modulus=`` a modulus identified on your
        own samples, which should replace the nominal one). Raises
        ``ValueError`` for an unknown ``name``, listing the known ones. See
        :mod:`tcarod.materials` for the values and their sources."""
    @staticmethod
    def materials() -> list[dict[str, Any]]:
        """The catalogued silicones of :meth:`from_material`.

        One dict per material: ``name``, ``label``, ``youngs_modulus`` [Pa], ``modulus_basis``,
        ``modulus_100`` [Pa] or ``None``, ``shore_hardness``, ``poisson`` [-],
        ``density`` [kg/m^3], ``sources``."""
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
    """A string-like actuator embedded in the body.

    ``Actuator.tca`` (input: temperature [C]),
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
        undeformed body (makes contraction TCAs act); sets ``length_ratio``.

        A TCA shorter than its span is taken in series with inextensible
        leads filling the rest of the span: relaxed with its coils touching in
        the reference shape, it takes all of the span's elongation."""
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
    """A body with its embedded actuators (see ``tcarod.Robot``).

    Building checks that each routing, and each TCA's whole coil (offset plus
    half the coil's outer diameter), lies inside the section (``ValueError``
    naming ``actuators[i]``), unless ``spacer_disks=True``: actuators on
    spacer disks outside the body."""

    def __new__(cls, body: Body, actuators: Sequence[Actuator] = (), *, spacer_disks: bool = False) -> Self: ...
    def __getnewargs_ex__(self) -> tuple[tuple[Any, ...], dict[str, Any]]: ...
    def __eq__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    @property
    def spacer_disks(self) -> bool:
        """Whether the actuators run through spacer disks outside the section.

        ``True``: the routing- and coil-inside-the-section rule is waived."""
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
        equilibrium_tol: float | None = None,
    ) -> Solution:
        """Solve the forward kinetostatics: the robot's shape at the given inputs.

        Multiple shooting on the Cosserat rod (the paper's eqs 22-33), with
        continuation in the inputs and loads where Newton fails (docs: The solver).

        Parameters
        ----------
        inputs : float or sequence of float
            One input per actuator: temperature [C] for a TCA, tension [N] for a
            tendon, pull [m] for a linear tendon.
        steps : int, optional
            RK4 steps over the body, 1 to 100,000 (default 100).
        tol : float, optional
            Newton tolerance on the dimensionless residual (default 1e-10).
        max_iter : int, optional
            Newton iterations per Newton run (a continuation corrector takes at
            most 8), 1 to 100,000 (default 50).
        warm_start : Solution, optional
            A nearby solution of this robot, or of a robot with the same actuators
            under other loads (load continuation).
        stability : {"report", "require", "continue", "off"}, optional
            ``"report"`` (default): the verdict comes with the solve (one tangent
            IVP) in ``Solution.stable``; an unstable equilibrium also warns
            ``UnstableEquilibriumWarning``. ``"require"``: raise
            ``UnstableEquilibriumError`` (attributes ``margin`` [-] and
            ``solution``). ``"continue"``: move from an unstable equilibrium to a
            stable one at the same inputs; ``Solution.continued`` records how.
            ``"off"``: no verdict (hot loops).
        require_stable : bool, optional
            ``True`` is ``stability="require"``.
        max_evaluations : int, optional
            IVP budget of the solve, continuation included, 1 to 1e8 (default
            20,000).
        time_limit : float, optional
            Wall-time limit [s] (default none).
        equilibrium_tol : float, optional
            Opt-in accuracy control, 1e-12 to 1: the largest relative error of the
            global equilibrium check (base wrench against the loads) the solution
            may have; above it the solve is repeated on finer RK4 grids, and
            ``Solution.steps`` reports the grid used.

        Returns
        -------
        Solution
            The shape (centre line, frames, strains, internal wrench), the
            actuators' tensions and elongations, and the solver's counts.

        Raises
        ------
        ValueError
            An argument outside its range (named, with its unit).
        TypeError
            An argument of the wrong type.
        ConvergenceError
            Newton and continuation fail, the budget (``reason == "budget"``) or
            the time limit runs out, or ``equilibrium_tol`` cannot be met.
        UnstableEquilibriumError
            With ``stability="require"``, an unstable equilibrium.

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot
        >>> robot = fig6_square_robot()      # the paper's Fig. 6 square, two TCA legs
        >>> sol = robot.solve([100.0, 100.0])
        >>> sol.stable, round(float(sol.tip_position[0]) * 1e3, 2)   # tip x [mm]
        (True, -6.13)
        """
    def sweep(
        self,
        inputs: Sequence[Sequence[float] | _FloatArray] | _FloatArray,
        *,
        steps: int = 100,
        tol: float = 1e-10,
        max_iter: int = 50,
        stability: _Policy = "report",
    ) -> list[Solution]:
        """Solve along rows of ``inputs``, each warm-started from the previous one.

        ``inputs`` has shape ``(k, n_actuators)``; ``stability`` as for ``solve`` (one
        warning names the unstable rows; ``"continue"`` follows the physical
        robot's quasi-static path)."""

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
def _experiment_robot(name: Literal["fig6_circle", "fig6_square"], gravity: bool) -> Robot:
    """The Rust fixture ``name`` of ``src/experiments.rs`` (for tests; not public API)."""
