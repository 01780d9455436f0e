"""Exact costs and lower bounds of drift transfers over boxes of dates (the certified layer).

A leg i -> j that leaves at date t and arrives at date t' > t needs the drift orbit
whose J2 rate closes the RAAN gap in exactly t' - t (Eq. 10 inverted):

    rate_d = rate_j + s * mu_s(t) / (t' - t),

where ``s`` is the side of the asymptote (+1: the drift orbit precesses faster than the
target) and ``mu_s(t)`` the gap ``G(t) = Omega_j(t) - Omega_i(t)`` wrapped into
[0, 2 pi) for that side.  With the rate fixed and the drift inclination chosen
(Table 3, or either debris' inclination), the radius follows in closed form
(:func:`~sdc_cvx.orbits.circular_a_for_raan_rate`), and so does the cost (Eq. 11-13).
:func:`leg_cost_at` is that exact cost for given dates.

:func:`leg_box_bound` is a lower bound of the same cost over every (t, t') in a box
``[t1, t2] x [t3, t4]`` with ``t' - t >= T_min``.  Between two wraps of the gap
``mu_s`` is linear in t, so ``mu_s(t) / (t' - t)`` is linear-fractional: over the
polygon (box cut by ``t' - t >= T_min``) its range is spanned by the polygon's
vertices.  That range of drift rates is an interval of drift radii for each
inclination, and the minimum of the cost over an interval is exact
(:class:`LegCosts`): the ends, the kinks of the cost at the two debris radii and its
interior local minima, found once per edge.  So the bound is never above the true
cost of any leg in the box, and it tends to the true cost as the box shrinks.

Dates are in days after t0, rates in rad/day, radii in m, costs in m/s.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from . import eccentricity
from .leg_minima import scanned_minimisers
from .model_protocol import TransferModel
from .orbits import MU_EARTH, SECONDS_PER_DAY, circular_a_for_raan_rate, raan_rate
from .transfer import (
    CLOSED_GAP_RAD,
    LegAtDates,
    NodeOrbits,
    cheapest_transfer,
    duration_window_interval,
    raan_gap,
    transfer_duration,
    transfer_dv,
)

TWO_PI = 2.0 * np.pi
INCLINATION_RULES = ("table3", "free")


@dataclass(frozen=True)
class LegCosts:
    """Transfer cost of every edge as a function of the drift radius, per drift inclination.

    ``cost(e, c, a)`` is Eq. 11-13 for edge ``e`` with the drift inclination of its
    origin (``c = 0``) or of its target (``c = 1``) and drift radius ``a`` [m].
    ``minimum_on(e, c, lo, hi)`` is its exact minimum over ``[lo, hi]``: the minimum
    of the two ends and of the points in ``candidates`` that lie inside (the kinks at
    the two debris radii and the interior local minima).

    Attributes
    ----------
    origin, target : NodeOrbits
        Orbits of the edges' ends, shape (E,); rates in rad/s as everywhere.
    a_low, a_high : float
        Drift radius bounds [m].
    candidates : ndarray
        Shape (E, 2, K): radii where the cost may have a local minimum inside the band
        (``nan`` padding).
    candidate_cost : ndarray
        Shape (E, 2, K): the cost there (``inf`` padding).
    """

    origin: NodeOrbits
    target: NodeOrbits
    a_low: float
    a_high: float
    candidates: np.ndarray
    candidate_cost: np.ndarray
    mu: float = MU_EARTH
    model: TransferModel = field(default_factory=lambda: IMPULSIVE)
    memo: dict = field(default_factory=dict, repr=False, compare=False)
    """What a transfer model derives once per edge of this table and keeps (its own keys)."""
    eccentricity: tuple | None = None
    """``(origin, target)`` :class:`~sdc_cvx.physics.eccentricity.Eccentricities` of the
    edges: the impulsive leg's cost then prices the eccentricity it must change (issue 46);
    None, the paper's circular leg."""

    @classmethod
    def build(cls, origin: NodeOrbits, target: NodeOrbits, a_low: float, a_high: float, *,
              mu: float = MU_EARTH, chunk: int = 2048, model=None,
              on_chunk: Callable[[int, int], None] | None = None,
              eccentricity: tuple | None = None) -> LegCosts:  # fmt: skip
        """Scan every edge's cost over the band and keep its possible minimisers.

        ``model`` is the transfer model (:mod:`~sdc_cvx.physics.models`; default the
        impulsive drift leg).  ``on_chunk(done, total)`` is called after each ``chunk``
        of edges (the longest step of a large catalog's setup: a clock and a fraction
        done); it may raise to stop the build.  ``eccentricity``: the edges' ends'
        :class:`~sdc_cvx.physics.eccentricity.Eccentricities` (attribute of the same name).
        """
        model = IMPULSIVE if model is None else model
        count = len(origin.a)
        candidates = scanned_minimisers(origin, target, a_low, a_high, mu, model, chunk=chunk,
                                        on_chunk=on_chunk)  # fmt: skip
        self = cls(origin, target, float(a_low), float(a_high), candidates,
                   np.empty(0), mu, model, eccentricity=eccentricity)  # fmt: skip
        edges = np.arange(count)[:, None, None]
        choice = np.arange(2)[None, :, None]
        cost = self.cost(edges, choice, np.where(np.isnan(candidates), a_low, candidates))
        object.__setattr__(self, "candidate_cost", np.where(np.isnan(candidates), np.inf, cost))
        return self

    def __getstate__(self):
        """Pickled without the memo (a worker derives again what it needs)."""
        return {**self.__dict__, "memo": {}}

    def inclination(self, e, c):
        """Drift inclination [rad] of choice ``c`` (0: origin's, 1: target's) for edge ``e``."""
        return np.where(np.asarray(c) == 0, self.origin.inc[e], self.target.inc[e])

    def cost(self, e, c, a):
        """Transfer cost [m/s] of edge ``e``, inclination choice ``c``, drift radius ``a`` [m]."""
        o, t = self.origin, self.target
        return self.model.leg_dv(o.a[e], o.inc[e], t.a[e], t.inc[e], a, self.inclination(e, c),
                                 mu=self.mu)  # fmt: skip

    def minimum_on(self, e, c, lo, hi):
        """Exact minimum [m/s] of the cost over drift radii ``[lo, hi]`` (``inf`` if empty).

        Returns
        -------
        value, argmin : ndarray
            The minimum and a radius [m] where it is reached (``nan`` if empty).
        """
        e, c = np.asarray(e), np.asarray(c)  # not broadcast: an edge's constants once
        shape = np.broadcast_shapes(e.shape, c.shape, np.shape(lo), np.shape(hi))
        lo, hi = np.broadcast_to(lo, shape), np.broadcast_to(hi, shape)
        empty = ~(lo <= hi)
        lo_s, hi_s = np.where(empty, self.a_low, lo), np.where(empty, self.a_low, hi)
        f_lo, f_hi = self.cost(e, c, lo_s), self.cost(e, c, hi_s)
        points = np.broadcast_to(self.candidates[e, c], (*shape, self.candidates.shape[-1]))
        inside = (points >= lo_s[..., None]) & (points <= hi_s[..., None])
        f_in = np.where(inside, self.candidate_cost[e, c], np.inf)
        k = np.argmin(f_in, axis=-1)
        f_best_in = np.take_along_axis(f_in, k[..., None], axis=-1)[..., 0]
        a_best_in = np.take_along_axis(points, k[..., None], axis=-1)[..., 0]
        value = np.minimum(np.minimum(f_lo, f_hi), f_best_in)
        argmin = np.where(f_best_in <= np.minimum(f_lo, f_hi), a_best_in,
                          np.where(f_lo <= f_hi, lo_s, hi_s))  # fmt: skip
        return np.where(empty, np.inf, value), np.where(empty, np.nan, argmin)

    def floor(self, e):
        """Cheapest transfer [m/s] of edges ``e`` at any date, either inclination, any radius."""
        return np.minimum(*(self.minimum_on(e, c, self.a_low, self.a_high)[0] for c in (0, 1)))

    def cost_at(self, e, t, t_arrive, *, rule: str, j2: float, t_min: float = 0.0) -> LegAtDates:
        """Exact cheapest leg of edges ``e`` between dates [days], in this table's model."""
        return self.model.cost_at(self, e, t, t_arrive, rule=rule, j2=j2, t_min=t_min)

    def box_bound(self, e, t1, t2, t3, t4, *, rule: str, j2: float, t_min: float = 0.0,
                  cap=np.inf, floor=-np.inf):  # fmt: skip
        """Lower bound [m/s] of edges ``e`` over boxes of dates [days], in this table's model.

        A model may stop refining a box's bound once it reaches ``cap`` [m/s] (the value
        returned is then at least ``cap``, and still a valid bound), and may start from
        ``floor`` [m/s], a bound already proven for the box (that of a box holding it).
        """
        return self.model.box_bound(self, e, t1, t2, t3, t4, rule=rule, j2=j2, t_min=t_min,
                                    cap=cap, floor=floor)  # fmt: skip

    def special_dates(self, e: int, start: float, stop: float) -> np.ndarray:
        """Dates in [start, stop] [days] a schedule of edge ``e`` may need exactly."""
        return self.model.special_dates(self, e, start, stop)


