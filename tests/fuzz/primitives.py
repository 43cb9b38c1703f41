"""Building blocks of the fuzz strategies: fixtures by name, recorded calls,
hostile values (special floats, huge integers, wrong types) and number /
vector strategies that mix valid and invalid draws."""

from __future__ import annotations

import math
from pathlib import Path
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from hypothesis import strategies as st

#: A valid design file (the Fig. 6 square), mutated by the design-file strategies.
DESIGN_TEXT = (Path(__file__).resolve().parents[2] / "examples" / "designs" / "fig6_square.toml").read_text(
    encoding="utf-8"
)

# --------------------------------------------------------------------- values


@dataclass(frozen=True)
class Fix:
    """A named fixture, built by the harness (see ``harness.fixture``);
    ``args`` parametrise the few fixtures built per call."""

    name: str
    args: tuple[Any, ...] = ()


@dataclass(frozen=True)
class Call:
    """One call of entry point ``entry`` with ``args`` and ``kwargs``."""

    entry: str
    args: tuple[Any, ...] = ()
    kwargs: dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        parts = [_short(a) for a in self.args] + [f"{k}={_short(v)}" for k, v in self.kwargs.items()]
        return f"{self.entry}({', '.join(parts)})"


def _short(v: Any) -> str:
    try:
        r = repr(v)
    except ValueError:  # an int too long to print
        r = f"<{type(v).__name__} too long to print>"
    return r if len(r) <= 120 else r[:117] + "..."


class Opaque:
    """An object of no numeric kind."""

    def __repr__(self) -> str:
        return "Opaque()"


class EvilLen:
    """Claims 2**62 items; indexing fails (a panic "capacity overflow" bait)."""

    def __len__(self) -> int:
        return 2**62

    def __getitem__(self, i: int) -> float:
        raise IndexError(i)

    def __iter__(self) -> Any:
        return iter(())

    def __repr__(self) -> str:
        return "EvilLen()"


class LyingLen:
    """Claims 2**62 items and yields a number at every index: ``list()`` and
    NumPy allocate by the claim before reading (a ``MemoryError`` bait)."""

    def __len__(self) -> int:
        return 2**62

    def __getitem__(self, i: int) -> float:
        return 1.0

    def __repr__(self) -> str:
        return "LyingLen()"


SPECIAL_FLOATS = [
    math.nan,
    math.inf,
    -math.inf,
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.2250738585072014e-308,
    1e-300,
    1e300,
    -1e300,
    1.7976931348623157e308,
    -1.7976931348623157e308,
    1e15,
    -1.0,
]
HUGE_INTS = [-(2**63), 2**63, 2**64, -(2**31) - 1, 2**31, 10**400, -(10**400), 2**62]
BAD_TYPES = [
    None,
    "x",
    "1.0",
    "",
    b"ab",
    1j,
    complex(1.0, 0.0),
    np.complex128(1 + 1j),
    Opaque(),
    [],
    {},
    (),
    EvilLen(),
    LyingLen(),
    True,
    False,
]

bad_type = st.sampled_from(BAD_TYPES)
special_float = st.sampled_from(SPECIAL_FLOATS)
huge_int = st.sampled_from(HUGE_INTS)


def num(lo: float, hi: float) -> st.SearchStrategy[float]:
    """A finite float in the working range ``[lo, hi]``."""
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


def fnum(lo: float, hi: float) -> st.SearchStrategy[Any]:
    """Mostly ``num(lo, hi)``; sometimes an edge value, a huge int, any float or a wrong type."""
    return st.one_of(
        *[num(lo, hi)] * 18,
        special_float,
        huge_int,
        st.floats(),
        bad_type,
        st.builds(np.float64, num(lo, hi)),
        st.integers(-3, 300),
    )


def flen(lo: float, hi: float) -> st.SearchStrategy[Any]:
    """A length [m] as :func:`fnum`, sometimes the same length typed in
    millimetres (1000 times larger: a ``UnitsWarning`` or an error that
    asks about millimetres)."""
    return st.one_of(*[fnum(lo, hi)] * 4, num(lo, hi).map(lambda x: x * 1e3), st.integers(1, 100))


