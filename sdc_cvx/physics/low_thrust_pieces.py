"""The low-thrust leg's cost and RAAN closure as closed forms on pieces of the drift band.

The low-thrust leg (:mod:`~sdc_cvx.physics.low_thrust`) leaving at date t and arriving
at t' = t + D flies a drift radius a_d; write it as the circular speed ``w = V(a_d)``.
Its RAAN closes when

    phi(w; t, D) = beta(w) + rel(w) D - g t - G0  is a multiple of 2 pi,

with ``rel(w) = Omega_dot(w, I_d) - Omega_dot_j`` (the coast's relative rate),
``beta(w) = dOmega_thrust(w) - Omega_dot(w, I_d) t_thrust(w)``, ``g = Omega_dot_j -
Omega_dot_i`` and ``G0 = Omega_j(0) - Omega_i(0)``: the vehicle's RAAN turned over the
leg minus the target's, ``Omega_j(t + D) - Omega_i(t)``.

The drift band splits into at most four *pieces* at the two debris speeds and at the
asymptote ``rel(w) = 0``.  On a piece, with the signs of ``w - V_i`` and ``w - V_j``
fixed:

- the cost is linear in w, ``dV = c0 + c1 w``, so it rises from one end of the piece
  (its *cheap end*) to the other, and ``t_thrust = dV / f`` with it;
- ``dOmega_thrust = p0 + p1 w^8`` and ``Omega_dot(w, I_d) = q w^7``, so
  ``phi = alpha w^8 + gamma(D) w^7 + const(t, D)``: one stationary point at most
  (``w^6 (8 alpha w + 7 gamma)``), so phi is monotone on at most two sub-pieces;
- the sign of rel is fixed, so Table 3 (``max(I_i, I_j)`` only where the coast
  precesses at least as fast as the target, ``min`` only where at most) allows or
  forbids the whole piece for each drift inclination.

:mod:`~sdc_cvx.physics.low_thrust_bounds` prices legs and bounds boxes of dates with them.
Dates are in days after t0, rates in rad/day, speeds in m/s, costs in m/s.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
.. [2] T. N. Edelbaum, "Propulsion requirements for controllable satellites", ARS
   Journal, 31(8), 1079-1089, 1961 (the plane change's cost, pi/2 V dI).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .orbits import R_EARTH, SECONDS_PER_DAY, circular_speed

PIECES = 4
"""Pieces of the drift band per inclination: split at V_i, V_j and the asymptote."""


def pow7(w):
    """``w ** 7`` by three products (a float power is several times slower)."""
    w3 = w * w * w
    return w3 * w3 * w


class Pieces(NamedTuple):
    """Per (choice, piece, element): the piece's ends and the coefficients on it.

    Arrays are shaped (2 * PIECES, edges) in the table of every edge
    (:func:`edge_table`): the drift inclination choice (0: origin's, 1: target's) times
    the piece; or 1-D, one per row a search works on (:meth:`rows`).  On a piece
    ``beta(w) = p0 + alpha w^8 + gamma0 w^7`` with ``alpha = p1 - q c1 / f`` and
    ``gamma0 = -q c0 / f``.
    """

    lo: np.ndarray  # piece ends [m/s]
    hi: np.ndarray
    allowed: np.ndarray  # the rule allows this inclination on this piece
    inc: np.ndarray  # drift inclination [rad]
    c0: np.ndarray  # dV = c0 + c1 w [m/s]
    c1: np.ndarray
    p0: np.ndarray  # dOmega_thrust = p0 + p1 w^8 [rad]
    alpha: np.ndarray  # beta's w^8 coefficient [rad / (m/s)^8]
    gamma0: np.ndarray  # beta's w^7 coefficient [rad / (m/s)^7]
    q: np.ndarray  # Omega_dot(w, I_d) = q w^7 [rad/day]
    rate_j: np.ndarray  # target's rate [rad/day]
    g: np.ndarray  # rate_j - rate_i [rad/day]
    gap0: np.ndarray  # Omega_j(0) - Omega_i(0) [rad]
    f_day: float  # thrust acceleration [m/s per day]

    def dv(self, w):
        return self.c0 + self.c1 * w

    def thrust_days(self, w):
        return self.dv(w) / self.f_day

    def rel(self, w):
        return self.q * pow7(w) - self.rate_j

    def beta(self, w):
        """RAAN the thrust turns minus the coast's rate times the thrust time [rad]."""
        return self.p0 + pow7(w) * (self.alpha * w + self.gamma0)

    def beta_stationary(self):
        """Speed where beta is stationary (``nan`` if none): ``-7 gamma0 / (8 alpha)``."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.alpha != 0, -7.0 * self.gamma0 / (8.0 * self.alpha), np.nan)

    def phi(self, w, t, duration):
        """The closure residual [rad]: a multiple of 2 pi where the leg closes."""
        return (self.p0 + pow7(w) * (self.alpha * w + self.gamma0 + self.q * duration)
                - self.rate_j * duration - self.g * t - self.gap0)  # fmt: skip

    def phi_stationary(self, duration):
        """Speed where phi is stationary for this duration (``nan`` if none)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.alpha != 0, -7.0 * (self.gamma0 + self.q * duration)
                            / (8.0 * self.alpha), np.nan)  # fmt: skip

    def phi_slope(self, w, duration):
        w3 = w * w * w
        return w3 * w3 * (8.0 * self.alpha * w + 7.0 * (self.gamma0 + self.q * duration))

    def take(self, index):
        """The rows at ``index`` (integers, or a mask) of 1-D pieces."""
        index = np.flatnonzero(index) if index.dtype == bool else index
        return Pieces(*(v.take(index) for v in self[:-1]), self.f_day)

    def rows(self, piece, column):
        """1-D pieces of rows ``(piece, column)`` of pieces shaped (2 * PIECES, count)."""
        flat = piece * self.lo.shape[1] + column  # the fields are C-contiguous
        return Pieces(*(v.ravel().take(flat) for v in self[:-1]), self.f_day)

    def cost_of(self, index, w):
        """The cost [m/s] of the rows at ``index`` of 1-D pieces at speeds ``w``."""
        return self.c0[index] + self.c1[index] * w