def _rates_per_day(orbits: NodeOrbits):
    return orbits.rate * SECONDS_PER_DAY


def allowed_choices(legs: LegCosts, e, side, rule: str):
    """Inclination choices (0: origin's, 1: target's) allowed on ``side`` for edges ``e``.

    ``table3``: the larger inclination where the drift precesses faster than the target
    (side +1), the smaller where it does not (side -1): one choice per side.  ``free``:
    both.  Returns a list of arrays of choices (each shaped like ``e``).
    """
    if rule == "free":
        return [np.zeros_like(e), np.ones_like(e)]
    larger_is_target = legs.target.inc[e] > legs.origin.inc[e]
    pick_target = larger_is_target if side > 0 else ~larger_is_target
    return [pick_target.astype(int)]


def wrapped_gap(legs: LegCosts, e, t, side):
    """RAAN gap mu_s(t) >= 0 [rad] that a drift on ``side`` must close, leaving at ``t`` [days]."""
    gap = legs.target.raan[e] - legs.origin.raan[e] + (
        _rates_per_day(legs.target)[e] - _rates_per_day(legs.origin)[e]) * t  # fmt: skip
    positive = np.mod(gap, TWO_PI)
    return positive if side > 0 else np.mod(TWO_PI - positive, TWO_PI)


