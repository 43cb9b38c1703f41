"""The forward model of the Fig. 6 square manipulator in NumPy/SciPy: the code
a Python user would write (RK4 on a NumPy state, a 6x6 ``np.linalg.solve``
per stage for eq (25), ``scipy.optimize.root`` for the shooting), used as the
baseline of ``tcarod bench`` and checked against the Rust core by
``tests/test_batch.py``.

Same equations and conventions as ``src/rod/ode.rs`` (eqs 22-31) and
``src/solve/residual.rs`` (eqs 32-33): state
``[p, q (quaternion), v, u, delta_1, delta_2]``, unknowns
``[v(0), L u(0), delta_1 / L, delta_2 / L]``, scaled tip residuals (32)-(33)
and elongation agreement. The TCA force law comes from ``tcarod.Tca`` (the
model under study here is the rod, not the TCA law).

Run ``python benches/numpy_baseline.py`` to time it against the core in one
process and print the ratio.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy.optimize import root

from tcarod import Tca, _core

FloatArray = npt.NDArray[np.float64]

LENGTH = 0.040
SIDE = 10e-3
DENSITY, YOUNGS, POISSON = 1040.0, 37.8e3, 0.5
G0 = 9.81
OFFSETS = (np.array([3e-3, 2.5e-3, 0.0]), np.array([3e-3, -2.5e-3, 0.0]))


@dataclass
class Fig6Square:
    """Fig. 6 square manipulator (as ``tcarod::experiments::fig6_square``)."""

    gravity: bool = True

    def __post_init__(self) -> None:
        a = SIDE * SIDE
        i = SIDE**4 / 12.0
        b = SIDE  # square: a = b
        j = b * b**3 * (1.0 / 3.0 - 0.21 * (1.0 - 1.0 / 12.0))
        g = YOUNGS / (2.0 * (1.0 + POISSON))
        self.kse = np.array([g * a, g * a, YOUNGS * a])
        self.kbt = np.array([YOUNGS * i, YOUNGS * i, g * j])
        self.fe = DENSITY * a * np.array([0.0, 0.0, -G0 if self.gravity else 0.0])
        # 38.2 turns per leg: 76.4 per U-shaped TCA, the default turns reading (tcarod.models.manipulators)
        self.tca = Tca.from_pitch_angle(
            LENGTH, math.radians(15.0), 1.7e-3, 38.2, "extension", _core.Material.silver_coated_nylon()
        )

    def tension(self, delta: float, temperature: float) -> float:
        """TCA tension [N] at elongation ``delta`` [m]: eq (6), with coil contact below 0."""
        if delta >= 0.0:
            return float(self.tca.force(delta, temperature))
        d = self.tca.fibre_diameter(temperature)
        k = self.tca.material.youngs_modulus(temperature) * math.pi * max(self.tca.coil_diameter - d, d) * d / LENGTH
        return float(self.tca.force(0.0, temperature)) + k * delta


def rot(q: FloatArray) -> FloatArray:
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def hat(r: FloatArray) -> FloatArray:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def deriv(m: Fig6Square, y: FloatArray, tau: FloatArray) -> FloatArray:
    """``dy/ds``, eqs (22)-(31), with the 6x6 system (25) solved by NumPy."""
    q, v, u = y[3:7], y[7:10], y[10:13]
    r_mat = rot(q)
    nse = m.kse * (v - np.array([0.0, 0.0, 1.0]))
    nbt = m.kbt * u
    big = np.zeros((6, 6))
    big[:3, :3] = np.diag(m.kse)
    big[3:, 3:] = np.diag(m.kbt)
    rhs = np.concatenate([-np.cross(u, nse) - r_mat.T @ m.fe, -np.cross(u, nbt) - np.cross(v, nse)])
    dy = np.empty_like(y)
    for i, r in enumerate(OFFSETS):
        pb = v + np.cross(u, r)
        nrm = np.linalg.norm(pb)
        a_i = (np.eye(3) * nrm * nrm - np.outer(pb, pb)) * (tau[i] / nrm**3)
        rh = hat(r)
        g_i = np.cross(u, pb)
        big[:3, :3] += a_i
        big[:3, 3:] -= a_i @ rh
        big[3:, :3] += rh @ a_i
        big[3:, 3:] -= rh @ a_i @ rh
        rhs[:3] -= a_i @ g_i
        rhs[3:] -= rh @ (a_i @ g_i)
        dy[13 + i] = nrm - 1.0
    dy[7:13] = np.linalg.solve(big, rhs)
    dy[0:3] = r_mat @ v
    w, x, yq, z = q
    ux, uy, uz = u
    dy[3:7] = 0.5 * np.array(
        [-x * ux - yq * uy - z * uz, w * ux + yq * uz - z * uy, w * uy + z * ux - x * uz, w * uz + x * uy - yq * ux]
    )
    return dy


def integrate(m: Fig6Square, x: FloatArray, tau: FloatArray, steps: int) -> FloatArray:
    """Tip state after RK4 with ``steps`` steps from scaled unknowns ``x``."""
    y = np.zeros(15)
    y[3] = 1.0
    y[7:10] = x[0:3]
    y[10:13] = x[3:6] / LENGTH
    h = LENGTH / steps
    for _ in range(steps):
        k1 = deriv(m, y, tau)
        k2 = deriv(m, y + 0.5 * h * k1, tau)
        k3 = deriv(m, y + 0.5 * h * k2, tau)
        k4 = deriv(m, y + h * k3, tau)
        y = y + h / 6.0 * (k1 + 2.0 * (k2 + k3) + k4)
        y[3:7] /= np.linalg.norm(y[3:7])
    return y


def residual(x: FloatArray, m: Fig6Square, temperatures: FloatArray, steps: int) -> FloatArray:
    """Scaled shooting residual at unknowns ``x`` (``scipy.optimize.root`` argument order)."""
    delta = x[6:8] * LENGTH
    tau = np.array([m.tension(delta[i], temperatures[i]) for i in range(2)])
    y = integrate(m, x, tau, steps)
    r_mat = rot(y[3:7])
    v, u = y[7:10], y[10:13]
    rf = m.kse * (v - np.array([0.0, 0.0, 1.0]))
    rm = m.kbt * u
    for i, r in enumerate(OFFSETS):
        pb = v + np.cross(u, r)
        t = pb / np.linalg.norm(pb)
        rf = rf + t * tau[i]
        rm = rm + np.cross(r, t) * tau[i]
    del r_mat  # no tip load on the Fig. 6 manipulator
    return np.concatenate([rf / m.kse, rm / m.kbt * LENGTH, (y[13:15] - delta) / LENGTH])


def solve(
    m: Fig6Square, temperatures: FloatArray, steps: int = 100, x0: FloatArray | None = None
) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """Forward solve: ``(tip position [m], tip rotation, unknowns, residual evaluations)``."""
    if x0 is None:
        x0 = np.zeros(8)
        x0[2] = 1.0
        for i in range(2):
            x0[6 + i] = float(m.tca.displacement(0.0, temperatures[i])) / LENGTH
    sol = root(residual, x0, args=(m, temperatures, steps), method="hybr", options={"xtol": 1e-13})
    if not sol.success:
        raise RuntimeError(f"NumPy baseline did not converge: {sol.message}")
    tau = np.array([m.tension(sol.x[6 + i] * LENGTH, temperatures[i]) for i in range(2)])
    y = integrate(m, sol.x, tau, steps)
    return y[0:3], rot(y[3:7]), sol.x, int(sol.nfev)


def timings(repeats: int = 5) -> dict[str, float]:
    """Median seconds of one IVP and one cold forward solve, NumPy and Rust, in this process."""
    m = Fig6Square(True)
    t = np.array([100.0, 100.0])
    _, _, x, _ = solve(m, t)
    tau = np.array([m.tension(x[6 + i] * LENGTH, t[i]) for i in range(2)])

    def med(f: object, n: int) -> float:
        out = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            for _ in range(n):
                f()  # type: ignore[operator]
            out.append((time.perf_counter() - t0) / n)
        return float(np.median(out))

    np_ivp = med(lambda: integrate(m, x, tau, 100), 3)
    np_solve = med(lambda: solve(m, t), 1)
    rs_ivp = float(np.median(_core.bench_time("ivp", repeats, 0.05)))
    rs_solve = float(np.median(_core.bench_time("cold", repeats, 0.05)))
    return {"numpy_ivp_s": np_ivp, "numpy_cold_solve_s": np_solve, "rust_ivp_s": rs_ivp, "rust_cold_solve_s": rs_solve}


if __name__ == "__main__":
    r = timings()
    print(
        f"IVP (100 RK4 steps):  NumPy {r['numpy_ivp_s'] * 1e3:9.3f} ms   Rust {r['rust_ivp_s'] * 1e6:8.1f} us   ratio {r['numpy_ivp_s'] / r['rust_ivp_s']:7.0f}x"
    )
    print(
        f"cold forward solve:   NumPy {r['numpy_cold_solve_s'] * 1e3:9.3f} ms   Rust {r['rust_cold_solve_s'] * 1e6:8.1f} us   "
        f"ratio {r['numpy_cold_solve_s'] / r['rust_cold_solve_s']:7.0f}x"
    )
