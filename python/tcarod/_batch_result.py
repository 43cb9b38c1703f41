"""Stacked results of many forward solves (:class:`BatchResult`, made by
:func:`tcarod.batch.solve_batch`; import it from :mod:`tcarod.batch`)."""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any, Callable, Iterable

import numpy as np
import numpy.typing as npt

from ._optional import require

__all__ = ["BatchResult"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]


@dataclass(frozen=True, eq=False)
class BatchResult:
    """Stacked results of ``n`` forward solves, row ``k`` for input row ``k``.

    Made by :func:`tcarod.batch.solve_batch`. The names are the per-solve
    results' in the plural. ``==`` compares every array exactly (NaN equal to
    NaN); results pickle, so they come back from process pools. A result
    prints as a one-line summary.

    Attributes
    ----------
    tip_positions : numpy.ndarray
        ``(n, 3)`` [m], world frame (``Solution.tip_position`` per solve); NaN
        where a solve did not converge.
    tip_rotations : numpy.ndarray
        ``(n, 3, 3)`` [-], body to world; NaN where a solve did not converge.
    iterations, evaluations : numpy.ndarray
        ``(n,)`` Newton iterations and IVPs of each row (of a row that did not
        converge: the work it spent).
    converged : numpy.ndarray
        ``(n,)`` bool.
    inputs : numpy.ndarray or None
        ``(n, n_actuators)``: what was solved (temperature [C] for TCAs).
    wrenches : numpy.ndarray or None
        ``(n, 6)``: tip force [N] and moment [N m], if given.
    tensions : numpy.ndarray or None
        ``(n, n_actuators)`` [N] (negative: the actuator pushes); NaN where a
        solve did not converge.
    stable, margin : numpy.ndarray or None
        ``(n,)`` stability verdict and margin [-] (> 0 if and only if stable;
        ``stable`` False and ``margin`` NaN where there is none); ``None``
        with ``stability="off"``.
    arc_length, positions : numpy.ndarray or None
        ``(nodes,)`` [m] and ``(n, nodes, 3)`` [m]: every row's centre line
        with ``shapes=True``, else ``None``.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot, solve_batch
    >>> temps = np.linspace(25.0, 100.0, 4)
    >>> res = solve_batch(fig6_square_robot(), np.column_stack([temps, temps]), steps=20)
    >>> len(res), res.success, res.tip_positions.shape, res.tensions.shape
    (4, True, (4, 3), (4, 2))
    >>> res.message
    'all 4 solves converged'
    >>> float(res.inputs[-1, 0])         # [C]
    100.0
    """

    tip_positions: FloatArray
    tip_rotations: FloatArray
    iterations: IntArray
    evaluations: IntArray
    converged: BoolArray
    inputs: FloatArray | None = None
    wrenches: FloatArray | None = None
    tensions: FloatArray | None = None
    stable: BoolArray | None = None
    margin: FloatArray | None = None
    arc_length: FloatArray | None = None
    positions: FloatArray | None = None

    def __len__(self) -> int:
        return int(self.tip_positions.shape[0])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, BatchResult):
            return NotImplemented
        for f in fields(self):
            a, b = getattr(self, f.name), getattr(other, f.name)
            if (a is None) != (b is None):
                return False
            if a is not None and not np.array_equal(a, b, equal_nan=a.dtype.kind == "f"):
                return False
        return True

    __hash__ = None  # type: ignore[assignment]  # mutable arrays inside

    def _summary(self) -> list[tuple[str, str]]:
        """``(name, value)`` pairs of the repr and the notebook table: counts
        and ranges, never whole arrays (a batch may hold millions of rows)."""
        n = len(self)
        ok = int(np.count_nonzero(self.converged))
        out = [("rows", str(n)), ("converged", f"{ok}/{n}")]
        if self.inputs is not None:
            out.append(("actuators", str(self.inputs.shape[1])))
        if n:
            out.append(("iterations", f"median {np.median(self.iterations):g}, max {int(self.iterations.max())}"))
            out.append(("IVPs", f"median {np.median(self.evaluations):g}, max {int(self.evaluations.max())}"))
        if ok:
            tips = self.tip_positions[self.converged] * 1e3
            lo, hi = tips.min(axis=0), tips.max(axis=0)
            out.append(("tip range [mm]", ", ".join(f"{a:.4g}..{b:.4g}" for a, b in zip(lo, hi))))
        if self.stable is not None:
            out.append(("stable", f"{int(np.count_nonzero(self.stable))}/{n}"))
        if self.positions is not None:
            out.append(("shapes", f"{self.positions.shape[1]} nodes per row"))
        return out

    def __repr__(self) -> str:
        """A one-line summary (counts and ranges; the arrays are the fields)."""
        body = "; ".join(f"{k} {v}" if k != "rows" else f"{v} rows" for k, v in self._summary())
        return f"<BatchResult: {body}>"

    def _repr_html_(self) -> str:
        """The notebook view: the summary as a table."""
        import html

        rows = "".join(f"<tr><td>{html.escape(k)}</td><td>{html.escape(v)}</td></tr>" for k, v in self._summary())
        return f"<div><b>tcarod BatchResult</b><table>{rows}</table></div>"

    @property
    def success(self) -> bool:
        """Whether every row converged (SciPy naming).

        Returns
        -------
        bool
            ``True`` if every row converged.
        """
        return bool(np.all(self.converged))

    @property
    def status(self) -> IntArray:
        """Status code of each row (SciPy naming).

        Returns
        -------
        numpy.ndarray
            ``(n,)`` int: 0 converged, 1 not converged (NaN pose).
        """
        return np.where(self.converged, 0, 1).astype(np.int64)

    @property
    def message(self) -> str:
        """Summary of the batch in words.

        Returns
        -------
        str
            How many rows converged, and the first that did not.
        """
        failed = int(np.count_nonzero(~self.converged))
        if failed == 0:
            return f"all {len(self)} solves converged"
        first = int(np.flatnonzero(~self.converged)[0])
        return f"{failed} of {len(self)} solves did not converge (first: row {first}); their poses are NaN"

    @property
    def nit(self) -> IntArray:
        """Newton iterations per row (alias of ``iterations``).

        Returns
        -------
        numpy.ndarray
            ``(n,)`` int [-].
        """
        return self.iterations

    @property
    def nfev(self) -> IntArray:
        """IVPs integrated per row (alias of ``evaluations``).

        Returns
        -------
        numpy.ndarray
            ``(n,)`` int [-].
        """
        return self.evaluations

    def plot_tips(self, **kwargs: Any) -> Any:
        """Plot the tip trajectory of the batch in 3-D [mm].

        Rows in order, the stable rows apart from the unstable ones when there is
        a verdict, and the shapes of a few rows when the batch kept them
        (``shapes=True``).

        Parameters
        ----------
        **kwargs
            Passed to :func:`tcarod.plotting.batch.plot_tips` (``shapes``: how
            many shapes to draw; ``title``).

        Returns
        -------
        matplotlib.figure.Figure
            The figure (Agg canvas; save it with ``fig.savefig(path)``).

        Raises
        ------
        ImportError
            matplotlib is missing (``pip install 'tcarod[plot]'``).
        ValueError
            No row converged (no tip to draw).

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot, solve_batch
        >>> temps = np.linspace(25.0, 100.0, 4)
        >>> fig = solve_batch(fig6_square_robot(), np.column_stack([temps, temps]), steps=20).plot_tips()
        >>> fig.savefig("tips.png")
        """
        if _TIP_PLOTTER is None:
            raise RuntimeError("no tip plotter registered: import tcarod (the package), not tcarod.batch alone")
        return _TIP_PLOTTER(self, **kwargs)

    def to_pandas(self) -> Any:
        """One row per solve as a pandas DataFrame (the ``pandas`` extra).

        Returns
        -------
        pandas.DataFrame
            Columns ``input_<i>`` (one per actuator; temperature [C] for a TCA),
            ``force_x_n`` ... ``moment_z_nm`` if wrenches were given, ``tip_x_m``,
            ``tip_y_m``, ``tip_z_m`` [m], ``tension_<i>_n`` [N], ``converged``,
            ``status``, ``nit``, ``nfev``, and ``stable``, ``margin`` [-] with a
            verdict.

        Raises
        ------
        ImportError
            pandas is missing (``pip install 'tcarod[pandas]'``).

        Examples
        --------
        >>> from tcarod.batch import fig6_square_robot, solve_batch
        >>> temps = np.linspace(25.0, 100.0, 4)
        >>> df = solve_batch(fig6_square_robot(), np.column_stack([temps, temps]), steps=20).to_pandas()
        >>> list(df.columns[:5]), len(df)
        (['input_0', 'input_1', 'tip_x_m', 'tip_y_m', 'tip_z_m'], 4)
        """
        pd: Any = require("pandas")
        cols: dict[str, Any] = {}
        if self.inputs is not None:
            for i in range(self.inputs.shape[1]):
                cols[f"input_{i}"] = self.inputs[:, i]
        if self.wrenches is not None:
            for i, name in enumerate(
                ("force_x_n", "force_y_n", "force_z_n", "moment_x_nm", "moment_y_nm", "moment_z_nm")
            ):
                cols[name] = self.wrenches[:, i]
        for i, axis in enumerate("xyz"):
            cols[f"tip_{axis}_m"] = self.tip_positions[:, i]
        if self.tensions is not None:
            for i in range(self.tensions.shape[1]):
                cols[f"tension_{i}_n"] = self.tensions[:, i]
        cols["converged"] = self.converged
        cols["status"] = self.status
        cols["nit"] = self.iterations
        cols["nfev"] = self.evaluations
        if self.stable is not None and self.margin is not None:
            cols["stable"] = self.stable
            cols["margin"] = self.margin
        return pd.DataFrame(cols)

    @staticmethod
    def concatenate(parts: Iterable[BatchResult]) -> BatchResult:
        """Stack the results of consecutive blocks of rows.

        Parameters
        ----------
        parts : iterable of BatchResult
            The blocks, in row order (e.g. from :func:`tcarod.batch.iter_batches`).

        Returns
        -------
        BatchResult
            One result with every row; an optional array is kept only if every
            block has it.

        Raises
        ------
        ValueError
            Blocks that kept shapes on different nodes.

        Examples
        --------
        >>> from tcarod.batch import BatchResult, fig6_square_robot, iter_batches
        >>> rows = np.full((6, 2), 50.0)        # [C]
        >>> whole = BatchResult.concatenate(iter_batches(fig6_square_robot(), rows, steps=20, chunk_size=2, block_chunks=1))
        >>> len(whole), whole.success
        (6, True)
        """
        ps = list(parts)
        if not ps:
            return BatchResult(
                np.empty((0, 3)), np.empty((0, 3, 3)), np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0, bool)
            )

        def cat(name: str) -> Any:
            xs = [getattr(p, name) for p in ps]
            return None if any(x is None for x in xs) else np.concatenate(xs)

        arc_length, positions = _concatenate_shapes(ps)
        return BatchResult(
            np.concatenate([p.tip_positions for p in ps]),
            np.concatenate([p.tip_rotations for p in ps]),
            np.concatenate([p.iterations for p in ps]),
            np.concatenate([p.evaluations for p in ps]),
            np.concatenate([p.converged for p in ps]),
            inputs=cat("inputs"),
            wrenches=cat("wrenches"),
            tensions=cat("tensions"),
            stable=cat("stable"),
            margin=cat("margin"),
            arc_length=arc_length,
            positions=positions,
        )