def radius_interval(legs: LegCosts, e, c, rate_lo, rate_hi, *, j2):
    """Drift radii [m] in the band whose rate [rad/day] lies in ``[rate_lo, rate_hi]``.

    The rate of a circular orbit of fixed inclination is monotonic in its radius, so the
    set is an interval; ``(nan, nan)`` where it is empty.
    """
    inc = legs.inclination(e, c)
    r_low = raan_rate(legs.a_low, 0.0, inc, j2=j2, mu=legs.mu) * SECONDS_PER_DAY
    r_high = raan_rate(legs.a_high, 0.0, inc, j2=j2, mu=legs.mu) * SECONDS_PER_DAY
    reach_lo, reach_hi = np.minimum(r_low, r_high), np.maximum(r_low, r_high)
    lo, hi = np.maximum(rate_lo, reach_lo), np.minimum(rate_hi, reach_hi)
    empty = ~(lo <= hi)
    with np.errstate(invalid="ignore", divide="ignore"):
        a1 = circular_a_for_raan_rate(lo / SECONDS_PER_DAY, inc, j2=j2, mu=legs.mu)
        a2 = circular_a_for_raan_rate(hi / SECONDS_PER_DAY, inc, j2=j2, mu=legs.mu)
    a1 = np.where(np.isnan(a1), np.where(lo == r_low, legs.a_low, legs.a_high), a1)
    a2 = np.where(np.isnan(a2), np.where(hi == r_low, legs.a_low, legs.a_high), a2)
    polar = r_low == r_high  # cos I = 0: every radius has the rate 0
    a1, a2 = np.where(polar, legs.a_low, a1), np.where(polar, legs.a_high, a2)
    a_lo = np.clip(np.minimum(a1, a2), legs.a_low, legs.a_high)
    a_hi = np.clip(np.maximum(a1, a2), legs.a_low, legs.a_high)
    return np.where(empty, np.nan, a_lo), np.where(empty, np.nan, a_hi)


