"""TCA classes of ``tcarod._core`` (src/python/material.rs, tca.rs)."""

from typing import Any, final

from typing_extensions import Self, disjoint_base

from ._common import _Chirality, _FloatArray

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
        """The fraction ``fraction`` [-] (0 < fraction <= 1) of this TCA as a segment in series.

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
    def _free_stroke_flat(self, temperature: _FloatArray) -> _FloatArray: ...
    def _blocked_force_flat(self, temperature: _FloatArray) -> _FloatArray: ...
