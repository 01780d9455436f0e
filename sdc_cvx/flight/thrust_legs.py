"""Fly a low-thrust leg: its spirals and plane change as thrust arcs, then the rendezvous.

The leg of the plan (:mod:`~sdc_cvx.physics.low_thrust`) is first phased
(:func:`~sdc_cvx.physics.low_thrust_phasing.phase_low_thrust_leg`: the departure date and
coast radius that bring the vehicle to the debris itself), then flown through the
propagator with the vehicle's constant acceleration ``f``
(:mod:`~sdc_cvx.flight.thrust`):

1. ``spiral_out``: tangential thrust from the vehicle's mean radius to the coast's, for
   ``|V(a) - V(a_d)| / f``;
2. ``plane_change`` (right after it when the coast has the target's inclination, else
   right before spiral D): out-of-plane thrust switched at the antinodes, for
   ``(pi/2) V |dI| / f``, ``dI`` from the vehicle's mean inclination to the debris';
3. the coast, its mean motion trimmed on the way so that the vehicle meets the debris at
   the end of the leg, the rest of the leg flown ahead at each trim (:func:`_coast`);
4. ``spiral_in``: tangential thrust from the mean radius reached to the debris' (its orbit
   averaged as SGP4 flies it), then ``arrive``, the small impulse onto that averaged
   radius, and the corrections of :mod:`~sdc_cvx.flight.corrections`.

The trims, ``arrive`` and the corrections are flown as impulses: centimetres to a few
metres per second, which ``f`` delivers in minutes to hours (a thrust arc that short
against an orbit acts as an impulse to first order); :func:`impulse_note` says how long.

References
----------
.. [1] T. N. Edelbaum, "Propulsion Requirements for Controllable Satellites", ARS Journal
   31(8), 1079–1089, 1961.
.. [2] C. N. McGrath and M. Macdonald, "General Perturbation Method for Satellite
   Constellation Reconfiguration Using Low-Thrust Maneuvers", Journal of Guidance,
   Control, and Dynamics 42(8), 1676–1692, 2019.
"""

from __future__ import annotations

import numpy as np

from ..physics.elements import secular_rates
from ..physics.impulses import with_horizontal_speed
from ..physics.low_thrust_phasing import (
    LowThrustLegPlan,
    as_leg_plan,
    low_thrust_leg_at,
    phase_low_thrust_leg,
)
from ..physics.orbits import SECONDS_PER_DAY, circular_speed
from ..physics.phasing import MeanOrbit
from .corrections import aim_at
from .propagation import ForceModel
from .rates import propagated_mean_state
from .thrust import Thrust
from .track import Track

TRIMS = (0.5, 0.2, 0.05, 0.01)
"""When the coast's mean motion is trimmed: at these fractions of the coast left."""


def phase(origin: MeanOrbit, target: MeanOrbit, t_ready, leg, accel, factors, bounds, on_time,
          latest, consts) -> dict:  # fmt: skip
    """The phased low-thrust leg (as :func:`~sdc_cvx.flight.replay.fly` uses it): the plan
    point's and the phased leg's costs in the flight's mean model, whether it arrives in
    time, and a note when no phasing was found."""
    a_plan, i_plan = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
    # the plan coasts at the origin's or the target's inclination: the one flown is the
    # vehicle's, or the target's as SGP4 flies it (the catalog's differ from these mean
    # ones by up to 0.01 deg: 0.1 deg of RAAN over a 200-day coast)
    i_plan = target.inc if abs(i_plan - target.inc) < abs(i_plan - origin.inc) else origin.inc
    consts = dict(consts, drift_factors=factors, laps=leg.laps)
    point = low_thrust_leg_at(origin, target, t_ready, a_plan, i_plan, accel, **consts)
    note = None
    try:
        phased, in_time = phase_low_thrust_leg(origin, target, t_ready, a_plan, i_plan, accel,
                                               a_bounds=bounds, latest_arrival=on_time,
                                               **consts)  # fmt: skip
        if not in_time and latest > on_time:
            phased, in_time = phase_low_thrust_leg(origin, target, t_ready, a_plan, i_plan,
                                                   accel, a_bounds=bounds,
                                                   latest_arrival=latest, **consts)  # fmt: skip
    except ValueError:  # no phasing found: the plan's point, unphased
        phased, in_time = as_leg_plan(origin, target, t_ready, a_plan, i_plan, point), False
        note = "no phasing found; flown unphased"
    return {"phased": phased, "in_time": in_time, "point_dv": float(point["dv"]),
            "model_dv": phased.dv, "depart": phased.depart, "arrive": phased.arrive,
            "note": note}  # fmt: skip


def _spiral(track: Track, leg: int, kind: str, a_to: float, accel: float, model: ForceModel,
            pole):  # fmt: skip
    """A tangential arc from the vehicle's mean radius to ``a_to`` [m] (mean)."""
    now = propagated_mean_state(track.r, track.v, track.t, model, pole)
    dv = abs(circular_speed(now.a, mu=model.mu) - circular_speed(a_to, mu=model.mu))
    thrust = Thrust(accel, "tangential", 1.0 if a_to > now.a else -1.0)
    return track.thrust(track.t + dv / accel, thrust, model, pole, leg, kind)