def fint(lo: int, hi: int) -> st.SearchStrategy[Any]:
    """Mostly an int in ``[lo, hi]``; sometimes negative, huge, a float or a wrong type."""
    return st.one_of(
        *[st.integers(lo, hi)] * 16,
        st.integers(-(2**70), 2**70),
        huge_int,
        st.sampled_from([-1, 0, 1, 1.5, 2.0, math.nan]),
        bad_type,
        st.builds(np.int64, st.integers(lo, hi)),
    )


def fvec(n: int, lo: float, hi: float) -> st.SearchStrategy[Any]:
    """Mostly ``n`` numbers in range (list or array); sometimes the wrong length, edge values or a wrong type."""
    good = st.lists(num(lo, hi), min_size=n, max_size=n)
    return st.one_of(
        *[good] * 12,
        good.map(lambda v: np.asarray(v, dtype=np.float64)),
        st.lists(fnum(lo, hi), min_size=n, max_size=n),
        st.lists(fnum(lo, hi), min_size=0, max_size=n + 2),
        good.map(lambda v: np.asarray(v, dtype=np.complex128)),
        good.map(tuple),
        good.map(lambda v: np.asarray(v, dtype=np.float64).reshape(n, 1)),
        good.map(lambda v: [[x] for x in v]),
        bad_type,
    )


