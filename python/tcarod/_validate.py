"""Argument checks shared by the Python-level modules (one contract, one place).

* a wrong type (``str``, ``bytes``, ``None``, ``complex``, an object that is
  not a real number) -> ``TypeError`` naming the argument;
* a real number outside the allowed range (NaN, inf, a size <= 0, a count
  beyond its cap) -> ``ValueError`` naming the argument, the value and the
  allowed range;
* Python ints beyond the double range are real numbers: they become +-inf
  and are rejected as out of range (``ValueError``), never ``OverflowError``.
"""

from __future__ import annotations

import math
import numbers
import operator
import warnings
from typing import Any, Final

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

#: Caps on the work one call may request (documented ``ValueError`` beyond).
MAX_SEGMENTS: Final[int] = 1000
MAX_OUTPUT_POINTS: Final[int] = 1_000_000
MAX_RK4_STEPS: Final[int] = 10_000_000
MAX_GRID_POINTS: Final[int] = 100_000
MAX_PROFILE_KNOTS: Final[int] = 100_000
#: Most items read from a sequence that is not a list, tuple or array (its
#: ``__len__`` is only a claim, and NumPy allocates by it).
MAX_SEQUENCE_ITEMS: Final[int] = 10_000_000
#: Temperatures [C] above this look like Kelvin (a ``UnitsWarning``, not an error).
KELVIN_LOOKING_C: Final[float] = 273.0


def _any(value: object) -> Any:
    return value


def _type_name(value: object) -> str:
    return type(value).__name__


def real(
    name: str,
    value: object,
    *,
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
    reason: str = "",
) -> float:
    """``value`` as a finite float in ``[lo, hi]`` (open ends if asked).

    ``TypeError`` if it is not a real number (bool counts as a number, as in
    Python); ``ValueError`` naming ``name`` if not finite or out of range:
    ``invalid NAME = VALUE UNIT: allowed RANGE UNIT (reason)``, the value
    written as a person would (:func:`human`: ``0.004``, ``170``, ``1e-300``),
    as the core's errors are.
    """
    value = _any(value)
    if isinstance(value, (str, bytes, bytearray, complex, np.complexfloating)) or value is None:
        raise TypeError(f"{name} must be a real number{_u(unit)}, not {_type_name(value)}")
    if isinstance(value, np.ndarray):
        if value.ndim != 0:
            raise TypeError(f"{name} must be a real number{_u(unit)}, not an array of shape {value.shape}")
        value = _any(value[()])
        if isinstance(value, np.complexfloating):
            raise TypeError(f"{name} must be a real number{_u(unit)}, not complex")
    if not isinstance(value, (numbers.Real, np.number)):
        raise TypeError(f"{name} must be a real number{_u(unit)}, not {_type_name(value)}")
    try:
        x = float(value)
    except OverflowError:  # an int beyond the double range: a real number, +-inf
        x = math.inf if _any(value) > 0 else -math.inf
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a real number{_u(unit)}, not {_type_name(value)}") from exc
    why = f" ({reason})" if reason else ""
    bounds = _range(lo, hi, lo_open, hi_open) + (_v(unit) if lo is not None or hi is not None else "")
    if not math.isfinite(x):
        raise ValueError(f"invalid {name} = {human(x)}{_v(unit)}: allowed a finite number{bounds}{why}")
    bad_lo = lo is not None and (x <= lo if lo_open else x < lo)
    bad_hi = hi is not None and (x >= hi if hi_open else x > hi)
    if bad_lo or bad_hi:
        # a length valid once read as millimetres: say so
        in_mm = x * 1e-3
        fits = (lo is None or in_mm >= lo) and (hi is None or in_mm <= hi)
        hint = mm_hint(x) if unit == "m" and fits else ""
        raise ValueError(f"invalid {name} = {human(x)}{_v(unit)}: allowed{bounds}{why}{hint}")
    return x


