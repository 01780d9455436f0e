"""Exact costs and certified lower bounds of low-thrust legs over boxes of dates.

A low-thrust leg (:mod:`~sdc_cvx.physics.low_thrust`) flying the drift speed w, leaving
at t and arriving at t + D, closes its RAAN where ``phi(w; t, D)`` is a multiple of 2 pi
(phi and its parts as :mod:`~sdc_cvx.physics.low_thrust_pieces` defines them); it is
possible when also ``D >= t_thrust(w)`` (a coast t_C = D - t_thrust >= 0) and ``D >=
T_min``.  On each *piece* of the drift band the cost is linear in w and phi has one
stationary point at most.

:func:`cost_at` is the exact cheapest leg between two dates: on each allowed piece, the
first root of ``phi = 2 pi k`` (any k: every lap count) from the cheap end, within the
radii whose thrust fits in D.

:func:`box_bound` is a lower bound of the cost over every (t, t') in a box
``[t1, t2] x [t3, t4]``.  For an interval W of speeds inside a piece, phi's range over
W and the box is enclosed by interval arithmetic: ``beta`` by its ends and its
stationary point, ``rel`` by its ends, and ``rel D - g t`` exactly over the two ends of
rel and the polygon ``{t in [t1, t2], t + D in [t3, t4], D >= max(T_min, min_W
t_thrust)}`` (:func:`_linear_range`).  If that range holds no multiple of 2 pi, no leg of the box
flies a speed of W.  That enclosure proves whole pieces empty at once.  From the cheap
end of each piece a search then moves a frontier over intervals proven empty; the cost
at the frontier is below the cost of every leg of the box on that piece (the cost rises
away from the cheap end).  Its steps use a mean-value enclosure from the frontier pos:
phi's exact range at pos over the box plus ``(w - pos)`` times the range of phi's slope
``w^6 (8 alpha w + 7 (gamma0 + q D))`` (:func:`_mean_value`), which keeps the
cancellation between the thrust's and the coast's rates that the separate enclosures
lose, so the frontier reaches the first root in a few Newton steps instead of creeping.
Both enclosures tighten as W and the box shrink, so the bound tends to the exact cost.
A box inside one already bounded (a refined date cell) starts each piece's frontier
where the cost reaches that bound: below it, the larger box's proof holds for it too.

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

from .low_thrust_pieces import PIECES, Pieces, edge_table
from .transfer import CLOSED_GAP_RAD, LegAtDates

TWO_PI = 2.0 * np.pi
ROOT_ITERATIONS = 40
"""Safeguarded Newton steps for a root of phi on a monotone sub-piece."""
SEARCH_ITERATIONS = 64
"""Steps of a bound's frontier search at most (it stops earlier once resolved)."""
BOX_CHUNK = 8192
"""Boxes bounded at once (the search's temporaries are about 16 of its arrays per box)."""
SPEED_TOL = 3e-4
"""Step of speed [m/s] below which a bound's frontier search stops: the bound is then
within about ``4 * 2.1 * SPEED_TOL`` of the best the enclosure proves (the cost's slope
in w is at most 2 + (pi/2) dI)."""
BOUND_TOL_MPS = 4 * 2.1 * SPEED_TOL
"""How far below the exact cost the bound of a box shrunk to a point may stay [m/s]."""


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
    shape, n = e.shape, e.size
    e_flat, t_flat, d_flat = e.ravel(), t.ravel(), (t_arrive - t).ravel()
    # one row per (element, piece) the rule allows, numbered piece * n + element
    table = edge_table(legs, e_flat, accel, rule, j2)
    piece, elem = np.divmod(np.flatnonzero(table.allowed[:, e_flat].ravel()), n)
    p = table.rows(piece, e_flat[elem])
    duration = d_flat[elem]
    up = p.c1 >= 0  # the cost rises with w: the cheap end is the piece's low speed
    w0, w1 = np.where(up, p.lo, p.hi), np.where(up, p.hi, p.lo)
    ok = np.flatnonzero((duration >= max(t_min, 0.0)) & (p.thrust_days(w0) <= duration + 1e-12))
    piece, elem, p, duration, w0, w1 = piece[ok], elem[ok], p.take(ok), duration[ok], w0[ok], w1[ok]
    # the radii whose thrust fits in D: from the cheap end to where t_thrust(w) = D
    with np.errstate(divide="ignore", invalid="ignore"):
        w_fit = np.where(p.c1 != 0, (duration * p.f_day - p.c0) / p.c1, w1)
    w_end = np.where(p.thrust_days(w1) <= duration, w1, np.clip(w_fit, np.minimum(w0, w1),
                                                                np.maximum(w0, w1)))  # fmt: skip
    if not len(piece):  # no piece of any element can fly
        return LegAtDates(np.full(shape, np.inf), np.full(shape, np.nan),
                          np.full(shape, np.nan), np.zeros(shape), np.zeros(shape, dtype=int))
    root = _first_root(p, t_flat[elem], duration, w0, w_end)
    found = np.isfinite(root)
    # per element, the cheapest piece's row
    cost = np.full((2 * PIECES, n), np.inf)
    cost[piece[found], elem[found]] = p.cost_of(found, root[found])
    pick = np.argmin(cost, axis=0)
    value = cost[pick, np.arange(n)]
    row_of = np.zeros((2 * PIECES, n), dtype=int)
    row_of[piece, elem] = np.arange(len(piece))
    row = row_of[pick, np.arange(n)]
    found = np.isfinite(value)
    w = np.where(found, root[row], 1.0)
    rel = p.q[row] * w**7 - p.rate_j[row]
    coast = d_flat - (p.c0[row] + p.c1[row] * w) / p.f_day
    out = LegAtDates(value, np.where(found, legs.mu / w**2, np.nan),
                     np.where(found, p.inc[row], np.nan),
                     np.where(found, np.where(rel >= 0, 1.0, -1.0), 0.0),
                     np.where(found, _laps(rel, coast), 0))  # fmt: skip
    return LegAtDates(*(v.reshape(shape) for v in out))


