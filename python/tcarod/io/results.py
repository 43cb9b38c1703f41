"""Results as files: a forward solution's shape and everything solved, as a
dict / JSON document, a CSV table (one row per node) or a VTK polyline for
ParaView (the ``export`` extra, meshio).

Every key and column names its unit (SI: ``_m``, ``_n``, ``_nm``,
``_per_m``); dimensionless quantities carry none. NaN and infinity are
refused (they are not JSON, and a solution never holds them).

The methods ``Solution.to_dict``, ``to_json``, ``to_csv`` and ``to_vtk`` call
the functions here (:mod:`tcarod._hooks` registers them with the bindings
when tcarod is imported); :func:`write_shape` picks the format from the
file's suffix.

The document
------------

:func:`solution_dict` (``Solution.to_dict()``, ``to_json()``) holds:

Arrays become nested lists of floats; ``n`` is the number of nodes,
``k`` the number of actuators. World frame unless noted.

========================  ===========  ==========================================
key                       shape        meaning [unit]
========================  ===========  ==========================================
``format``                            ``"tcarod.solution/1"``
``tcarod_version``                    version that solved it
``nodes``                             ``n``
``arc_length_m``          (n,)         arc length of each node [m]
``positions_m``           (n, 3)       centre-line positions [m]
``rotations``             (n, 3, 3)    body-to-world rotation matrices [-]
                                       (column 3: the tangent ``d3``)
``nu``                    (n, 3)       linear strain, body frame [-]
``omega_per_m``           (n, 3)       angular strain, body frame [1/m]
``internal_force_n``      (n, 3)       internal force [N]
``internal_moment_nm``    (n, 3)       internal moment [N m]
``tip_position_m``        (3,)         tip position [m]
``tip_rotation``          (3, 3)       tip rotation [-]
``base_force_n``          (3,)         force transmitted to the base [N]
``base_moment_nm``        (3,)         moment about the origin at the base [N m]
``inputs``                (k,)         each actuator's input, in ``input_units``
``input_names``           (k,)         ``"temperature"`` (TCA), ``"tension"`` ...
``input_units``           (k,)         ``"C"`` (TCA), ``"N"``, ``"m"``
``tensions_n``            (k,)         actuator tensions [N] (< 0: pushes)
``elongations_m``         (k,)         actuator total elongations [m]
``elongation_profile_m``  (n, k)       elongation up to each node [m]
``actuator_paths_m``      k x (m, 3)   path of each actuator over its span [m]
``stable``                             verdict (bool) or ``None``
``stability_margin``                   margin [-], > 0 iff stable, or ``None``
``iterations``                         Newton iterations
``evaluations``                        IVPs integrated
``residual``                           final dimensionless residual [-]
``floor``                              rounding floor of the residual [-]
``steps``                              RK4 steps over the body
``status``                             0 converged, 1 converged at the floor
``message``                            the solve's outcome in words
``continuation_steps``    (j,)         homotopy parameters taken [-]
========================  ===========  ==========================================
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
from pathlib import Path
from typing import Any, Callable

import numpy as np

from .._core import __version__
from .._optional import require

__all__ = [
    "SOLUTION_FORMAT",
    "SHAPE_SUFFIXES",
    "dumps_json",
    "solution_csv",
    "solution_dict",
    "solution_json",
    "write_shape",
    "write_vtk",
]

#: Name and revision of the document :func:`solution_dict` returns (its
#: ``format`` key); the revision grows when a key changes meaning or goes away.
SOLUTION_FORMAT = "tcarod.solution/1"

#: File suffixes :func:`write_shape` understands.
SHAPE_SUFFIXES = (".json", ".csv", ".vtu", ".vtk")

_INPUT_NAME = re.compile(r"^(?P<name>.*?)\s*\[(?P<unit>[^\]]*)\]$")


def _floats(a: Any) -> Any:
    """Nested lists of Python floats from an array (JSON numbers)."""
    return np.asarray(a, dtype=float).tolist()


def _verdict(solution: Any, stability: bool | None) -> tuple[bool, float] | None:
    """``(stable, margin)``: the known verdict (``None``), computed if needed
    (``True``) or none (``False``)."""
    if stability is not None and not isinstance(stability, bool):
        raise TypeError(f"stability must be True, False or None, not {type(stability).__name__}")
    if stability is False:
        return None
    if stability is True:
        return bool(solution.stable), float(solution.stability_margin)
    known: tuple[bool, float] | None = solution._verdict
    return known


def _input_units(robot: Any) -> tuple[list[str], list[str]]:
    """Name and unit of each actuator's input (``"temperature"``, ``"C"`` for a TCA)."""
    names, units = [], []
    for a in robot.actuators:
        m = _INPUT_NAME.match(str(a.input_name))
        names.append(m.group("name") if m else str(a.input_name))
        units.append(m.group("unit") if m else "")
    return names, units