def edge_table(legs, e, accel: float, rule: str, j2: float) -> Pieces:
    """Pieces of every edge of ``legs``, fields shaped (2 * PIECES, edges), those of edges
    ``e`` filled in.

    Each edge's are computed once per cost table (kept in ``legs.memo``); rows of the
    others are left unset until asked for.
    """
    key = ("low-thrust pieces", accel, rule, j2)
    if key not in legs.memo:
        count = len(legs.origin.a)
        legs.memo[key] = (np.zeros(count, dtype=bool), Pieces(
            *(np.empty((2 * PIECES, count), dtype=bool if name == "allowed" else float)
              for name in Pieces._fields[:-1]), accel * SECONDS_PER_DAY))  # fmt: skip
    done, table = legs.memo[key]
    e = np.asarray(e)
    missing = np.unique(e[~done[e]])
    if len(missing):
        for column, value in zip(table[:-1], _edge_pieces(legs, missing, accel, rule, j2)[:-1],
                                 strict=True):  # fmt: skip
            column[:, missing] = value
        done[missing] = True
    return table


def _edge_pieces(legs, e, accel: float, rule: str, j2: float) -> Pieces:
    """Pieces of the edges ``e`` (1-D) for both drift inclinations, fields shaped
    (2 * PIECES, len(e))."""
    mu, r_eq = legs.mu, R_EARTH
    o, t = legs.origin, legs.target
    shape = e.shape
    v_i, v_j = circular_speed(o.a[e], mu=mu), circular_speed(t.a[e], mu=mu)
    inc_i, inc_j = o.inc[e], t.inc[e]
    d_inc = np.abs(inc_j - inc_i)
    delta = inc_j - inc_i
    with np.errstate(divide="ignore", invalid="ignore"):
        mean_cos = np.where(np.abs(delta) > 1e-9, (np.sin(inc_j) - np.sin(inc_i)) / delta,
                            np.cos(0.5 * (inc_i + inc_j)))  # fmt: skip
    k_i = 3.0 * j2 * r_eq**2 * np.cos(inc_i) / (16.0 * mu**3 * accel)
    k_j = 3.0 * j2 * r_eq**2 * np.cos(inc_j) / (16.0 * mu**3 * accel)
    k_plane = 0.75 * np.pi * j2 * r_eq**2 * d_inc * mean_cos / (mu**3 * accel)
    w_lo, w_hi = circular_speed(legs.a_high, mu=mu), circular_speed(legs.a_low, mu=mu)
    f_day = accel * SECONDS_PER_DAY
    rate_i, rate_j = o.rate[e] * SECONDS_PER_DAY, t.rate[e] * SECONDS_PER_DAY
    fields = {name: [] for name in Pieces._fields[:-1]}
    for inc in (inc_i, inc_j):
        q = -1.5 * j2 * r_eq**2 * np.cos(inc) / mu**3 * SECONDS_PER_DAY
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = rate_j / q
            asymptote = np.where(ratio > 0, np.abs(ratio) ** (1.0 / 7.0), np.nan)
        inner = np.stack([v_i, v_j, asymptote])
        inner = np.sort(np.where(np.isfinite(inner), np.clip(inner, w_lo, w_hi), w_hi), axis=0)
        ends = np.concatenate([np.full((1, *shape), w_lo), inner, np.full((1, *shape), w_hi)])
        is_max = inc >= np.maximum(inc_i, inc_j)
        is_min = inc <= np.minimum(inc_i, inc_j)
        for k in range(PIECES):
            lo, hi = ends[k], ends[k + 1]
            mid = 0.5 * (lo + hi)
            s_i, s_j = np.sign(mid - v_i), np.sign(mid - v_j)
            rel_sign = np.sign(q * mid**7 - rate_j)
            if rule == "free":
                allowed = np.ones(shape, dtype=bool)
            else:
                allowed = (inc_i == inc_j) | (is_max & (rel_sign >= 0)) | (is_min & (rel_sign <= 0))
            allowed = allowed & (hi > lo)
            for name, value in (("lo", lo), ("hi", hi), ("allowed", allowed), ("inc", inc),
                                ("c0", -s_i * v_i - s_j * v_j),
                                ("c1", s_i + s_j + 0.5 * np.pi * d_inc),
                                ("p0", k_i * s_i * v_i**8 + k_j * s_j * v_j**8),
                                ("alpha", -k_i * s_i - k_plane - k_j * s_j
                                 - q * (s_i + s_j + 0.5 * np.pi * d_inc) / f_day),
                                ("gamma0", q * (s_i * v_i + s_j * v_j) / f_day), ("q", q),
                                ("rate_j", rate_j), ("g", rate_j - rate_i),
                                ("gap0", t.raan[e] - o.raan[e])):  # fmt: skip
                fields[name].append(np.broadcast_to(value, shape))
    return Pieces(*(np.stack(v) for v in fields.values()), f_day)