def _concatenate_shapes(parts: list[BatchResult]) -> tuple[FloatArray | None, FloatArray | None]:
    """Arc length and stacked positions of consecutive blocks (``None`` unless
    every block kept shapes). A block in which no row converged has zero
    nodes; its rows become NaN on the other blocks' nodes."""
    if any(p.positions is None or p.arc_length is None for p in parts):
        return None, None
    grids = [p.arc_length for p in parts if p.arc_length is not None and p.arc_length.size]
    if not grids:
        return np.empty(0), np.concatenate([p.positions for p in parts if p.positions is not None])
    s = grids[0]
    if any(not np.array_equal(g, s) for g in grids):
        raise ValueError("parts: shapes on different nodes (different robots or steps) cannot be stacked")
    blocks = [
        p.positions if p.positions.shape[1] == s.size else np.full((len(p), s.size, 3), np.nan)
        for p in parts
        if p.positions is not None
    ]
    return s, np.concatenate(blocks)


#: ``BatchResult.plot_tips`` draws with this (``tcarod.plotting.batch.plot_tips``,
#: registered by ``tcarod._hooks``: the API does not import the plotting layer).
_TIP_PLOTTER: Callable[..., Any] | None = None


def _register_tip_plotter(plotter: Callable[..., Any]) -> None:
    """Register the function ``BatchResult.plot_tips`` calls (not public API)."""
    global _TIP_PLOTTER
    if not callable(plotter):
        raise TypeError("plotter must be callable")
    _TIP_PLOTTER = plotter


BatchResult.__module__ = "tcarod.batch"  # its public home (pickles and docs name it there)
