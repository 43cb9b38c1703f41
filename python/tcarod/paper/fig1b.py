"""Fig. 1(b) of the paper: a soft cylinder with three TCAs at 120 degrees for
3-D motion, one of them divided into segments at their own temperatures.

The paper shows Fig. 1(b) only as an *illustration*: it gives no dimensions.
The numbers here are illustrative choices, stated so that they can be changed:

* body: EcoFlex 10 (``psi = 1040 kg/m^3``, ``E_B = 37.8 kPa``, Poisson 0.5,
  Section V), solid circle of 12 mm diameter, 60 mm long, standing base-down
  (gravity ``-z``) unless ``gravity=False``;
* TCAs: the paper's manipulator TCA (Section V-B: ``D = 1.7 mm``,
  ``alpha0 = 15 deg``, coiled length = body length) with the twist density of
  its 40 mm manipulators (``N = 76.4`` turns per 40 mm, so 114.6 turns here);
* placement: straight, 4 mm off the axis, at body-frame angles 0, 120 and 240
  degrees (TCA 0 on body ``+x``).

A heated extension TCA lengthens, so the body bends *away* from it: heating
TCA 0 (at ``+x``) moves the tip toward ``-x``.

Standing, this slender body carries its own weight at about 80 % of its
Greenhill buckling load (``q_cr = 7.84 E I / L^3``): the three symmetric TCAs
keep it straight, but shapes are sensitive to loads and to asymmetry (one
eccentric TCA alone makes a hard, near-buckling problem). Use
``gravity=False`` or a shorter body for gentler cases.

The registry entry ``fig1b`` (:func:`predict_fig1b`) adds a workspace map (a ``k^3`` temperature grid) to
``tcarod reproduce``.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Final, Sequence

import numpy as np
import numpy.typing as npt

from ..rod import Actuator, Body, Robot, Routing, Section
from ..models.manipulators import (
    ECOFLEX10_DENSITY_KG_PER_M3,
    ECOFLEX10_POISSON,
    ECOFLEX10_YOUNGS_MODULUS_PA,
    TCA_COIL_DIAMETER_M,
    TCA_PITCH_ANGLE_RAD,
    TCA_TURNS,
    TURNS_ANCHOR_LENGTH_M,
    UPRIGHT,
)
from ..models.segmented import segmented_actuators
from ..tca import Tca

__all__ = [
    "FIG1B",
    "Fig1bManipulator",
    "Fig1bWorkspaceResult",
]

FloatArray = npt.NDArray[np.float64]

#: Twist density of the paper's manipulator TCAs: 76.4 turns per 40 mm [turns/m].
MANIPULATOR_TWIST_PER_M: Final[float] = TCA_TURNS / TURNS_ANCHOR_LENGTH_M


@dataclass(frozen=True)
class Fig1bManipulator:
    """An illustrative Fig. 1(b) manipulator: three TCAs around a silicone cylinder.

    See the module docstring. Lengths in m, ``angles_deg`` in degrees,
    ``alpha0_rad`` in rad. ``segments`` divides TCA 0 (the "leftmost" TCA of
    the figure) into that many equal segments in series, each anchored to the
    body at its ends and driven by its own temperature; 1 keeps it whole.

    Examples
    --------
    >>> from tcarod.paper.fig1b import FIG1B
    >>> sol = FIG1B.robot().solve(FIG1B.inputs([120.0, 25.0, 25.0]), steps=20)
    >>> FIG1B.n_inputs, bool(sol.tip_position[0] < 0)       # TCA 0 at +x bends it toward -x
    (3, True)
    """

    length_m: float = 0.060
    diameter_m: float = 12e-3
    offset_m: float = 4e-3
    angles_deg: tuple[float, ...] = (0.0, 120.0, 240.0)
    coil_diameter_m: float = TCA_COIL_DIAMETER_M
    alpha0_rad: float = TCA_PITCH_ANGLE_RAD
    segments: int = 1

    def tca(self) -> Tca:
        """One whole TCA spanning the body (coiled length = body length)."""
        return Tca.from_pitch_angle(
            self.length_m,
            self.alpha0_rad,
            self.coil_diameter_m,
            MANIPULATOR_TWIST_PER_M * self.length_m,
        )

    def routing(self, k: int) -> Any:
        """Straight routing of TCA ``k``: ``offset_m`` from the axis at ``angles_deg[k]``."""
        a = math.radians(self.angles_deg[k])
        return Routing.straight(self.offset_m * math.cos(a), self.offset_m * math.sin(a))

    def body(self, gravity: bool = True) -> Any:
        """The EcoFlex cylinder; standing base-down (gravity ``-z``, 9.81 m/s^2) if ``gravity``."""
        return Body(
            self.length_m,
            Section.circle(self.diameter_m),
            ECOFLEX10_YOUNGS_MODULUS_PA,
            poisson=ECOFLEX10_POISSON,
            density=ECOFLEX10_DENSITY_KG_PER_M3,
            gravity=list(UPRIGHT) if gravity else [0.0, 0.0, 0.0],
        )

    def actuators(self) -> list[Any]:
        """Actuators in input order: TCA 0's segments (proximal first), then TCAs 1, 2, ..."""
        tca = self.tca()
        acts: list[Any] = []
        for k in range(len(self.angles_deg)):
            if k == 0 and self.segments > 1:
                acts.extend(segmented_actuators(tca, self.routing(0), self.segments, 0.0, self.length_m))
            else:
                acts.append(Actuator.tca(tca, self.routing(k)))
        return acts

    @property
    def n_inputs(self) -> int:
        """Number of actuator inputs (temperatures [C]).

        Returns
        -------
        int
            TCAs, TCA 0 counted once per segment.
        """
        return len(self.angles_deg) - 1 + max(1, self.segments)

    def robot(self, gravity: bool = True) -> Any:
        """The robot: :meth:`body` with :meth:`actuators`."""
        return Robot(self.body(gravity), self.actuators())

    def inputs(
        self, temperatures_c: Sequence[float], segment_temperatures_c: Sequence[float] | None = None
    ) -> list[float]:
        """Actuator inputs [C] from one temperature per TCA.

        Parameters
        ----------
        temperatures_c : sequence of float
            One temperature [C] per TCA.
        segment_temperatures_c : sequence of float, optional
            With a segmented TCA 0: one per segment, proximal first, replacing
            ``temperatures_c[0]``.

        Returns
        -------
        list of float
            One input [C] per actuator.

        Examples
        --------
        >>> import dataclasses
        >>> from tcarod.paper.fig1b import FIG1B
        >>> dataclasses.replace(FIG1B, segments=2).inputs([0.0, 25.0, 25.0], [120.0, 60.0])
        [120.0, 60.0, 25.0, 25.0]
        """
        temps = [float(t) for t in temperatures_c]
        if len(temps) != len(self.angles_deg):
            raise ValueError(f"temperatures_c: expected {len(self.angles_deg)} values (one per TCA), got {len(temps)}")
        if self.segments <= 1:
            return temps
        seg = (
            [temps[0]] * self.segments if segment_temperatures_c is None else [float(t) for t in segment_temperatures_c]
        )
        if len(seg) != self.segments:
            raise ValueError(f"segment_temperatures_c: expected {self.segments} values, got {len(seg)}")
        return seg + temps[1:]