def _laps(rel, coast):
    """Whole relative laps [-] of a closing coast [days] beyond the smallest closing one."""
    with np.errstate(divide="ignore", invalid="ignore"):
        lap = TWO_PI / np.abs(rel)
        count = np.floor(coast / lap + 1e-9)
    return np.where(np.isfinite(count) & (count > 0), count, 0).astype(int)


def _first_root(p: Pieces, t, duration, w0, w_end):
    """First speed from ``w0`` towards ``w_end`` where phi is a multiple of 2 pi (``nan``: none),
    for 1-D pieces.

    phi has at most one stationary point on a piece: it is monotone on [w0, m] and on
    [m, w_end] (m the stationary point when it lies between), and the first multiple of
    2 pi it reaches on each is found by a safeguarded Newton iteration.
    """
    stationary = p.phi_stationary(duration)
    between = (stationary - w0) * (stationary - w_end) < 0
    middle = np.where(between, stationary, w_end)
    root = np.full(w0.shape, np.nan)
    for start, stop in ((w0, middle), (middle, w_end)):
        index = np.flatnonzero(np.isnan(root))
        if not len(index):
            break
        sub = p.take(index)
        a, b = start[index], stop[index]
        tt, dd = t[index], duration[index]
        f_a, f_b = sub.phi(a, tt, dd), sub.phi(b, tt, dd)
        near = np.rint(f_a / TWO_PI)
        at_start = np.abs(f_a - TWO_PI * near) < CLOSED_GAP_RAD
        rising = f_b >= f_a
        k = np.where(at_start, near, np.where(rising, np.ceil(f_a / TWO_PI),
                                              np.floor(f_a / TWO_PI)))  # fmt: skip
        target = TWO_PI * k
        hit = at_start | np.where(rising, target <= f_b, target >= f_b)
        w = np.where(hit, a, np.nan)
        inner = np.flatnonzero(hit & ~at_start)  # a multiple of 2 pi strictly inside
        w[inner] = _solve(sub.take(inner), tt[inner], dd[inner], a[inner], b[inner],
                          target[inner], f_a[inner], f_b[inner])  # fmt: skip
        root[index] = w
    return root


def _solve(p: Pieces, t, duration, a, b, target, f_a, f_b):
    """Root of ``phi(w) = target`` on [a, b] where phi is monotone and ``target`` lies
    between ``f_a`` and ``f_b`` (safeguarded Newton; each root stops once converged)."""
    lo, hi = a.copy(), b.copy()
    g_lo = f_a - target
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(f_b != f_a, a + (b - a) * (target - f_a) / (f_b - f_a), a)
    active = np.arange(len(w))
    for _ in range(ROOT_ITERATIONS):
        sub = p.take(active)
        x, dd = w[active], duration[active]
        g = sub.phi(x, t[active], dd) - target[active]
        same = np.sign(g) == np.sign(g_lo[active])
        lo[active], hi[active] = np.where(same, x, lo[active]), np.where(same, hi[active], x)
        g_lo[active] = np.where(same, g, g_lo[active])
        with np.errstate(divide="ignore", invalid="ignore"):
            step = x - g / sub.phi_slope(x, dd)
        l_a, h_a = lo[active], hi[active]
        inside = np.isfinite(step) & ((step - l_a) * (step - h_a) <= 0)
        x_new = np.where(inside, step, 0.5 * (l_a + h_a))
        w[active] = x_new
        moving = (np.abs(x_new - x) > 1e-12 * np.abs(x)) & (g != 0)
        active = active[moving]
        if not len(active):
            break
    return w


