"""Exact costs and certified lower bounds of low-thrust legs over boxes of dates.

The low-thrust leg (:mod:`~sdc_cvx.physics.low_thrust`) leaving at date t and arriving
at t' = t + D flies a drift radius a_d; write it as the circular speed ``w = V(a_d)``.
Its RAAN closes when

    phi(w; t, D) = beta(w) + rel(w) D - g t - G0  is a multiple of 2 pi,

with ``rel(w) = Omega_dot(w, I_d) - Omega_dot_j`` (the coast's relative rate),
``beta(w) = dOmega_thrust(w) - Omega_dot(w, I_d) t_thrust(w)``, ``g = Omega_dot_j -
Omega_dot_i`` and ``G0 = Omega_j(0) - Omega_i(0)``: the vehicle's RAAN turned over the
leg minus the target's, ``Omega_j(t + D) - Omega_i(t)``.  The leg is possible when
also ``D >= t_thrust(w)`` (a coast t_C = D - t_thrust >= 0) and ``D >= T_min``.

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

:func:`cost_at` is the exact cheapest leg between two dates: on each allowed piece, the
first root of ``phi = 2 pi k`` (any k: every lap count) from the cheap end, within the
radii whose thrust fits in D.

:func:`box_bound` is a lower bound of the cost over every (t, t') in a box
``[t1, t2] x [t3, t4]``.  For an interval W of speeds inside a piece, phi's range over
W and the box is enclosed by interval arithmetic: ``beta`` by its ends and its
stationary point, ``rel`` by its ends, and ``rel D - g t`` (bilinear) by the vertices
of the polygon ``{t in [t1, t2], t + D in [t3, t4], D >= max(T_min, min_W t_thrust)}``
times the two ends of rel.  If that range holds no multiple of 2 pi, no leg of the box
flies a speed of W.  From the cheap end of each piece an exponential search moves a
frontier over intervals so proven empty; the cost at the frontier is then below the
cost of every leg of the box on that piece (the cost rises away from the cheap end).
The enclosure tightens as W and the box shrink, so the bound tends to the exact cost.

Dates are in days after t0, rates in rad/day, speeds in m/s, costs in m/s.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
.. [2] R. E. Moore, R. B. Kearfott and M. J. Cloud, "Introduction to Interval
   Analysis", SIAM, 2009 (range enclosures).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .orbits import R_EARTH, SECONDS_PER_DAY, circular_speed
from .transfer import CLOSED_GAP_RAD, LegAtDates

TWO_PI = 2.0 * np.pi
PIECES = 4
"""Pieces of the drift band per inclination: split at V_i, V_j and the asymptote."""
ROOT_ITERATIONS = 40
"""Safeguarded Newton steps for a root of phi on a monotone sub-piece."""
SEARCH_ITERATIONS = 64
"""Steps of a bound's frontier search at most (it stops earlier once resolved)."""
BOX_CHUNK = 8192
"""Boxes bounded at once (the search's temporaries are about 16 of its arrays per box)."""
SPEED_TOL = 1e-3
"""Step of speed [m/s] below which a bound's frontier search stops: the bound is then
within about ``4 * 2.1 * SPEED_TOL`` of the best the enclosure proves (the cost's slope
in w is at most 2 + (pi/2) dI)."""
BOUND_TOL_MPS = 4 * 2.1 * SPEED_TOL
"""How far below the exact cost the bound of a box shrunk to a point may stay [m/s]."""


def _pow7(w):
    """``w ** 7`` by three products (a float power is several times slower)."""
    w3 = w * w * w
    return w3 * w3 * w


