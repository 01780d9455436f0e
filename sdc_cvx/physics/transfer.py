"""The drift transfer strategy (paper Part III-C to III-I), as pure vectorised numpy.

A transfer from debris i to debris j is: a Hohmann transfer to a circular drift
orbit (a_d, I_d) at the departure date, a coast on the drift orbit while J2
closes the RAAN gap, and a Hohmann transfer to debris j (Fig. 9).  The plane
change is done once, on whichever Hohmann transfer changes the inclination, at
its higher-radius impulse.

Sides.  The duration (Eq. 10) has an asymptote where the drift orbit precesses at
the target's rate.  ``side = +1`` means the drift orbit precesses *faster* than the
target (the vehicle catches the target up from behind: for retrograde SSO this is
a drift orbit *below* the target); ``side = -1`` slower.  Stating sides by rate
rather than altitude keeps Table 3 valid for prograde orbits too, since
``d(rate)/dI > 0`` at every inclination.

All angles are rad, lengths m, times s, speeds m/s.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .orbits import J2, MU_EARTH, circular_a_for_raan_rate, hohmann_dv, raan_rate, wrap_angle

CLOSED_GAP_RAD = 1e-9
"""RAAN gap [rad] below which two RAANs coincide (Eq. 10 gives a zero-length leg)."""


class NodeOrbits(NamedTuple):
    """Orbits of debris (or of the vehicle) as broadcastable arrays.

    Attributes
    ----------
    a : ndarray
        Semi-major axis [m] (orbits are treated as circular of radius ``a`` for costs).
    inc : ndarray
        Inclination [rad].
    raan : ndarray
        RAAN at the mission start t0 [rad].
    rate : ndarray
        Secular J2 RAAN rate [rad/s] (Eq. 7, with the debris' own eccentricity).
    """

    a: np.ndarray
    inc: np.ndarray
    raan: np.ndarray
    rate: np.ndarray

    @classmethod
    def from_elements(cls, a, e, inc, raan, *, j2=J2, mu=MU_EARTH):
        """Build from elements at t0: ``a`` [m], ``e`` [-], ``inc`` [rad], ``raan`` [rad]."""
        a, e, inc, raan = (np.asarray(v, dtype=float) for v in (a, e, inc, raan))
        return cls(a, inc, raan, raan_rate(a, e, inc, j2=j2, mu=mu))

    def take(self, index) -> NodeOrbits:
        """The orbits at ``index`` (numpy fancy indexing on every field)."""
        return NodeOrbits(*(np.asarray(field)[index] for field in self))

    def raan_at(self, t):
        """RAAN [rad] at ``t`` seconds after t0 (linear J2 drift, Part III-A)."""
        return self.raan + self.rate * t


def raan_gap(origin: NodeOrbits, target: NodeOrbits, t):
    """RAAN of the target minus RAAN of the origin at date ``t`` [s after t0], in rad (unwrapped).

    This is the numerator of Eq. 10: ``Omega_j(t0) - Omega_i(t0) + (rate_j - rate_i) t``.
    """
    return target.raan - origin.raan + (target.rate - origin.rate) * t


def drift_rate(a_drift, inc_drift, *, j2=J2, mu=MU_EARTH):
    """RAAN rate [rad/s] of the circular drift orbit (Eq. 8 with e_d = 0)."""
    return raan_rate(a_drift, 0.0, inc_drift, j2=j2, mu=mu)


def drift_duration(gap, rate_target, rate_drift):
    """Coast time on the drift orbit until its RAAN meets the target's (Eq. 10).

    The gap is taken modulo 2 pi with the sign of ``rate_drift - rate_target`` so the
    duration is non-negative on whichever side of the asymptote the drift orbit is.

    Parameters
    ----------
    gap : array_like
        Target RAAN minus vehicle RAAN at the departure date [rad] (any value).
    rate_target, rate_drift : array_like
        RAAN rates of the target and of the drift orbit [rad/s].

    Returns
    -------
    ndarray
        Duration [s]; ``0`` when the RAANs already coincide, ``inf`` when the rates are
        equal and the gap is not zero (on the asymptote).
    """
    relative = np.asarray(rate_drift, dtype=float) - rate_target
    wrapped = wrap_angle(gap, relative)
    with np.errstate(divide="ignore", invalid="ignore"):
        duration = np.abs(wrapped / relative)
    # RAANs within CLOSED_GAP_RAD of each other coincide: a gap a rounding error short of
    # a full turn (a departure computed at a RAAN crossing) is no gap, not a full cycle
    closed = (np.abs(wrapped) < CLOSED_GAP_RAD) | (np.abs(wrapped) > 2.0 * np.pi - CLOSED_GAP_RAD)
    return np.where(closed, 0.0, np.where(relative == 0.0, np.inf, duration))


def drift_inclination(inc_from, inc_to, side):
    """Drift inclination by the paper's Table 3: the fastest RAAN correction.

    ``side = +1`` (drift faster than the target) takes ``max(I_i, I_j)``,
    ``side = -1`` takes ``min(I_i, I_j)``: either choice pushes the drift rate away
    from the target's rate (``d(rate)/dI > 0``).  For retrograde orbits this is
    exactly Table 3 (below the target: max; above: min).

    Parameters
    ----------
    inc_from, inc_to : array_like
        Inclinations of the departure and target debris [rad].
    side : array_like
        +1 or -1.

    Returns
    -------
    ndarray
        Drift inclination [rad].
    """
    return np.where(
        np.asarray(side) > 0, np.maximum(inc_from, inc_to), np.minimum(inc_from, inc_to)
    )


def transfer_dv(origin_a, origin_inc, target_a, target_inc, a_drift, inc_drift, *, mu=MU_EARTH):
    """Cost of the drift transfer: Hohmann to the drift orbit plus Hohmann to the target (Eq. 11).

    Each Hohmann transfer carries the plane change between its two orbits at its
    higher-radius impulse (Eq. 13).  With the drift orbit equal to the departure
    orbit the first transfer costs nothing (drift on the departure orbit is legal).

    Parameters
    ----------
    origin_a, origin_inc : array_like
        Departure orbit radius [m] and inclination [rad].
    target_a, target_inc : array_like
        Target orbit radius [m] and inclination [rad].
    a_drift, inc_drift : array_like
        Drift orbit radius [m] and inclination [rad].

    Returns
    -------
    ndarray
        Total impulse [m/s].
    """
    first = hohmann_dv(origin_a, a_drift, np.abs(inc_drift - origin_inc), mu=mu)
    second = hohmann_dv(a_drift, target_a, np.abs(target_inc - inc_drift), mu=mu)
    return first + second


def transfer_duration(
    origin: NodeOrbits, target: NodeOrbits, a_drift, inc_drift, t_depart, *, j2=J2, mu=MU_EARTH
):
    """Duration [s] of the transfer i -> drift (a_d, I_d) -> j leaving at ``t_depart`` (Eq. 10)."""
    return drift_duration(
        raan_gap(origin, target, t_depart),
        target.rate,
        drift_rate(a_drift, inc_drift, j2=j2, mu=mu),
    )


def required_drift_rate(gap, rate_target, side, duration):
    """RAAN rate [rad/s] a drift orbit needs to close ``gap`` in ``duration`` [s] on ``side``.

    Inverse of Eq. 10: ``rate_d = rate_j + wrap(gap, side) / duration``.
    """
    return rate_target + wrap_angle(gap, side) / np.asarray(duration, dtype=float)


def drift_a_for_duration(gap, rate_target, side, inc_drift, duration, *, j2=J2, mu=MU_EARTH):
    """Drift semi-major axis [m] whose coast closes ``gap`` in exactly ``duration`` [s] on ``side``.

    The inverse of Eq. 10 composed with Eq. 8.  For a circular drift orbit the rate is
    a power law of ``a``, so the inverse is exact in closed form
    (:func:`~sdc_cvx.physics.orbits.circular_a_for_raan_rate`); no iterative root-find is needed.

    Returns
    -------
    ndarray
        Semi-major axis [m]; ``nan`` where no drift orbit of that inclination can.
    """
    rate = required_drift_rate(gap, rate_target, side, duration)
    return circular_a_for_raan_rate(rate, inc_drift, j2=j2, mu=mu)


def duration_bounded_interval(
    gap, rate_target, side, inc_drift, max_duration, a_low, a_high, *, j2=J2, mu=MU_EARTH
):
    """Drift radii in ``[a_low, a_high]`` on ``side`` whose coast lasts at most ``max_duration``.

    The drift rate is monotonic in the radius, so the set is an interval: the part
    of the altitude band beyond the radius where the duration equals ``max_duration``.

    Parameters
    ----------
    gap : array_like
        Target minus origin RAAN at departure [rad].
    rate_target : array_like
        Target RAAN rate [rad/s].
    side : array_like
        +1 (drift faster than the target) or -1.
    inc_drift : array_like
        Drift inclination [rad].
    max_duration : float or array_like
        Duration bound [s] (T0 of Part IV-B).
    a_low, a_high : float
        Drift radius bounds [m].

    Returns
    -------
    lo, hi : ndarray
        Interval bounds [m]; both ``nan`` where no drift orbit is fast enough.
    """
    side = np.asarray(side, dtype=float)
    rate_needed = required_drift_rate(gap, rate_target, side, max_duration)

    def fast_enough(a):
        return side * (drift_rate(a, inc_drift, j2=j2, mu=mu) - rate_needed) >= 0.0

    ok_low, ok_high = fast_enough(a_low), fast_enough(a_high)
    a_edge = np.clip(circular_a_for_raan_rate(rate_needed, inc_drift, j2=j2, mu=mu), a_low, a_high)
    lo = np.where(ok_low, a_low, a_edge)
    hi = np.where(ok_high, a_high, a_edge)
    empty = ~(ok_low | ok_high)
    return np.where(empty, np.nan, lo), np.where(empty, np.nan, hi)


def duration_window_interval(gap, rate_target, side, inc_drift, min_duration, max_duration,
                             a_low, a_high, *, j2=J2, mu=MU_EARTH):  # fmt: skip
    """Drift radii on ``side`` whose coast lasts between ``min_duration`` and ``max_duration`` [s].

    :func:`duration_bounded_interval` for the upper bound, minus the radii fast enough
    to finish before ``min_duration`` (T_min, Part II-B), which lie at the far end of
    the band from the asymptote, so the result is still an interval.
    """
    lo, hi = duration_bounded_interval(
        gap, rate_target, side, inc_drift, max_duration, a_low, a_high, j2=j2, mu=mu
    )
    if not np.any(np.asarray(min_duration) > 0):
        return lo, hi
    fast_lo, fast_hi = duration_bounded_interval(
        gap, rate_target, side, inc_drift, min_duration, a_low, a_high, j2=j2, mu=mu
    )
    has_fast = np.isfinite(fast_lo)
    fast_at_low_end = has_fast & (fast_lo <= lo)
    lo = np.where(fast_at_low_end, np.maximum(lo, fast_hi), lo)
    hi = np.where(has_fast & ~fast_at_low_end, np.minimum(hi, fast_lo), hi)
    empty = ~(lo <= hi)
    return np.where(empty, np.nan, lo), np.where(empty, np.nan, hi)


class LegAtDates(NamedTuple):
    """The cheapest leg of an edge between two dates, in any transfer model.

    Attributes
    ----------
    cost : ndarray
        ΔV [m/s]; ``inf`` where no leg of the model flies between the two dates.
    a_drift, inc_drift : ndarray
        Drift radius [m] and inclination [rad] (``nan`` where none).
    side : ndarray
        +1 where the drift orbit precesses faster than the target, -1 slower (0: none).
    laps : ndarray of int
        Relative laps of the coast beyond the first that closes the RAAN gap.
    """

    cost: np.ndarray
    a_drift: np.ndarray
    inc_drift: np.ndarray
    side: np.ndarray
    laps: np.ndarray


class TransferChoice(NamedTuple):
    """Cheapest drift transfer found per edge (arrays aligned with the input edges).

    Attributes
    ----------
    a_drift : ndarray
        Drift radius [m] (``nan`` where infeasible).
    inc_drift : ndarray
        Drift inclination [rad].
    side : ndarray
        +1 (drift faster than the target) or -1; 0 where infeasible.
    duration : ndarray
        Transfer duration [s] (``inf`` where infeasible).
    dv : ndarray
        Transfer cost [m/s] (``inf`` where infeasible).
    """

    a_drift: np.ndarray
    inc_drift: np.ndarray
    side: np.ndarray
    duration: np.ndarray
    dv: np.ndarray


def cheapest_transfer(
    origin: NodeOrbits,
    target: NodeOrbits,
    t_depart,
    max_duration,
    a_low,
    a_high,
    *,
    inclination="table3",
    sides=(1.0, -1.0),
    j2=J2,
    mu=MU_EARTH,
) -> TransferChoice:
    """Pre-optimised transfer of each edge: minimum cost with duration <= T0 (Part IV-B).

    ``min over (a_d, I_d, side) of DV(a_d, I_d)  s.t.  T(a_d, I_d, t_depart) <= T0`` and
    ``a_low <= a_d <= a_high``.  For each side and drift inclination the feasible radii
    form an interval (:func:`duration_bounded_interval`); the cost is minimised on it by
    a grid that includes the cost's kinks at the two debris radii, refined by golden
    section, all vectorised across edges.

    Parameters
    ----------
    origin, target : NodeOrbits
        Departure and target debris, arrays of shape (M,).
    t_depart : float or array_like
        Departure date [s after t0].
    max_duration : float
        Duration bound T0 [s].
    a_low, a_high : float
        Drift radius bounds [m].
    inclination : {"table3", "free"}
        ``"table3"``: the inclination of Table 3 for each side; ``"free"``: try both
        debris inclinations on both sides and keep the cheaper.
    sides : tuple of {1, -1}
        Sides of the asymptote to consider (default both).

    Returns
    -------
    TransferChoice
    """
    gap = raan_gap(origin, target, t_depart)
    candidates = []
    for side in sides:
        if inclination == "table3":
            incs = [drift_inclination(origin.inc, target.inc, side)]
        elif inclination == "free":
            incs = [origin.inc, target.inc]
        else:
            raise ValueError(f"inclination must be 'table3' or 'free', got {inclination!r}")
        for inc_drift in incs:
            inc_drift = np.broadcast_to(inc_drift, np.shape(gap))
            lo, hi = duration_bounded_interval(
                gap, target.rate, side, inc_drift, max_duration, a_low, a_high, j2=j2, mu=mu
            )

            def cost(a, inc_drift=inc_drift):
                return transfer_dv(
                    origin.a[:, None],
                    origin.inc[:, None],
                    target.a[:, None],
                    target.inc[:, None],
                    a,
                    inc_drift[:, None],
                    mu=mu,
                )

            kinks = np.stack(
                [np.broadcast_to(origin.a, lo.shape), np.broadcast_to(target.a, lo.shape)], axis=1
            )
            a_best, dv_best = minimize_on_interval(cost, lo, hi, kinks)
            candidates.append((side, inc_drift, a_best, dv_best))

    dvs = np.stack([c[3] for c in candidates])
    best = np.argmin(dvs, axis=0)
    pick = np.arange(dvs.shape[1])
    dv = dvs[best, pick]
    feasible = np.isfinite(dv)
    a_drift = np.stack([c[2] for c in candidates])[best, pick]
    inc_drift = np.stack([c[1] for c in candidates])[best, pick]
    side = np.where(feasible, np.array([c[0] for c in candidates])[best], 0.0)
    duration = np.where(
        feasible,
        drift_duration(gap, target.rate, drift_rate(a_drift, inc_drift, j2=j2, mu=mu)),
        np.inf,
    )
    return TransferChoice(a_drift, inc_drift, side, duration, dv)


_GOLDEN = (np.sqrt(5.0) - 1.0) / 2.0


def minimize_on_interval(f, lo, hi, extra_points=None, *, n_grid=33, n_golden=32):
    """Vectorised bounded 1-D minimisation of ``f`` on ``[lo, hi]`` for M problems at once.

    A uniform grid (plus ``extra_points``, e.g. kinks, clipped into the interval) picks
    the best cell; golden-section search refines it.  Robust to kinks and to several
    local minima coarser than the grid.

    Parameters
    ----------
    f : callable
        ``f(x)`` with ``x`` of shape (M, K) returns values of shape (M, K); row m of
        ``x`` belongs to problem m.
    lo, hi : ndarray
        Interval bounds, shape (M,); ``nan`` marks an empty interval.
    extra_points : ndarray, optional
        Shape (M, P): points always evaluated.

    Returns
    -------
    x_best, f_best : ndarray
        Minimiser and minimum, shape (M,); ``nan`` and ``inf`` for empty intervals.
    """
    with np.errstate(all="ignore"):  # placeholder rows of empty intervals are discarded
        return _minimize_on_interval(f, lo, hi, extra_points, n_grid, n_golden)


def _minimize_on_interval(f, lo, hi, extra_points, n_grid, n_golden):
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    empty = ~(np.isfinite(lo) & np.isfinite(hi) & (lo <= hi))
    lo0, hi0 = np.where(empty, 0.0, lo), np.where(empty, 1.0, hi)
    points = lo0[:, None] + (hi0 - lo0)[:, None] * np.linspace(0.0, 1.0, n_grid)
    if extra_points is not None:
        points = np.concatenate([points, np.clip(extra_points, lo0[:, None], hi0[:, None])], axis=1)
    values = f(points)
    rows = np.arange(len(lo0))
    k = np.argmin(values, axis=1)
    x_grid, f_grid = points[rows, k], values[rows, k]
    step = (hi0 - lo0) / (n_grid - 1)
    a, b = np.maximum(lo0, x_grid - step), np.minimum(hi0, x_grid + step)
    c, d = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
    fc, fd = f(c[:, None])[:, 0], f(d[:, None])[:, 0]
    for _ in range(n_golden):
        left = fc < fd
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        d_new = np.where(left, c, a + _GOLDEN * (b - a))
        c_new = np.where(left, b - _GOLDEN * (b - a), d)
        fd_new = np.where(left, fc, np.nan)
        fc_new = np.where(left, np.nan, fd)
        x_eval = np.where(left, c_new, d_new)
        f_eval = f(x_eval[:, None])[:, 0]
        c, d = c_new, d_new
        fc = np.where(left, f_eval, fc_new)
        fd = np.where(left, fd_new, f_eval)
    x_fine = np.where(fc < fd, c, d)
    f_fine = np.minimum(fc, fd)
    better = f_fine < f_grid
    x_best = np.where(better, x_fine, x_grid)
    f_best = np.where(better, f_fine, f_grid)
    return np.where(empty, np.nan, x_best), np.where(empty, np.inf, f_best)
