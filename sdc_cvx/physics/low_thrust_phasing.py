"""Rendezvous phasing of a low-thrust drift leg: arrive at the debris, not only in its plane.

The low-thrust leg (:mod:`~sdc_cvx.physics.low_thrust`: spiral A, plane change, coast,
spiral D) closes the RAAN gap and, as the paper's impulsive leg, neglects where on its
orbit the target is.  A low-thrust leg needs no node to start from (its thrust is spread
around the orbit), so two continuous knobs move the vehicle's argument of latitude at
arrival against the target's: the departure date (a wait on the origin's orbit, hours to
days) and the drift radius (kilometres: the coast's mean motion and, through the RAAN
closure, its length).  For each departure delay the phase error is a function of the
drift radius with zeros every few kilometres on a long coast; :func:`phase_low_thrust_leg`
finds them on brackets of radii and keeps the cheapest leg whose arrival is late by at
most the time the mission can spare.

The mean-element model is the one the leg's RAAN closure uses, with the argument of
latitude carried the same way: first-order secular J2 rates
(:func:`~sdc_cvx.physics.elements.secular_rates`), along each spiral at the radius the
spiral has reached (tangential thrust on a near-circular orbit: the circular speed is
linear in time, ``dV/dt = -+f``) and along the plane change at the inclination it has
reached (linear in time), both integrated by Gauss-Legendre quadrature.  The coast's
rates may be scaled by measured factors (:mod:`sdc_cvx.flight.rates`).  All angles rad,
lengths m, times s.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013
   (Part III-F: phasing neglected).
.. [2] T. N. Edelbaum, "Propulsion Requirements for Controllable Satellites", ARS Journal
   31(8), 1079–1089, 1961.
.. [3] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.6 (secular J2 effects).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .elements import secular_rates
from .low_thrust import plane_change_dv, plane_change_raan_change, spiral_dv, spiral_raan_change
from .orbits import J2, MU_EARTH, R_EARTH, circular_speed, wrap_angle
from .phasing import (
    LATE_COST_MPS_PER_DAY,
    PHASE_TOL_RAD,
    RADIUS_POINTS,
    RADIUS_SPANS_M,
    MeanOrbit,
    grid_zeros,
)

TWO_PI = 2.0 * np.pi
QUADRATURE_NODES = 16
"""Gauss-Legendre nodes of the argument of latitude along a spiral or a plane change (the
rate is smooth in time: 16 nodes integrate it to rounding)."""
DELAYS_DAYS = (0.0, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0)
"""Departure delays tried [days] (a short coast phases by waiting on the origin's orbit, a
long one by its radius)."""

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(QUADRATURE_NODES)


class LowThrustLegPlan(NamedTuple):
    """A low-thrust leg with its phase epochs: the chosen phasing, or the plan's point.

    Attributes
    ----------
    depart, plane_start, coast_start, coast_end, spiral_in_start, arrive : float
        Epochs [s after t0]: spiral A starts at ``depart``; the plane change runs from
        ``plane_start`` for ``plane_seconds``; the coast from ``coast_start`` to
        ``coast_end``; spiral D from ``spiral_in_start`` to ``arrive``, the rendezvous.
    plane_seconds : float
        Duration of the plane change [s] (0 for a coplanar leg).
    a_drift, inc_drift : float
        Drift (coast) radius [m] and inclination [rad].
    dv : float
        The leg's ΔV in the mean-element model [m/s].
    phase_error : float
        Target's minus vehicle's argument of latitude at ``arrive`` [rad], in (-pi, pi].
    """

    depart: float
    plane_start: float
    plane_seconds: float
    coast_start: float
    coast_end: float
    spiral_in_start: float
    arrive: float
    a_drift: float
    inc_drift: float
    dv: float
    phase_error: float


def _wrap_pi(angle):
    return np.mod(np.asarray(angle) + np.pi, TWO_PI) - np.pi


def _quadrature(rate, seconds):
    """``int_0^seconds rate(s / seconds) ds`` by Gauss-Legendre (``rate`` of the fraction
    of the phase flown, in [0, 1], broadcast over a last axis of nodes)."""
    return 0.5 * np.asarray(seconds) * np.sum(rate(0.5 * (_NODES + 1.0)) * _WEIGHTS, axis=-1)


def spiral_arglat(a_from, a_to, inc, accel, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Argument of latitude [rad] turned during a tangential spiral ``a_from -> a_to`` [m]
    at inclination ``inc`` [rad], thrust acceleration ``accel`` [m/s^2] (first-order J2
    rates at the radius reached: ``V(t) = V_from -+ f t``)."""
    v_from, v_to, inc = np.broadcast_arrays(circular_speed(a_from, mu=mu),
                                            circular_speed(a_to, mu=mu), np.asarray(inc, float))

    def rate(fraction):
        speed = v_from[..., None] + (v_to - v_from)[..., None] * fraction
        return secular_rates(mu / speed**2, 0.0, inc[..., None], j2=j2, mu=mu, r_eq=r_eq).arglat

    return _quadrature(rate, np.abs(v_from - v_to) / accel)


