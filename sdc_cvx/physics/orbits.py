"""Orbit physics: J2 nodal precession, Keplerian speeds and impulsive manoeuvres.

Pure, vectorised numpy functions in SI units (m, s, rad, m/s).  Every function
broadcasts over its array arguments.  Equation numbers refer to Cerf's paper [1]_.

The gravity constants are keyword arguments with the defaults below, never
buried literals, so a study can reproduce the paper's own printed numbers
(``j2=1.086e-3``) and show the difference (docs/design.md §3).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import numpy as np

R_EARTH = 6378137.0
"""Earth equatorial radius R_T [m] (paper Part III-A)."""

MU_EARTH = 3.986e14
"""Earth gravitational parameter mu [m^3/s^2] (paper Part III-A)."""

J2 = 1.08263e-3
"""First zonal harmonic [-].  The paper prints 1.086e-3 but its C_J2 = 1.318e18 and
Table 2 follow from 1.0826e-3 (docs/design.md §3)."""

SECONDS_PER_DAY = 86400.0

DEFAULT_MAX_ECCENTRICITY = 0.05
"""Largest eccentricity kept by default: the transfer cost model treats orbits as circular
(used by the candidate selection, :mod:`sdc_cvx.inputs.selection`)."""


def raan_rate(a, e, inc, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Secular J2 precession rate of the right ascension of the ascending node (Eq. 7).

    ``dOmega/dt = -3/2 J2 n (R_T/a)^2 cos(I) / (1 - e^2)^2`` with ``n = sqrt(mu/a^3)``.

    Parameters
    ----------
    a : array_like
        Semi-major axis [m].
    e : array_like
        Eccentricity [-], in [0, 1).
    inc : array_like
        Inclination [rad].  Retrograde orbits (inc > pi/2) precess eastwards (rate > 0).
    j2, mu, r_eq : float
        Zonal coefficient [-], gravitational parameter [m^3/s^2], equatorial radius [m].

    Returns
    -------
    ndarray
        RAAN rate [rad/s].
    """
    a = np.asarray(a, dtype=float)
    n = np.sqrt(mu / a**3)
    return -1.5 * j2 * n * (r_eq / a) ** 2 * np.cos(inc) / (1.0 - np.square(e)) ** 2