class _Pieces(NamedTuple):
    """Per (choice, piece, element): the piece's ends and the coefficients on it.

    Arrays are shaped (2 * PIECES, *S): the drift inclination choice (0: origin's,
    1: target's) times the piece, for elements S.  On a piece ``beta(w) = p0 + alpha
    w^8 + gamma0 w^7`` with ``alpha = p1 - q c1 / f`` and ``gamma0 = -q c0 / f``.
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
        return self.q * _pow7(w) - self.rate_j

    def beta(self, w):
        """RAAN the thrust turns minus the coast's rate times the thrust time [rad]."""
        return self.p0 + _pow7(w) * (self.alpha * w + self.gamma0)

    def beta_stationary(self):
        """Speed where beta is stationary (``nan`` if none): ``-7 gamma0 / (8 alpha)``."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.alpha != 0, -7.0 * self.gamma0 / (8.0 * self.alpha), np.nan)

    def phi(self, w, t, duration):
        """The closure residual [rad]: a multiple of 2 pi where the leg closes."""
        return (self.p0 + _pow7(w) * (self.alpha * w + self.gamma0 + self.q * duration)
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
        """The rows at a flat ``index`` (every field raveled first)."""
        fields = [np.ravel(v)[index] for v in self[:-1]]
        return _Pieces(*fields, self.f_day)


def _pieces(legs, e, accel: float, rule: str, j2: float, shape) -> _Pieces:
    """Pieces of the drift band of edges ``e`` for both drift inclinations, shaped ``shape``.

    Computed once per distinct edge (a call usually holds a few edges and many dates),
    then spread to the elements.
    """
    unique, inverse = np.unique(np.broadcast_to(np.asarray(e), shape), return_inverse=True)
    per_edge = _edge_pieces(legs, unique, accel, rule, j2)
    index = inverse.reshape(shape)
    return _Pieces(*(v[:, index] for v in per_edge[:-1]), per_edge.f_day)


def _edge_pieces(legs, e, accel: float, rule: str, j2: float) -> _Pieces:
    """:func:`_pieces` of the edges ``e`` (1-D), fields shaped (2 * PIECES, len(e))."""
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
    fields = {name: [] for name in _Pieces._fields[:-1]}
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
    return _Pieces(*(np.stack(v) for v in fields.values()), f_day)


def cost_at(legs, e, t, t_arrive, *, accel: float, rule: str, j2: float,
            t_min: float = 0.0) -> LegAtDates:  # fmt: skip
    """Exact cheapest cost of low-thrust legs ``e`` leaving at ``t`` and arriving at ``t_arrive``.

    Parameters
    ----------
    legs : LegCosts
        The edges' orbits and the drift band.
    e : array_like of int
    t, t_arrive : array_like
        Departure and arrival dates [days].
    accel : float
        Thrust acceleration [m/s^2].
    rule : {"table3", "free"}
    j2 : float
    t_min : float
        Minimum transfer duration [days].

    Returns
    -------
    LegAtDates
    """
    e, t, t_arrive = np.broadcast_arrays(np.asarray(e), np.asarray(t, float),
                                         np.asarray(t_arrive, float))  # fmt: skip
    shape = e.shape
    duration = t_arrive - t
    p = _pieces(legs, e, accel, rule, j2, shape)
    t_all = np.broadcast_to(t, p.lo.shape)
    d_all = np.broadcast_to(duration, p.lo.shape)
    up = p.c1 >= 0  # the cost rises with w: the cheap end is the piece's low speed
    w0, w1 = np.where(up, p.lo, p.hi), np.where(up, p.hi, p.lo)
    ok = p.allowed & (d_all >= max(t_min, 0.0)) & (p.thrust_days(w0) <= d_all + 1e-12)
    # the radii whose thrust fits in D: from the cheap end to where t_thrust(w) = D
    with np.errstate(divide="ignore", invalid="ignore"):
        w_fit = np.where(p.c1 != 0, (d_all * p.f_day - p.c0) / p.c1, w1)
    w_end = np.where(p.thrust_days(w1) <= d_all, w1, np.clip(w_fit, np.minimum(w0, w1),
                                                              np.maximum(w0, w1)))  # fmt: skip
    root = _first_root(p, t_all, d_all, w0, w_end, ok)
    cost = np.where(np.isfinite(root), p.dv(np.where(np.isfinite(root), root, w0)), np.inf)
    pick = (np.argmin(cost, axis=0), *np.indices(shape))
    value = cost[pick]
    found = np.isfinite(value)
    w = np.where(found, root[pick], 1.0)
    rel = p.q[pick] * w**7 - p.rate_j[pick]
    coast = duration - (p.c0[pick] + p.c1[pick] * w) / p.f_day
    return LegAtDates(value, np.where(found, legs.mu / w**2, np.nan),
                      np.where(found, p.inc[pick], np.nan),
                      np.where(found, np.where(rel >= 0, 1.0, -1.0), 0.0),
                      np.where(found, _laps(rel, coast), 0))  # fmt: skip


def _laps(rel, coast):
    """Whole relative laps [-] of a closing coast [days] beyond the smallest closing one."""
    with np.errstate(divide="ignore", invalid="ignore"):
        lap = TWO_PI / np.abs(rel)
        count = np.floor(coast / lap + 1e-9)
    return np.where(np.isfinite(count) & (count > 0), count, 0).astype(int)


def _first_root(p: _Pieces, t, duration, w0, w_end, ok):
    """First speed from ``w0`` towards ``w_end`` where phi is a multiple of 2 pi (``nan``: none).

    phi has at most one stationary point on a piece: it is monotone on [w0, m] and on
    [m, w_end] (m the stationary point when it lies between), and the first multiple of
    2 pi it reaches on each is found by a safeguarded Newton iteration.
    """
    stationary = p.phi_stationary(duration)
    between = (stationary - w0) * (stationary - w_end) < 0
    middle = np.where(between, stationary, w_end)
    root = np.full(w0.shape, np.nan)
    for start, stop in ((w0, middle), (middle, w_end)):
        todo = ok & np.isnan(root)
        if not todo.any():
            break
        index = np.flatnonzero(todo)
        sub = p.take(index)
        a, b = start.ravel()[index], stop.ravel()[index]
        tt, dd = t.ravel()[index], duration.ravel()[index]
        f_a, f_b = sub.phi(a, tt, dd), sub.phi(b, tt, dd)
        near = np.rint(f_a / TWO_PI)
        at_start = np.abs(f_a - TWO_PI * near) < CLOSED_GAP_RAD
        rising = f_b >= f_a
        k = np.where(at_start, near, np.where(rising, np.ceil(f_a / TWO_PI),
                                              np.floor(f_a / TWO_PI)))  # fmt: skip
        target = TWO_PI * k
        hit = at_start | np.where(rising, target <= f_b, target >= f_b)
        w = np.where(at_start, a, _solve(sub, tt, dd, a, b, target, f_a, f_b))
        root.ravel()[index] = np.where(hit, w, np.nan)
    return root


def _solve(p: _Pieces, t, duration, a, b, target, f_a, f_b):
    """Root of ``phi(w) = target`` on [a, b] where phi is monotone (safeguarded Newton)."""
    lo, hi = a.copy(), b.copy()
    g_lo = f_a - target
    w = np.where(f_b != f_a, a + (b - a) * (target - f_a) / np.where(f_b != f_a, f_b - f_a, 1.0),
                 a)  # fmt: skip
    for _ in range(ROOT_ITERATIONS):
        g = p.phi(w, t, duration) - target
        same = np.sign(g) == np.sign(g_lo)
        lo, hi = np.where(same, w, lo), np.where(same, hi, w)
        g_lo = np.where(same, g, g_lo)
        slope = p.phi_slope(w, duration)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = w - g / slope
        inside = np.isfinite(step) & ((step - lo) * (step - hi) <= 0)
        w_new = np.where(inside, step, 0.5 * (lo + hi))
        if np.all(np.abs(w_new - w) <= 1e-12 * np.abs(w)):
            w = w_new
            break
        w = w_new
    return w


def box_bound(legs, e, t1, t2, t3, t4, *, accel: float, rule: str, j2: float,
              t_min: float = 0.0, cap=np.inf):  # fmt: skip
    """Lower bound [m/s] of low-thrust legs ``e`` over departures in [t1, t2], arrivals in [t3, t4].

    Only (t, t') with ``t' - t >= t_min`` count.  ``inf`` where no leg of the box is
    possible.  The module docstring says why the bound is valid and tends to the exact
    cost as the box shrinks.

    Parameters
    ----------
    legs : LegCosts
    e : array_like of int
    t1, t2, t3, t4 : array_like
        Departure and arrival date ranges [days], ``t1 <= t2``, ``t3 <= t4``.
    accel : float
        Thrust acceleration [m/s^2].
    rule : {"table3", "free"}
    j2, t_min : float
    cap : float or array_like
        A box's search stops once its bound reaches ``cap`` [m/s] (a caller that prunes
        above it needs no more): the bound returned is then at least ``cap``, still valid.

    Returns
    -------
    ndarray
    """
    dates = (np.asarray(v, float) for v in (t1, t2, t3, t4))
    e, t1, t2, t3, t4, cap = np.broadcast_arrays(np.asarray(e), *dates, np.asarray(cap, float))
    out = np.empty(e.shape)
    flat = [np.ravel(v) for v in (e, t1, t2, t3, t4, cap)]
    for start in range(0, e.size, BOX_CHUNK):  # in chunks: the search's temporaries stay small
        part = slice(start, start + BOX_CHUNK)
        out.ravel()[part] = _box_bound(legs, *(v[part] for v in flat), accel, rule, j2, t_min)
    return out


def _box_bound(legs, e, t1, t2, t3, t4, cap, accel, rule, j2, t_min):
    """:func:`box_bound` of a 1-D chunk of boxes."""
    shape = e.shape
    p = _pieces(legs, e, accel, rule, j2, shape)
    box = tuple(np.broadcast_to(v, p.lo.shape).ravel() for v in (t1, t2, t3, t4))
    up = p.c1 >= 0
    w0, w1 = np.where(up, p.lo, p.hi).ravel(), np.where(up, p.hi, p.lo).ravel()
    flat = p.take(slice(None))
    n_box = int(np.prod(shape))
    bound = np.full(w0.shape, np.inf)
    best = cap.copy()  # per box, the least bound of its settled pieces (or the cap)

    def settle(index, value):
        bound[index] = value
        np.minimum.at(best, index % n_box, value)

    def undecided(index, floor):
        # a piece whose cost here is already at least a settled piece's bound of the
        # same box cannot lower the box's bound: settle it there (a valid bound)
        over = floor >= best[index % n_box]
        settle(index[over], floor[over])
        return ~over

    # a piece whose cheap end may fly is exact at once
    live = np.flatnonzero(p.allowed.ravel())
    at_end = ~_empty(flat.take(live), *(v[live] for v in box), w0[live], w0[live], t_min)
    settle(live[at_end], flat.take(live[at_end]).dv(w0[live[at_end]]))
    live = live[~at_end]
    live = live[undecided(live, flat.take(live).dv(w0[live]))]
    # a piece proven empty as a whole holds no leg
    live = live[~_empty(flat.take(live), *(v[live] for v in box), w0[live], w1[live], t_min)]
    # frontier search: [w0, pos] is proven empty.  Each step proposes 0.9 of the distance
    # at which phi's enclosure, its parts moving at their present rates, would first reach
    # a multiple of 2 pi (Newton's step); it moves only if the interval proof holds, and
    # tries a quarter of that after a miss
    pos = w0[live].copy()
    frac = np.full(len(live), 0.97)
    for _ in range(SEARCH_ITERATIONS):
        if not len(live):
            break
        sub, dates, stop = flat.take(live), tuple(v[live] for v in box), w1[live]
        ahead = np.sign(stop - pos)
        proposal = np.maximum(frac * _first_reach(sub, dates, pos, ahead, t_min), SPEED_TOL)
        nxt = np.where(proposal >= np.abs(stop - pos), stop, pos + ahead * proposal)
        proven = _empty(sub, *dates, pos, nxt, t_min)
        pos = np.where(proven, nxt, pos)
        frac = np.where(proven, 0.97, 0.25 * frac)
        # every sub-interval up to the far end proven empty: no leg on this piece
        through = proven & (nxt == stop)
        done = through | (~proven & (proposal <= SPEED_TOL))
        settle(live[done], np.where(through[done], np.inf, sub.take(done).dv(pos[done])))
        keep = ~done
        keep[keep] = undecided(live[keep], sub.take(keep).dv(pos[keep]))
        live, pos, frac = live[keep], pos[keep], frac[keep]
    if len(live):  # out of steps: the frontier is still a valid bound
        settle(live, flat.take(live).dv(pos))
    return np.min(bound.reshape(p.lo.shape), axis=0)


def _phi_parts(p: _Pieces, t1, t2, t3, t4, x, y, t_min):
    """Enclosures [rad] of phi's two parts over speeds between ``x`` and ``y`` and the box:
    ``beta(w) - G0`` and ``rel(w) D - g t`` (``(inf, -inf)`` for the second where the box
    holds no (t, D) with D >= T_min and the thrust time).

    Returns
    -------
    beta_lo, beta_hi, linear_lo, linear_hi : ndarray
    """
    w_lo, w_hi = np.minimum(x, y), np.maximum(x, y)
    d_min = np.maximum(max(t_min, 0.0), np.minimum(p.thrust_days(w_lo), p.thrust_days(w_hi)))
    ws = p.beta_stationary()
    inside = (ws > w_lo) & (ws < w_hi)
    # beta at w_lo stands in for the stationary point when it is not inside
    b_lo, b_hi = p.beta(w_lo), p.beta(w_hi)
    b_ws = p.beta(np.where(inside, ws, w_lo))
    linear_lo, linear_hi = _linear_range(p.rel(w_lo), p.rel(w_hi), p.g, t1, t2, t3, t4, d_min)
    return (np.minimum(np.minimum(b_lo, b_hi), b_ws) - p.gap0,
            np.maximum(np.maximum(b_lo, b_hi), b_ws) - p.gap0, linear_lo, linear_hi)


def _linear_range(rel_lo, rel_hi, g, t1, t2, t3, t4, d_min):
    """Exact range [rad] of ``rel D - g t`` over ``rel in [rel_lo, rel_hi]`` and the dates
    ``{t in [t1, t2], t + D in [t3, t4], D >= d_min}`` (``(inf, -inf)`` where empty).

    D >= 0, so the least value takes ``rel_lo`` and the largest ``rel_hi``.  For a rate c
    and a departure t, the best D is an end of ``[max(t3 - t, d_min), t4 - t]`` by the
    sign of c; the result is linear in t, or (through ``max``) concave for the largest and
    convex for the least value with one kink at ``t = t3 - d_min``: its extremes over
    the departures that can still arrive, ``[t1, min(t2, t4 - d_min)]``, lie at the two
    ends or at the kink.
    """
    t_end = np.minimum(t2, t4 - d_min)
    tol = 1e-12 * np.maximum(1.0, np.abs(t4) + np.abs(d_min))
    feasible = t1 <= t_end + tol
    t_end = np.maximum(t_end, t1)
    kink = np.minimum(np.maximum(t3 - d_min, t1), t_end)
    out = []
    for c, pick in ((rel_lo, np.minimum), (rel_hi, np.maximum)):
        longest = (c >= 0) if pick is np.maximum else (c < 0)
        values = [c * np.where(longest, t4 - t, np.maximum(t3 - t, d_min)) - g * t
                  for t in (t1, kink, t_end)]  # fmt: skip
        out.append(pick(pick(values[0], values[1]), values[2]))
    return np.where(feasible, out[0], np.inf), np.where(feasible, out[1], -np.inf)


def _empty(p: _Pieces, t1, t2, t3, t4, x, y, t_min):
    """True where no leg of the box flies a speed between ``x`` and ``y`` (interval proof)."""
    beta_lo, beta_hi, linear_lo, linear_hi = _phi_parts(p, t1, t2, t3, t4, x, y, t_min)
    lo, hi = beta_lo + linear_lo, beta_hi + linear_hi
    no_multiple = (np.floor((hi + CLOSED_GAP_RAD) / TWO_PI)
                   < np.ceil((lo - CLOSED_GAP_RAD) / TWO_PI))  # fmt: skip
    return ~(linear_lo <= linear_hi) | no_multiple


def _first_reach(p: _Pieces, dates, pos, ahead, t_min):
    """Distance [m/s] from ``pos`` (towards ``ahead``) at which the enclosure of phi over
    ``[pos, pos + distance]`` would first touch a multiple of 2 pi if its parts kept their
    rates at ``pos`` (``inf``: never).  Each part widens the enclosure on its own (the
    interval proof does not see that they may cancel), so their rates add; the rates are
    the parts' derivatives in w at ``pos`` (for the linear part, that of its extreme
    vertex, which moves with the thrust time where the cut D >= t_thrust binds)."""
    t1, t2, t3, t4 = dates
    w = pos
    w6 = w**6
    tau = p.thrust_days(w)
    d_min = np.maximum(max(t_min, 0.0), tau)
    d_slope = np.where(tau > t_min, p.c1 / p.f_day, 0.0)  # d(d_min)/dw
    zero = np.zeros_like(w)
    t = np.stack([t1, t1, t2, t2, t1, t2, t3 - d_min, t4 - d_min])
    d = np.stack([t3 - t1, t4 - t1, t3 - t2, t4 - t2, d_min, d_min, d_min, d_min])
    t_slope = np.stack([zero, zero, zero, zero, zero, zero, -d_slope, -d_slope])
    d_slopes = np.stack([zero, zero, zero, zero, d_slope, d_slope, d_slope, d_slope])
    tol = 1e-12 * np.maximum(1.0, np.abs(t) + np.abs(d))
    vertex = ((t >= t1 - tol) & (t <= t2 + tol) & (t + d >= t3 - tol) & (t + d <= t4 + tol)
              & (d >= d_min - tol))  # fmt: skip
    rel, rel_slope = p.rel(w), 7.0 * p.q * w6
    value = rel * d - p.g * t
    slope = rel_slope * d + rel * d_slopes - p.g * t_slope
    rows = np.arange(len(w))
    low_k = np.argmin(np.where(vertex, value, np.inf), axis=0)
    high_k = np.argmax(np.where(vertex, value, -np.inf), axis=0)
    beta = p.beta(w) - p.gap0
    beta_slope = ahead * w6 * (8.0 * p.alpha * w + 7.0 * p.gamma0)
    lo, hi = beta + value[low_k, rows], beta + value[high_k, rows]
    with np.errstate(invalid="ignore", divide="ignore"):
        rising = np.maximum(beta_slope, 0) + np.maximum(ahead * slope[high_k, rows], 0)
        falling = np.maximum(-beta_slope, 0) + np.maximum(-ahead * slope[low_k, rows], 0)
        below = lo - TWO_PI * np.floor(lo / TWO_PI)
        above = TWO_PI * np.ceil(hi / TWO_PI) - hi
        reach = np.minimum(np.where(falling > 0, below / falling, np.inf),
                           np.where(rising > 0, above / rising, np.inf))  # fmt: skip
    no_polygon = ~vertex.any(axis=0)
    return np.where(np.isnan(reach) | no_polygon, np.inf, reach)
