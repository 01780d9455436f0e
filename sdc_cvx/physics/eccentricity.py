"""The eccentricity a leg must change, priced (issue 46, item 2).

The paper's leg (Part III) joins circular orbits.  Real debris have mean eccentricity
vectors ``ē = e (cos omega, sin omega)`` in their node frames (up to 0.02 in GTOC9),
turned by J2 at the apsidal rate ``domega/dt = 3/4 n J2 (R/p)^2 (5 cos^2 I - 1)``
(about 3 deg/day in sun-synchronous LEO).  A vehicle leaving debris i at ``t_d`` with
i's vector, drifting on an orbit whose apsides turn at ``w_d`` and arriving at debris j
at ``t_a`` must change its vector by

``de_req = | ē_j(t_a) - R(w_d (t_a - t_d)) ē_i(t_d) |``

(the planes meet at the arrival, so the node frames agree there).  The transfers'
tangential impulses change it for free up to ``rho = (|a_d - a_i| + |a_j - a_d|) / a``
(two impulses half an orbit apart move ``a`` by their sum and the vector by their
difference); beyond that a change ``de`` costs ``v de / 2`` alone, but far less inside
the large burns of a plane change (second order).  The form used, which matched
independently optimised rendezvous of the same legs within a few m/s (issue 46):

``dv = sqrt(dv_paper^2 + (v/2)^2 max(de_req^2 - rho^2, 0))``,

``v`` the circular speed at the mean radius of the two debris.  It is increasing in
``dv_paper`` and ``de_req`` and decreasing in ``rho``, so a lower bound of it over a box
of dates and drift radii is the form at the least ``dv_paper``, the least ``de_req`` and
the largest ``rho`` over the box (:func:`priced_bound`).  The least ``de_req``
(:func:`required_change_bound`): each vector is a fixed part plus parts turned by
angles that lie in intervals over the box; a part of length ``L`` turned by an angle
within ``h`` of an interval's middle is within ``2 L sin(h/2)`` of the part turned by the
middle angle, so ``de_req >= |A_mid - B_mid| - r_A - r_B``, exact as the box shrinks.

SGP4's element sets add J3's long-period term to the mean vector: a constant
``-1/2 (J3/J2) (R/p) sin I`` along the node frame's y axis (the "frozen" eccentricity,
about 1e-3 in sun-synchronous LEO; Hoots & Roehrich [2]_), which J2 does not turn.  GTOC9's
debris have none (:class:`Eccentricities`).

All SI: m, m/s, rad, s (rates rad/s).

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] F. R. Hoots and R. L. Roehrich, "Spacetrack Report No. 3: Models for Propagation of
   NORAD Element Sets", 1980 (SGP4's long-period periodics, ``aycof``).
.. [3] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., Microcosm
   Press, 2013, §6.3 (the eccentricity changed by tangential impulses), §9.6 (J2 rates).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .elements import secular_rates
from .orbits import J2, MU_EARTH, R_EARTH
from .orbits import SECONDS_PER_DAY as DAY_S

SGP4_J3_OVER_J2 = -2.53881e-6 / 1.082616e-3
"""SGP4's J3/J2 (WGS-72, the constants of its element sets)."""


