"""Near-circular mean elements under secular J2, and impulses on them (a leg's guidance model).

A flown leg is planned in *mean* elements (issue 46): the short-period J2 terms averaged
out, so that a state moves by constant rates and months of drift cost one multiplication.
The state is the non-singular set of near-circular orbits (Vallado [2]_ §2.4.2, Schaub &
Junkins [3]_ §9.4.1), relative to the equator of the pole (the frame's z axis):

``y = (a, ex, ey, inc, raan, u)``: semi-major axis [m], the eccentricity vector
``e (cos omega, sin omega)`` in the node frame (along the ascending node and 90 deg after
it, in the orbit plane) [-], inclination, RAAN and the mean argument of latitude
``u = omega + M`` [rad], unwrapped (it counts the revolutions).  Arrays ``(..., 6)``.

- :func:`advance`: secular J2 (:func:`~sdc_cvx.physics.elements.secular_rates`, the
  Kozai rates of mean elements): ``raan`` and ``u`` move at their rates, the eccentricity
  vector turns at the apsidal rate ``domega/dt = 3/4 n J2 (R/p)^2 (5 cos^2 I - 1)`` (about
  3 deg/day in sun-synchronous LEO); ``rates`` multiply the three rates (1 for the
  first-order ones; a flight measures them in its force model,
  :func:`sdc_cvx.flight.rates.drift_factors`).
- :func:`apply_impulse`: an impulse of RTN components at the state's position, exact in
  the two-body sense (the state taken as osculating, the velocity changed, the elements
  recomputed).  Against a numerical J2 propagation measured by orbit averaging, a 50 m/s
  impulse so modelled is some 30 m off in mean ``a`` (the short-period terms change with
  the orbit): a leg flown from this model is re-planned after each impulse from the
  measured state (:mod:`sdc_cvx.flight.guidance`).
- :func:`state_of` / :func:`mean_of`: the Keplerian state of such elements, and back.
- :func:`stage`: :func:`advance` then :func:`apply_impulse` for one state, in scalar
  arithmetic (the leg optimiser evaluates thousands of such stages one at a time, where
  numpy's per-call overhead would be ten times the arithmetic).

All SI (m, m/s, rad, s); every function broadcasts over leading axes.

References
----------
.. [1] Y. Kozai, "The motion of a close earth satellite", Astronomical Journal 64, 367, 1959.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., Microcosm
   Press, 2013, §2.4 (non-singular elements), §9.6 (secular J2 effects).
.. [3] H. Schaub and J. L. Junkins, *Analytical Mechanics of Space Systems*, 4th ed., AIAA,
   2018, §9.4 (near-circular elements).
"""

from __future__ import annotations

import math

import numpy as np

from .elements import secular_rates
from .orbits import J2, MU_EARTH, R_EARTH

A, EX, EY, INC, RAAN, U = range(6)
"""Positions of the elements in a state vector ``y``."""
TWO_PI = 2.0 * np.pi
UNIT_RATES = (1.0, 1.0, 1.0)
"""Rate factors of the first-order model (RAAN, argument of perigee, argument of latitude)."""


def wrap(angle):
    """``angle`` [rad] in [-pi, pi)."""
    return np.mod(np.asarray(angle) + np.pi, TWO_PI) - np.pi