def maybe(s: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    return st.one_of(st.none(), s)


def fix(*names: str) -> st.SearchStrategy[Any]:
    """One of the named fixtures, sometimes a wrong type."""
    return st.one_of(*(st.just(Fix(n)) for n in names), *(st.just(Fix(n)) for n in names), bad_type)


def this(*names: str) -> st.SearchStrategy[Any]:
    """The object a method is called on (``self``): always a fixture, since
    ``Class.method(None, ...)`` is not a call a user makes."""
    return st.sampled_from([Fix(n) for n in names])


def call(entry: str, *args: st.SearchStrategy[Any], **kwargs: st.SearchStrategy[Any]) -> st.SearchStrategy[Call]:
    """A :class:`Call` with each positional argument drawn from ``args`` and
    each keyword either drawn from ``kwargs`` or left out."""
    pos = st.tuples(*args)
    kws = st.fixed_dictionaries({}, optional=kwargs) if kwargs else st.just({})
    return st.builds(lambda a, k: Call(entry, a, k), pos, kws)


# --------------------------------------------------------------- entry points

TEMP = fnum(25.0, 160.0)
TEMPS2 = fvec(2, 25.0, 160.0)
ROBOTS = fix("R", "RNG")
GROUPS = st.one_of(st.just([0, 0]), st.just([0, 0]), st.lists(fint(0, 2), min_size=0, max_size=3), bad_type)
#: ``fixed_inputs`` of the inverse problems: one actuator held (the common
#: case), dicts with any keys and values, or a wrong type.
FIXED_INPUTS = st.one_of(
    st.just({1: 25.0}),
    # keys: actuator indices, out of range or of the wrong (hashable) type
    st.dictionaries(
        st.one_of(st.integers(-1, 2), st.sampled_from(["0", 1.5, True, None, 2**70])),
        st.one_of(TEMP, bad_type),
        max_size=3,
    ),
    bad_type,
)
VEC3_POS = fvec(3, -0.05, 0.05)
VEC3_NORMAL = st.one_of(st.just([-1.0, 0.0, 0.0]), fvec(3, -1.0, 1.0))
SOLVE_KW: dict[str, st.SearchStrategy[Any]] = {
    "steps": fint(2, 200),
    "tol": fnum(1e-12, 1e-6),
    "max_iter": fint(1, 80),
}
MATERIAL_KW: dict[str, st.SearchStrategy[Any]] = {
    "youngs_modulus": fnum(1e8, 1e10),
    "shear_modulus": fnum(1e7, 1e9),
    "expansion": fnum(0.0, 1e-3),
    "youngs_modulus_slope": fnum(-1e7, 0.0),
    "expansion_slope": fnum(0.0, 1e-5),
    "t_ref": fnum(0.0, 40.0),
    "t_min": fnum(0.0, 40.0),
    "t_max": fnum(60.0, 200.0),
}
INPUT_ROWS = st.one_of(
    st.lists(st.lists(num(25.0, 160.0), min_size=2, max_size=2), min_size=0, max_size=5),
    st.lists(fvec(2, 25.0, 160.0), min_size=0, max_size=4),
    st.integers(0, 6).map(lambda n: np.linspace(25.0, 160.0, 2 * n).reshape(n, 2)),
    bad_type,
)


def design_text_strategy() -> st.SearchStrategy[str]:
    """A valid design file with one mutation: a value replaced, a line
    dropped or duplicated, garbage or deep nesting inserted."""
    lines = DESIGN_TEXT.splitlines()
    junk = st.one_of(
        st.sampled_from(
            [
                "nan",
                "inf",
                "-inf",
                "1e400",
                "0",
                "-1",
                '"x"',
                "[]",
                "{}",
                "true",
                "99999999999999999999999",
                "[1, 2]",
                '{ kind = "blob" }',
                "= =",
                "[[actuators]]",
                "[body]",
                '"' + "a" * 10,
            ]
        ),
        st.integers(1, 3000).map(lambda n: "[" * n + "]" * n),
        st.integers(1, 3000).map(lambda n: "{a=" * n + "1" + "}" * n),
        st.integers(1, 50_000).map(lambda n: " " * n),
        st.integers(1, 5000).map(lambda n: "[" + ".".join(["a"] * n) + "]"),
        st.text(max_size=40),
    )

    def mutate(k: int, how: int, j: str) -> str:
        out = list(lines)
        k %= len(out)
        if how == 0 and "=" in out[k]:
            key = out[k].split("=", 1)[0]
            out[k] = f"{key}= {j}"
        elif how == 1:
            del out[k]
        elif how == 2:
            out.insert(k, out[k])
        else:
            out.insert(k, j)
        return "\n".join(out)

    return st.builds(mutate, st.integers(0, 10_000), st.integers(0, 3), junk)


def argv_strategy() -> st.SearchStrategy[list[Any]]:
    token = st.one_of(
        # no bare "reproduce" / "bench": running every experiment or benchmark is valid, long work
        st.sampled_from(
            [
                "solve",
                "--json",
                "--out",
                "-T",
                "--temperature",
                "--version",
                "--help",
                "nope",
                "-",
                "--",
                "--repeats",
                "--min-time",
                "--batch",
                "fig99",
            ]
        ),
        st.just(Fix("DESIGN_PATH")),
        st.just(Fix("BAD_DESIGN_PATH")),
        st.just(Fix("OUT_DIR")),
        st.floats().map(str),
        st.text(max_size=12),
    )
    solve = st.builds(
        lambda paths, temps, js: [
            "solve",
            *paths,
            "--out",
            Fix("OUT_DIR"),
            *(["-T", *temps] if temps else []),
            *(["--json"] if js else []),
        ],
        st.lists(
            st.sampled_from([Fix("DESIGN_PATH"), Fix("BAD_DESIGN_PATH"), Fix("MISSING_PATH")]), min_size=1, max_size=2
        ),
        st.lists(
            st.one_of(st.floats(20, 170).map(lambda x: f"{x:.3g}"), st.floats().map(str), st.text(max_size=5)),
            max_size=3,
        ),
        st.booleans(),
    )
    garbage = st.lists(token, max_size=6)
    fast_errors = st.sampled_from(
        [
            ["reproduce", "nope"],
            ["reproduce", "fig5", "fig99"],
            ["reproduce", "--help"],
            ["bench", "--repeats", "-1"],
            ["bench", "--min-time", "nan"],
            ["bench", "--min-time", "1e300"],
            ["bench", "--batch", "-5"],
            ["bench", "--help"],
        ]
    )
    return st.one_of(garbage, garbage, garbage, solve, fast_errors)