class Eccentricities(NamedTuple):
    """Mean eccentricity vectors of debris (arrays, one entry a debris) in their node frames.

    ``ex``, ``ey``: the part J2 turns, at t = 0 [-]; ``argp_rate``: its apsidal rate
    [rad/s]; ``fixed_y``: the part it does not (SGP4's J3 term, module docstring) [-];
    ``a``: the debris' semi-major axis [m] (the speed of the form).
    """

    ex: np.ndarray
    ey: np.ndarray
    argp_rate: np.ndarray
    fixed_y: np.ndarray
    a: np.ndarray

    @classmethod
    def from_elements(cls, a, e, inc, argp, *, frozen: bool, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
        """From mean elements at t = 0: ``a`` [m], ``e``, ``inc``, ``argp`` [rad]; with
        ``frozen``, SGP4's J3 term (element sets of SGP4; not GTOC9's)."""
        a, e, inc, argp = (np.asarray(v, dtype=float) for v in (a, e, inc, argp))
        rate = secular_rates(a, e, inc, j2=j2, mu=mu, r_eq=r_eq).argp
        fixed = (-0.5 * SGP4_J3_OVER_J2 * r_eq / (a * (1.0 - e**2)) * np.sin(inc) if frozen
                 else np.zeros_like(a))  # fmt: skip
        return cls(e * np.cos(argp), e * np.sin(argp), rate, fixed, a)

    def take(self, index) -> Eccentricities:
        return Eccentricities(*(np.asarray(field)[index] for field in self))

    def at(self, t):
        """The vectors at ``t`` [s]: ``(x, y)`` arrays."""
        turn = self.argp_rate * t
        c, s = np.cos(turn), np.sin(turn)
        return c * self.ex - s * self.ey, s * self.ex + c * self.ey + self.fixed_y


def drift_argp_rate(a_drift, inc_drift, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Apsidal rate [rad/s] of a circular drift orbit (Vallado [3]_ Eq. 9-41)."""
    return secular_rates(a_drift, 0.0, inc_drift, j2=j2, mu=mu, r_eq=r_eq).argp


def required_change(origin: Eccentricities, target: Eccentricities, t_depart, t_arrive,
                    drift_rate):  # fmt: skip
    """``de_req`` [-] of legs leaving at ``t_depart`` and arriving at ``t_arrive`` [s] on
    drifts whose apsides turn at ``drift_rate`` [rad/s] (module docstring; broadcast)."""
    xi, yi = origin.at(t_depart)
    xj, yj = target.at(t_arrive)
    turn = drift_rate * (t_arrive - t_depart)
    c, s = np.cos(turn), np.sin(turn)
    return np.hypot(xj - (c * xi - s * yi), yj - (s * xi + c * yi))


def room(a_origin, a_drift, a_target):
    """``rho`` [-]: the change of eccentricity the transfers make for free."""
    a_mean = 0.5 * (np.asarray(a_origin) + np.asarray(a_target))
    return (np.abs(a_drift - a_origin) + np.abs(a_target - a_drift)) / a_mean


def speed(origin: Eccentricities, target: Eccentricities, *, mu=MU_EARTH):
    """``v`` [m/s] of the form: the circular speed at the two debris' mean radius."""
    return np.sqrt(mu / (0.5 * (origin.a + target.a)))


def priced(dv_paper, de_required, rho, v):
    """The leg's ΔV [m/s] with its eccentricity priced (module docstring)."""
    excess = np.maximum(np.square(de_required) - np.square(rho), 0.0)
    return np.sqrt(np.square(dv_paper) + 0.25 * np.square(v) * excess)


def _chord(length, half_width):
    """How far a vector of ``length`` moves when turned by up to ``half_width`` [rad]."""
    return 2.0 * np.abs(length) * np.sin(0.5 * np.minimum(np.abs(half_width), np.pi))


def required_change_bound(origin: Eccentricities, target: Eccentricities, t1, t2, t3, t4,
                          rate_lo, rate_hi):  # fmt: skip
    """A lower bound of ``de_req`` [-] over departures in [t1, t2], arrivals in [t3, t4]
    [s] (only ``t' - t >= 0`` matters) and drift apsidal rates in [rate_lo, rate_hi]
    [rad/s] (module docstring); exact when the box is a point."""
    t1, t2, t3, t4, rate_lo, rate_hi = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (t1, t2, t3, t4, rate_lo, rate_hi)))
    # the target's vector: turned by argp_rate_j t_a over [t3, t4]
    t_a, h_a = 0.5 * (t3 + t4), 0.5 * np.abs(target.argp_rate) * (t4 - t3)
    xj, yj = target.at(t_a)
    r_target = _chord(np.hypot(target.ex, target.ey), h_a)
    # the vehicle's: i's at t_d turned by the drift, w_d (t_a - t_d)
    t_d, h_d = 0.5 * (t1 + t2), 0.5 * np.abs(origin.argp_rate) * (t2 - t1)
    durations = np.stack([t3 - t2, t3 - t1, t4 - t2, t4 - t1])
    products = np.concatenate([rate_lo * durations, rate_hi * durations])
    turn_lo, turn_hi = products.min(axis=0), products.max(axis=0)
    turn, h_turn = 0.5 * (turn_lo + turn_hi), 0.5 * (turn_hi - turn_lo)
    xi, yi = origin.at(t_d)
    c, s = np.cos(turn), np.sin(turn)
    xb, yb = c * xi - s * yi, s * xi + c * yi
    r_vehicle = (_chord(np.hypot(origin.ex, origin.ey), h_d + h_turn)
                 + _chord(origin.fixed_y, h_turn))  # fmt: skip
    return np.maximum(np.hypot(xj - xb, yj - yb) - r_target - r_vehicle, 0.0)