def _plane_change(track: Track, leg: int, inc_to: float, accel: float, model: ForceModel,
                  pole):  # fmt: skip
    """An out-of-plane arc from the vehicle's mean inclination to ``inc_to`` [rad]."""
    now = propagated_mean_state(track.r, track.v, track.t, model, pole)
    dv = 0.5 * np.pi * circular_speed(now.a, mu=model.mu) * abs(inc_to - now.inc)
    thrust = Thrust(accel, "plane", 1.0 if inc_to > now.inc else -1.0)
    return track.thrust(track.t + dv / accel, thrust, model, pole, leg, "plane_change")


def fly_leg(track: Track, leg: int, phased: LowThrustLegPlan, goal_orbit, accel: float,
            model: ForceModel, pole, ephemeris) -> list:  # fmt: skip
    """The thrust arcs, trims and ``arrive`` impulse of low-thrust leg ``leg`` (1-based)
    as ``phased`` has it, towards ``goal_orbit`` (the debris' orbit averaged as SGP4 flies
    it) and debris ``leg`` of ``ephemeris`` (module docstring)."""
    track.coast(phased.depart, model, pole)
    out = [_spiral(track, leg, "spiral_out", phased.a_drift, accel, model, pole)]
    plane_first = phased.plane_seconds > 0.0 and phased.plane_start < phased.coast_start
    if plane_first:
        out.append(_plane_change(track, leg, goal_orbit.inc, accel, model, pole))

    def rest(flown: Track) -> list:  # what follows the coast
        arcs = []
        if not plane_first and phased.plane_seconds > 0.0:
            arcs.append(_plane_change(flown, leg, goal_orbit.inc, accel, model, pole))
        return arcs + [_spiral(flown, leg, "spiral_in", goal_orbit.a, accel, model, pole)]

    out += _coast(track, leg, phased.coast_end, rest, ephemeris, model, pole)
    out += rest(track)
    out.append(track.impulse(leg, "arrive", aim_at(track, model, pole, goal_orbit.a,
                                                   track.normal)))  # fmt: skip
    return [m for m in out if m is not None]


def _coast(track: Track, leg: int, t_leave: float, rest, ephemeris, model: ForceModel,
           pole) -> list:  # fmt: skip
    """Coast to ``t_leave`` [s], trimming the mean motion on the way (:data:`TRIMS`) so
    that the vehicle meets debris ``leg`` at the end of ``rest`` (the thrust arcs after the
    coast).  At each trim the rest of the leg is flown ahead on a copy of the track: the
    angle from the vehicle to the debris in its plane at that arrival ``t_a``, ``gap``, is
    closed by ``d(n) = gap / (t_a - t)``, i.e. a tangential impulse ``dv = v da / (2 a)``
    with ``da = -2/3 a d(n) / n`` (the offset in radius lasts until the arrival: the plane
    change keeps it, spiral D starts and ends that much later).  The thrust arcs' own
    errors, where a model of their argument of latitude would miss by a tenth of a
    radian, are then flown, not modelled."""
    trims = []
    start, span = track.t, t_leave - track.t
    for fraction in TRIMS:
        t_trim = t_leave - fraction * span
        if t_trim < start + 0.5 * SECONDS_PER_DAY or t_leave - t_trim < 0.25 * SECONDS_PER_DAY:
            continue
        track.coast(t_trim, model, pole)
        ahead = Track(track.t, track.r.copy(), track.v.copy())
        ahead.coast(t_leave, model, pole)
        rest(ahead)
        r_d, _ = ephemeris.state(leg, np.array([ahead.t]))
        gap = np.arctan2(np.dot(np.cross(ahead.r, r_d[0]), ahead.normal),
                         np.dot(ahead.r, r_d[0]))  # fmt: skip
        now = propagated_mean_state(track.r, track.v, track.t, model, pole)
        rate = secular_rates(now.a, 0.0, now.inc, j2=model.j2, mu=model.mu,
                             r_eq=model.r_eq).arglat  # fmt: skip
        da = -2.0 / 3.0 * now.a * (gap / (ahead.t - track.t)) / rate
        r_hat = track.r / np.linalg.norm(track.r)
        horizontal = np.linalg.norm(track.v - np.dot(track.v, r_hat) * r_hat)
        dv = 0.5 * np.linalg.norm(track.v) * da / now.a  # vis-viva, tangential
        trims.append(track.impulse(leg, "trim", with_horizontal_speed(
            track.r, track.v, track.normal, horizontal + dv)))  # fmt: skip
    track.coast(t_leave, model, pole)
    return trims


def impulse_note(maneuvers, accel: float) -> str:
    """What the impulses of a low-thrust flight stand for: their ΔV and thrust time."""
    dv = sum(m.dv_mps for m in maneuvers if m.end_s is None)
    return (f"low thrust: the trims, arrivals and corrections ({dv:.2f} m/s) are flown as "
            f"impulses; at {accel:g} m/s^2 they take {dv / accel / 3600.0:.1f} h of thrust "
            "in all")  # fmt: skip
