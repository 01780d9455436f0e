"""Linearisation of each edge's cost and duration around a reference (paper Eq. 17, 18, 20).

Units: the model works in scaled units, so every coefficient here is in km (drift
radius offsets alpha), days (dates, durations) and m/s (costs).

For edge e = i -> j with drift side and inclination fixed by the pre-optimisation:

- cost ``C(a)`` is approximated on the trust interval ``[a_ref + alpha_lo, a_ref + alpha_hi]``
  by the **maximum of two secants**, split at the cost's kink (the drift orbit at a
  debris radius, docs/design.md §7) when it lies inside the interval, else at the reference.
  For a cost that is convex there (kinks of Eq. 13 are convex V shapes) this is exact
  at three points and never crosses the kink with one line; the paper's single secant
  (Eq. 18) is the special case of a split at an end.
- duration ``T(a, t)`` (Eq. 10) is convex in ``a`` on each side of its asymptote, so
  its secant over the alpha interval (Eq. 17-18) over-estimates it; it is linear in
  the departure date ``t`` as long as the RAAN gap does not wrap, which the date
  window guarantees, so ``T2`` is the exact slope at ``a_ref``.

``T_L(alpha, tau) = T0 + T1 alpha + T2 tau``, ``tau = t_depart - t_ref``  (Eq. 20).

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ...physics.leg_bounds import IMPULSIVE
from ...physics.models import TransferModel
from ...physics.orbits import SECONDS_PER_DAY, wrap_angle
from ...physics.transfer import NodeOrbits, drift_rate

KM = 1e3
WRAP_MARGIN_DAYS = 1e-3


class EdgeGeometry(NamedTuple):
    """What is fixed about each kept edge: its ends, drift side and drift inclination.

    Attributes
    ----------
    origin, target : NodeOrbits
        Orbits of debris i and j, arrays of shape (m,).
    side : ndarray
        +1 (drift faster than the target) or -1, shape (m,).
    inc_drift : ndarray
        Drift inclination [rad], shape (m,).
    a_low, a_high : float
        Drift radius bounds [m].
    j2 : float
    model : TransferModel
        The leg physics (:mod:`~sdc_cvx.physics.models`), impulsive by default.
    """

    origin: NodeOrbits
    target: NodeOrbits
    side: np.ndarray
    inc_drift: np.ndarray
    a_low: float
    a_high: float
    j2: float
    model: TransferModel = IMPULSIVE

    def cost(self, a):
        """True cost [m/s] of each edge with drift radius ``a`` [m] (Eq. 11-13)."""
        return self.model.leg_dv(
            self.origin.a, self.origin.inc, self.target.a, self.target.inc, a, self.inc_drift
        )

    def duration_days(self, a, t_days):
        """True duration [days] of each edge with drift radius ``a`` [m] leaving at ``t_days``."""
        seconds = self.model.leg_seconds(
            self.origin, self.target, a, self.inc_drift, t_days * SECONDS_PER_DAY, j2=self.j2
        )
        return seconds / SECONDS_PER_DAY

    def radius_window(self, t_days, max_days):
        """Drift radii [m] on the edge's side whose leg from ``t_days`` lasts <= ``max_days``."""
        return self.model.duration_window(
            self.origin, self.target, self.side, self.inc_drift, t_days * SECONDS_PER_DAY, 0.0,
            max_days * SECONDS_PER_DAY, self.a_low, self.a_high, j2=self.j2,
        )  # fmt: skip

    def unwrapped_date_window(self, t_days, a_ref):
        """Departure dates [days] around ``t_days`` over which the RAAN gap does not wrap.

        Within it the duration is linear in the date (Eq. 10); at one end the gap
        closes (duration 0), at the other it would need a full extra revolution.  The
        gap is the one the coast closes with the drift radius ``a_ref`` [m] (for a
        low-thrust leg it moves with the radius; the impulsive gap does not).
        """
        t_seconds = t_days * SECONDS_PER_DAY
        gap = wrap_angle(self.model.closure_gap(self.origin, self.target, a_ref, t_seconds,
                                                j2=self.j2), self.side)  # fmt: skip
        closing = (self.target.rate - self.origin.rate) * SECONDS_PER_DAY  # rad/day
        with np.errstate(divide="ignore", invalid="ignore"):
            ends = np.stack([-gap / closing, (2 * np.pi * self.side - gap) / closing])
        ends = np.where(closing == 0.0, np.array([[-np.inf], [np.inf]]), ends)
        # stay a hair inside: exactly at an end, rounding may wrap the gap a full turn
        return t_days + ends.min(axis=0) + WRAP_MARGIN_DAYS, t_days + ends.max(
            axis=0
        ) - WRAP_MARGIN_DAYS