def priced_bound(dv_paper_low, de_required_low, rho_high, v):
    """A lower bound [m/s] of :func:`priced` from the least ``dv_paper`` and ``de_req``
    and the largest ``rho`` over a box (the form is monotonic in each)."""
    return priced(dv_paper_low, de_required_low, rho_high, v)


BOUND_PIECES = 16
"""Pieces a box's interval of drift radii is bounded on, each apart, where the box holds
a zero-length leg (:func:`leg_bound`: its radius free over a side of the band, the
interval does not shrink with the box)."""


def leg_cost(origin: Eccentricities, target: Eccentricities, dv_paper, a_origin, a_drift,
             a_target, inc_drift, t_depart, t_arrive, *, j2=J2, mu=MU_EARTH,
             r_eq=R_EARTH):  # fmt: skip
    """The priced ΔV [m/s] of legs (:func:`priced`): paper ΔV ``dv_paper`` [m/s], radii
    [m], drift inclination [rad], dates [s] (broadcast)."""
    rate = drift_argp_rate(a_drift, inc_drift, j2=j2, mu=mu, r_eq=r_eq)
    de = required_change(origin, target, t_depart, t_arrive, rate)
    return priced(dv_paper, de, room(a_origin, a_drift, a_target), speed(origin, target, mu=mu))


def leg_bound(origin: Eccentricities, target: Eccentricities, minimum_on, a_origin, a_target,
              lo, hi, inc_drift, t1, t2, t3, t4, *, pieces=1, j2=J2, mu=MU_EARTH,
              r_eq=R_EARTH):  # fmt: skip
    """A lower bound [m/s] of the priced ΔV over drift radii [lo, hi] [m] and dates in the
    box [t1, t2] x [t3, t4] [s]: on each of ``pieces`` pieces of the radii, the least
    paper ΔV (``minimum_on(lo, hi)``, exact), the least ``de_req``
    (:func:`required_change_bound`) and the largest ``rho`` (at a piece's end: ``rho`` is
    piecewise linear, convex), the least over the pieces (``inf`` where empty).  Exact
    when the box shrinks to a point and its radii with it."""
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    with np.errstate(all="ignore"):
        return _leg_bound(origin, target, minimum_on, a_origin, a_target, lo, hi, inc_drift,
                          t1, t2, t3, t4, pieces, j2=j2, mu=mu, r_eq=r_eq)  # fmt: skip