def human(x: float) -> str:
    """``x`` as a person writes it: at most 10 significant digits, trailing
    zeros dropped, an exponent only far from 1 (``4``, ``0.004``, ``0.3`` for
    ``0.1 + 0.2``, ``1e-300``); the core's ``error::human`` in Python."""
    if not math.isfinite(x):
        return "NaN" if math.isnan(x) else ("inf" if x > 0 else "-inf")
    if x == 0.0:
        return "0"
    if 1e-4 <= abs(x) < 1e15:
        decimals = max(0, 9 - math.floor(math.log10(abs(x))))
        text = f"{x:.{decimals}f}"
        return text.rstrip("0").rstrip(".") if "." in text else text
    return f"{x:.10g}"


#: Lengths [m] above this, for a part of a soft robot, look like millimetres
#: given as metres (the core's ``error::MM_LOOKING_M``) ...
MM_LOOKING_M: Final[float] = 1.0
#: ... up to this: beyond 10,000 mm the value is no millimetre typo.
MM_LOOKING_MAX_M: Final[float] = 1e4


def mm_hint(value: float) -> str:
    """``" (millimetres? lengths are in metres: 4 mm is 0.004 m)"`` for a
    length ``value`` [m] above :data:`MM_LOOKING_M` (up to
    :data:`MM_LOOKING_MAX_M`), else ``""``."""
    if math.isfinite(value) and MM_LOOKING_M < abs(value) <= MM_LOOKING_MAX_M:
        return f" (millimetres? lengths are in metres: {human(value)} mm is {human(value * 1e-3)} m)"
    return ""


def positive(name: str, value: object, unit: str = "") -> float:
    """A finite float > 0."""
    return real(name, value, lo=0.0, lo_open=True, unit=unit)


def integer(name: str, value: object, lo: int, hi: int) -> int:
    """``value`` as an int in ``[lo, hi]``: ``TypeError`` unless it is an
    integer (``operator.index``; floats are refused as ``range()`` does),
    ``ValueError`` naming ``name`` and the range otherwise."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an integer, not bool")
    try:
        n = operator.index(value)  # type: ignore[arg-type]
    except TypeError:
        raise TypeError(f"{name} must be an integer, not {_type_name(value)}") from None
    if not lo <= n <= hi:
        shown = str(n) if abs(n) < 10**30 else f"{'-' if n < 0 else ''}an integer of {len(str(abs(n)))} digits"
        raise ValueError(f"invalid {name} = {shown}: allowed an integer in {lo}..{hi}")
    return n


def real_array(
    name: str, value: Any, *, ndim: int | None = None, max_size: int = MAX_OUTPUT_POINTS, unit: str = ""
) -> FloatArray:
    """``value`` as a finite float64 array: ``TypeError`` for strings,
    ``None``, complex or non-numeric elements; ``ValueError`` for NaN/inf,
    the wrong number of dimensions or more than ``max_size`` elements."""
    if value is None or isinstance(value, (str, bytes, bytearray)):
        raise TypeError(f"{name} must be real numbers{_u(unit)}, not {_type_name(value)}")
    _check_len(name, value, max_size)
    if isinstance(value, (list, tuple)):
        # NumPy allocates by a nested sequence's __len__ too: refuse a claim beyond the cap
        for item in value:
            if not isinstance(item, (list, tuple, np.ndarray, str, bytes, bytearray)):
                _check_len(f"{name} element", item, max_size)
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError, OverflowError) as exc:  # ragged or exotic
        raise ValueError(f"invalid {name}: not an array of real numbers ({exc})") from None
    except MemoryError:  # a length claimed deeper down
        raise ValueError(f"invalid {name}: more values than memory holds (a length it claims)") from None
    if raw.size > max_size:
        raise ValueError(f"invalid {name}: {raw.size} values, at most {max_size} allowed")
    if raw.dtype.kind in "cSUVmMO" and raw.size:
        if raw.dtype.kind == "O":
            for x in raw.flat:
                real(f"{name} element", x, unit=unit)
            raw = np.asarray([real(name, x) for x in raw.flat], dtype=np.float64).reshape(raw.shape)
        else:
            raise TypeError(f"{name} must be real numbers{_u(unit)}, not {raw.dtype}")
    if raw.dtype.kind == "O":  # empty object array
        raw = raw.astype(np.float64)
    arr = np.asarray(raw, dtype=np.float64)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"invalid {name}: need {ndim} dimension(s), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"invalid {name}: need finite numbers{_u(unit)}, got NaN or inf")
    return arr


def vector(name: str, value: Any, size: int, unit: str = "") -> list[float]:
    """A sequence of exactly ``size`` finite reals."""
    arr = real_array(name, value, ndim=1, max_size=max(size, 16), unit=unit)
    if arr.size != size:
        raise ValueError(f"invalid {name}: expected {size} values{_u(unit)}, got {arr.size}")
    return [float(x) for x in arr]


def sequence(name: str, value: Any, max_len: int) -> list[Any]:
    """``value`` as a list of at most ``max_len`` items (``TypeError`` if it
    is not a sized iterable or is a string)."""
    if isinstance(value, (str, bytes, bytearray)) or value is None:
        raise TypeError(f"{name} must be a sequence, not {_type_name(value)}")
    _check_len(name, value, max_len)
    try:
        items = list(value)
    except TypeError:
        raise TypeError(f"{name} must be a sequence, not {_type_name(value)}") from None
    if len(items) > max_len:
        raise ValueError(f"invalid {name}: {len(items)} items, at most {max_len} allowed")
    return items


def instance(name: str, value: object, cls: type | tuple[type, ...], what: str) -> Any:
    """``value`` if it is an instance of ``cls``, else ``TypeError`` naming ``what``."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be {what}, not {_type_name(value)}")
    return value