def box_bound(legs, e, t1, t2, t3, t4, *, accel: float, rule: str, j2: float,
              t_min: float = 0.0, cap=np.inf, floor=-np.inf):  # fmt: skip
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
    floor : float or array_like
        A lower bound already proven for each box [m/s] (that of a box holding it, say):
        no leg of the box costs less, so on each piece the search starts where the cost
        reaches it (the pieces' speeds below are proven empty).  The bound returned is at
        least ``floor``.

    Returns
    -------
    ndarray
    """
    dates = (np.asarray(v, float) for v in (t1, t2, t3, t4))
    e, t1, t2, t3, t4, cap, floor = np.broadcast_arrays(np.asarray(e), *dates,
                                                        np.asarray(cap, float),
                                                        np.asarray(floor, float))  # fmt: skip
    # a box whose floor already reaches its cap needs no search (its parent's proof holds)
    out = np.array(floor, dtype=float)
    search = np.flatnonzero(floor.ravel() < cap.ravel())
    flat = [np.ravel(v).take(search) for v in (e, t1, t2, t3, t4, cap, floor)]
    for start in range(0, search.size, BOX_CHUNK):  # in chunks: the temporaries stay small
        part = slice(start, start + BOX_CHUNK)
        out.ravel()[search[part]] = _box_bound(legs, *(v[part] for v in flat), accel, rule, j2,
                                               t_min)  # fmt: skip
    return out


def _box_bound(legs, e, t1, t2, t3, t4, cap, floor, accel, rule, j2, t_min):
    """:func:`box_bound` of a 1-D chunk of boxes.

    Works on *rows*, one per (box, piece) the rule allows, numbered ``piece * boxes + box``.
    """
    table = edge_table(legs, e, accel, rule, j2)
    n_box = len(e)
    live = np.flatnonzero(table.allowed[:, e].ravel())
    piece, box = np.divmod(live, n_box)
    rows = table.rows(piece, e[box])
    dates = tuple(v[box] for v in (t1, t2, t3, t4))
    up = rows.c1 >= 0  # the cost rises with w: the cheap end is the piece's low speed
    w0, w1 = np.where(up, rows.lo, rows.hi), np.where(up, rows.hi, rows.lo)
    # speeds that cost less than the floor hold no leg: the search starts where the cost
    # reaches it (a piece that costs less throughout: anywhere, it holds no leg)
    below = rows.dv(w0) < floor[box]
    with np.errstate(divide="ignore", invalid="ignore"):
        w_floor = np.clip((floor[box] - rows.c0) / rows.c1, rows.lo, rows.hi)
    w0 = np.where(below & ~np.isnan(w_floor), w_floor, w0)
    bound = np.full(len(live), np.inf)
    best = cap.copy()  # per box, the least bound of its settled pieces (or the cap)

    def settle(index, value):
        bound[index] = value
        np.minimum.at(best, box[index], value)

    def undecided(index, cost):
        # a piece whose cost here is already at least a settled piece's bound of the
        # same box cannot lower the box's bound: settle it there (a valid bound)
        over = cost >= best[box[index]]
        settle(index[over], cost[over])
        return ~over

    # a piece proven empty as a whole holds no leg (most pieces of most boxes)
    index = np.flatnonzero(~_empty(rows, *dates, w0, w1, t_min))
    # a piece whose cheap end may fly is exact at once
    sub, sub_dates = rows.take(index), tuple(v[index] for v in dates)
    at_end = _holds_multiple(*_at_speed(sub, sub_dates, w0[index], t_min)[:2])
    settle(index[at_end], rows.cost_of(index[at_end], w0[index[at_end]]))
    index = index[~at_end]
    index = index[undecided(index, rows.cost_of(index, w0[index]))]
    # frontier search: [w0, pos] is proven empty.  Each step proposes 0.97 of the distance
    # at which the mean-value enclosure of phi from pos (its range there, its slope's
    # range) would first reach a multiple of 2 pi at its present slope (Newton's step);
    # it moves only if the enclosure over the step proves it empty, and tries a quarter
    # of that after a miss
    pos = w0[index]
    frac = np.full(len(index), 0.97)
    sub, sub_dates, stop = rows.take(index), tuple(v[index] for v in dates), w1[index]
    for _ in range(SEARCH_ITERATIONS):
        if not len(index):
            break
        ahead = np.sign(stop - pos)
        here = _at_speed(sub, sub_dates, pos, t_min)
        proposal = np.maximum(frac * _first_reach(sub, here, pos, ahead), SPEED_TOL)
        nxt = np.where(proposal >= np.abs(stop - pos), stop, pos + ahead * proposal)
        proven = ~_holds_multiple(*_mean_value(sub, here, pos, nxt))
        pos = np.where(proven, nxt, pos)
        frac = np.where(proven, 0.97, 0.25 * frac)
        # every sub-interval up to the far end proven empty: no leg on this piece
        through = proven & (nxt == stop)
        done = through | (~proven & (proposal <= SPEED_TOL))
        settle(index[done], np.where(through[done], np.inf, sub.cost_of(done, pos[done])))
        keep = ~done
        keep[keep] = undecided(index[keep], sub.cost_of(keep, pos[keep]))
        if not keep.all():
            index, pos, frac, stop = index[keep], pos[keep], frac[keep], stop[keep]
            sub, sub_dates = sub.take(keep), tuple(v[keep] for v in sub_dates)
    if len(index):  # out of steps: the frontier is still a valid bound
        settle(index, rows.cost_of(index, pos))
    out = np.full(n_box, np.inf)
    np.minimum.at(out, box, bound)
    return np.maximum(out, floor)


def _phi_parts(p: Pieces, t1, t2, t3, t4, x, y, t_min):
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
    rel_a, rel_b = p.rel(w_lo), p.rel(w_hi)  # rel is monotone: rising or falling with w
    linear_lo, linear_hi = _linear_range(np.minimum(rel_a, rel_b), np.maximum(rel_a, rel_b), p.g,
                                         t1, t2, t3, t4, d_min)  # fmt: skip
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
    departures = (t1, kink, t_end)
    longest = [t4 - t for t in departures]
    shortest = [np.maximum(t3 - t, d_min) for t in departures]
    drift = [g * t for t in departures]
    least = [rel_lo * np.where(rel_lo < 0, d_long, d_short) - g_t
             for d_long, d_short, g_t in zip(longest, shortest, drift, strict=True)]  # fmt: skip
    most = [rel_hi * np.where(rel_hi >= 0, d_long, d_short) - g_t
            for d_long, d_short, g_t in zip(longest, shortest, drift, strict=True)]  # fmt: skip
    return (np.where(feasible, np.minimum(np.minimum(least[0], least[1]), least[2]), np.inf),
            np.where(feasible, np.maximum(np.maximum(most[0], most[1]), most[2]), -np.inf))


def _empty(p: Pieces, t1, t2, t3, t4, x, y, t_min):
    """True where no leg of the box flies a speed between ``x`` and ``y`` (interval proof)."""
    beta_lo, beta_hi, linear_lo, linear_hi = _phi_parts(p, t1, t2, t3, t4, x, y, t_min)
    return ~_holds_multiple(beta_lo + linear_lo, beta_hi + linear_hi)


def _holds_multiple(lo, hi):
    """True where ``[lo, hi]`` [rad] may hold a multiple of 2 pi (within CLOSED_GAP_RAD);
    ``lo > hi`` is an empty range (no leg), which holds none."""
    return (lo <= hi) & (np.floor((hi + CLOSED_GAP_RAD) / TWO_PI)
                         >= np.ceil((lo - CLOSED_GAP_RAD) / TWO_PI))  # fmt: skip


class _AtSpeed(NamedTuple):
    """phi at one speed w over a box: its exact range [rad] (``lo > hi``: no leg of the
    box flies w), and the range of the durations [days] of the legs that may fly there."""

    lo: np.ndarray
    hi: np.ndarray
    d_lo: np.ndarray
    d_hi: np.ndarray


def _at_speed(p: Pieces, dates, w, t_min) -> _AtSpeed:
    """phi's exact range at speed ``w`` [m/s] over the box ``dates`` (:class:`_AtSpeed`).

    The legs that may fly w take D >= d_min = max(T_min, t_thrust(w)); their durations
    lie in ``[max(t3 - min(t2, t4 - d_min), d_min), t4 - t1]``.
    """
    t1, t2, t3, t4 = dates
    d_min = np.maximum(max(t_min, 0.0), p.thrust_days(w))
    rel = p.rel(w)
    lo, hi = _linear_range(rel, rel, p.g, t1, t2, t3, t4, d_min)
    beta = p.beta(w) - p.gap0
    return _AtSpeed(beta + lo, beta + hi, np.maximum(t3 - np.minimum(t2, t4 - d_min), d_min),
                    t4 - t1)  # fmt: skip


def _slope_range(p: Pieces, w_a, w_b, d_lo, d_hi):
    """Range [rad / (m/s)] of phi's slope in w, ``w^6 (8 alpha w + 7 (gamma0 + q D))``,
    over speeds between ``w_a`` and ``w_b`` and durations in ``[d_lo, d_hi]``.

    The bracket is linear in w and D (its range: its corners), ``w^6 > 0`` monotone.
    """
    w_lo, w_hi = np.minimum(w_a, w_b), np.maximum(w_a, w_b)
    a_lo, a_hi = 8.0 * p.alpha * w_lo, 8.0 * p.alpha * w_hi
    q_lo, q_hi = 7.0 * p.q * d_lo, 7.0 * p.q * d_hi
    rest = 7.0 * p.gamma0
    low = np.minimum(a_lo, a_hi) + np.minimum(q_lo, q_hi) + rest
    high = np.maximum(a_lo, a_hi) + np.maximum(q_lo, q_hi) + rest
    w3_lo, w3_hi = w_lo * w_lo * w_lo, w_hi * w_hi * w_hi
    w6_lo, w6_hi = w3_lo * w3_lo, w3_hi * w3_hi
    return (low * np.where(low < 0, w6_hi, w6_lo), high * np.where(high > 0, w6_hi, w6_lo))


def _mean_value(p: Pieces, here: _AtSpeed, pos, nxt):
    """Mean-value enclosure [rad] of phi over speeds between ``pos`` and ``nxt`` and the
    box: its range at ``pos`` plus ``(w - pos)`` times its slope's range.

    For each leg (t, D), ``phi(w) = phi(pos) + (w - pos) phi'(xi)`` with xi between (phi
    is smooth on a piece).  ``pos`` must be the cheaper end (the search moves away from
    the cheap end): its thrust is the shortest, so every leg that may fly a speed of the
    step may fly ``pos`` too and is in ``here``.  Unlike the parts' separate enclosures
    (:func:`_empty`), it keeps the cancellation between the thrust's and the coast's
    rates, so the frontier reaches the bound in a few steps.
    """
    m_lo, m_hi = _slope_range(p, pos, nxt, here.d_lo, here.d_hi)
    step = nxt - pos
    lo_step, hi_step = step * m_lo, step * m_hi
    return (here.lo + np.minimum(0.0, np.minimum(lo_step, hi_step)),
            here.hi + np.maximum(0.0, np.maximum(lo_step, hi_step)))


def _first_reach(p: Pieces, here: _AtSpeed, pos, ahead):
    """Distance [m/s] from ``pos`` (towards ``ahead``) at which the mean-value enclosure
    (:func:`_mean_value`) would first touch a multiple of 2 pi if phi's slope kept its
    range at ``pos`` (``inf``: never)."""
    m_lo, m_hi = _slope_range(p, pos, pos, here.d_lo, here.d_hi)
    rising = np.maximum(np.where(ahead > 0, m_hi, -m_lo), 0.0)
    falling = np.maximum(np.where(ahead > 0, -m_lo, m_hi), 0.0)
    lo, hi = here.lo, here.hi
    with np.errstate(invalid="ignore", divide="ignore"):
        # the proof counts a multiple within CLOSED_GAP_RAD of the enclosure as reached
        below = np.maximum(lo - TWO_PI * np.floor(lo / TWO_PI) - CLOSED_GAP_RAD, 0.0)
        above = np.maximum(TWO_PI * np.ceil(hi / TWO_PI) - hi - CLOSED_GAP_RAD, 0.0)
        reach = np.minimum(np.where(falling > 0, below / falling, np.inf),
                           np.where(rising > 0, above / rising, np.inf))  # fmt: skip
    return np.where(np.isnan(reach) | ~(lo <= hi), np.inf, reach)
