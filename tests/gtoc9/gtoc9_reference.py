"""The tests' own GTOC9: debris ephemeris, ODE and a shooting transfer, written from
GTOC9's equations page and independent of ``sdc_cvx.gtoc9`` (whose verdicts they check).

Units: m, m/s, s; epochs MJD2000 [days].
"""

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import root

from tests.conftest import SHARED_DATA

DEBRIS_FILE = SHARED_DATA / "gtoc9" / "debris_data.txt"
MU, RE, J2 = 398600.4418e9, 6378137.0, 1.08262668e-3
C_EXHAUST = 340.0 * 9.80665


def debris_rows() -> dict[int, np.ndarray]:
    """id -> (t0, a, e, i, Omega0, omega0, M0) of GTOC9's debris file."""
    table = np.loadtxt(DEBRIS_FILE)
    return {int(row[0]): row[1:] for row in table}


def debris_state(row, mjd2000: float):
    """GTOC9's ephemeris: elements advanced by n and the secular J2 rates, then Kepler."""
    t0, a, e, inc, raan0, argp0, m0 = row
    n = np.sqrt(MU / a**3)
    p = a * (1 - e**2)
    dt = (mjd2000 - t0) * 86400.0
    raan = raan0 - 1.5 * J2 * (RE / p) ** 2 * n * np.cos(inc) * dt
    argp = argp0 + 0.75 * J2 * (RE / p) ** 2 * n * (5 * np.cos(inc) ** 2 - 1) * dt
    mean = m0 + n * dt
    big_e = mean
    for _ in range(30):
        big_e = big_e - (big_e - e * np.sin(big_e) - mean) / (1 - e * np.cos(big_e))
    nu = 2 * np.arctan2(np.sqrt(1 + e) * np.sin(big_e / 2), np.sqrt(1 - e) * np.cos(big_e / 2))
    r = p / (1 + e * np.cos(nu))
    r_pf = np.array([r * np.cos(nu), r * np.sin(nu), 0.0])
    v_pf = np.sqrt(MU / p) * np.array([-np.sin(nu), e + np.cos(nu), 0.0])
    co, so, ci, si, cw, sw = (np.cos(raan), np.sin(raan), np.cos(inc), np.sin(inc),
                              np.cos(argp), np.sin(argp))  # fmt: skip
    rot = np.array([[co * cw - so * sw * ci, -co * sw - so * cw * ci, so * si],
                    [so * cw + co * sw * ci, -so * sw + co * cw * ci, -co * si],
                    [sw * si, cw * si, ci]])  # fmt: skip
    return rot @ r_pf, rot @ v_pf


def rhs(_t, y):
    r = y[:3]
    rn = np.linalg.norm(r)
    k = 1.5 * J2 * (RE / rn) ** 2
    z2 = 5 * (r[2] / rn) ** 2
    acc = -MU / rn**3 * r * np.array([1 + k * (1 - z2), 1 + k * (1 - z2), 1 + k * (3 - z2)])
    return np.concatenate([y[3:], acc])


def fly(r, v, seconds):
    """Two-body + J2 from (r, v) over ``seconds``: the end state and all steps (6, k)."""
    sol = solve_ivp(rhs, (0, seconds), np.concatenate([r, v]), method="DOP853",
                    rtol=1e-12, atol=1e-6)  # fmt: skip
    return sol.y[:3, -1], sol.y[3:, -1], sol.y


def shoot(r0, v_guess, seconds, r_target):
    """The velocity at ``r0`` that reaches ``r_target`` after ``seconds`` (root finding)."""
    sol = root(lambda v: (fly(r0, v, seconds)[0] - r_target) / 1e3, v_guess, method="hybr",
               options={"xtol": 1e-13})  # fmt: skip
    assert sol.success, sol.message
    return sol.x


def osculating_perigee(y):
    r, v = y[:3], y[3:]
    h = np.cross(r, v, axis=0)
    e = np.cross(v, h, axis=0) / MU - r / np.linalg.norm(r, axis=0)
    return (np.sum(h * h, axis=0) / MU) / (1 + np.linalg.norm(e, axis=0))


def _stumpff(z):
    if z > 0:
        s = np.sqrt(z)
        return (s - np.sin(s)) / s**3, (1 - np.cos(s)) / z
    if z < 0:
        s = np.sqrt(-z)
        return (np.sinh(s) - s) / s**3, (np.cosh(s) - 1) / -z
    return 1 / 6, 1 / 2


def lambert(r1, r2, seconds, normal):
    """Keplerian single-revolution Lambert arc (universal variables, Curtis Algorithm
    5.2) turning about ``normal`` (the departure orbit's angular momentum: GTOC9's orbits
    are retrograde): the velocities at ``r1`` and ``r2`` (the shooting's first guess)."""
    n1, n2 = np.linalg.norm(r1), np.linalg.norm(r2)
    angle = np.arccos(np.clip(r1 @ r2 / (n1 * n2), -1, 1))
    if np.cross(r1, r2) @ normal < 0:
        angle = 2 * np.pi - angle
    a = np.sin(angle) * np.sqrt(n1 * n2 / (1 - np.cos(angle)))

    def y(z):
        s, c = _stumpff(z)
        return n1 + n2 + a * (z * s - 1) / np.sqrt(c)

    def f(z):
        s, c = _stumpff(z)
        return (y(z) / c) ** 1.5 * s + a * np.sqrt(y(z)) - np.sqrt(MU) * seconds

    lo, hi = -4 * np.pi**2, 4 * np.pi**2
    while y(lo) < 0:
        lo += 0.1
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    z = 0.5 * (lo + hi)
    f_, g = 1 - y(z) / n1, a * np.sqrt(y(z) / MU)
    g_dot = 1 - y(z) / n2
    return (r2 - f_ * r1) / g, (g_dot * r2 - r1) / g