def claimed_len(name: str, value: Any, max_len: int = MAX_SEQUENCE_ITEMS) -> None:
    """Refuse a sequence other than a list, tuple or array whose ``len()``
    claims more than ``max_len`` items (``ValueError``), before NumPy or
    ``list()`` allocates by that claim."""
    if not isinstance(value, (list, tuple, np.ndarray)):
        _check_len(name, value, max_len)


def warn_units(message: str, stacklevel: int = 3) -> None:
    """Warn with ``tcarod.UnitsWarning``: a valid value that looks like the wrong unit."""
    from ._core import UnitsWarning

    warnings.warn(message, UnitsWarning, stacklevel=stacklevel)


def warn_if_kelvin(name: str, values: Any, stacklevel: int = 4) -> None:
    """``UnitsWarning`` if a temperature [C] in ``values`` exceeds
    :data:`KELVIN_LOOKING_C` (NaN and non-numbers are left to the checks)."""
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError, OverflowError, MemoryError):
        return
    with np.errstate(invalid="ignore"):
        hot = arr[np.isfinite(arr) & (arr > KELVIN_LOOKING_C)]
    if hot.size:
        warn_units(
            f"{name} = {float(hot.flat[0]):g} C: temperatures are in degrees Celsius; "
            f"did you give Kelvin? (25 C is 298.15 K)",
            stacklevel,
        )


def _check_len(name: str, value: Any, max_len: int) -> None:
    """Refuse a claimed ``len()`` beyond ``max_len`` before iterating it."""
    if hasattr(value, "__len__") and not isinstance(value, np.ndarray):
        try:
            n = len(value)
        except (TypeError, OverflowError, ValueError):
            raise ValueError(f"invalid {name}: its length is not a usable size") from None
        if n > max_len:
            raise ValueError(f"invalid {name}: {n} items, at most {max_len} allowed")


def _u(unit: str) -> str:
    return f" [{unit}]" if unit else ""


def _v(unit: str) -> str:
    """The unit after a value: `` m``; nothing for a dimensionless ``-``."""
    return f" {unit}" if unit and unit != "-" else ""


def _range(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    if lo is None and hi is None:
        return ""
    if hi is None:
        return f" {'>' if lo_open else '>='} {lo:g}"
    if lo is None:
        return f" {'<' if hi_open else '<='} {hi:g}"
    return f" in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