def _leg_bound(origin, target, minimum_on, a_origin, a_target, lo, hi, inc_drift, t1, t2, t3,
               t4, pieces, *, j2, mu, r_eq):  # fmt: skip
    empty = ~(lo <= hi)
    lo_s, hi_s = np.where(empty, 0.0, lo), np.where(empty, 0.0, hi)
    v = speed(origin, target, mu=mu)
    best = np.full(np.broadcast_shapes(lo.shape, np.shape(t1)), np.inf)
    edges = np.linspace(0.0, 1.0, pieces + 1)
    for k in range(pieces):
        a1 = lo_s + edges[k] * (hi_s - lo_s)
        a2 = lo_s + edges[k + 1] * (hi_s - lo_s)
        dv_low = minimum_on(a1, a2)
        rates = [drift_argp_rate(a, inc_drift, j2=j2, mu=mu, r_eq=r_eq) for a in (a1, a2)]
        de_low = required_change_bound(origin, target, t1, t2, t3, t4, np.minimum(*rates),
                                       np.maximum(*rates))  # fmt: skip
        rho_high = np.maximum(room(a_origin, a1, a_target), room(a_origin, a2, a_target))
        best = np.minimum(best, priced_bound(dv_low, de_low, rho_high, v))
        if np.all(hi_s == lo_s):  # a point: one piece says it all
            break
    return np.where(empty, np.inf, best)


GRID_POINTS = 65
"""Radii tried by a zero-length leg with its eccentricity priced (:func:`table_cost_at`)."""


def table_cost_at(legs, e, c, value, a, lo, hi, t, t_arrive, j2):
    """:func:`_table_cost_at`, quietly."""
    with np.errstate(all="ignore"):  # rows without a leg (nan radii) end as inf
        return _table_cost_at(legs, e, c, value, a, lo, hi, t, t_arrive, j2)


def _table_cost_at(legs, e, c, value, a, lo, hi, t, t_arrive, j2):
    """The exact costs of a cost table's (:class:`~sdc_cvx.physics.leg_bounds.LegCosts`)
    legs ``e`` (inclination choice ``c``) between dates [days], with the eccentricity
    priced (:func:`leg_cost`), from the paper's ``value`` at radius ``a``: at the radius
    the dates fix, or, for a zero-length leg free to take any radius of ``[lo, hi]``, the
    cheapest of a grid of them and of the paper's cheapest (a leg that flies: never below
    the true least)."""
    ecc_o, ecc_t = (side.take(e) for side in legs.eccentricity)
    o, tg = legs.origin, legs.target
    inc = legs.inclination(e, c)
    consts = {"j2": j2, "mu": legs.mu}

    def priced(radius, paper):
        return leg_cost(ecc_o, ecc_t, paper, o.a[e], radius, tg.a[e], inc, t * DAY_S,
                        t_arrive * DAY_S, **consts)

    cost = np.where(np.isfinite(value), priced(np.where(np.isfinite(a), a, legs.a_low), value),
                    np.inf)  # fmt: skip
    wide = np.isfinite(value) & (hi > lo)
    if wide.any():
        for f in np.linspace(0.0, 1.0, GRID_POINTS):
            radius = np.where(wide, lo + f * (hi - lo), a)
            paper = legs.cost(e, c, np.where(np.isfinite(radius), radius, legs.a_low))
            here = np.where(wide, priced(radius, paper), np.inf)
            a = np.where(here < cost, radius, a)
            cost = np.minimum(cost, here)
    return cost, a


def table_box_bound(legs, e, c, lo, hi, t1, t2, t3, t4, j2, t_min=0.0):
    """A lower bound of a cost table's priced cost over the radii [lo, hi] [m] and the
    box of dates [t1, t2] x [t3, t4] [days] (:func:`leg_bound`; ``inf`` where empty)."""
    ecc_o, ecc_t = (side.take(e) for side in legs.eccentricity)
    days = DAY_S

    def minimum_on(a1, a2):
        return legs.minimum_on(e, c, a1, a2)[0]

    zero = t_min <= 0.0 and bool(np.any(np.asarray(t3) <= np.asarray(t2)))
    return leg_bound(ecc_o, ecc_t, minimum_on, legs.origin.a[e], legs.target.a[e], lo, hi,
                     legs.inclination(e, c), t1 * days, t2 * days, t3 * days, t4 * days,
                     pieces=BOUND_PIECES if zero else 1, j2=j2, mu=legs.mu)  # fmt: skip