def circular_a_for_raan_rate(rate, inc, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Semi-major axis of the circular orbit of inclination ``inc`` precessing at ``rate``.

    The exact inverse of Eq. 8 for a circular drift orbit (e = 0):
    ``a = (-C_J2 cos(I) / rate)^(2/7)`` with ``C_J2 = 3/2 J2 sqrt(mu) R_T^2``.

    Parameters
    ----------
    rate : array_like
        Target RAAN rate [rad/s].
    inc : array_like
        Inclination of the circular orbit [rad].

    Returns
    -------
    ndarray
        Semi-major axis [m]; ``nan`` where no orbit of that inclination has that rate
        (rate of the wrong sign for the inclination, or zero).
    """
    c_j2 = 1.5 * j2 * np.sqrt(mu) * r_eq**2
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = -c_j2 * np.cos(inc) / np.asarray(rate, dtype=float)
        return np.where((ratio > 0.0) & np.isfinite(ratio), np.abs(ratio) ** (2.0 / 7.0), np.nan)


def orbital_speed(r, a, *, mu=MU_EARTH):
    """Keplerian speed at radius ``r`` on an orbit of semi-major axis ``a`` (Eq. 12, vis-viva).

    Parameters
    ----------
    r : array_like
        Radius of the manoeuvre point [m].
    a : array_like
        Semi-major axis of the orbit [m].

    Returns
    -------
    ndarray
        Speed [m/s].
    """
    return np.sqrt(mu * (2.0 / np.asarray(r, dtype=float) - 1.0 / np.asarray(a, dtype=float)))


def circular_speed(a, *, mu=MU_EARTH):
    """Speed on a circular orbit of radius ``a`` [m] (Eq. 12 with r = a), in m/s."""
    return np.sqrt(mu / np.asarray(a, dtype=float))


def impulse(v_before, v_after, plane_change):
    """Magnitude of an impulse that changes speed and orbital plane at once (Eq. 13).

    ``|V_a - V_b| = sqrt(V_a^2 + V_b^2 - 2 V_a V_b cos(di))`` written as
    ``sqrt((V_a - V_b)^2 + 4 V_a V_b sin^2(di/2))``, which is the same quantity
    without the cancellation that makes Eq. 13 inaccurate for tiny angles.

    Parameters
    ----------
    v_before, v_after : array_like
        Speeds before and after the manoeuvre [m/s].
    plane_change : array_like
        Angle between the two velocity vectors [rad] (the inclination change
        when the manoeuvre is at a node).

    Returns
    -------
    ndarray
        Impulse magnitude [m/s].
    """
    v_before = np.asarray(v_before, dtype=float)
    v_after = np.asarray(v_after, dtype=float)
    return _impulse(v_after - v_before, v_before, v_after, plane_change)


def _impulse(speed_change, v_before, v_after, plane_change):
    """Eq. 13 from a speed change computed without cancellation by the caller."""
    half_chord = np.sin(0.5 * np.asarray(plane_change, dtype=float))
    return np.sqrt(speed_change**2 + 4.0 * v_before * v_after * half_chord**2)


def hohmann_dv(a_from, a_to, plane_change=0.0, *, mu=MU_EARTH):
    """Cost of a Hohmann transfer between circular orbits, with a combined plane change.

    Two tangential impulses at the apsides of the transfer ellipse
    ``a_t = (a_from + a_to) / 2`` (Eq. 11-12); the plane change is combined (Eq. 13)
    with the impulse at the higher radius, where the speed is lowest.  When the
    radii are equal this is a pure plane change ``2 V sin(di/2)``.  The cost is
    symmetric in its two ends.

    Parameters
    ----------
    a_from, a_to : array_like
        Radii of the initial and final circular orbits [m].
    plane_change : array_like, optional
        Inclination change [rad] (sign irrelevant).

    Returns
    -------
    ndarray
        Total impulse [m/s].
    """
    a_from = np.asarray(a_from, dtype=float)
    a_to = np.asarray(a_to, dtype=float)
    r_low = np.minimum(a_from, a_to)
    r_high = np.maximum(a_from, a_to)
    # transfer-ellipse speeds (Eq. 12) written as v_circ * sqrt(1 +/- x), and their
    # differences to the circular speeds without cancellation (exactly 0 when r_low == r_high)
    x = (r_high - r_low) / (r_high + r_low)
    v_low, v_high = circular_speed(r_low, mu=mu), circular_speed(r_high, mu=mu)
    dv_low = v_low * x / (np.sqrt(1.0 + x) + 1.0)
    speed_change_high = v_high * x / (1.0 + np.sqrt(1.0 - x))
    dv_high = _impulse(speed_change_high, v_high - speed_change_high, v_high, plane_change)
    return dv_low + dv_high


def wrap_angle(angle, direction):
    """Angle taken modulo 2 pi into ``[0, 2 pi)`` (direction > 0) or ``(-2 pi, 0]`` (direction < 0).

    (An angle within one rounding error of a multiple of 2 pi on the far side may
    come out as exactly +/- 2 pi, the nearest float to the true result.)

    Used for the RAAN gap of Eq. 10, which is taken modulo 360 deg with the sign of
    the relative drift rate so that the drift duration is positive.

    Parameters
    ----------
    angle : array_like
        Angle [rad].
    direction : array_like
        Sign of the wanted result (> 0 or < 0).

    Returns
    -------
    ndarray
        Wrapped angle [rad].
    """
    positive = np.mod(angle, 2.0 * np.pi)
    negative = np.where(positive > 0.0, positive - 2.0 * np.pi, 0.0)
    return np.where(np.asarray(direction) > 0, positive, negative)


def perigee_lowering_dv(a, perigee_radius, *, mu=MU_EARTH):
    """Impulse turning a circular orbit of radius ``a`` into an ellipse of lower perigee.

    One tangential burn at what becomes the apogee (Eq. 12): ``v_circ(a) - v(a on the
    ellipse)``.  Deorbiting a debris this way costs about 200 m/s from SSO altitudes to a
    50 km perigee (paper Part V-D); raising the perigee back costs the same again.

    Parameters
    ----------
    a : array_like
        Radius of the circular orbit [m].
    perigee_radius : array_like
        Perigee radius of the ellipse [m], at most ``a``.

    Returns
    -------
    ndarray
        Impulse [m/s].
    """
    a = np.asarray(a, dtype=float)
    a_ellipse = 0.5 * (a + np.asarray(perigee_radius, dtype=float))
    return circular_speed(a, mu=mu) - orbital_speed(a, a_ellipse, mu=mu)