@dataclass(frozen=True)
class TrustRegion:
    """Reference point and trust interval half-widths of every edge (Part IV-C).

    Attributes
    ----------
    a_ref : ndarray
        Reference drift radius [m].
    t_ref : ndarray
        Reference departure date [days].
    alpha_km : ndarray
        Half-width of the drift-radius interval [km].
    tau_days : ndarray
        Half-width of the departure-date interval [days].
    """

    a_ref: np.ndarray
    t_ref: np.ndarray
    alpha_km: np.ndarray
    tau_days: np.ndarray


@dataclass(frozen=True)
class Coefficients:
    """Eq. 20 coefficients and trust bounds of every edge, in scaled units.

    Cost: ``C_L = max(c0[0] + c1[0] alpha, c0[1] + c1[1] alpha)`` [m/s], alpha in km.
    Duration: ``T_L = t0 + t1 alpha + t2 (t_depart - t_ref)`` [days] (one secant, Eq. 17),
    or the paper's two half-segments through the reference (Fig. 14):
    ``T_L = t_mid + (t1_lo if alpha < 0 else t1_hi) alpha + t2 (t_depart - t_ref)``.
    Bounds: ``alpha_lo <= alpha <= alpha_hi`` [km], ``depart_lo <= t_depart <= depart_hi``
    [days]; ``available`` is False for edges with no valid interval at their reference.
    """

    a_ref: np.ndarray  # reference radius [m] actually used (clipped into the valid window)
    c0: np.ndarray  # shape (2, m)
    c1: np.ndarray  # shape (2, m)
    t0: np.ndarray
    t1: np.ndarray
    t_mid: np.ndarray  # true duration at the reference [days]
    t1_lo: np.ndarray  # slope of the half-segment on [alpha_lo, 0] [days/km]
    t1_hi: np.ndarray  # slope of the half-segment on [0, alpha_hi] [days/km]
    t2: np.ndarray
    t_ref: np.ndarray
    alpha_lo: np.ndarray
    alpha_hi: np.ndarray
    depart_lo: np.ndarray
    depart_hi: np.ndarray
    available: np.ndarray

    @classmethod
    def fixed(cls, costs, durations, tmax_days) -> Coefficients:
        """Edges of fixed cost [m/s] and duration [days]: no drift-radius freedom, no date term.

        The model then is a plain time-limited path problem, whose optimum can be
        enumerated by hand (model and backend tests).
        """
        costs = np.asarray(costs, dtype=float)
        m = len(costs)
        zero = np.zeros(m)
        durations = np.broadcast_to(np.asarray(durations, dtype=float), (m,))
        return cls(
            a_ref=np.full(m, 7e6), c0=np.stack([costs, costs]), c1=np.zeros((2, m)),
            t0=durations, t1=zero, t_mid=durations, t1_lo=zero, t1_hi=zero, t2=zero,
            t_ref=zero, alpha_lo=zero, alpha_hi=zero, depart_lo=zero,
            depart_hi=np.full(m, float(tmax_days)), available=np.ones(m, dtype=bool),
        )  # fmt: skip

    def cost(self, alpha_km):
        """Linearised cost [m/s] at ``alpha_km``."""
        return np.max(self.c0 + self.c1 * alpha_km, axis=0)

    def duration(self, alpha_km, t_depart, *, two_segments=False):
        """Linearised duration [days] at ``alpha_km`` and departure date ``t_depart``."""
        if two_segments:
            slope = np.where(np.asarray(alpha_km) < 0, self.t1_lo, self.t1_hi)
            return self.t_mid + slope * alpha_km + self.t2 * (t_depart - self.t_ref)
        return self.t0 + self.t1 * alpha_km + self.t2 * (t_depart - self.t_ref)


