"""Plots of the models: workspace maps, thermal step responses, shape
trajectories along a heating transient (and their animation frames)."""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .. import _validate as V
from ..models.thermal import ThermalModel, VoltageProfile
from ..models.trajectory import ShapeTrajectory
from ..models.workspace import Workspace
from ._figure import detached, new_figure, save_png
from .solution import plot_solution

__all__ = ["plot_shape_trajectory", "plot_step_response", "plot_workspace", "save_trajectory_frames"]


def plot_workspace(ws: Workspace, colour_by: str = "bending") -> Figure:
    """3-D scatter of the reachable tip positions [mm] of a workspace map.

    Parameters
    ----------
    ws : Workspace
        A map from :func:`tcarod.models.workspace.workspace_map`.
    colour_by : {"bending", "max_temperature"}, optional
        Colour by the tip's bending angle [deg] (default) or by the hottest
        input [C].

    Returns
    -------
    matplotlib.figure.Figure
        The figure (a pyplot figure when pyplot is in use, see
        :mod:`tcarod.plotting`).

    Raises
    ------
    TypeError
        ``ws`` is not a ``Workspace`` or ``colour_by`` not a str.
    ValueError
        An unknown ``colour_by``.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.workspace import workspace_map
    >>> from tcarod.plotting import plot_workspace
    >>> ws = workspace_map(fig6_square_robot(), [25.0, 60.0, 100.0], steps=20)   # [C] per TCA
    >>> plot_workspace(ws).axes[0].get_title()
    'Reachable tip positions: 3^2 = 9 input combinations'
    """
    V.instance("ws", ws, Workspace, "a Workspace")
    if not isinstance(colour_by, str):
        raise TypeError(f"colour_by must be a str, not {type(colour_by).__name__}")
    ok = np.all(np.isfinite(ws.tip_positions_m), axis=1)
    p = ws.tip_positions_m[ok] * 1e3
    if colour_by == "bending":
        c = np.degrees(ws.bending_angle_rad[ok])
        label = "bending angle of the tip [deg]"
    elif colour_by == "max_temperature":
        c = ws.temperatures_c[ok].max(axis=1)
        label = "hottest actuator [°C]"
    else:
        raise ValueError(f"colour_by = {colour_by!r}: use 'bending' or 'max_temperature'")
    fig = new_figure(6.0, 5.0)
    ax: Any = fig.add_subplot(projection="3d")
    sc = ax.scatter(p[:, 0], p[:, 1], p[:, 2], c=c, cmap="viridis", s=14)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm]")
    n_in = ws.temperatures_c.shape[1]
    ax.set_title(f"Reachable tip positions: {len(ws.grid_c)}^{n_in} = {ws.temperatures_c.shape[0]} input combinations")
    fig.colorbar(sc, ax=ax, shrink=0.7, label=label)
    return fig


def plot_step_response(model: ThermalModel, voltage_v: float, duration_s: float | None = None) -> Figure:
    """Temperature [C] of a TCA after a voltage step at t = 0.

    The steady state and the time constant are marked.

    Parameters
    ----------
    model : ThermalModel
        The TCA's electro-thermal model.
    voltage_v : float
        The step [V].
    duration_s : float, optional
        Time shown [s] (default five time constants).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        A non-finite voltage or a non-positive duration.

    Examples
    --------
    >>> from tcarod.models.thermal import ThermalModel
    >>> from tcarod.plotting import plot_step_response
    >>> heater = ThermalModel(fibre_length_m=0.155, threads=3, resistance=60.0)     # [m], [ohm]
    >>> plot_step_response(heater, 1.0).axes[0].get_xlabel()
    'time [s]'
    """
    V.instance("model", model, ThermalModel, "a ThermalModel")
    voltage_v = V.real("voltage_v", voltage_v, unit="V")
    tau = model.time_constant_s
    dur = 5.0 * tau if duration_s is None else V.positive("duration_s", duration_s, "s")
    t = np.linspace(0.0, dur, 400)
    traj = model.transient(VoltageProfile.step(voltage_v), t)
    fig = new_figure(5.0, 3.4)
    ax = fig.subplots()
    ax.plot(t, traj.temperature_c, color="black", label=f"{voltage_v:g} V step ({traj.method})")
    try:
        tss = model.steady_temperature(voltage_v)
        ax.axhline(tss, color="0.5", linestyle="--", label=f"steady state {tss:.1f} °C")
        t63 = model.ambient_c + (1.0 - math.exp(-1.0)) * (tss - model.ambient_c)
        ax.plot([tau], [t63], "o", color="black", markerfacecolor="white", label=f"tau = {tau:.2f} s")
    except ValueError:
        pass
    ax.axhline(model.t_max_c, color="red", linewidth=0.8, label=f"t_max {model.t_max_c:g} °C")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("temperature [°C]")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize="small")
    return fig


