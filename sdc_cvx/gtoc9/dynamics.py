"""GTOC9's spacecraft dynamics between two events: two-body + J2 (its equations page).

``r'' = -mu r / |r|^3 {1 + 3/2 J2 (r_eq/|r|)^2 (k - 5 z^2/|r|^2)}`` with ``k = 1`` for x and
y, ``k = 3`` for z, in the frame of GTOC9's elements (z the axis J2 acts about), with
GTOC9's ``mu``, ``r_eq`` and ``J2`` (:mod:`sdc_cvx.flight.gtoc9_ephemeris`).  Integrated by
Hairer's DOP853 (SciPy's Fortran ``ode("dop853")``: 2.4 times faster than ``solve_ivp``'s
Python DOP853, same method) at ``rtol = 1e-13``, ``atol = 1e-6`` (m, m/s).  Units: m, m/s, s.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import ode

from ..flight.gtoc9_ephemeris import GTOC9_J2, GTOC9_MU, GTOC9_R_EQ

RTOL = 1e-13
ATOL = 1e-6


def acceleration(state) -> list[float]:
    """The time derivative of ``(x, y, z, vx, vy, vz)`` [m, m/s] under GTOC9's ODE."""
    x, y, z, vx, vy, vz = state
    r2 = x * x + y * y + z * z
    r = math.sqrt(r2)
    q = 1.5 * GTOC9_J2 * GTOC9_R_EQ**2 / r2
    s = 5.0 * z * z / r2
    g = -GTOC9_MU / (r2 * r)
    return [vx, vy, vz, g * x * (1.0 + q * (1.0 - s)), g * y * (1.0 + q * (1.0 - s)),
            g * z * (1.0 + q * (3.0 - s))]  # fmt: skip


def propagate(r0, v0, seconds: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Propagate ``(r0, v0)`` [m, m/s] over ``seconds`` [s] (>= 0).

    Returns
    -------
    r, v : ndarray (3,)
        The state at the end [m, m/s].
    states : ndarray (6, k)
        The state at every integration step, both ends included (for the perigee).
    """
    y0 = np.concatenate([np.asarray(r0, float), np.asarray(v0, float)])
    if seconds <= 0.0:
        return y0[:3].copy(), y0[3:].copy(), y0[:, None]
    steps: list[np.ndarray] = []
    solver = ode(lambda t, y: acceleration(y)).set_integrator("dop853", rtol=RTOL, atol=ATOL,
                                                              nsteps=10**9)  # fmt: skip
    solver.set_solout(lambda t, y: steps.append(np.array(y)))
    solver.set_initial_value(y0, 0.0)
    end = solver.integrate(float(seconds))
    if not solver.successful():
        raise RuntimeError(f"GTOC9 propagation over {seconds} s failed "
                           f"(DOP853 code {solver.get_return_code()})")  # fmt: skip
    return end[:3].copy(), end[3:].copy(), np.array(steps).T


def perigee_radius(states) -> np.ndarray:
    """Osculating (Keplerian, GTOC9's mu) perigee radius [m] of each state ``(6, k)``;
    ``r_p = p / (1 + e)``, which holds for any orbit shape."""
    r = np.asarray(states[:3], float)
    v = np.asarray(states[3:], float)
    h = np.cross(r, v, axis=0)
    p = np.sum(h * h, axis=0) / GTOC9_MU
    e_vec = np.cross(v, h, axis=0) / GTOC9_MU - r / np.linalg.norm(r, axis=0)
    return p / (1.0 + np.linalg.norm(e_vec, axis=0))