#: The default illustrative manipulator (12 mm x 60 mm, three TCAs 4 mm off-axis).
FIG1B: Final[Fig1bManipulator] = Fig1bManipulator()


@dataclass(frozen=True, eq=False)
class Fig1bWorkspaceResult:
    """A workspace map of :data:`FIG1B` for ``tcarod reproduce fig1b``.

    Examples
    --------
    >>> from tcarod.paper.fig1b import FIG1B, Fig1bWorkspaceResult
    >>> from tcarod.models.workspace import workspace_map
    >>> result = Fig1bWorkspaceResult(workspace_map(FIG1B.robot(), [25.0, 120.0], steps=20))
    >>> result.name, len(result.to_json()["tip_position_m"])
    ('fig1b', 8)
    """

    workspace: Any  # tcarod.models.workspace.Workspace
    name: str = "fig1b"

    def table(self) -> str:
        """Summary: grid size, solves, time, and the extent of the reachable tip positions [mm]."""
        w = self.workspace
        tips = w.tip_positions_m * 1e3
        lines = [
            "Fig. 1(b) (illustrative): EcoFlex cylinder 12 mm x 60 mm, three TCAs at 120 deg, 4 mm off-axis",
            f"workspace map: {w.temperatures_c.shape[0]} temperature triples "
            f"({len(w.grid_c)} levels per TCA: {', '.join(f'{t:g}' for t in w.grid_c)} C), "
            f"{w.n_failed} failed, {w.elapsed_s:.2f} s",
        ]
        ok = np.all(np.isfinite(tips), axis=1)
        for k, axis in enumerate("xyz"):
            lines.append(f"tip {axis} [mm]: {np.min(tips[ok, k]):8.2f} .. {np.max(tips[ok, k]):8.2f}")
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """Grid [C] and tip positions [m] (``null`` where a solve failed)."""
        w = self.workspace
        return {
            "name": self.name,
            "illustrative": True,
            "grid_c": [float(t) for t in w.grid_c],
            "temperatures_c": w.temperatures_c.tolist(),
            "tip_position_m": [
                None if not np.all(np.isfinite(p)) else [float(x) for x in p] for p in w.tip_positions_m
            ],
            "elapsed_s": float(w.elapsed_s),
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """3-D scatter of the tip positions (see :func:`tcarod.plotting.plot_workspace`)."""
        from ..plotting import plot_workspace, save_png  # matplotlib only when plotting

        return save_png(plot_workspace(self.workspace), path)


def predict_fig1b() -> Fig1bWorkspaceResult:
    """Workspace map of :data:`FIG1B` over a 5 x 5 x 5 temperature grid (25-160 C)."""
    from ..models.workspace import workspace_map

    grid = np.linspace(25.0, 160.0, 5)
    return Fig1bWorkspaceResult(workspace_map(FIG1B.robot(), grid))
