"""The TCA constitutive law (paper Section II, eqs 1-6), vectorised over NumPy.

Units: lengths and displacements in m, forces in N (tension > 0, i.e. a force
that pulls the TCA longer), torques in N m, temperatures in degrees C.
"""

from __future__ import annotations

from typing import Union, overload

import numpy as np
import numpy.typing as npt

from . import _core

ArrayLike = Union[float, "npt.ArrayLike"]
FloatArray = npt.NDArray[np.float64]

__all__ = ["Material", "Tca"]

Material = _core.Material


def _broadcast(a: ArrayLike, b: ArrayLike, names: tuple[str, str]) -> tuple[FloatArray, FloatArray, tuple[int, ...], bool]:
    try:
        x = np.asarray(a, dtype=np.float64)
        y = np.asarray(b, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{names[0]} and {names[1]} must be numbers or numeric arrays: {exc}") from None
    try:
        x, y = np.broadcast_arrays(x, y)
    except ValueError:
        raise ValueError(
            f"{names[0]} (shape {x.shape}) and {names[1]} (shape {y.shape}) cannot be broadcast together"
        ) from None
    scalar = x.ndim == 0
    shape = x.shape
    return (
        np.ascontiguousarray(x.ravel()),
        np.ascontiguousarray(y.ravel()),
        shape,
        scalar,
    )


def _unwrap(out: FloatArray, shape: tuple[int, ...], scalar: bool) -> float | FloatArray:
    if scalar:
        return float(out[0])
    return out.reshape(shape)


class Tca(_core.Tca):
    """A twisted-and-coiled actuator built from what a user measures.

    Parameters
    ----------
    fibre_length : float
        Twisted-fibre length ``l`` [m] (before coiling).
    coiled_length : float
        Coiled length ``L`` [m]; ``0 < L < l/2``.
    coil_diameter : float
        Outer coil diameter ``D`` [m].
    turns : float
        Inserted twist ``N`` [turns].
    chirality : {"extension", "contraction"}
        Extension (heterochiral) TCAs lengthen when heated; contraction
        (homochiral) ones shorten (the untwisting term's sign is reversed).
    material : Material, optional
        Fibre material; defaults to :meth:`Material.silver_coated_nylon`.

    Derived quantities (paper, below eq. 6): ``alpha0 = asin(L/l)`` [rad],
    ``n_coils = 2 cos(alpha0) l / (pi D)``, ``phi0 = 2 pi N`` [rad],
    ``d0 = 2 D L / l`` [m].

    The TCA starts with its coils touching, so ``displacement >= 0``: under a
    compressive load it stays at zero until heating overcomes the load
    (the onset temperature).

    All solves accept scalars or NumPy arrays (broadcast together) and return
    a float for scalar input, an array of the broadcast shape otherwise.
    """

    @overload
    def displacement(self, force: float, temperature: float) -> float: ...
    @overload
    def displacement(self, force: ArrayLike, temperature: ArrayLike) -> float | FloatArray: ...
    def displacement(self, force: ArrayLike, temperature: ArrayLike) -> float | FloatArray:
        """Elongation [m] under axial ``force`` [N] (tension > 0) at ``temperature`` [C]."""
        f, t, shape, scalar = _broadcast(force, temperature, ("force", "temperature"))
        return _unwrap(self._displacement_flat(f, t), shape, scalar)

    @overload
    def force(self, displacement: float, temperature: float) -> float: ...
    @overload
    def force(self, displacement: ArrayLike, temperature: ArrayLike) -> float | FloatArray: ...
    def force(self, displacement: ArrayLike, temperature: ArrayLike) -> float | FloatArray:
        """Axial force [N] (tension > 0) holding the TCA at ``displacement`` [m] (>= 0) at ``temperature`` [C]."""
        d, t, shape, scalar = _broadcast(displacement, temperature, ("displacement", "temperature"))
        return _unwrap(self._force_flat(d, t), shape, scalar)

    @overload
    def temperature(self, force: float, displacement: float) -> float: ...
    @overload
    def temperature(self, force: ArrayLike, displacement: ArrayLike) -> float | FloatArray: ...
    def temperature(self, force: ArrayLike, displacement: ArrayLike) -> float | FloatArray:
        """Temperature [C] at which ``force`` [N] gives ``displacement`` [m].

        Raises ``ValueError`` if no temperature in the material's range does it.
        """
        f, d, shape, scalar = _broadcast(force, displacement, ("force", "displacement"))
        return _unwrap(self._temperature_flat(f, d), shape, scalar)

    def onset_temperature(self, force: ArrayLike) -> float | FloatArray:
        """Temperature [C] at which the coils separate under ``force`` [N] (< 0: compressive)."""
        return self.temperature(force, 0.0)

    def free_stroke(self, temperature: ArrayLike) -> float | FloatArray:
        """Unloaded elongation [m] at ``temperature`` [C]."""
        return self.displacement(0.0, temperature)

    def blocked_force(self, temperature: ArrayLike) -> float | FloatArray:
        """Force [N] holding the TCA at its coiled length at ``temperature`` [C].

        Negative (the TCA pushes) for a heated extension TCA, positive (it pulls)
        for a heated contraction TCA.
        """
        return self.force(0.0, temperature)
