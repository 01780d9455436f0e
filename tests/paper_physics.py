"""The transfer physics the brute forces need, re-derived from Cerf's paper alone.

The brute forces of the test tree (``tests/planner/bruteforce.py`` and through it
``tests/campaign/bruteforce.py``) must not share the physics of the code they check: an
error in ``sdc_cvx.physics`` would then be in both and cancel out (issue 27).  This module
writes the few functions they need straight from the paper's equations (Part III-A, III-C,
III-F and III-H: Eq. 7-13 and Table 3), with nothing imported from ``sdc_cvx``.
``tests/physics/test_paper_physics.py`` checks that it agrees with the package's own
implementation, and with the paper's printed numbers.

The call signatures and conventions are those of the functions they stand in for (SI
units: m, s, rad, m/s; a drift orbit's *side* of the Eq. 10 asymptote is ``+1`` when it
precesses faster than the target, ``-1`` slower).

Reference: M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and
Trajectory Optimization", JOTA 156(3), 761-796, 2013 (``../shared/paper/cerf-sdc-mission.md``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

R_EARTH = 6378137.0
"""Earth equatorial radius R_T [m] (paper, below Eq. 7)."""
MU = 3.986e14
"""Earth gravitational constant mu [m^3/s^2] (paper, below Eq. 7)."""
J2 = 1.08263e-3
"""First zonal coefficient.  The paper prints 1.086e-3, but its C_J2 = 1.318e18 and its
Table 2 follow from 1.0826e-3 (the project's design notes, §3, and the package's default)."""
C_J2 = 1.5 * J2 * np.sqrt(MU) * R_EARTH**2
"""C_J2 = 3/2 J2 sqrt(mu) R_T^2 [m^3.5/s] of Eq. 7 (1.318e18 in the paper)."""
SECONDS_PER_DAY = 86400.0
CLOSED_GAP_RAD = 1e-9
"""RAAN gap [rad] below which the two RAANs already coincide: the Eq. 10 duration is 0
(also for a gap a rounding error short of a full turn), as in the code under test."""


def raan_rate(a, e, inc):
    """Secular J2 RAAN rate [rad/s], Eq. 7: ``-C_J2 cos I / (a^(7/2) (1 - e^2)^2)``."""
    a, e = np.asarray(a, dtype=float), np.asarray(e, dtype=float)
    return -C_J2 * np.cos(inc) / (a**3.5 * (1.0 - e * e) ** 2)


def drift_rate(a, inc):
    """RAAN rate [rad/s] of a circular drift orbit, Eq. 8 (or 14) with e_d = 0 (Part III-H)."""
    return raan_rate(a, 0.0, inc)


class NodeOrbits(NamedTuple):
    """Debris orbits as arrays: radius ``a`` [m], ``inc`` [rad], RAAN at t0 ``raan`` [rad] and
    its J2 rate ``rate`` [rad/s] (Eq. 7 with the debris' own eccentricity)."""

    a: np.ndarray
    inc: np.ndarray
    raan: np.ndarray
    rate: np.ndarray

    @classmethod
    def from_elements(cls, a, e, inc, raan):
        """From the elements at t0: ``a`` [m], ``e`` [-], ``inc`` [rad], ``raan`` [rad]."""
        a, e, inc, raan = (np.asarray(x, dtype=float) for x in (a, e, inc, raan))
        return cls(a, inc, raan, raan_rate(a, e, inc))

    def take(self, index) -> NodeOrbits:
        """The orbits at ``index`` (numpy indexing of every field)."""
        return NodeOrbits(*(np.asarray(x)[index] for x in self))

    def raan_at(self, t):
        """Omega(t) = Omega(t0) + rate (t - t0), ``t`` in s after t0 (Part III-A)."""
        return self.raan + self.rate * t


def raan_gap(origin: NodeOrbits, target: NodeOrbits, t):
    """Numerator of Eq. 10 [rad], unwrapped: Omega_j(t0) - Omega_i(t0) + (rate_j - rate_i) t."""
    return target.raan - origin.raan + (target.rate - origin.rate) * t


def transfer_duration(origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart):
    """Coast time [s] on the drift orbit (a_d, I_d) leaving ``origin`` at ``t_depart`` [s], Eq. 10.

    ``t2 - t1 = gap / (rate_d - rate_j)``, the gap "taken modulo 360 deg in order to match
    the sign" of the denominator (Part III-C), so the duration is the first positive one:
    ``mod(sign(rate_d - rate_j) gap, 2 pi) / |rate_d - rate_j|``.  0 where the RAANs already
    coincide (within :data:`CLOSED_GAP_RAD`), ``inf`` on the asymptote rate_d = rate_j.
    """
    relative = drift_rate(a_drift, inc_drift) - target.rate
    towards = np.where(relative < 0.0, -1.0, 1.0)
    ahead = np.mod(towards * raan_gap(origin, target, t_depart), 2.0 * np.pi)
    closed = (ahead < CLOSED_GAP_RAD) | (ahead > 2.0 * np.pi - CLOSED_GAP_RAD)
    with np.errstate(divide="ignore", invalid="ignore"):  # 0/0 and x/0: replaced below
        duration = ahead / np.abs(relative)
    return np.where(closed, 0.0, np.where(relative == 0.0, np.inf, duration))


def drift_inclination(inc_from, inc_to, side):
    """Table 3: the debris inclination that speeds the RAAN correction up the most.

    The criterion of Part III-H is the largest precession rate difference between drift
    and target.  By Eq. 8 the rate is ``-cos I`` times a positive factor of the radius, so
    the faster of the two inclinations at any radius is the one of larger ``-cos I``:
    ``side = +1`` (drift faster than the target) takes it, ``side = -1`` the other.  For
    retrograde orbits ``+1`` is a drift orbit below the target, and this is Table 3's
    ``Max(I1, I2)`` below, ``Min(I1, I2)`` above.
    """
    inc_from, inc_to = np.asarray(inc_from, dtype=float), np.asarray(inc_to, dtype=float)
    to_is_faster = -np.cos(inc_to) > -np.cos(inc_from)
    faster = np.where(to_is_faster, inc_to, inc_from)
    slower = np.where(to_is_faster, inc_from, inc_to)
    return np.where(np.asarray(side) > 0, faster, slower)


def speed(r, a):
    """Keplerian speed [m/s] at radius ``r`` on an orbit of semi-major axis ``a``, Eq. 12."""
    return np.sqrt(MU * (2.0 / np.asarray(r, dtype=float) - 1.0 / np.asarray(a, dtype=float)))


def impulse(v_before, v_after, plane_change):
    """``||V_a - V_b||`` of Eq. 13, the two velocities ``plane_change`` [rad] apart (Fig. 10).

    The vector difference itself: V_b along x, V_a at the angle di in the (x, y) plane.
    """
    return np.hypot(v_after * np.cos(plane_change) - v_before, v_after * np.sin(plane_change))


def hohmann(a_1, a_2, plane_change):
    """Two-impulse Hohmann transfer [m/s] between circular orbits of radii ``a_1``, ``a_2``.

    Eq. 11-13 for one half of Fig. 9: the transfer ellipse has its perigee on the lower
    orbit and its apogee on the higher one (semi-major axis their mean), each impulse is the
    Eq. 12 speed change at its apsis, and the inclination change is combined (Eq. 13) with
    the apogee impulse, where the speeds are lowest (Part III-H, Fig. 12).
    """
    low, high = np.minimum(a_1, a_2), np.maximum(a_1, a_2)
    a_t = 0.5 * (low + high)
    perigee = np.abs(speed(low, a_t) - speed(low, low))
    apogee = impulse(speed(high, a_t), speed(high, high), plane_change)
    return perigee + apogee


def transfer_dv(origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift):
    """Cost [m/s] of debris i -> circular drift orbit (a_d, I_d) -> debris j, Eq. 11.

    ``dV_P1 + dV_A1`` (Hohmann to the drift orbit) ``+ dV_A2 + dV_P2`` (Hohmann to the
    target), each Hohmann carrying the inclination change between its two orbits.
    """
    first = hohmann(origin_a, a_drift, np.abs(np.subtract(inc_drift, origin_inc)))
    second = hohmann(a_drift, target_a, np.abs(np.subtract(target_inc, inc_drift)))
    return first + second