def leg_cost_at(legs: LegCosts, e, t, t_arrive, *, rule: str, j2: float, t_min: float = 0.0):
    """Exact cheapest cost [m/s] of edge ``e`` leaving at ``t`` and arriving at ``t_arrive`` [days].

    The drift rate is fixed by the dates (Eq. 10 inverted) on each side; the cost is the
    cheaper allowed inclination whose radius lies in the band.  A leg of zero duration
    is possible only where the RAANs coincide at ``t`` (within 1e-9 rad): any drift
    radius then works and the cost is the cheapest one.

    Returns
    -------
    LegAtDates
        ``inf`` / ``nan`` / ``nan`` / 0 where no drift orbit of the band does it; no
        extra laps (the drift rate closes the gap's first wrap).
    """
    e, t, t_arrive = np.broadcast_arrays(np.asarray(e), np.asarray(t, float),
                                         np.asarray(t_arrive, float))  # fmt: skip
    best = np.full(e.shape, np.inf)
    best_a, best_inc, best_side = (
        np.full(e.shape, np.nan),
        np.full(e.shape, np.nan),
        np.zeros(e.shape),
    )
    duration = t_arrive - t
    ok = duration >= max(t_min, 0.0)
    rate_j = _rates_per_day(legs.target)[e]
    for side in (1.0, -1.0):
        mu = wrapped_gap(legs, e, t, side)
        closed = (mu < CLOSED_GAP_RAD) | (TWO_PI - mu < CLOSED_GAP_RAD)
        with np.errstate(divide="ignore", invalid="ignore"):
            rate = rate_j + side * mu / duration
        for c in allowed_choices(legs, e, side, rule):
            zero = closed & (duration == 0.0)
            lo, hi = radius_interval(legs, e, c, rate, rate, j2=j2)
            if zero.any():
                # a zero-length leg: any drift radius on this side of the asymptote (its rate
                # at least the target's for side +1, at most for side -1: Table 3's pairing)
                side_lo, side_hi = (rate_j, np.inf) if side > 0 else (-np.inf, rate_j)
                z_lo, z_hi = radius_interval(legs, e, c, side_lo, side_hi, j2=j2)
                lo, hi = np.where(zero, z_lo, lo), np.where(zero, z_hi, hi)
            value, a = legs.minimum_on(e, c, lo, hi)
            if legs.eccentricity is not None:
                value, a = eccentricity.table_cost_at(legs, e, c, value, a, lo, hi, t,
                                                         t_arrive, j2)  # fmt: skip
            value = np.where(ok & ((duration > 0) | zero), value, np.inf)
            better = value < best
            best = np.where(better, value, best)
            best_a = np.where(better, a, best_a)
            best_inc = np.where(better, legs.inclination(e, c), best_inc)
            best_side = np.where(better, side, best_side)
    return LegAtDates(best, best_a, best_inc, best_side, np.zeros(e.shape, dtype=int))


