"""Orbital elements: the Keplerian state conversions and the secular J2 rates of mean elements.

The planner needs only the RAAN rate (paper Eq. 7, :func:`~sdc_cvx.physics.orbits.raan_rate`);
a plan that flies also needs *where on its orbit* each debris is (issue 26): the argument
of perigee and the mean anomaly drift too.  First-order secular J2 rates of mean elements
(Vallado [2]_ Eq. 9-41; Curtis [3]_ Eq. 4.52-4.53 and Example 10.2):

- ``dOmega/dt = -3/2 n J2 (R/p)^2 cos I``
- ``domega/dt = 3/4 n J2 (R/p)^2 (5 cos^2 I - 1)``  (``= 3/4 n J2 (R/p)^2 (4 - 5 sin^2 I)``)
- ``dM/dt = n [1 + 3/4 J2 (R/p)^2 sqrt(1 - e^2) (3 cos^2 I - 1)]``

with ``n = sqrt(mu / a^3)`` and ``p = a (1 - e^2)``.  On a near-circular orbit the
argument of latitude ``u = omega + M`` (mean) is the position along the orbit and moves
at ``domega/dt + dM/dt``.

The state conversions (:func:`elements_to_state`, :func:`state_to_elements`, Vallado [2]_
Algorithms 9 and 10, Curtis [3]_ Algorithms 4.2 and 4.5) and :func:`rtn_basis` work in
any frame whose z axis is the reference pole (the Earth's rotation axis for the J2
elements); they broadcast over leading axes, vectors on the last axis (``(..., 3)``).

All angles are rad, lengths m, times s.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §2.2-2.3 (Kepler's equation), §2.5-2.6 (COE2RV, RV2COE),
   §9.6 (secular J2 effects).
.. [3] H. D. Curtis, *Orbital Mechanics for Engineering Students*, 3rd ed.,
   Butterworth-Heinemann, 2014, §4.4-4.7 and Example 10.2 (Example 12.2 in the 2nd ed.:
   the J2 rates of a 300 km x 3062 km orbit at 28 deg, -0.172 deg/h and +0.282 deg/h).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .orbits import J2, MU_EARTH, R_EARTH


class SecularRates(NamedTuple):
    """First-order secular J2 rates of mean elements [rad/s] (broadcast arrays)."""

    raan: np.ndarray
    argp: np.ndarray
    mean_anomaly: np.ndarray

    @property
    def arglat(self) -> np.ndarray:
        """Rate of the mean argument of latitude ``u = omega + M`` [rad/s]."""
        return self.argp + self.mean_anomaly


def secular_rates(a, e, inc, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH) -> SecularRates:
    """Secular J2 rates of RAAN, argument of perigee and mean anomaly (module docstring).

    Parameters
    ----------
    a : array_like
        Mean semi-major axis [m].
    e : array_like
        Mean eccentricity [-], in [0, 1).
    inc : array_like
        Mean inclination [rad].
    j2, mu, r_eq : float
        Zonal coefficient [-], gravitational parameter [m^3/s^2], equatorial radius [m].

    Returns
    -------
    SecularRates
        ``raan``, ``argp`` and ``mean_anomaly`` rates [rad/s]; the mean anomaly's
        includes the Keplerian mean motion ``n``.
    """
    a, e, inc = (np.asarray(v, dtype=float) for v in (a, e, inc))
    n = np.sqrt(mu / a**3)
    eta2 = 1.0 - np.square(e)
    k = 0.75 * j2 * (r_eq / (a * eta2)) ** 2  # 3/4 J2 (R/p)^2
    cos2 = np.square(np.cos(inc))
    return SecularRates(
        raan=-2.0 * k * n * np.cos(inc),
        argp=k * n * (5.0 * cos2 - 1.0),
        mean_anomaly=n * (1.0 + k * np.sqrt(eta2) * (3.0 * cos2 - 1.0)),
    )


class Elements(NamedTuple):
    """Osculating Keplerian elements (broadcast arrays; :func:`state_to_elements`).

    ``a`` [m], ``e`` [-], ``inc``, ``raan``, ``argp``, ``mean_anomaly`` and ``arglat``
    [rad]; the angles other than ``inc`` in [0, 2 pi).
    """

    a: np.ndarray
    e: np.ndarray
    inc: np.ndarray
    raan: np.ndarray
    argp: np.ndarray
    mean_anomaly: np.ndarray
    arglat: np.ndarray


CIRCULAR_E = 1e-12
"""Eccentricity below which :func:`state_to_elements` takes the orbit as circular
(``argp = 0``): the eccentricity vector of a circular state is round-off, about 1e-16."""


def _unit(vectors: np.ndarray) -> np.ndarray:
    return vectors / np.linalg.norm(vectors, axis=-1, keepdims=True)


def eccentric_anomaly(mean_anomaly, e, *, tol=1e-14, max_iter=50) -> np.ndarray:
    """Solve Kepler's equation ``M = E - e sin E`` for ``E`` (Newton, vectorised).

    Parameters
    ----------
    mean_anomaly : array_like
        Mean anomaly ``M`` [rad], any value (reduced to (-pi, pi] first).
    e : array_like
        Eccentricity [-], in [0, 1).
    tol : float
        Largest step [rad] accepted as converged.
    max_iter : int
        Newton steps at most (from ``E0 = M + e sin M``, about 5 below e = 0.9).

    Returns
    -------
    ndarray
        Eccentric anomaly ``E`` [rad], in (-pi, pi] plus ``M``'s whole turns.

    References
    ----------
    Vallado [2]_ Algorithm 2 (KepEqtnE).
    """
    m = np.asarray(mean_anomaly, dtype=float)
    e = np.asarray(e, dtype=float)
    turns = np.round(m / (2.0 * np.pi)) * 2.0 * np.pi
    m = m - turns
    # Newton from E0 = pi (with M's sign) converges for any M when e is large
    ecc = np.where(e > 0.8, np.pi * np.sign(m), m + e * np.sin(m))
    for _ in range(max_iter):
        step = (ecc - e * np.sin(ecc) - m) / (1.0 - e * np.cos(ecc))
        ecc = ecc - step
        if np.all(np.abs(step) < tol):
            break
    return ecc + turns


def elements_to_state(a, e, inc, raan, argp, mean_anomaly, *, mu=MU_EARTH):
    """Position and velocity from Keplerian elements (elliptic orbits).

    Parameters
    ----------
    a : array_like
        Semi-major axis [m], > 0.
    e : array_like
        Eccentricity [-], in [0, 1).
    inc, raan, argp, mean_anomaly : array_like
        Inclination, right ascension of the ascending node, argument of perigee and mean
        anomaly [rad], measured from the frame's x axis and xy plane (z: the pole).
    mu : float
        Gravitational parameter [m^3/s^2].

    Returns
    -------
    r, v : ndarray
        Position [m] and velocity [m/s], shape ``(..., 3)`` (the elements broadcast).

    References
    ----------
    Vallado [2]_ Algorithm 10 (COE2RV); Curtis [3]_ Algorithm 4.5.
    """
    a, e, inc, raan, argp, mean_anomaly = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (a, e, inc, raan, argp, mean_anomaly))
    )
    ecc = eccentric_anomaly(mean_anomaly, e)
    cos_e, sin_e = np.cos(ecc), np.sin(ecc)
    eta = np.sqrt(1.0 - e * e)
    x_pf, y_pf = a * (cos_e - e), a * eta * sin_e  # perifocal position
    rate = np.sqrt(mu / a) / (1.0 - e * cos_e)  # n a / (1 - e cos E) = sqrt(mu/a) / (...)
    vx_pf, vy_pf = -rate * sin_e, rate * eta * cos_e
    co, so, ci, si = np.cos(raan), np.sin(raan), np.cos(inc), np.sin(inc)
    cw, sw = np.cos(argp), np.sin(argp)
    p_hat = np.stack([co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si], axis=-1)
    q_hat = np.stack([-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si], axis=-1)
    r = x_pf[..., None] * p_hat + y_pf[..., None] * q_hat
    v = vx_pf[..., None] * p_hat + vy_pf[..., None] * q_hat
    return r, v


def state_to_elements(r, v, *, mu=MU_EARTH) -> Elements:
    """Osculating Keplerian elements of position and velocity (elliptic orbits).

    Parameters
    ----------
    r : array_like
        Position [m], shape ``(..., 3)``, in a frame whose z axis is the pole.
    v : array_like
        Velocity [m/s], same shape.
    mu : float
        Gravitational parameter [m^3/s^2].

    Returns
    -------
    Elements
        ``a`` [m] (from the energy; negative if hyperbolic, where the angles other than
        ``inc``, ``raan`` and ``arglat`` mean nothing), ``e``, ``inc``, ``raan``,
        ``argp``, ``mean_anomaly`` and ``arglat`` (the argument of latitude, the angle
        from the ascending node to ``r`` in the orbit plane, in the direction of motion).

    Notes
    -----
    Singular cases, handled without NaN:

    - ``e -> 0``: the perigee is undefined; ``argp`` and ``mean_anomaly`` are each
      ill-conditioned (``argp`` follows the tiny eccentricity vector) but their sum, the
      mean argument of latitude, is fine, and ``arglat`` (the true one) is well defined.
      Below ``e =`` :data:`CIRCULAR_E` (round-off), ``argp = 0`` and ``mean_anomaly``
      is the mean argument of latitude.
    - ``inc -> 0`` (or pi): the node is undefined; ``raan`` is ill-conditioned and, for
      an exactly equatorial orbit, 0 (the x axis then stands for the node, so ``arglat``
      is the true longitude).

    References
    ----------
    Vallado [2]_ Algorithm 9 (RV2COE); Curtis [3]_ Algorithm 4.2.
    """
    r = np.asarray(r, dtype=float)
    v = np.asarray(v, dtype=float)
    r, v = np.broadcast_arrays(r, v)
    rn = np.linalg.norm(r, axis=-1)
    v2 = np.sum(v * v, axis=-1)
    rv = np.sum(r * v, axis=-1)
    h = np.cross(r, v)
    hn = np.linalg.norm(h, axis=-1)
    a = 1.0 / (2.0 / rn - v2 / mu)
    e_vec = ((v2 - mu / rn)[..., None] * r - rv[..., None] * v) / mu
    e = np.linalg.norm(e_vec, axis=-1)
    h_xy = np.hypot(h[..., 0], h[..., 1])
    inc = np.arctan2(h_xy, h[..., 2])
    equatorial = h_xy <= 1e-15 * hn
    raan = np.where(equatorial, 0.0, np.arctan2(h[..., 0], -h[..., 1]))
    node = np.stack([np.cos(raan), np.sin(raan), np.zeros_like(raan)], axis=-1)
    side = np.cross(h, node) / hn[..., None]  # in-plane, 90 deg ahead of the node
    arglat = np.arctan2(np.sum(r * side, axis=-1), np.sum(r * node, axis=-1))
    argp = np.arctan2(np.sum(e_vec * side, axis=-1), np.sum(e_vec * node, axis=-1))
    argp = np.where(e > CIRCULAR_E, argp, 0.0)
    nu = arglat - argp  # true anomaly
    ecc = np.arctan2(np.sqrt(np.maximum(1.0 - e * e, 0.0)) * np.sin(nu), e + np.cos(nu))
    mean_anomaly = ecc - e * np.sin(ecc)
    turn = 2.0 * np.pi
    return Elements(
        a=a,
        e=e,
        inc=inc,
        raan=np.mod(raan, turn),
        argp=np.mod(argp, turn),
        mean_anomaly=np.mod(mean_anomaly, turn),
        arglat=np.mod(arglat, turn),
    )


def rtn_basis(r, v) -> np.ndarray:
    """The radial, transverse and normal unit vectors of an orbit (the RTN/RSW frame).

    Parameters
    ----------
    r : array_like
        Position [m], shape ``(..., 3)``.
    v : array_like
        Velocity [m/s], same shape.

    Returns
    -------
    ndarray
        Shape ``(..., 3, 3)``; rows: radial ``r/|r|``, transverse (in the orbit plane,
        perpendicular to ``r`` on the side of the motion: ``N x R``) and normal
        ``h/|h|`` (``h = r x v``).  ``basis @ x`` gives a vector's RTN components.

    References
    ----------
    Vallado [2]_ §3.3 (the RSW satellite coordinate system).
    """
    r = np.asarray(r, dtype=float)
    v = np.asarray(v, dtype=float)
    radial = _unit(r)
    normal = _unit(np.cross(r, v))
    return np.stack([radial, np.cross(normal, radial), normal], axis=-2)