def _cross(a, b):
    """``a x b`` over the last axis (``np.cross`` without its axis bookkeeping)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


def _dot(a, b):
    return a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1] + a[..., 2] * b[..., 2]


KEPLER_STEPS = 4
"""Newton steps on Kepler's equation from ``E = M + e sin M``: the error falls as ``e^(2^k)``,
below 1e-16 rad after four at e = 0.1 (these are near-circular orbits)."""


def state_of(y, *, mu=MU_EARTH):
    """Position [m] and velocity [m/s] (``(..., 3)`` each) of elements ``y`` taken as
    osculating Keplerian ones (Vallado [2]_ Algorithm 10, in the near-circular elements;
    :func:`~sdc_cvx.physics.elements.elements_to_state` for any orbit)."""
    y = np.asarray(y, dtype=float)
    a, ex, ey, inc, raan, u = (y[..., k] for k in range(6))
    e = np.hypot(ex, ey)
    argp = np.arctan2(ey, ex)
    m = np.mod(u - argp, TWO_PI)
    ecc = m + e * np.sin(m)
    for _ in range(KEPLER_STEPS):
        ecc = ecc - (ecc - e * np.sin(ecc) - m) / (1.0 - e * np.cos(ecc))
    cos_e, sin_e = np.cos(ecc), np.sin(ecc)
    eta = np.sqrt(1.0 - e * e)
    x_pf, y_pf = a * (cos_e - e), a * eta * sin_e
    rate = np.sqrt(mu / a) / (1.0 - e * cos_e)
    vx_pf, vy_pf = -rate * sin_e, rate * eta * cos_e
    co, so, ci, si = np.cos(raan), np.sin(raan), np.cos(inc), np.sin(inc)
    cw, sw = np.cos(argp), np.sin(argp)
    p_hat = np.empty((*np.shape(a), 3))
    q_hat = np.empty_like(p_hat)
    p_hat[..., 0] = co * cw - so * sw * ci
    p_hat[..., 1] = so * cw + co * sw * ci
    p_hat[..., 2] = sw * si
    q_hat[..., 0] = -co * sw - so * cw * ci
    q_hat[..., 1] = -so * sw + co * cw * ci
    q_hat[..., 2] = cw * si
    r = x_pf[..., None] * p_hat + y_pf[..., None] * q_hat
    v = vx_pf[..., None] * p_hat + vy_pf[..., None] * q_hat
    return r, v


def mean_of(r, v, u_near=0.0, *, mu=MU_EARTH):
    """Elements ``y`` (``(..., 6)``) of positions ``r`` and velocities ``v`` (Keplerian).

    ``u`` is taken within pi of ``u_near`` [rad] (its revolutions counted from there), the
    RAAN in [-pi, pi); inclined orbits only (the node must exist).
    """
    r, v = np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(v, dtype=float))
    radius = np.sqrt(_dot(r, r))
    speed2 = _dot(v, v)
    h = _cross(r, v)
    h_norm = np.sqrt(_dot(h, h))
    a = 1.0 / (2.0 / radius - speed2 / mu)
    e_vec = ((speed2 - mu / radius)[..., None] * r - _dot(r, v)[..., None] * v) / mu
    inc = np.arctan2(np.hypot(h[..., 0], h[..., 1]), h[..., 2])
    raan = np.arctan2(h[..., 0], -h[..., 1])
    c_node, s_node = np.cos(raan), np.sin(raan)
    # the node (c, s, 0) and the in-plane direction 90 deg after it, h x node / |h|
    side = np.empty_like(h)
    side[..., 0] = -h[..., 2] * s_node
    side[..., 1] = h[..., 2] * c_node
    side[..., 2] = h[..., 0] * s_node - h[..., 1] * c_node
    side /= h_norm[..., None]
    ex = e_vec[..., 0] * c_node + e_vec[..., 1] * s_node
    ey = _dot(e_vec, side)
    arglat = np.arctan2(_dot(r, side), r[..., 0] * c_node + r[..., 1] * s_node)
    e, argp = np.hypot(ex, ey), np.arctan2(ey, ex)
    nu = arglat - argp
    ecc = np.arctan2(np.sqrt(np.maximum(1.0 - e * e, 0.0)) * np.sin(nu), e + np.cos(nu))
    u = argp + ecc - e * np.sin(ecc)
    u = u_near + wrap(u - u_near)
    out = np.empty((*np.shape(a), 6))
    out[..., 0], out[..., 1], out[..., 2] = a, ex, ey
    out[..., 3], out[..., 4], out[..., 5] = inc, raan, u
    return out


def rates_of(y, rates=UNIT_RATES, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Secular rates [rad/s] of RAAN, argument of perigee and mean argument of latitude of
    elements ``y`` (Kozai's first order, each times its factor in ``rates``)."""
    y = np.asarray(y, dtype=float)
    s = secular_rates(y[..., A], np.hypot(y[..., EX], y[..., EY]), y[..., INC], j2=j2, mu=mu,
                      r_eq=r_eq)  # fmt: skip
    return s.raan * rates[0], s.argp * rates[1], s.arglat * rates[2]