def solution_dict(solution: Any, *, stability: bool | None = None) -> dict[str, Any]:
    """Everything a forward solution holds, as a JSON-ready dict.

    The keys, with their shapes and units, are listed in the module's
    documentation (:mod:`tcarod.io.results`, "The document").

    Parameters
    ----------
    solution : Solution
        A forward solution (``Robot.solve``).
    stability : bool or None, optional
        ``None`` (default): the verdict if it is already known (every solve
        with the default policy ``stability="report"`` computes it), else
        ``stable`` and ``stability_margin`` are ``None``. ``True``: compute it
        if needed (one tangent integration). ``False``: leave it out
        (``None``).

    Returns
    -------
    dict
        The document above; ``json.dumps`` writes it as it is.

    Raises
    ------
    TypeError
        If ``stability`` is not a bool or None.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> sol = fig6_square_robot().solve([60.0, 25.0])
    >>> doc = sol.to_dict()
    >>> doc["nodes"] == len(doc["arc_length_m"]) == len(sol.s)
    True
    >>> doc["input_units"], doc["stable"]
    (['C', 'C'], True)
    """
    verdict = _verdict(solution, stability)
    names, units = _input_units(solution.robot)
    return {
        "format": SOLUTION_FORMAT,
        "tcarod_version": __version__,
        "nodes": len(solution.s),
        "arc_length_m": _floats(solution.s),
        "positions_m": _floats(solution.positions),
        "rotations": _floats(solution.rotations),
        "nu": _floats(solution.nu),
        "omega_per_m": _floats(solution.omega),
        "internal_force_n": _floats(solution.internal_force),
        "internal_moment_nm": _floats(solution.internal_moment),
        "tip_position_m": _floats(solution.tip_position),
        "tip_rotation": _floats(solution.tip_rotation),
        "base_force_n": _floats(solution.base_force),
        "base_moment_nm": _floats(solution.base_moment),
        "inputs": _floats(solution.inputs),
        "input_names": names,
        "input_units": units,
        "tensions_n": _floats(solution.tensions),
        "elongations_m": _floats(solution.elongations),
        "elongation_profile_m": _floats(solution.elongation_profile),
        "actuator_paths_m": [_floats(p) for p in solution.actuator_paths],
        "stable": None if verdict is None else verdict[0],
        "stability_margin": None if verdict is None else verdict[1],
        "iterations": int(solution.iterations),
        "evaluations": int(solution.evaluations),
        "residual": float(solution.residual),
        "floor": float(solution.floor),
        "steps": int(solution.steps),
        "status": int(solution.status),
        "message": str(solution.message),
        "continuation_steps": _floats(solution.continuation_steps),
    }


def solution_json(solution: Any) -> dict[str, Any]:
    """The document of :func:`solution_dict` (``Solution.to_dict()``), by its older name.

    Parameters
    ----------
    solution : Solution
        A forward solution.

    Returns
    -------
    dict
        The same document as :func:`solution_dict`.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.io.results import solution_dict, solution_json
    >>> sol = fig6_square_robot().solve([60.0, 25.0], steps=20)
    >>> solution_json(sol) == solution_dict(sol)
    True
    """
    return solution_dict(solution)


def dumps_json(doc: dict[str, Any], indent: int | None = 2) -> str:
    """A JSON document as text, refusing NaN and infinity.

    Parameters
    ----------
    doc : dict
        A JSON-ready document (e.g. :func:`solution_dict`).
    indent : int or None, optional
        Spaces of indentation (default 2); ``None``: one line.

    Returns
    -------
    str
        The JSON text.

    Raises
    ------
    ValueError
        A NaN or infinite number (invalid JSON: fail loudly).

    Examples
    --------
    >>> from tcarod.io.results import dumps_json
    >>> dumps_json({"tip_position_m": [0.0, 0.0, 0.04]}, indent=None)
    '{"tip_position_m": [0.0, 0.0, 0.04]}'
    >>> dumps_json({"x": float("nan")})
    Traceback (most recent call last):
    ...
    ValueError: Out of range float values are not JSON compliant...
    """
    return json.dumps(doc, indent=indent, allow_nan=False)


def _path(path: Any, name: str = "path") -> Path:
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"{name} must be a str or os.PathLike, not {type(path).__name__}")
    return Path(path)