def leg_box_bound(legs: LegCosts, e, t1, t2, t3, t4, *, rule: str, j2: float,
                  t_min: float = 0.0):  # fmt: skip
    """Lower bound [m/s] of edge ``e``'s cost over departures in [t1, t2], arrivals in [t3, t4].

    Only (t, t') with ``t' - t >= t_min`` count.  ``inf`` where no leg in the box is
    possible.  See the module docstring for why the bound is valid and exact in the limit.

    Parameters
    ----------
    legs : LegCosts
    e : array_like of int
        Edge of each box.
    t1, t2, t3, t4 : array_like
        Departure and arrival date ranges [days], ``t1 <= t2``, ``t3 <= t4``.
    rule : {"table3", "free"}
        Drift inclination rule.
    j2 : float
    t_min : float
        Minimum transfer duration T_min [days].

    Returns
    -------
    ndarray
        The bound [m/s], shaped like the broadcast inputs.
    """
    e = np.asarray(e)  # not broadcast: an edge's constants are computed once
    t1, t2, t3, t4 = np.broadcast_arrays(*(np.asarray(v, float) for v in (t1, t2, t3, t4)))
    best = np.full(np.broadcast_shapes(e.shape, t1.shape), np.inf)
    rate_rel_o = _rates_per_day(legs.target)[e] - _rates_per_day(legs.origin)[e]
    rate_j = _rates_per_day(legs.target)[e]
    gap0 = legs.target.raan[e] - legs.origin.raan[e]
    g1, g2 = gap0 + rate_rel_o * t1, gap0 + rate_rel_o * t2
    for side in (1.0, -1.0):
        # pieces of [t1, t2] between wraps of the gap for this side: on piece p the gap to
        # close is s * (G(t) - 2 pi m) with m = floor(G / 2 pi) (+1 for s = -1) constant
        signed1, signed2 = side * g1, side * g2
        k_first = np.floor(np.minimum(signed1, signed2) / TWO_PI)
        k_last = np.floor(np.maximum(signed1, signed2) / TWO_PI)
        pieces = int(np.max(k_last - k_first)) + 1 if best.size else 0
        for p in range(pieces):
            k = k_first + p
            valid = k <= k_last
            # dates where side * G(t) = 2 pi k and 2 pi (k + 1), clipped to [t1, t2]
            slope = side * rate_rel_o
            with np.errstate(divide="ignore", invalid="ignore"):
                ta = np.where(slope != 0, (TWO_PI * k - side * gap0) / slope, -np.inf)
                tb = np.where(slope != 0, (TWO_PI * (k + 1) - side * gap0) / slope, np.inf)
            lo_t, hi_t = np.minimum(ta, tb), np.maximum(ta, tb)
            pa, pb = np.maximum(t1, lo_t), np.minimum(t2, hi_t)
            valid &= pa <= pb

            def gap_on_piece(t, k=k, side=side):
                return side * (gap0 + rate_rel_o * t) - TWO_PI * k

            rho_lo, rho_hi, feasible = _ratio_range(gap_on_piece, pa, pb, t3, t4, t_min)
            feasible &= valid
            for c in allowed_choices(legs, e, side, rule):
                r1, r2 = rate_j + side * rho_lo, rate_j + side * rho_hi
                lo, hi = radius_interval(legs, e, c, np.minimum(r1, r2), np.maximum(r1, r2),
                                         j2=j2)  # fmt: skip
                if legs.eccentricity is None:
                    value, _ = legs.minimum_on(e, c, lo, hi)
                else:
                    value = eccentricity.table_box_bound(legs, e, c, lo, hi, pa, pb, t3, t4, j2,
                                                         t_min)  # fmt: skip
                best = np.where(feasible, np.minimum(best, value), best)
    return best


def _ratio_range(gap_on_piece, pa, pb, t3, t4, t_min):
    """Range of ``gap(t) / (t' - t)`` over t in [pa, pb], t' in [t3, t4], t' - t >= t_min.

    The ratio is linear-fractional, so its extremes are at the polygon's vertices: the
    box corners that satisfy the cut and the cut line's crossings with the box edges.
    A vertex with t' = t gives +inf (or the whole range [0, inf) if the gap is 0 there).
    """
    # the vertices' departure dates (the box's two, and the cut line's at t3 and t4), and
    # the gap at each, once
    starts = (pa, pb, t3 - t_min, t4 - t_min)
    gaps = [np.maximum(gap_on_piece(np.clip(t, pa, pb)), 0.0) for t in starts]
    # the box corners, then the cut line t' = t + t_min crossing the four box edges
    vertices = ((0, t3), (0, t4), (1, t3), (1, t4), (0, pa + t_min), (1, pb + t_min),
                (2, t3), (3, t4))  # fmt: skip
    low, high = np.inf, -np.inf
    feasible = False
    for start, tp in vertices:
        t, gap = starts[start], gaps[start]
        tol = 1e-12 * np.maximum(1.0, np.abs(tp))
        inside = ((t >= pa - tol) & (t <= pb + tol) & (tp >= t3 - tol) & (tp <= t4 + tol)
                  & (tp - t >= t_min - tol))  # fmt: skip
        denom = tp - t
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(denom > 0, gap / np.maximum(denom, 1e-300), np.inf)
        low = np.minimum(low, np.where(inside, np.where((denom <= 0) & (gap <= 0), 0.0, ratio),
                                       np.inf))  # fmt: skip
        high = np.maximum(high, np.where(inside, ratio, -np.inf))
        feasible = feasible | inside
    return low, high, feasible