def plane_change_arglat(a, inc_from, inc_to, accel, *, j2=J2, mu=MU_EARTH, r_eq=R_EARTH):
    """Argument of latitude [rad] turned during the plane change ``inc_from -> inc_to``
    [rad] at radius ``a`` [m] (inclination linear in time, Edelbaum)."""
    seconds = plane_change_dv(a, inc_from, inc_to, mu=mu) / accel
    a, inc_from, inc_to = np.broadcast_arrays(*(np.asarray(x, float) for x in (a, inc_from,
                                                                              inc_to)))

    def rate(fraction):
        inc = inc_from[..., None] + (inc_to - inc_from)[..., None] * fraction
        return secular_rates(a[..., None], 0.0, inc, j2=j2, mu=mu, r_eq=r_eq).arglat

    return _quadrature(rate, seconds)


def low_thrust_leg_at(origin: MeanOrbit, target: MeanOrbit, t_depart, a_drift, inc_drift,
                      accel, *, laps=0, drift_factors=(1.0, 1.0), j2=J2, mu=MU_EARTH,
                      r_eq=R_EARTH) -> dict:  # fmt: skip
    """The low-thrust leg leaving at ``t_depart`` on drift radius ``a_drift`` (broadcast).

    Parameters
    ----------
    origin, target : MeanOrbit
        The vehicle's orbit before it leaves, and the target's.
    t_depart : array_like
        Start of spiral A [s after t0].
    a_drift, inc_drift : array_like
        Coast radius [m] and inclination [rad] (``origin.inc`` or ``target.inc``).
    accel : float
        Thrust acceleration [m/s^2].
    laps : int
        Relative laps of the coast beyond the first that closes the RAAN gap.
    drift_factors : (float, float)
        The coast's RAAN and argument-of-latitude rates as flown, over the first-order
        rates (:func:`sdc_cvx.flight.rates.drift_factors`).

    Returns
    -------
    dict of ndarray
        ``t_a``, ``t_b``, ``t_c``, ``t_d`` (phase durations [s]; ``t_c`` NaN where the
        coast's and the target's RAAN rates are equal), ``arrive`` [s], ``dv`` [m/s],
        ``phase_error`` [rad, (-pi, pi]].
    """
    consts = dict(j2=j2, mu=mu, r_eq=r_eq)
    t0 = np.asarray(t_depart, dtype=float)
    a_d, i_d = np.asarray(a_drift, dtype=float), np.asarray(inc_drift, dtype=float)
    dv_a = spiral_dv(origin.a, a_d, mu=mu)
    dv_b = plane_change_dv(a_d, origin.inc, target.inc, mu=mu)
    dv_d = spiral_dv(a_d, target.a, mu=mu)
    t_a, t_b, t_d = dv_a / accel, dv_b / accel, dv_d / accel
    raan_thrust = (spiral_raan_change(origin.a, a_d, origin.inc, accel, **consts)
                   + plane_change_raan_change(a_d, origin.inc, target.inc, accel, **consts)
                   + spiral_raan_change(a_d, target.a, target.inc, accel, **consts))  # fmt: skip
    coast = secular_rates(a_d, 0.0, i_d, **consts)
    thrust = t_a + t_b + t_d
    gap = target.raan_at(t0 + thrust) - origin.raan_at(t0) - raan_thrust
    t_c = _coast(gap, coast.raan * drift_factors[0] - target.raan_rate, laps)
    if target.wander is not None:  # its RAAN's mean rate over that coast, once more
        turned = target.raan_at(t0 + thrust + t_c) - target.raan_at(t0 + thrust)
        with np.errstate(divide="ignore", invalid="ignore"):
            mean_rate = np.where(t_c > 1.0, turned / t_c, target.raan_rate)
        t_c = _coast(gap, coast.raan * drift_factors[0] - mean_rate, laps)
    arrive = t0 + thrust + t_c
    arglat = (origin.arglat_at(t0) + spiral_arglat(origin.a, a_d, origin.inc, accel, **consts)
              + plane_change_arglat(a_d, origin.inc, target.inc, accel, **consts)
              + coast.arglat * drift_factors[1] * t_c
              + spiral_arglat(a_d, target.a, target.inc, accel, **consts))  # fmt: skip
    return {"t_a": t_a, "t_b": t_b, "t_c": t_c, "t_d": t_d, "arrive": arrive,
            "dv": dv_a + dv_b + dv_d,
            "phase_error": _wrap_pi(target.arglat_at(arrive) - arglat)}  # fmt: skip