def _write_text(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8", newline="")


def _to_json(solution: Any, path: Any = None, *, stability: bool | None = None, indent: int | None = 2) -> str:
    """``Solution.to_json``: the JSON text of :func:`solution_dict`, written to ``path`` if given."""
    if indent is not None and (isinstance(indent, bool) or not isinstance(indent, int)):
        raise TypeError(f"indent must be an int or None, not {type(indent).__name__}")
    if indent is not None and not 0 <= indent <= 16:
        raise ValueError(f"indent: {indent} spaces, allowed 0 to 16 (or None for one line)")
    text = dumps_json(solution_dict(solution, stability=stability), indent)
    if path is not None:
        _write_text(_path(path), text + "\n")
    return text


def _csv_columns(solution: Any) -> tuple[list[str], np.ndarray]:
    """Column names and the ``(n, columns)`` table of :func:`solution_csv`."""
    n = len(solution.s)
    k = len(solution.tensions)
    names = ["s_m", "x_m", "y_m", "z_m"]
    names += [f"r{i}{j}" for i in (1, 2, 3) for j in (1, 2, 3)]
    names += ["nu_1", "nu_2", "nu_3", "omega_1_per_m", "omega_2_per_m", "omega_3_per_m"]
    names += ["force_x_n", "force_y_n", "force_z_n", "moment_x_nm", "moment_y_nm", "moment_z_nm"]
    names += [f"elongation_{a}_m" for a in range(k)]
    table = np.column_stack(
        [
            solution.s,
            solution.positions,
            np.asarray(solution.rotations).reshape(n, 9),
            solution.nu,
            solution.omega,
            solution.internal_force,
            solution.internal_moment,
            np.asarray(solution.elongation_profile).reshape(n, k),
        ]
    )
    return names, table


def solution_csv(solution: Any, path: Any = None) -> str:
    """The shape as CSV: a header row, then one row per node.

    Columns: ``s_m`` (arc length [m]); ``x_m``, ``y_m``, ``z_m`` (centre-line
    position, world frame [m]); ``r11`` ... ``r33`` (row ``i``, column ``j``
    of the body-to-world rotation [-]; ``r13, r23, r33`` is the tangent);
    ``nu_1`` ... ``nu_3`` (linear strain, body frame [-]); ``omega_1_per_m``
    ... ``omega_3_per_m`` (angular strain, body frame [1/m]); ``force_x_n`` ...
    ``force_z_n`` (internal force, world frame [N]); ``moment_x_nm`` ...
    ``moment_z_nm`` (internal moment, world frame [N m]); ``elongation_<a>_m``
    (elongation of actuator ``a`` accumulated up to the node [m]). Numbers
    are written with the shortest text that reads back to the same float.
    Values with no node (inputs, tensions, the verdict) are in
    :func:`solution_dict`.

    Parameters
    ----------
    solution : Solution
        A forward solution.
    path : str or os.PathLike, optional
        Where to write the table (UTF-8; parent directories are created).

    Returns
    -------
    str
        The CSV text.

    Raises
    ------
    TypeError
        If ``path`` is not a str or path.
    OSError
        If the file cannot be written.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> sol = fig6_square_robot().solve([60.0, 25.0])
    >>> lines = sol.to_csv().splitlines()
    >>> lines[0].startswith("s_m,x_m,y_m,z_m,r11")
    True
    >>> len(lines) - 1 == len(sol.s)
    True
    """
    names, table = _csv_columns(solution)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(names)
    w.writerows([repr(float(x)) for x in row] for row in table)
    text = buf.getvalue()
    if path is not None:
        _write_text(_path(path), text)
    return text


_VTK_SUFFIXES = (".vtu", ".vtk")


def write_vtk(solution: Any, path: Any) -> Path:
    """Write the centre line as a VTK polyline for ParaView, with meshio.

    ``.vtu``: XML, ``.vtk``: legacy.

    Points: the nodes' positions [m]. Cells: one ``line`` per segment between
    consecutive nodes. Point data (one value per node): ``arc_length_m``;
    ``d1``, ``d2``, ``d3`` (the body axes in the world frame [-], ``d3`` the
    tangent: for glyphs, or a tube of the section's shape); ``nu`` [-] and
    ``omega_per_m`` [1/m] (strains, body frame); ``internal_force_n`` [N]
    and ``internal_moment_nm`` [N m]; ``elongation_<a>_m`` (elongation of
    actuator ``a`` accumulated up to the node [m]). Values with no node (inputs,
    tensions, the stability verdict) are in :func:`solution_dict`: write the
    JSON document beside the VTK file.

    Parameters
    ----------
    solution : Solution
        A forward solution.
    path : str or os.PathLike
        A file ending in ``.vtu`` or ``.vtk`` (parent directories are created).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    tcarod.MissingDependencyError
        (an ``ImportError``) if meshio is not installed: ``pip install 'tcarod[export]'``.
    ValueError
        If ``path`` does not end in ``.vtu`` or ``.vtk``.
    TypeError
        If ``path`` is not a str or path.

    Examples
    --------
    >>> import meshio                           # the `export` extra
    >>> from tcarod.batch import fig6_square_robot
    >>> sol = fig6_square_robot().solve([60.0, 25.0], steps=20)
    >>> out = sol.to_vtk("square.vtu")
    >>> meshio.read(out).points.shape == (len(sol.s), 3)
    True
    """
    p = _path(path)
    if p.suffix.lower() not in _VTK_SUFFIXES:
        raise ValueError(f"path: {str(p)!r} must end in .vtu or .vtk (VTK formats meshio writes)")
    meshio: Any = require("meshio")
    pos = np.ascontiguousarray(solution.positions, dtype=float)
    n = pos.shape[0]
    rot = np.asarray(solution.rotations, dtype=float)
    k = len(solution.tensions)
    lines = np.column_stack([np.arange(n - 1), np.arange(1, n)]).astype(np.int64)
    point_data: dict[str, Any] = {
        "arc_length_m": np.asarray(solution.s, dtype=float),
        "d1": np.ascontiguousarray(rot[:, :, 0]),
        "d2": np.ascontiguousarray(rot[:, :, 1]),
        "d3": np.ascontiguousarray(rot[:, :, 2]),
        "nu": np.asarray(solution.nu, dtype=float),
        "omega_per_m": np.asarray(solution.omega, dtype=float),
        "internal_force_n": np.asarray(solution.internal_force, dtype=float),
        "internal_moment_nm": np.asarray(solution.internal_moment, dtype=float),
    }
    profile = np.asarray(solution.elongation_profile, dtype=float).reshape(n, k)
    for a in range(k):  # one scalar per actuator: the legacy format pads 2-vectors to 3
        point_data[f"elongation_{a}_m"] = np.ascontiguousarray(profile[:, a])
    mesh = meshio.Mesh(pos, [("line", lines)], point_data=point_data)
    p.parent.mkdir(parents=True, exist_ok=True)
    mesh.write(p, file_format="vtu" if p.suffix.lower() == ".vtu" else "vtk")
    return p


def write_shape(solution: Any, path: Any, *, stability: bool | None = None) -> Path:
    """Write a forward solution to ``path``, the format chosen by its suffix.

    ``.json``: :func:`solution_dict` (``Solution.to_json``); ``.csv``: one row
    per node (``Solution.to_csv``); ``.vtu`` / ``.vtk``: a VTK polyline for
    ParaView (``Solution.to_vtk``; needs the ``export`` extra, meshio).

    Parameters
    ----------
    solution : Solution
        A forward solution.
    path : str or os.PathLike
        The file; parent directories are created.
    stability : bool or None, optional
        As for :func:`solution_dict` (JSON only: the other formats hold node
        values only).

    Returns
    -------
    pathlib.Path
        The file written.

    Raises
    ------
    ValueError
        If the suffix is none of ``.json``, ``.csv``, ``.vtu``, ``.vtk``.
    tcarod.MissingDependencyError
        For ``.vtu`` / ``.vtk`` without meshio.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.io import write_shape
    >>> sol = fig6_square_robot().solve([60.0, 25.0])
    >>> out = write_shape(sol, pathlib.Path(tempfile.mkdtemp()) / "finger.csv")
    >>> out.read_text().startswith("s_m,x_m,y_m,z_m")
    True
    """
    p = _path(path)
    suffix = p.suffix.lower()
    if suffix == ".json":
        _to_json(solution, p, stability=stability)
    elif suffix == ".csv":
        solution_csv(solution, p)
    elif suffix in _VTK_SUFFIXES:
        write_vtk(solution, p)
    else:
        raise ValueError(f"path: suffix {p.suffix!r} of {str(p)!r} is not one of {', '.join(SHAPE_SUFFIXES)}")
    return p


#: The functions behind ``Solution.to_dict``, ``to_json``, ``to_csv`` and
#: ``to_vtk`` (:mod:`tcarod._hooks` registers :func:`export` with the bindings).
METHODS: dict[str, Callable[..., Any]] = {
    "to_dict": solution_dict,
    "to_json": _to_json,
    "to_csv": solution_csv,
    "to_vtk": write_vtk,
}


def export(name: str, solution: Any, *args: Any, **kwargs: Any) -> Any:
    """Run the export method ``name`` of ``solution`` (the bindings call this)."""
    return METHODS[name](solution, *args, **kwargs)