def crossing_dates(legs: LegCosts, e: int, start: float, stop: float) -> np.ndarray:
    """Dates in [start, stop] [days] where the RAANs of edge ``e``'s two debris coincide."""
    rel = (legs.target.rate[e] - legs.origin.rate[e]) * SECONDS_PER_DAY
    gap0 = legs.target.raan[e] - legs.origin.raan[e]
    if rel == 0.0:
        return np.empty(0)
    g1, g2 = sorted((gap0 + rel * start, gap0 + rel * stop))
    ks = np.arange(np.ceil(g1 / TWO_PI), np.floor(g2 / TWO_PI) + 1)
    return np.sort((TWO_PI * ks - gap0) / rel)


@dataclass(frozen=True)
class ImpulsiveModel:
    """The paper's impulsive drift leg (Part III): Hohmann, coast, Hohmann.

    A transfer model (:class:`~sdc_cvx.physics.model_protocol.TransferModel`): the leg's cost
    and duration (:mod:`~sdc_cvx.physics.transfer`), its exact cost between two dates
    and its bound over a box of dates (this module), the dates a schedule may need
    exactly (RAAN crossings: zero-length legs) and the pre-optimised transfer (Part IV-B).
    """

    name: ClassVar[str] = "impulsive"
    bound_tol_mps: ClassVar[float] = 0.0
    """How far below the exact cost a box shrunk to a point may still be bounded [m/s]."""

    def leg_dv(self, origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift, *,
               mu=MU_EARTH):  # fmt: skip
        """Leg ΔV [m/s] (Eq. 11-13)."""
        return transfer_dv(origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift, mu=mu)

    def leg_seconds(self, origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart,
                    *, laps=0, j2, mu=MU_EARTH):  # fmt: skip
        """Leg duration [s] leaving at ``t_depart`` [s] (Eq. 10), plus ``laps`` relative laps."""
        seconds = transfer_duration(origin, target, a_drift, inc_drift, t_depart, j2=j2, mu=mu)
        rel = np.abs(raan_rate(a_drift, 0.0, inc_drift, j2=j2, mu=mu) - target.rate)
        with np.errstate(divide="ignore", invalid="ignore"):
            return seconds + np.where(np.asarray(laps) > 0, laps * TWO_PI / rel, 0.0)

    def phase_days(self, origin_a, origin_inc, target_a, target_inc, a_drift, duration_days):
        """None to report: the leg is all coast, the impulses take no time."""
        return {}

    cost_at = staticmethod(leg_cost_at)

    def box_bound(self, legs, e, t1, t2, t3, t4, *, rule: str, j2: float, t_min: float = 0.0,
                  cap=np.inf, floor=-np.inf):  # fmt: skip
        """:func:`leg_box_bound` (exact in closed form: ``cap`` and ``floor`` save nothing)."""
        return leg_box_bound(legs, e, t1, t2, t3, t4, rule=rule, j2=j2, t_min=t_min)

    special_dates = staticmethod(crossing_dates)
    cheapest_transfer = staticmethod(cheapest_transfer)

    def closure_gap(self, origin, target, a_drift, t_depart, *, j2, mu=MU_EARTH):
        """The RAAN gap [rad] the coast must close (Eq. 10's numerator; no thrust phase)."""
        return raan_gap(origin, target, t_depart)

    def duration_window(self, origin, target, side, inc_drift, t_depart, min_seconds,
                        max_seconds, a_low, a_high, *, j2, mu=MU_EARTH):  # fmt: skip
        """Drift radii on ``side`` whose leg lasts between the bounds [s]: one interval
        (:func:`~sdc_cvx.physics.transfer.duration_window_interval`)."""
        return duration_window_interval(raan_gap(origin, target, t_depart), target.rate, side,
                                        inc_drift, min_seconds, max_seconds, a_low, a_high,
                                        j2=j2, mu=mu)  # fmt: skip

    def describe(self) -> dict:
        """The model's name and parameters, for ``solution.json``."""
        return {"transfer": self.name}


IMPULSIVE = ImpulsiveModel()
"""The impulsive drift leg, the paper's and the default transfer model."""
