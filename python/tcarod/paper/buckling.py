"""Beyond the paper: buckling and loss of stability of soft bodies.

Two studies, registered as ``tcarod reproduce buckling``:

1. **Self-weight buckling of an upright soft column.** A 50 mm EcoFlex 10
   column (10 x 9 mm rectangle, so that it buckles about its weak axis),
   clamped base-down, under growing gravity (gravity scale from 0.1 to 3,
   i.e. rho A g L^3 / EI from 0.5 to 15). The straight branch is followed through
   Greenhill's load rho A g L^3 / EI = 7.837 (a bifurcation; stable below,
   unstable above); a stable sweep jumps onto the post-buckled branch there
   and follows it as it bends over.
2. **A TCA manipulator heated through a loss of stability.** The paper's
   fixtures never lose stability: the Fig. 6 circle (4.3 against 7.84 for
   self-weight buckling) and square stay stable from 25 to 160 C (margin
   >= 0.4), and the square's passive TCA columns lean it to the side its
   heated TCA bends it to. A plausible variant does: the Fig. 6 circle with
   its pre-curvature turned toward the TCA side (+x) and twice the weight
   (a denser filler; rho A g L^3 / EI = 8.6). Its in-plane equilibrium is
   unstable at 25 C: the body stands buckled sideways (out of the bending
   plane, found by a stable sweep in gravity from 1 to 2 g). Heated, the
   sideways shape swings round toward the bending side and merges with the
   in-plane shape at a bifurcation near 115 C, above which the in-plane
   equilibrium is stable. A shooting solve of the in-plane shape at 25-114 C
   returns an equilibrium the robot cannot hold.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Final

import numpy as np

from .. import _core
from ..models.manipulators import (
    ECOFLEX10_DENSITY_KG_PER_M3,
    ECOFLEX10_POISSON,
    ECOFLEX10_YOUNGS_MODULUS_PA,
    UPRIGHT,
)
from ..models.stability import Branch, follow_branch, plot_branch

__all__ = ["BucklingResult", "column_robot", "heavy_circle", "predict_buckling", "weight_parameter"]

#: EcoFlex 10 (Section V, the core's fixture): density [kg/m^3], Young's modulus [Pa], Poisson ratio [-].
ECOFLEX10: Final[tuple[float, float, float]] = (
    ECOFLEX10_DENSITY_KG_PER_M3,
    ECOFLEX10_YOUNGS_MODULUS_PA,
    ECOFLEX10_POISSON,
)
#: Greenhill's self-weight buckling load of an upright clamped column, rho A g L^3 / EI [-].
GREENHILL: Final[float] = 7.837
#: The soft column: length [m], section width and height [m].
COLUMN_LENGTH_M: Final[float] = 0.05
COLUMN_SECTION_M: Final[tuple[float, float]] = (10e-3, 9e-3)
#: Weight factor of the heated variant of the Fig. 6 circle [-].
HEAVY_FACTOR: Final[float] = 2.0


def column_robot() -> _core.Robot:
    """The upright soft column under 1 g (gravity ``-z``).

    EcoFlex 10, 50 mm long, 10 x 9 mm section, no actuators.

    Returns
    -------
    Robot
        The column.

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot, weight_parameter
    >>> round(weight_parameter(column_robot()), 2)    # [-], below Greenhill's 7.84: it stands
    5.0
    """
    rho, e, nu = ECOFLEX10
    body = _core.Body(
        COLUMN_LENGTH_M,
        _core.Section.rectangle(*COLUMN_SECTION_M),
        e,
        poisson=nu,
        density=rho,
        gravity=list(UPRIGHT),
    )
    return _core.Robot(body, [])


def weight_parameter(robot: _core.Robot) -> float:
    """The weight parameter ``rho A g L^3 / EI`` of ``robot`` at its gravity [-].

    About the weak axis; an upright clamped column buckles under its own
    weight above Greenhill's 7.837.

    Parameters
    ----------
    robot : Robot
        The robot (its body's density, section, modulus, gravity and length).

    Returns
    -------
    float
        ``rho A g L^3 / EI`` [-].

    Examples
    --------
    >>> from tcarod.paper.buckling import column_robot, weight_parameter
    >>> round(weight_parameter(column_robot()), 3)
    4.998
    """
    b = robot.body
    area, ix, iy, _ = b.section.properties
    g = float(np.linalg.norm(b.gravity))
    return b.density * area * g * b.length**3 / (b.youngs_modulus * min(ix, iy))


def heavy_circle(weight: float = HEAVY_FACTOR) -> _core.Robot:
    """The Fig. 6 circle manipulator with its gravity scaled and its pre-curvature toward +x.

    Parameters
    ----------
    weight : float, optional
        Factor on the body's weight, applied to gravity [-] (default 2).

    Returns
    -------
    Robot
        The manipulator, upright.

    Examples
    --------
    >>> from tcarod.paper.buckling import heavy_circle
    >>> robot = heavy_circle(2.0)
    >>> robot.body.gravity.tolist()                # [m/s^2]: twice 1 g, upright
    [0.0, 0.0, -19.62]
    """
    base = _core._experiment_robot("fig6_circle", True)
    b = base.body
    body = b.replace(omega_star=[-w for w in b.omega_star], gravity=[g * weight for g in b.gravity])
    return _core.Robot(body, base.actuators)


@dataclass(frozen=True)
class BucklingResult:
    """Branches of the upright column and of the heated heavy circle manipulator.

    Made by :func:`predict_buckling` (``tcarod reproduce buckling``).

    Examples
    --------
    >>> from tcarod.paper.buckling import predict_buckling
    >>> result = predict_buckling()                  # a few seconds
    >>> round(result.column_critical_scale(), 2)          # gravity scale [-] where the column buckles
    1.54
    """

    column_weight_per_g: float
    column_branch: Branch
    column_sweep: Branch
    circle_weight: float
    circle_planar: Branch
    circle_sweep: Branch

    @property
    def name(self) -> str:
        """Registry name.

        Returns
        -------
        str
            ``"buckling"``.
        """
        return "buckling"

    def column_critical_scale(self) -> float:
        """Gravity scale of the first bifurcation of the straight column [-].

        Returns
        -------
        float
            Scale [-]; NaN if the branch has none.
        """
        b = self.column_branch.bifurcations
        return float(b[0]) if len(b) else float("nan")

    def circle_critical_c(self) -> float:
        """Temperature where the in-plane shape of the heated circle turns stable [C].

        Returns
        -------
        float
            Temperature [C]; NaN if the branch has none.
        """
        b = self.circle_planar.bifurcations
        return float(b[0]) if len(b) else float("nan")

    def table(self) -> str:
        """The studies as a text table.

        Returns
        -------
        str
            The critical weight parameter against Greenhill's, the circle's
            critical temperature [C] and the jumps of the stable sweeps.
        """
        q = self.column_critical_scale() * self.column_weight_per_g
        lines = [
            "Self-weight buckling of an upright EcoFlex column (50 mm, 10 x 9 mm)",
            f"  rho A g L^3/EI at 1 g: {self.column_weight_per_g:.3f}",
            f"  straight branch loses stability at rho A g L^3/EI = {q:.4f} "
            f"(Greenhill {GREENHILL}: {100 * (q / GREENHILL - 1):+.3f} %; a stubby column, L/h = 5.6:"
            " shear and axial compliance lower it; a slender one matches to 0.02 %, tests/integration/stability.rs)",
            f"  stable sweep: {len(self.column_sweep)} points, jumps at gravity scale "
            + ", ".join(f"{p:.4f}" for p, _, _ in self.column_sweep.jumps),
            "  tip at 3 g (post-buckled) [mm]: "
            + ", ".join(f"{x * 1e3:.2f}" for x in self.column_sweep.tip_positions[-1]),
            "",
            f"Fig. 6 circle, pre-curved toward +x, weight x {self.circle_weight:g} "
            f"(rho A g L^3/EI = {4.3 * self.circle_weight:.1f}), heated 25 -> 160 C",
            f"  in-plane equilibrium stable from {self.circle_critical_c():.2f} C "
            f"(unstable below; {int((~self.circle_planar.stable).sum())} of {len(self.circle_planar)} points)",
            f"  stable sweep (body buckled sideways at 25 C): {len(self.circle_sweep)} points, "
            f"events {[(k, round(p, 2)) for k, p, _ in self.circle_sweep.events]}, "
            f"jumps {[round(p, 2) for p, _, _ in self.circle_sweep.jumps]}",
            "  tip y [mm] along the sweep at 25 / 60 / 100 C: "
            + " / ".join(
                f"{np.interp(t, self.circle_sweep.parameter, self.circle_sweep.tip_positions[:, 1]) * 1e3:.1f}"
                for t in (25, 60, 100)
            ),
        ]
        return "\n".join(lines)

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable branches, every key naming its unit.

        Returns
        -------
        dict
            Parameters, tip positions [m], stability and margins [-] of each
            branch, with the critical values.
        """

        def br(b: Branch) -> dict[str, Any]:
            return {
                "parameter": b.parameter.tolist(),
                "tip_positions_m": b.tip_positions.tolist(),
                "stable": b.stable.tolist(),
                "margin": b.margin.tolist(),
                "events": [{"kind": k, "parameter": p, "tip_position_m": t.tolist()} for k, p, t in b.events],
                "jumps": [
                    {"parameter": p, "tip_before_m": a.positions[-1].tolist(), "tip_after_m": c.positions[-1].tolist()}
                    for p, a, c in b.jumps
                ],
            }

        return {
            "name": self.name,
            "column_weight_parameter_per_g": self.column_weight_per_g,
            "column_critical_weight_parameter": self.column_critical_scale() * self.column_weight_per_g,
            "greenhill": GREENHILL,
            "column_branch_gravity_scale": br(self.column_branch),
            "column_sweep_gravity_scale": br(self.column_sweep),
            "circle_weight_factor": self.circle_weight,
            "circle_critical_temperature_c": self.circle_critical_c(),
            "circle_planar_temperature_c": br(self.circle_planar),
            "circle_sweep_temperature_c": br(self.circle_sweep),
        }

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write the branches as a PNG to ``path``.

        Parameters
        ----------
        path : str or os.PathLike
            Output file.

        Returns
        -------
        pathlib.Path
            The path written.
        """
        from ..plotting import save_png

        from .._optional import require

        plt = require("matplotlib.pyplot")
        fig, (a, b) = plt.subplots(1, 2, figsize=(11.0, 4.2))
        plot_branch(self.column_branch, component=1, ax=a, label="straight")
        plot_branch(self.column_sweep, component=1, ax=a, label="stable sweep")
        a.axvline(GREENHILL / self.column_weight_per_g, color="0.6", lw=0.8)
        a.set_xlabel("gravity scale [-]")
        a.set_ylabel("tip y [mm] (weak-axis buckling)")
        a.set_title("upright soft column (solid stable, dashed unstable)")
        a.legend()
        plot_branch(self.circle_planar, component=0, ax=b, label="in-plane x")
        plot_branch(self.circle_sweep, component=1, ax=b, label="stable sweep y")
        plot_branch(self.circle_sweep, component=0, ax=b, label="stable sweep x")
        b.set_xlabel("temperature [C]")
        b.set_ylabel("tip position [mm]")
        b.set_title(f"Fig. 6 circle, flipped pre-curvature, weight x {self.circle_weight:g}")
        b.legend()
        fig.tight_layout()
        return save_png(fig, path)


def predict_buckling() -> BucklingResult:
    """Run both stability studies: the self-weight column and the heated heavy circle.

    Returns
    -------
    BucklingResult
        The followed branches and stable sweeps.

    Examples
    --------
    >>> from tcarod.paper.buckling import predict_buckling
    >>> result = predict_buckling()                  # a few seconds
    >>> result.table().splitlines()[0]
    'Self-weight buckling of an upright EcoFlex column (50 mm, 10 x 9 mm)'
    """
    col = column_robot()
    q1 = weight_parameter(col)
    column_branch = follow_branch(col, "gravity_scale", 0.1, 3.0, step=0.02, max_step=0.05)
    column_sweep = follow_branch(col, "gravity_scale", 0.1, 3.0, step=0.02, max_step=0.05, stable_only=True)
    circle = heavy_circle(1.0)
    # stable shape at HEAVY_FACTOR x weight and 25 C: sweep the weight up at 25 C
    up = follow_branch(circle, "gravity_scale", 1.0, HEAVY_FACTOR, inputs=[25.0], stable_only=True)
    heavy = heavy_circle(HEAVY_FACTOR)
    start = heavy.solve([25.0], warm_start=up.solutions[-1], stability="require")  # the stable sweep ended stable
    planar = follow_branch(heavy, "inputs", 25.0, 160.0, step=0.02, max_step=0.05)
    sweep = follow_branch(heavy, "inputs", 25.0, 160.0, step=0.02, max_step=0.05, warm_start=start, stable_only=True)
    return BucklingResult(q1, column_branch, column_sweep, HEAVY_FACTOR, planar, sweep)