def plot_shape_trajectory(traj: ShapeTrajectory) -> Figure:
    """Tip position [mm] and actuator temperatures [C] against time [s].

    Parameters
    ----------
    traj : ShapeTrajectory
        A quasi-static trajectory (:func:`tcarod.models.trajectory.quasi_static_trajectory`).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels sharing the time axis.

    Raises
    ------
    TypeError
        ``traj`` is not a ``ShapeTrajectory``.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> from tcarod.models.trajectory import quasi_static_trajectory
    >>> robot = fig6_square_robot()
    >>> heater = ThermalModel(fibre_length_m=robot.actuators[0].tca_model.fibre_length, threads=3, resistance=60.0)
    >>> step = VoltageProfile.step(1.0)                    # 1 V from t = 0
    >>> traj = quasi_static_trajectory(robot, [heater, heater], [step, step], np.linspace(0.0, 20.0, 3), steps=20)
    >>> from tcarod.plotting import plot_shape_trajectory
    >>> plot_shape_trajectory(traj).axes[0].get_ylabel()
    'tip position [mm]'
    """
    V.instance("traj", traj, ShapeTrajectory, "a ShapeTrajectory")
    fig = new_figure(6.0, 5.0)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    for k, name in enumerate("xyz"):
        ax1.plot(traj.time_s, traj.tip_positions_m[:, k] * 1e3, label=f"tip {name}")
    ax1.set_ylabel("tip position [mm]")
    ax1.grid(True, linewidth=0.3)
    ax1.legend(fontsize="small")
    for i in range(traj.temperatures_c.shape[1]):
        ax2.plot(traj.time_s, traj.temperatures_c[:, i], label=f"actuator {i}")
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("temperature [°C]")
    ax2.grid(True, linewidth=0.3)
    ax2.legend(fontsize="small")
    return fig


def save_trajectory_frames(traj: ShapeTrajectory, directory: str | os.PathLike[str], every: int = 1) -> list[Path]:
    """Write animation frames of a shape trajectory, one PNG per time.

    One 3-D shape (:func:`tcarod.plotting.plot_solution`) per ``every``-th
    time of ``traj``, on fixed axes, titled with the time [s] and the
    temperatures [C].

    Parameters
    ----------
    traj : ShapeTrajectory
        A quasi-static trajectory.
    directory : str or os.PathLike
        Where to write ``frame_0000.png``, ... (created if needed).
    every : int, optional
        Write every ``every``-th time (default 1).

    Returns
    -------
    list of pathlib.Path
        The files written.

    Raises
    ------
    TypeError
        ``traj`` is not a ``ShapeTrajectory``.
    ValueError
        ``every`` < 1.

    Examples
    --------
    >>> from tcarod.batch import fig6_square_robot
    >>> from tcarod.models.thermal import ThermalModel, VoltageProfile
    >>> from tcarod.models.trajectory import quasi_static_trajectory
    >>> robot = fig6_square_robot()
    >>> heater = ThermalModel(fibre_length_m=robot.actuators[0].tca_model.fibre_length, threads=3, resistance=60.0)
    >>> step = VoltageProfile.step(1.0)                    # 1 V from t = 0
    >>> traj = quasi_static_trajectory(robot, [heater, heater], [step, step], np.linspace(0.0, 20.0, 3), steps=20)
    >>> from tcarod.plotting import save_trajectory_frames
    >>> paths = save_trajectory_frames(traj, "frames", every=2)
    >>> len(paths), paths[0].name
    (2, 'frame_0000.png')
    """
    V.instance("traj", traj, ShapeTrajectory, "a ShapeTrajectory")
    every = V.integer("every", every, 1, 2**31)
    out = Path(directory)
    tips = traj.tip_positions_m * 1e3
    lo = np.minimum(tips.min(axis=0), 0.0)
    hi = np.maximum(tips.max(axis=0), 0.0)
    centre, half = 0.5 * (lo + hi), 0.55 * float(np.max(hi - lo)) + 5.0
    paths = []
    for k in range(0, len(traj.solutions), every):
        temps = ", ".join(f"{t:.0f}" for t in traj.temperatures_c[k])
        with detached():  # written to a file, never shown: outside pyplot
            fig = plot_solution(traj.solutions[k], title=f"t = {traj.time_s[k]:.1f} s, T = [{temps}] °C")
        ax: Any = fig.axes[0]
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)
        paths.append(save_png(fig, out / f"frame_{k:04d}.png", dpi=80))
    return paths
