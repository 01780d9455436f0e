"""Impulses as vectors: the velocity a burn gives, for a speed and an orbital plane.

The planner's impulses are magnitudes (paper Eq. 12-13); a flown plan needs vectors.  A
burn at position ``r`` can put the velocity in any plane that contains ``r``: the planes
through ``r`` are those whose unit normals are ``n(theta) = cos(theta) h + sin(theta)
(r_hat x h)`` (``h`` the present unit normal), a rotation of the present plane about
``r_hat``.  At a node of two planes the rotation reaches the other plane exactly (a plane
change at the node, Eq. 13); elsewhere :func:`plane_towards` gives the nearest plane.
The new velocity is horizontal (a burn at an apse of a Hohmann transfer, Eq. 12):
``speed * (n x r_hat)``.

Pure numpy on vectors of shape (3,); SI units (m, m/s, rad).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.4-6.5 (combined plane changes).
"""

from __future__ import annotations

import numpy as np

from .elements import rtn_basis


def _unit(vector) -> np.ndarray:
    vector = np.asarray(vector, dtype=float)
    return vector / np.linalg.norm(vector)


def _planes_through(r, v) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``r_hat``, the present unit normal ``h`` and ``r_hat x h``."""
    r_hat = _unit(r)
    h = _unit(np.cross(r, v))
    return r_hat, h, np.cross(r_hat, h)


def plane_towards(r, v, normal) -> np.ndarray:
    """Unit normal of the plane through ``r`` nearest to the plane of unit normal ``normal``.

    The rotation of the present plane about ``r_hat`` that maximises ``n . normal``; the
    plane itself when ``r`` lies on it (at a node of the two planes).
    """
    _, h, side = _planes_through(r, v)
    theta = np.arctan2(np.dot(side, normal), np.dot(h, normal))
    return np.cos(theta) * h + np.sin(theta) * side


def plane_with_inclination(r, v, pole, inc) -> np.ndarray:
    """Unit normal of the plane through ``r`` with inclination ``inc`` [rad] about ``pole``.

    Of the two such planes, the one reached by the smaller rotation; when none has that
    inclination (``r`` far from the equator), the one of nearest inclination.
    """
    _, h, side = _planes_through(r, v)
    a, b = np.dot(h, pole), np.dot(side, pole)  # n(theta) . pole = a cos + b sin
    amplitude = np.hypot(a, b)
    phase = np.arctan2(b, a)
    offset = np.arccos(np.clip(np.cos(inc) / amplitude, -1.0, 1.0))
    thetas = np.array([phase + offset, phase - offset])
    thetas = np.mod(thetas + np.pi, 2.0 * np.pi) - np.pi
    theta = thetas[np.argmin(np.abs(thetas))]
    return np.cos(theta) * h + np.sin(theta) * side


def horizontal_velocity(r, normal, speed) -> np.ndarray:
    """Velocity [m/s] of magnitude ``speed`` along ``normal x r_hat`` (no radial part)."""
    return speed * np.cross(normal, _unit(r))


def with_horizontal_speed(r, v, normal, speed) -> np.ndarray:
    """``v`` with its radial part kept and its horizontal part ``speed`` [m/s] along
    ``normal x r_hat``: a burn that changes the energy and the plane but leaves the
    radial velocity (an eccentric orbit's) alone, as a tangential impulse would."""
    r_hat = _unit(r)
    return np.dot(v, r_hat) * r_hat + horizontal_velocity(r, normal, speed)


def rtn(r, v, vector) -> np.ndarray:
    """``vector`` in the local radial, transverse, normal frame of the state (r, v)."""
    return rtn_basis(np.asarray(r, dtype=float), np.asarray(v, dtype=float)) @ vector