def advance(y, dt, rates=UNIT_RATES, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Elements ``y`` after ``dt`` [s] of secular J2 (the module docstring)."""
    y = np.asarray(y, dtype=float)
    dt = np.asarray(dt, dtype=float)
    d_raan, d_argp, d_u = rates_of(y, rates, j2=j2, mu=mu, r_eq=r_eq)
    turn = d_argp * dt
    c, s = np.cos(turn), np.sin(turn)
    out = np.array(y, copy=True)
    out[..., EX] = c * y[..., EX] - s * y[..., EY]
    out[..., EY] = s * y[..., EX] + c * y[..., EY]
    out[..., RAAN] = y[..., RAAN] + d_raan * dt
    out[..., U] = y[..., U] + d_u * dt
    return out


def rtn_vectors(r, v):
    """Radial, transverse and normal unit vectors (``(..., 3)`` each) of states."""
    r, v = np.asarray(r, dtype=float), np.asarray(v, dtype=float)
    radial = r / np.sqrt(_dot(r, r))[..., None]
    normal = _cross(r, v)
    normal /= np.sqrt(_dot(normal, normal))[..., None]
    return radial, _cross(normal, radial), normal


def apply_impulse(y, dv_rtn, *, mu=MU_EARTH):
    """Elements ``y`` after an impulse of RTN components ``dv_rtn`` [m/s] (``(..., 3)``)
    at their position: two-body exact on the elements taken as osculating ones."""
    y = np.asarray(y, dtype=float)
    dv_rtn = np.asarray(dv_rtn, dtype=float)
    r, v = state_of(y, mu=mu)
    radial, transverse, normal = rtn_vectors(r, v)
    v_new = (v + dv_rtn[..., 0:1] * radial + dv_rtn[..., 1:2] * transverse
             + dv_rtn[..., 2:3] * normal)  # fmt: skip
    out = mean_of(r, v_new, y[..., U], mu=mu)
    out[..., RAAN] = y[..., RAAN] + wrap(out[..., RAAN] - y[..., RAAN])  # its turns kept
    return out


def difference(y, y_ref):
    """``y - y_ref`` with the RAAN difference wrapped to [-pi, pi) (``u`` left unwrapped:
    its revolutions are the caller's to count)."""
    d = np.asarray(y, dtype=float) - np.asarray(y_ref, dtype=float)
    d[..., RAAN] = wrap(d[..., RAAN])
    return d


def stage(y, dt: float, dv_rtn, rates=UNIT_RATES, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """:func:`advance` by ``dt`` [s], then :func:`apply_impulse` of ``dv_rtn`` [m/s], for
    one state ``y`` (a sequence of six floats): the same arithmetic in scalar floats.

    Returns
    -------
    tuple of float
        The six elements after the impulse.
    """
    a, ex, ey, inc, raan, u = (float(value) for value in y)
    # secular J2 over dt (advance)
    eta2 = 1.0 - (ex * ex + ey * ey)
    n = math.sqrt(mu / (a * a * a))
    k = 0.75 * j2 * (r_eq / (a * eta2)) ** 2
    ci = math.cos(inc)
    argp_rate = k * n * (5.0 * ci * ci - 1.0)
    raan += -2.0 * k * n * ci * rates[0] * dt
    turn = argp_rate * rates[1] * dt
    c, s = math.cos(turn), math.sin(turn)
    ex, ey = c * ex - s * ey, s * ex + c * ey
    u += (argp_rate + n * (1.0 + k * math.sqrt(eta2) * (3.0 * ci * ci - 1.0))) * rates[2] * dt
    # the Keplerian state (state_of)
    e = math.sqrt(ex * ex + ey * ey)
    argp = math.atan2(ey, ex)
    m = (u - argp) % TWO_PI
    ecc = m + e * math.sin(m)
    for _ in range(KEPLER_STEPS):
        ecc -= (ecc - e * math.sin(ecc) - m) / (1.0 - e * math.cos(ecc))
    cos_e, sin_e = math.cos(ecc), math.sin(ecc)
    eta = math.sqrt(1.0 - e * e)
    x_pf, y_pf = a * (cos_e - e), a * eta * sin_e
    speed = math.sqrt(mu / a) / (1.0 - e * cos_e)
    vx_pf, vy_pf = -speed * sin_e, speed * eta * cos_e
    co, so, si = math.cos(raan), math.sin(raan), math.sin(inc)
    cw, sw = math.cos(argp), math.sin(argp)
    px, py, pz = co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si
    qx, qy, qz = -co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si
    rx, ry, rz = x_pf * px + y_pf * qx, x_pf * py + y_pf * qy, x_pf * pz + y_pf * qz
    vx, vy, vz = vx_pf * px + vy_pf * qx, vx_pf * py + vy_pf * qy, vx_pf * pz + vy_pf * qz
    # the impulse in the local radial, transverse, normal frame (rtn_vectors)
    radius = math.sqrt(rx * rx + ry * ry + rz * rz)
    ux, uy, uz = rx / radius, ry / radius, rz / radius
    hx, hy, hz = ry * vz - rz * vy, rz * vx - rx * vz, rx * vy - ry * vx
    h = math.sqrt(hx * hx + hy * hy + hz * hz)
    nx, ny, nz = hx / h, hy / h, hz / h
    tx, ty, tz = ny * uz - nz * uy, nz * ux - nx * uz, nx * uy - ny * ux
    d_r, d_t, d_n = (float(value) for value in dv_rtn)
    vx += d_r * ux + d_t * tx + d_n * nx
    vy += d_r * uy + d_t * ty + d_n * ny
    vz += d_r * uz + d_t * tz + d_n * nz
    # back to elements (mean_of)
    speed2 = vx * vx + vy * vy + vz * vz
    rv = rx * vx + ry * vy + rz * vz
    hx, hy, hz = ry * vz - rz * vy, rz * vx - rx * vz, rx * vy - ry * vx
    h = math.sqrt(hx * hx + hy * hy + hz * hz)
    a = 1.0 / (2.0 / radius - speed2 / mu)
    f, g = (speed2 - mu / radius) / mu, rv / mu
    evx, evy, evz = f * rx - g * vx, f * ry - g * vy, f * rz - g * vz
    inc = math.atan2(math.hypot(hx, hy), hz)
    node = math.atan2(hx, -hy)
    cn, sn = math.cos(node), math.sin(node)
    sx, sy, sz = -hz * sn / h, hz * cn / h, (hx * sn - hy * cn) / h
    ex, ey = evx * cn + evy * sn, evx * sx + evy * sy + evz * sz
    arglat = math.atan2(rx * sx + ry * sy + rz * sz, rx * cn + ry * sn)
    e, argp = math.hypot(ex, ey), math.atan2(ey, ex)
    nu = arglat - argp
    ecc = math.atan2(math.sqrt(max(1.0 - e * e, 0.0)) * math.sin(nu), e + math.cos(nu))
    u_new = argp + ecc - e * math.sin(ecc)
    u += (u_new - u + math.pi) % TWO_PI - math.pi
    raan += (node - raan + math.pi) % TWO_PI - math.pi
    return (a, ex, ey, inc, raan, u)