def linearize(
    geometry: EdgeGeometry,
    region: TrustRegion,
    *,
    tmax_days: float,
    depart_range: tuple[float, float],
) -> Coefficients:
    """Secant coefficients of every edge on its trust region (Eq. 17, 18, 20).

    Parameters
    ----------
    geometry : EdgeGeometry
    region : TrustRegion
        References and half-widths; a reference outside the valid radius window is
        first clipped into it.
    tmax_days : float
        Longest useful transfer [days]: the radius interval stops where the duration
        at ``t_ref`` reaches it, which keeps it clear of the asymptote.
    depart_range : (array_like, array_like)
        Earliest and latest departure dates of each edge [days] (scalars or arrays):
        the mission's range, or an edge copy's date window.

    Returns
    -------
    Coefficients
    """
    t_ref = region.t_ref
    window_lo, window_hi = geometry.radius_window(t_ref, tmax_days)
    a_ref = np.clip(region.a_ref, window_lo, window_hi)
    a_lo = np.maximum(window_lo, a_ref - region.alpha_km * KM)
    a_hi = np.minimum(window_hi, a_ref + region.alpha_km * KM)
    wrap_lo, wrap_hi = geometry.unwrapped_date_window(t_ref, np.where(np.isfinite(a_ref), a_ref,
                                                                      geometry.target.a))
    range_lo = np.broadcast_to(np.asarray(depart_range[0], dtype=float), t_ref.shape)
    range_hi = np.broadcast_to(np.asarray(depart_range[1], dtype=float), t_ref.shape)
    depart_lo = np.maximum.reduce([wrap_lo, t_ref - region.tau_days, range_lo])
    depart_hi = np.minimum.reduce([wrap_hi, t_ref + region.tau_days, range_hi])
    # the date window holds t_ref unless the mission's departure range cuts it off; the
    # date term is exact across the whole unwrapped window, so only emptiness matters
    available = np.isfinite(a_ref) & (depart_lo <= depart_hi)

    # fill unavailable edges with a harmless placeholder so the arithmetic stays finite
    a_ref = np.where(available, a_ref, geometry.target.a)
    a_lo = np.where(available, a_lo, a_ref)
    a_hi = np.where(available, a_hi, a_ref)
    alpha_lo, alpha_hi = (a_lo - a_ref) / KM, (a_hi - a_ref) / KM

    c0, c1 = _cost_pieces(geometry, a_lo, a_ref, a_hi)
    with np.errstate(all="ignore"):
        t_at_lo = geometry.duration_days(a_lo, t_ref)
        t_at_hi = geometry.duration_days(a_hi, t_ref)
        width = alpha_hi - alpha_lo
        t1 = np.where(width > 0, (t_at_hi - t_at_lo) / np.where(width > 0, width, 1.0), 0.0)
        t0 = t_at_lo - t1 * alpha_lo
        t_mid = geometry.duration_days(a_ref, t_ref)
        t1_lo = np.where(
            alpha_lo < 0, (t_mid - t_at_lo) / np.where(alpha_lo < 0, -alpha_lo, 1.0), 0.0
        )
        t1_hi = np.where(
            alpha_hi > 0, (t_at_hi - t_mid) / np.where(alpha_hi > 0, alpha_hi, 1.0), 0.0
        )
        # exact date slope of Eq. 10 at a_ref: d/dt [gap(t) / (rate_d - rate_j)]
        relative = drift_rate(a_ref, geometry.inc_drift, j2=geometry.j2) - geometry.target.rate
        t2 = (geometry.target.rate - geometry.origin.rate) / relative
    finite = [np.isfinite(v) for v in (t0, t1, t2, t_mid, t1_lo, t1_hi)]
    usable = available & np.logical_and.reduce(finite)
    zero = np.zeros_like(t_ref)
    return Coefficients(
        a_ref=a_ref,
        c0=np.where(usable, c0, 0.0), c1=np.where(usable, c1, 0.0),
        t0=np.where(usable, t0, 0.0), t1=np.where(usable, t1, 0.0), t2=np.where(usable, t2, 0.0),
        t_mid=np.where(usable, t_mid, 0.0), t1_lo=np.where(usable, t1_lo, 0.0),
        t1_hi=np.where(usable, t1_hi, 0.0),
        t_ref=t_ref,
        alpha_lo=np.where(usable, alpha_lo, zero), alpha_hi=np.where(usable, alpha_hi, zero),
        depart_lo=np.where(usable, depart_lo, range_lo),
        depart_hi=np.where(usable, depart_hi, range_lo),
        available=usable,
    )  # fmt: skip


def _cost_pieces(geometry: EdgeGeometry, a_lo, a_ref, a_hi):
    """Two secants of the cost on [a_lo, split] and [split, a_hi], as (c0, c1) in m/s, km."""
    inside = lambda a: (a > a_lo) & (a < a_hi)  # noqa: E731
    split = np.where(
        inside(geometry.target.a), geometry.target.a,
        np.where(inside(geometry.origin.a), geometry.origin.a,
                 np.where(inside(a_ref), a_ref, 0.5 * (a_lo + a_hi))),
    )  # fmt: skip
    points = np.stack([a_lo, split, a_hi])
    costs = geometry.cost(points)
    offsets = (points - a_ref) / KM
    c0, c1 = [], []
    for left, right in ((0, 1), (1, 2)):
        width = offsets[right] - offsets[left]
        slope = np.where(
            width > 0, (costs[right] - costs[left]) / np.where(width > 0, width, 1.0), 0.0
        )
        c1.append(slope)
        c0.append(costs[left] - slope * offsets[left])
    c0, c1 = np.stack(c0), np.stack(c1)
    # a degenerate piece (zero width) would claim a flat line through one point: use the other
    degenerate = (offsets[1] - offsets[0] <= 0) | (offsets[2] - offsets[1] <= 0)
    keep = np.where(offsets[1] - offsets[0] > 0, 0, 1)
    rows = np.arange(c0.shape[1])
    c0 = np.where(degenerate, c0[keep, rows], c0)
    c1 = np.where(degenerate, c1[keep, rows], c1)
    return c0, c1
