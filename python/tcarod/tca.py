"""The TCA constitutive law (paper Section II, eqs 1-6), vectorised over NumPy.

Units: lengths and displacements in m, forces in N (tension > 0, i.e. a force
that pulls the TCA longer), torques in N m, temperatures in degrees C.

Errors: ``ValueError`` for numbers outside the law's domain (NaN, inf,
non-positive sizes, ``L >= l/2``, temperatures outside the material's range,
loads that straighten the fibre, shapes that do not broadcast); its message
names the argument and its unit. ``TypeError`` for arguments that are not real
numbers or arrays of them (``str``, ``None``, ``complex``), as with any Python
function taking a float. No function returns NaN. A temperature above 273 C
(one that looks like Kelvin) warns with ``tcarod.UnitsWarning``.
"""

from __future__ import annotations

import math
from typing import Union, overload

import numpy as np
import numpy.typing as npt

from . import _core
from . import _validate as V

ArrayLike = Union[float, "npt.ArrayLike"]
FloatArray = npt.NDArray[np.float64]

__all__ = ["Material", "Tca"]

Material = _core.Material

# dtype kinds accepted as real numbers: bool, signed and unsigned int, float.
_REAL_KINDS = "biuf"


def _real_scalar(name: str, value: object) -> float:
    """One element of an object array as a float; ints beyond the double range
    saturate to +-inf (rejected downstream, naming the argument)."""
    if isinstance(value, (bool, np.bool_)):
        return float(value)
    if isinstance(value, (int, np.integer)):
        try:
            return float(value)
        except OverflowError:
            return math.inf if value > 0 else -math.inf
    if isinstance(value, (float, np.floating)):
        return float(value)
    raise TypeError(f"{name} must be a real number or an array of real numbers, not {type(value).__name__}")


def _as_float_array(name: str, value: ArrayLike) -> FloatArray:
    """``value`` as a float64 array.

    Raises ``TypeError`` if ``value`` is not a real number or an array of real
    numbers (str, None, complex, ...) and ``ValueError`` if it is a ragged
    sequence or claims more items than memory holds (a sequence that is not
    a list, tuple or array is read up to ``MAX_SEQUENCE_ITEMS`` items).
    Values themselves (NaN, inf, ranges) are checked by the core.
    """
    # NumPy allocates by a sequence's __len__ before reading it: refuse a claim
    # beyond the cap here, and one nested inside a list (the allocation fails
    # at once) as a ValueError below
    V.claimed_len(name, value)
    try:
        arr = np.asarray(value)
    except ValueError as exc:  # ragged nested sequences
        raise ValueError(f"{name} must be a rectangular array of numbers: {exc}") from None
    except MemoryError:
        raise ValueError(f"invalid {name}: more values than memory holds (a length it claims)") from None
    if arr.dtype.kind in _REAL_KINDS:
        return arr.astype(np.float64)
    if arr.dtype.kind == "O":  # Python ints beyond int64, or mixed objects
        flat = [_real_scalar(name, v) for v in arr.ravel()]
        return np.asarray(flat, dtype=np.float64).reshape(arr.shape)
    raise TypeError(f"{name} must be a real number or an array of real numbers, not dtype {arr.dtype}")


def _broadcast(
    a: ArrayLike, b: ArrayLike, names: tuple[str, str]
) -> tuple[FloatArray, FloatArray, tuple[int, ...], bool]:
    x = _as_float_array(names[0], a)
    y = _as_float_array(names[1], b)
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


def _flat(value: ArrayLike, name: str) -> tuple[FloatArray, tuple[int, ...], bool]:
    x = _as_float_array(name, value)
    return np.ascontiguousarray(x.ravel()), x.shape, x.ndim == 0


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

    Examples
    --------
    >>> tca = tcarod.Tca(0.15, 0.04, 0.0017, 38.2)   # l, L, D [m], N [turns]
    >>> round(tca.free_stroke(100.0) * 1e3, 3)       # unloaded elongation at 100 C [mm]
    1.337
    >>> tca.free_stroke([25.0, 100.0]).round(5)      # arrays in, arrays out [m]
    array([0.     , 0.00134])
    >>> round(tca.blocked_force(100.0), 3)           # it pushes when heated [N]
    -0.492
    """

    @overload
    def displacement(self, force: float, temperature: float) -> float: ...
    @overload
    def displacement(self, force: ArrayLike, temperature: ArrayLike) -> float | FloatArray: ...
    def displacement(self, force: ArrayLike, temperature: ArrayLike) -> float | FloatArray:
        """Elongation [m] under axial ``force`` [N] (tension > 0) at ``temperature`` [C]."""
        f, t, shape, scalar = _broadcast(force, temperature, ("force", "temperature"))
        V.warn_if_kelvin("temperature", t)
        return _unwrap(self._displacement_flat(f, t), shape, scalar)

    @overload
    def force(self, displacement: float, temperature: float) -> float: ...
    @overload
    def force(self, displacement: ArrayLike, temperature: ArrayLike) -> float | FloatArray: ...
    def force(self, displacement: ArrayLike, temperature: ArrayLike) -> float | FloatArray:
        """Axial force [N] (tension > 0) holding the TCA at ``displacement`` [m] (>= 0) at ``temperature`` [C]."""
        d, t, shape, scalar = _broadcast(displacement, temperature, ("displacement", "temperature"))
        V.warn_if_kelvin("temperature", t)
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

    @overload
    def onset_temperature(self, force: float) -> float: ...
    @overload
    def onset_temperature(self, force: ArrayLike) -> float | FloatArray: ...
    def onset_temperature(self, force: ArrayLike) -> float | FloatArray:
        """Temperature [C] at which the coils separate under ``force`` [N] (< 0: compressive).

        Raises ``ValueError`` if the coils do not separate (or are already
        apart) anywhere in the material's temperature range.
        """
        return self.temperature(force, 0.0)

    @overload
    def free_stroke(self, temperature: float) -> float: ...
    @overload
    def free_stroke(self, temperature: ArrayLike) -> float | FloatArray: ...
    def free_stroke(self, temperature: ArrayLike) -> float | FloatArray:
        """Unloaded elongation [m] at ``temperature`` [C] (the core's ``Tca::free_stroke``)."""
        t, shape, scalar = _flat(temperature, "temperature")
        V.warn_if_kelvin("temperature", t)
        return _unwrap(self._free_stroke_flat(t), shape, scalar)

    @overload
    def blocked_force(self, temperature: float) -> float: ...
    @overload
    def blocked_force(self, temperature: ArrayLike) -> float | FloatArray: ...
    def blocked_force(self, temperature: ArrayLike) -> float | FloatArray:
        """Force [N] holding the TCA at its coiled length at ``temperature`` [C].

        Negative (the TCA pushes) for a heated extension TCA, positive (it pulls)
        for a heated contraction TCA (the core's ``Tca::blocked_force``).
        """
        t, shape, scalar = _flat(temperature, "temperature")
        V.warn_if_kelvin("temperature", t)
        return _unwrap(self._blocked_force_flat(t), shape, scalar)