def _coast(gap, rel, laps):
    """The coast [s] that closes the RAAN ``gap`` [rad] at the relative rate ``rel``
    [rad/s], ``laps`` whole turns more (NaN where ``rel`` is 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t_c = (wrap_angle(gap, rel) + np.sign(rel) * laps * TWO_PI) / rel
    return np.where(rel != 0.0, np.maximum(t_c, 0.0), np.nan)


def as_leg_plan(origin: MeanOrbit, target: MeanOrbit, t_depart, a_drift, inc_drift,
                leg: dict) -> LowThrustLegPlan:  # fmt: skip
    """The epochs of one leg of :func:`low_thrust_leg_at` (scalars): the plane change
    right after spiral A when the coast has the target's inclination (the nearer of the
    two), else right before spiral D (:mod:`~sdc_cvx.physics.low_thrust`)."""
    t_a, t_b, t_c, t_d = (float(leg[name]) for name in ("t_a", "t_b", "t_c", "t_d"))
    t0 = float(t_depart)
    plane_first = abs(inc_drift - target.inc) < abs(inc_drift - origin.inc) and t_b > 0.0
    coast_start = t0 + t_a + (t_b if plane_first else 0.0)
    coast_end = coast_start + t_c
    plane_start = t0 + t_a if plane_first else coast_end
    spiral_in = coast_end + (0.0 if plane_first else t_b)
    return LowThrustLegPlan(t0, plane_start, t_b, coast_start, coast_end, spiral_in,
                            spiral_in + t_d, float(a_drift), float(inc_drift),
                            float(leg["dv"]), float(leg["phase_error"]))  # fmt: skip


def phase_low_thrust_leg(origin: MeanOrbit, target: MeanOrbit, t_ready, a_drift, inc_drift,
                         accel, *, laps=0, drift_factors=(1.0, 1.0), a_bounds=(0.0, np.inf),
                         latest_arrival=np.inf, late_cost=LATE_COST_MPS_PER_DAY,
                         spans=RADIUS_SPANS_M, delays_days=DELAYS_DAYS, j2=J2, mu=MU_EARTH,
                         r_eq=R_EARTH) -> tuple[LowThrustLegPlan, bool]:  # fmt: skip
    """The cheapest phased low-thrust leg near the plan's drift orbit (module docstring).

    Parameters
    ----------
    origin, target, accel, laps, drift_factors
        As :func:`low_thrust_leg_at`.
    t_ready : float
        Earliest departure [s after t0].
    a_drift, inc_drift : float
        The plan's coast orbit [m, rad]: the radius is searched within ``spans`` of it,
        the inclination kept.
    a_bounds : (float, float)
        Drift radii allowed [m] (the mission's altitude bounds).
    latest_arrival : float
        Latest rendezvous epoch the mission can spare [s after t0].
    late_cost : float
        When no phased leg arrives by ``latest_arrival``: the ΔV [m/s] a day of lateness
        is worth, to choose among the late ones.
    spans : sequence of float
        Half-widths [m] of the brackets of radii tried, one after the other.
    delays_days : sequence of float
        Departure delays tried [days], one after the other.

    Returns
    -------
    (LowThrustLegPlan, bool)
        The cheapest phased leg arriving by ``latest_arrival`` (over every delay, in the
        first bracket that has one), and True; or, when none does, the one of least ΔV plus
        ``late_cost`` per day late, of all those tried, and False.

    Raises
    ------
    ValueError
        No drift radius in the brackets and no delay brings the vehicle to the target.
    """
    consts = dict(laps=laps, drift_factors=drift_factors, j2=j2, mu=mu, r_eq=r_eq)

    def leg_at(delay, radius):
        return low_thrust_leg_at(origin, target, t_ready + delay, radius, inc_drift, accel,
                                 **consts)  # fmt: skip

    found, in_time = [], False  # (radii, delays) of every bracket and delay tried
    for span in spans:  # every delay of a bracket; the next bracket only if none is in time
        low, high = max(a_drift - span, a_bounds[0]), min(a_drift + span, a_bounds[1])
        grid = np.linspace(low, high, RADIUS_POINTS)
        for delay in np.asarray(delays_days, dtype=float) * 86400.0:
            roots, delays = grid_zeros(lambda d, r: leg_at(d, r)["phase_error"], grid,
                                       np.array([delay]))  # fmt: skip
            good = np.abs(leg_at(delays, roots)["phase_error"]) < PHASE_TOL_RAD
            if good.any():
                found.append((roots[good], delays[good]))
                in_time |= bool((leg_at(delays[good], roots[good])["arrive"]
                                 <= latest_arrival).any())  # fmt: skip
        if in_time:
            break
    if not found:
        raise ValueError(f"no drift radius within {spans[-1] / 1e3:g} km of the plan's and no "
                         f"departure within {max(delays_days):g} days meets the target")
    roots = np.concatenate([f[0] for f in found])
    delays = np.concatenate([f[1] for f in found])
    legs = leg_at(delays, roots)
    late_days = np.maximum(legs["arrive"] - latest_arrival, 0.0) / 86400.0
    pick = int(np.argmin(np.where(late_days > 0, np.inf, legs["dv"]) if in_time
                         else legs["dv"] + late_cost * late_days))  # fmt: skip
    chosen = {name: value[pick] for name, value in legs.items()}
    return as_leg_plan(origin, target, t_ready + delays[pick], roots[pick], inc_drift,
                       chosen), in_time  # fmt: skip
