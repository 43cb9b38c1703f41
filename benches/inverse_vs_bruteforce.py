"""Finite-difference inverse (paper Section IV) against brute-force optimisation.

Run as a script (``python benches/inverse_vs_bruteforce.py [--repeats N]``).
The paper (Section IV) reports its finite-difference scheme "roughly eight
times faster" than a brute-force optimisation over the same forward model.
Two problems, each solved both ways to the same answer:

(a) one grasp temperature (Table I finger, 2 g, eq 44): the paper's
    incremental eq-43 method (:func:`tcarod.models.grasp.grasp`, 10 increments;
    ``12 + 2N`` IVPs per increment plus one BVP) against bounded Brent on the
    tip gap over full BVP solves with the contact force as a dead tip load
    (:func:`tcarod.models.bruteforce.brute_force_blocked_temperature`). The direct
    mixed solve (temperature as a shooting unknown) is timed too.
(b) one tip-position solve (Fig. 6 square manipulator, 40 mm, upright, the
    two TCA legs as two variables, target = the tip at 90 / 140 C, start
    25 / 25 C): :func:`tcarod.inverse.tip_position` against Nelder-Mead on
    the tip distance over full BVP solves
    (:func:`tcarod.models.bruteforce.brute_force_tip_position`).

Prints the median wall time of ``--repeats`` runs of each, the ratio, and
the answers' agreement. Timings depend on the machine; no test asserts them.
"""

from __future__ import annotations

import argparse
import statistics
import time
from typing import Callable, TypeVar

import numpy as np

from tcarod.models.bruteforce import brute_force_blocked_temperature, brute_force_tip_position
from tcarod.models.grasp import grasp, table1_finger
from tcarod.inverse import tip_position
from tcarod.models.manipulators import square_manipulator

T = TypeVar("T")


def median_time(fn: Callable[[], T], repeats: int) -> tuple[float, T]:
    """Median wall time [s] of ``repeats`` calls (after one warm-up call) and the last result."""
    out = fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=7, help="timed runs per method (default 7)")
    args = parser.parse_args()
    r = args.repeats

    # (a) grasp temperature, 2 g
    finger = table1_finger()
    mass = 2e-3
    t_fd, g = median_time(lambda: grasp(mass, finger), r)
    t_fd2, g2 = median_time(lambda: grasp(mass, finger, increments=2), r)
    t_direct, gd = median_time(lambda: grasp(mass, finger, method="direct"), r)
    t_bf, bf = median_time(
        lambda: brute_force_blocked_temperature(finger, g.block_point_m, g.normal, g.force_per_finger_n), r
    )
    print("(a) grasp temperature, Table I finger, 2 g (force per finger %.3f mN)" % (g.force_per_finger_n * 1e3))
    print(f"    finite differences, eq 43 (10 increments): {t_fd * 1e3:8.1f} ms  T = {g.temperature_c:.6f} C")
    print(f"    finite differences, eq 43 (2 increments):  {t_fd2 * 1e3:8.1f} ms  T = {g2.temperature_c:.6f} C")
    print(f"    direct mixed solve:                        {t_direct * 1e3:8.1f} ms  T = {gd.temperature_c:.6f} C")
    print(
        f"    brute force (Brent on the tip gap):        {t_bf * 1e3:8.1f} ms  T = {bf.variables[0]:.6f} C"
        f"  ({bf.forward_solves} BVP solves)"
    )
    print(
        f"    ratio brute force / finite differences: {t_bf / t_fd:.1f}x with 10 increments, "
        f"{t_bf / t_fd2:.1f}x with 2 (paper: ~8x)"
    )

    # (b) tip position, Fig. 6 square manipulator
    robot = square_manipulator(0.040)
    truth = robot.solve([90.0, 140.0])
    target = np.asarray(truth.tip_position)
    t_fd_b, inv = median_time(lambda: tip_position(robot, target, groups=[0, 1], start=[25.0, 25.0]), r)
    t_bf_b, bfb = median_time(lambda: brute_force_tip_position(robot, target, groups=[0, 1], start=[25.0, 25.0]), r)
    print("(b) tip position, Fig. 6 square manipulator (40 mm, upright), target = tip at 90 / 140 C")
    print(
        f"    finite differences (J from IVPs):          {t_fd_b * 1e3:8.1f} ms  T = "
        f"{inv.variables[0]:.4f} / {inv.variables[1]:.4f} C, error {inv.error:.1e} m, {inv.iterations} iterations"
    )
    print(
        f"    brute force (Nelder-Mead on tip error):    {t_bf_b * 1e3:8.1f} ms  T = "
        f"{bfb.variables[0]:.4f} / {bfb.variables[1]:.4f} C, error {bfb.error_m:.1e} m ({bfb.forward_solves} BVP solves)"
    )
    print(f"    ratio brute force / finite differences: {t_bf_b / t_fd_b:.1f}x (paper: ~8x)")
    print(f"medians of {r} runs each")


if __name__ == "__main__":
    main()
