"""Rendezvous phasing of an impulsive drift leg: arrive at the debris, not only in its plane.

The planner's leg (paper Part III-C to III-F, :mod:`~sdc_cvx.physics.transfer`) closes the
RAAN gap and neglects where on its orbit the target is: "negligible provided that the
return transfer takes place at the adequate phasing opportunity" (Part III-F).  A leg that
flies has its four impulses at definite epochs:

1. ``b1`` leaves the origin's orbit at one of its nodes (a plane change needs one; a
   coplanar impulse loses nothing there), the ``k``-th node after the vehicle is ready;
2. ``b2``, half a transfer orbit later at the opposite node, puts it on the drift orbit;
3. ``b3`` leaves the drift orbit at the node nearest the date the RAANs meet (Eq. 10);
4. ``b4``, half a transfer orbit later, puts it on the target's orbit: the rendezvous.

Each Hohmann transfer carries its plane change at its higher-radius impulse (Eq. 13); at
``b3`` the plane change is the whole angle between the drift and the target planes, which
includes the small RAAN residual of placing ``b3`` on a node rather than at the exact
closure date.  The vehicle arrives at the argument of latitude of ``b3`` plus 180 deg; the
target must be there too.  Two knobs move that: the node ``k`` of the departure (hours)
and the drift radius (kilometres: it changes the drift's mean motion and duration).  For
each ``k`` the phase error is a function of the drift radius with zeros every few
kilometres; :func:`phase_leg` finds them all on a bracket of radii and keeps the cheapest
whose arrival is late by at most the time the mission can spare.  Each zero lies in a
bracket of neighbouring radii of a grid, refined by bisection; only the brackets that may
arrive in time are refined, the others only when none does (then in the order of a floor
of their ΔV plus lateness, until the floor passes the best found).

Everything here is the mean-element model with first-order secular J2 rates
(:func:`~sdc_cvx.physics.elements.secular_rates`): the numerical replay
(:mod:`sdc_cvx.flight`) says how well it holds.  All angles rad, lengths m, times s.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.6 (phasing) and §9.6 (secular J2 effects).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .elements import secular_rates
from .orbits import J2, MU_EARTH, R_EARTH, circular_speed, orbital_speed, wrap_angle

TWO_PI = 2.0 * np.pi
PHASE_TOL_RAD = 1e-6
"""Largest phase error [rad] of a phased leg (about 7 m along an orbit at 800 km)."""
NODES_PER_LEG = 32
"""Departure nodes tried at once (half an orbit apart: about 26 hours at 800 km)."""
NODE_BLOCKS = 32
"""Blocks of :data:`NODES_PER_LEG` nodes tried, one after the other, until one meets the
target in time: up to about 17 days of waiting, a synodic period of orbits 25 km apart (a
leg whose RAANs meet at once phases by waiting until a drift is needed)."""
RADIUS_SPANS_M = (12e3, 50e3, 200e3)
"""Half-widths [m] of the brackets of drift radii searched around the plan's, the next
only when the one before meets the target nowhere (a leg whose drift orbit is its
departure orbit, the plan's zero-length legs, phases only by moving it far)."""
BISECTIONS = 30
"""Halvings of a bracket of radii (2 m to 33 m wide): 2e-9 to 3e-8 m, a phase error far
below :data:`PHASE_TOL_RAD` at the steepest 8 rad per km."""
LATE_COST_MPS_PER_DAY = 2.0
"""What a day of lateness is worth [m/s] when no phasing arrives in time (a zero-length leg
of the plan, flown after corrections): waiting a synodic period is then cheaper than a
drift fast enough to keep the date, and the legs after it may make the days up."""
ARRIVAL_SLACK_S = 86400.0
"""A bracket of radii whose two ends both arrive later than this after the latest arrival
[s] holds no leg in time (the arrival moves by less than an orbit across a bracket where
the phase error crosses zero): it is refined only if no bracket is in time."""
LATE_CHUNK = 20000
"""Brackets refined at once when no phased leg is in time (:func:`_least_late`)."""
RADIUS_POINTS = 12001
"""Points of each bracket before the zeros are refined by bisection (2 m apart in the
first: the phase error turns up to about 8 rad per km on a half-year drift)."""


class MeanOrbit(NamedTuple):
    """A near-circular orbit in mean elements, carried by secular J2 rates.

    Attributes
    ----------
    a, e, inc : float
        Mean semi-major axis [m], eccentricity [-] and inclination [rad].
    raan, arglat : float
        RAAN and mean argument of latitude [rad] at t = 0.
    raan_rate, arglat_rate : float
        Their secular rates [rad/s].
    wander : tuple of ndarray, optional
        ``(t, raan, arglat)``: dates [s] and how far from those lines the RAAN and the
        argument of latitude are there [rad], followed linearly between the dates, 0
        outside them (a debris fitted to its SGP4 states over a window,
        :func:`sdc_cvx.flight.rates.fitted_orbit`: drag lowers it and speeds its argument
        of latitude up; ``None``, the lines alone).
    """

    a: float
    e: float
    inc: float
    raan: float
    arglat: float
    raan_rate: float
    arglat_rate: float
    wander: tuple | None = None

    @classmethod
    def from_elements(cls, a, e, inc, raan, arglat, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
        rates = secular_rates(a, e, inc, j2=j2, mu=mu, r_eq=r_eq)
        return cls(float(a), float(e), float(inc), float(raan), float(arglat),
                   float(rates.raan), float(rates.arglat))  # fmt: skip

    def raan_at(self, t):
        t = np.asarray(t, dtype=float)
        return self.raan + self.raan_rate * t + self._wander(t, 1)

    def arglat_at(self, t):
        t = np.asarray(t, dtype=float)
        return self.arglat + self.arglat_rate * t + self._wander(t, 2)

    def _wander(self, t, column: int):
        if self.wander is None:
            return 0.0
        return np.interp(t, self.wander[0], self.wander[column], left=0.0, right=0.0)


class PhasedLeg(NamedTuple):
    """A leg with its impulse epochs: the chosen phasing, or the plan's point unphased.

    Attributes
    ----------
    epochs : ndarray (4,)
        Epochs of ``b1``..``b4`` [s after t0]; ``b4`` is the rendezvous.
    a_drift, inc_drift : float
        Drift orbit radius [m] and inclination [rad].
    impulses : ndarray (4,)
        Impulse magnitudes [m/s] in the mean-element model (Eq. 12-13).
    plane_changes : ndarray (4,)
        Plane change [rad] each impulse carries.
    raan_residual : float
        Target RAAN minus drift RAAN at ``b3`` [rad] (part of ``b3``'s plane change).
    phase_error : float
        Target's minus vehicle's argument of latitude at ``b4`` [rad], in (-pi, pi].
    node : int
        Departure node ``k`` (0: the first node after the vehicle is ready).
    """

    epochs: np.ndarray
    a_drift: float
    inc_drift: float
    impulses: np.ndarray
    plane_changes: np.ndarray
    raan_residual: float
    phase_error: float
    node: int

    @property
    def dv(self) -> float:
        return float(np.sum(self.impulses))


def _wrap_pi(angle):
    return np.mod(np.asarray(angle) + np.pi, TWO_PI) - np.pi


def _hohmann_impulses(r_from, r_to, plane_change, mu):
    """The two impulses [m/s] of a Hohmann transfer, in time order, the plane change at
    the higher radius (Eq. 12-13), and the plane change each one carries."""
    a_t = 0.5 * (r_from + r_to)
    first = np.abs(orbital_speed(r_from, a_t, mu=mu) - circular_speed(r_from, mu=mu))
    second = np.abs(circular_speed(r_to, mu=mu) - orbital_speed(r_to, a_t, mu=mu))
    up = r_to >= r_from  # the plane change rides on the impulse at the higher radius
    v_before = np.where(up, orbital_speed(r_to, a_t, mu=mu), circular_speed(r_from, mu=mu))
    v_after = np.where(up, circular_speed(r_to, mu=mu), orbital_speed(r_from, a_t, mu=mu))
    combined = np.sqrt((v_after - v_before) ** 2
                       + 4.0 * v_before * v_after * np.sin(0.5 * plane_change) ** 2)  # fmt: skip
    zero = np.zeros_like(combined)
    return (np.where(up, first, combined), np.where(up, combined, second),
            np.where(up, zero, plane_change), np.where(up, plane_change, zero))  # fmt: skip


def _half_transfer(r_from, r_to, inc, *, j2, mu, r_eq):
    """Duration [s] and RAAN drift [rad] of half a Hohmann transfer orbit (apse to apse)."""
    a_t = 0.5 * (r_from + r_to)
    e_t = np.abs(r_to - r_from) / (r_from + r_to)
    rates = secular_rates(a_t, e_t, inc, j2=j2, mu=mu, r_eq=r_eq)
    seconds = np.pi / rates.arglat
    return seconds, rates.raan * seconds


def leg_at(origin: MeanOrbit, target: MeanOrbit, t_ready, a_drift, inc_drift, node, *,
           laps=0, drift_factors=(1.0, 1.0), j2=J2, mu=MU_EARTH, r_eq=R_EARTH,
           costs=True) -> dict:  # fmt: skip
    """The leg leaving at departure node ``node`` on drift radius ``a_drift`` (broadcast).

    Parameters
    ----------
    origin, target : MeanOrbit
        The vehicle's orbit when it is ready to leave, and the target's.
    t_ready : float
        Earliest departure [s after t0].
    a_drift, inc_drift : array_like
        Drift orbit radius [m] and inclination [rad].
    node : array_like of int
        Departure node (0: the first after ``t_ready``).
    laps : int
        Relative laps of the coast beyond the first that closes the RAAN gap.
    drift_factors : (float, float)
        The drift orbit's RAAN and argument-of-latitude rates as flown, over the
        first-order rates (1, 1: the first-order model; :mod:`sdc_cvx.flight.rates`
        measures them by propagation).
    costs : bool
        False: ``epochs`` and ``phase_error`` only (the search for the phase error's
        zeros needs no more).

    Returns
    -------
    dict of ndarray
        ``epochs`` (4, ...), ``impulses`` (4, ...), ``plane_changes`` (4, ...),
        ``raan_residual``, ``phase_error`` (see :class:`PhasedLeg`).
    """
    consts = dict(j2=j2, mu=mu, r_eq=r_eq)
    a_d, i_d = np.asarray(a_drift, dtype=float), np.asarray(inc_drift, dtype=float)
    node = np.asarray(node)
    to_node = np.mod(-origin.arglat_at(t_ready), np.pi) / origin.arglat_rate
    t_b1 = t_ready + to_node + node * np.pi / origin.arglat_rate
    up = a_d >= origin.a
    half_1, raan_1 = _half_transfer(origin.a, a_d, np.where(up, origin.inc, i_d), **consts)
    t_b2 = t_b1 + half_1
    raan_b2 = origin.raan_at(t_b1) + raan_1
    first_order = secular_rates(a_d, 0.0, i_d, **consts)
    drift_raan = first_order.raan * drift_factors[0]
    drift_arglat = first_order.arglat * drift_factors[1]
    gap = target.raan_at(t_b2) - raan_b2
    t_close = t_b2 + _closing(gap, drift_raan - target.raan_rate, half_1, laps)
    if target.wander is not None:  # its RAAN's mean rate over that coast, once more
        turned = target.raan_at(t_close) - target.raan_at(t_b2)
        with np.errstate(divide="ignore", invalid="ignore"):
            mean_rate = np.where(t_close > t_b2 + 1.0, turned / (t_close - t_b2),
                                 target.raan_rate)  # fmt: skip
        t_close = t_b2 + _closing(gap, drift_raan - mean_rate, half_1, laps)
    half_node = np.pi / drift_arglat
    m = np.maximum(np.round((t_close - t_b2) / half_node), 0.0)
    t_b3 = t_b2 + m * half_node
    up_2 = target.a >= a_d
    half_2, _ = _half_transfer(a_d, target.a, np.where(up_2, i_d, target.inc), **consts)
    t_b4 = t_b3 + half_2
    # the vehicle arrives at the node opposite b3's: b1's node + pi (b2) + m pi + pi
    arglat_b1 = origin.arglat_at(t_b1)
    arrival_arglat = arglat_b1 + np.pi + m * np.pi + np.pi
    phase_error = _wrap_pi(target.arglat_at(t_b4) - arrival_arglat)
    if not costs:
        return {"epochs": np.stack(np.broadcast_arrays(t_b1, t_b2, t_b3, t_b4)),
                "phase_error": phase_error}  # fmt: skip
    raan_residual = _wrap_pi(target.raan_at(t_b3) - (raan_b2 + drift_raan * (t_b3 - t_b2)))
    cos_angle = (np.cos(i_d) * np.cos(target.inc)
                 + np.sin(i_d) * np.sin(target.inc) * np.cos(raan_residual))  # fmt: skip
    plane_3 = np.arccos(np.clip(cos_angle, -1.0, 1.0))
    leg = {
        "epochs": np.stack(np.broadcast_arrays(t_b1, t_b2, t_b3, t_b4)),
        "raan_residual": raan_residual,
        "phase_error": phase_error,
    }
    i1, i2, p1, p2 = _hohmann_impulses(origin.a, a_d, np.abs(i_d - origin.inc), mu)
    i3, i4, p3, p4 = _hohmann_impulses(a_d, target.a, plane_3, mu)
    return leg | {
        "impulses": np.stack(np.broadcast_arrays(i1, i2, i3, i4)),
        "plane_changes": np.stack(np.broadcast_arrays(p1, p2, p3, p4)),
    }


def _closing(gap, rel, half_1, laps):
    """The coast [s] that closes the RAAN ``gap`` [rad] at the relative rate ``rel``
    [rad/s] (Eq. 10, the gap taken with the rate's sign), ``laps`` whole turns more."""
    wrapped = wrap_angle(gap, rel)
    # RAANs that met during the first transfer (a zero-length leg of the plan, whose
    # transfers take no time) are met, not a whole relative turn away
    just_met = np.abs(wrapped - np.sign(rel) * TWO_PI) < np.abs(rel) * half_1
    wrapped = np.where(just_met, wrapped - np.sign(rel) * TWO_PI, wrapped)
    with np.errstate(divide="ignore", invalid="ignore"):
        return (wrapped + np.sign(rel) * laps * TWO_PI) / rel


class Brackets(NamedTuple):
    """Brackets of radii where a phase error changes sign: ``[lo, hi]``, the error at
    ``lo``, and each one's row (departure node or delay)."""

    lo: np.ndarray
    hi: np.ndarray
    e_lo: np.ndarray
    rows: np.ndarray

    def take(self, mask) -> Brackets:
        return Brackets(*(v[mask] for v in self))


def grid_brackets(error_at, grid, rows) -> Brackets:
    """Where ``error_at(row, x)`` changes sign between neighbours of ``grid`` (not a jump
    at +/- pi), for each of ``rows``."""
    error = error_at(rows[:, None], grid[None, :])
    cross = (np.sign(error[:, :-1]) != np.sign(error[:, 1:])) & (
        np.abs(error[:, :-1] - error[:, 1:]) < np.pi)  # fmt: skip
    at, cols = np.nonzero(cross)
    return Brackets(grid[cols], grid[cols + 1], error[at, cols], rows[at])


def refine(error_at, brackets: Brackets):
    """The zeros in ``brackets``, by :data:`BISECTIONS` halvings all at once; the zeros
    and their rows."""
    lo, hi, e_lo, rows = brackets
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        e_mid = error_at(rows, mid)
        same = np.sign(e_mid) == np.sign(e_lo)
        lo, e_lo = np.where(same, mid, lo), np.where(same, e_mid, e_lo)
        hi = np.where(same, hi, mid)
    return 0.5 * (lo + hi), rows


def grid_zeros(error_at, grid, rows):
    """Where ``error_at(row, x)`` vanishes along ``grid`` for each of ``rows``: every sign
    change between neighbours (not a jump at +/- pi) refined by :data:`BISECTIONS`
    halvings, all brackets at once; the zeros and their rows."""
    return refine(error_at, grid_brackets(error_at, grid, rows))


def phase_leg(origin: MeanOrbit, target: MeanOrbit, t_ready, a_drift, inc_drift, *, laps=0,
              drift_factors=(1.0, 1.0), a_bounds=(0.0, np.inf), latest_arrival=np.inf,
              late_cost=LATE_COST_MPS_PER_DAY, nodes=NODES_PER_LEG, spans=RADIUS_SPANS_M,
              j2=J2, mu=MU_EARTH, r_eq=R_EARTH) -> tuple[PhasedLeg, bool]:  # fmt: skip
    """The cheapest phased leg near the plan's drift orbit (module docstring).

    Parameters
    ----------
    origin, target, t_ready, laps, drift_factors
        As :func:`leg_at`.
    a_drift, inc_drift : float
        The plan's drift orbit [m, rad]: the radius is searched within ``spans`` of it,
        the inclination kept.
    a_bounds : (float, float)
        Drift radii allowed [m] (the mission's altitude bounds).
    latest_arrival : float
        Latest rendezvous epoch the mission can spare [s after t0].
    late_cost : float
        When no phased leg arrives by ``latest_arrival``: the ΔV [m/s] a day of lateness
        is worth, to choose among the late ones (:data:`LATE_COST_MPS_PER_DAY`).
    nodes : int
        Departure nodes tried at once (up to :data:`NODE_BLOCKS` blocks of them).
    spans : sequence of float
        Half-widths [m] of the brackets of radii tried, one after the other.

    Returns
    -------
    (PhasedLeg, bool)
        The cheapest phased leg arriving by ``latest_arrival`` (of the first brackets and
        nodes that have one), and True; or, when none does, the one of least ΔV plus
        ``late_cost`` per day late, of all those tried, and False.

    Raises
    ------
    ValueError
        No drift radius in the brackets and no departure node brings the vehicle to the
        target (no zero of the phase error).
    """
    consts = dict(laps=laps, drift_factors=drift_factors, j2=j2, mu=mu, r_eq=r_eq)

    def error_at(node, radius):
        return leg_at(origin, target, t_ready, radius, inc_drift, node, costs=False,
                      **consts)["phase_error"]  # fmt: skip

    def arrival(node, radius):
        return leg_at(origin, target, t_ready, radius, inc_drift, node, costs=False,
                      **consts)["epochs"][3]  # fmt: skip

    def phased(brackets):  # the good zeros of ``brackets``, their nodes and legs
        roots, rows = refine(error_at, brackets)
        legs = leg_at(origin, target, t_ready, roots, inc_drift, rows, **consts)
        good = np.abs(legs["phase_error"]) < PHASE_TOL_RAD  # not a jump of the node count
        return roots[good], rows[good], {name: value[..., good] for name, value in legs.items()}

    zeros, waiting = [], []  # of the blocks tried, none in time: zeros; brackets unrefined
    found, in_time = None, False
    for span in spans:
        low, high = max(a_drift - span, a_bounds[0]), min(a_drift + span, a_bounds[1])
        grid = np.linspace(low, high, RADIUS_POINTS)
        for block in range(NODE_BLOCKS):  # later departures only when the first meet none
            k = np.arange(block * nodes, (block + 1) * nodes)
            brackets = grid_brackets(error_at, grid, k)
            soonest = np.minimum(arrival(brackets.rows, brackets.lo),
                                 arrival(brackets.rows, brackets.hi))  # fmt: skip
            soon = soonest <= latest_arrival + ARRIVAL_SLACK_S
            waiting.append((brackets.take(~soon), soonest[~soon]))
            if not soon.any():
                continue
            zeros.append(phased(brackets.take(soon)))
            if (zeros[-1][2]["epochs"][3] <= latest_arrival).any():
                found, in_time = zeros[-1], True
                break
        if in_time:
            break
    if found is None:  # none in time: the least ΔV plus lateness of all those tried
        found = _least_late(zeros, waiting, phased, origin, target, inc_drift, latest_arrival,
                            late_cost, mu)  # fmt: skip
    roots, rows, legs = found
    if not len(roots):
        raise ValueError(f"no drift radius within {spans[-1] / 1e3:g} km of the plan's and no "
                         f"departure within {NODE_BLOCKS * nodes} nodes meets the target")
    late = legs["epochs"][3] > latest_arrival
    pick = int(np.argmin(np.where(late, np.inf, legs["impulses"].sum(axis=0)) if in_time
                         else _score(legs, latest_arrival, late_cost)))  # fmt: skip
    chosen = PhasedLeg(
        epochs=legs["epochs"][:, pick], a_drift=float(roots[pick]), inc_drift=float(inc_drift),
        impulses=legs["impulses"][:, pick], plane_changes=legs["plane_changes"][:, pick],
        raan_residual=float(legs["raan_residual"][pick]),
        phase_error=float(legs["phase_error"][pick]), node=int(rows[pick]),
    )  # fmt: skip
    return chosen, in_time


def _score(legs, latest_arrival, late_cost):
    """ΔV plus ``late_cost`` per day late [m/s] of phased legs."""
    late_days = np.maximum(legs["epochs"][3] - latest_arrival, 0.0) / 86400.0
    return legs["impulses"].sum(axis=0) + late_cost * late_days


def _least_late(zeros, waiting, phased, origin, target, inc_drift, latest_arrival, late_cost,
                mu, chunk=LATE_CHUNK):  # fmt: skip
    """Every zero that may score below the best (ΔV plus lateness): the brackets left
    unrefined, refined in the order of a floor of their score, until the floor reaches
    the best refined so far; with the zeros already refined, as one ``(roots, rows,
    legs)``.

    The floor: the lateness of the earliest end of the bracket, less
    :data:`ARRIVAL_SLACK_S`, and the ΔV of the leg's transfers with the second plane
    change taken as the inclination difference alone (the angle between the planes is
    never less), at the cheaper end less a centimetre per second (a bracket is metres
    wide).
    """
    brackets = Brackets(*(np.concatenate([w[0][field] for w in waiting]) for field in range(4)))
    soonest = np.concatenate([w[1] for w in waiting])
    late_days = np.maximum(soonest - ARRIVAL_SLACK_S - latest_arrival, 0.0) / 86400.0

    def transfers(a):
        first = _hohmann_impulses(origin.a, a, np.abs(inc_drift - origin.inc), mu)
        second = _hohmann_impulses(a, target.a, np.abs(target.inc - inc_drift), mu)
        return first[0] + first[1] + second[0] + second[1]

    floor = (np.minimum(transfers(brackets.lo), transfers(brackets.hi)) - 0.01
             + late_cost * late_days)  # fmt: skip
    order = np.argsort(floor)
    best = min((float(np.min(_score(z[2], latest_arrival, late_cost)))
                for z in zeros if len(z[0])), default=np.inf)  # fmt: skip
    for start in range(0, len(order), chunk):
        part = order[start:start + chunk]
        if floor[part[0]] >= best:
            break
        zeros.append(phased(brackets.take(part)))
        if len(zeros[-1][0]):
            best = min(best, float(np.min(_score(zeros[-1][2], latest_arrival, late_cost))))
    zeros = [z for z in zeros if len(z[0])] or [phased(brackets.take(order[:0]))]
    return (np.concatenate([z[0] for z in zeros]), np.concatenate([z[1] for z in zeros]),
            {name: np.concatenate([z[2][name] for z in zeros], axis=-1)
             for name in zeros[0][2]})  # fmt: skip
