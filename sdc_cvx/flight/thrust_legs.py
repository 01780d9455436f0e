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
   radius, and the corrections, thrust arcs too
   (:mod:`~sdc_cvx.flight.thrust_corrections`).

The trims and ``arrive`` are flown as impulses: millimetres to centimetres per second,
which ``f`` delivers in seconds to minutes (an arc that short against an orbit acts as an
impulse); :func:`impulse_note` says how long.

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
from ..physics.low_thrust_phasing import (
    DELAYS_DAYS,
    LowThrustLegPlan,
    as_leg_plan,
    low_thrust_leg_at,
    phase_low_thrust_leg,
)
from ..physics.orbits import SECONDS_PER_DAY, circular_speed
from ..physics.phasing import MeanOrbit
from .corrections import (
    aim_at,
    debris_orbit,
    eccentricity_vector,
    in_node_frame,
    trim,
    trim_epochs,
)
from .propagation import ForceModel
from .rates import propagated_mean_state
from .thrust import Thrust
from .thrust_corrections import (
    eccentricity_change,
    thrust_eccentricity,
    thrust_semi_major_axis,
)
from .track import Track

COAST_MARGIN_S = 2.0 * SECONDS_PER_DAY
"""Time [s] the coast keeps after matching the eccentricity: the radius arc back onto the
coast's and the trims that phase the arrival."""


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
    # the plan's own departure is tried too: a vehicle ready early (an early arrival) that
    # left at once would find the RAANs where the plan does not have them
    early = (leg.departure_day * SECONDS_PER_DAY - t_ready) / SECONDS_PER_DAY
    delays = tuple(sorted(set(DELAYS_DAYS) | ({float(early)} if early > 0 else set())))
    consts = dict(consts, drift_factors=factors, laps=leg.laps, delays_days=delays)
    point = low_thrust_leg_at(origin, target, t_ready, a_plan, i_plan, accel,
                              **{k: v for k, v in consts.items() if k != "delays_days"})
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
    out += _coast_eccentricity(track, leg, phased, goal_orbit, accel, model, pole,
                               ephemeris)  # fmt: skip

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


def _coast_eccentricity(track: Track, leg: int, phased: LowThrustLegPlan, goal_orbit,
                        accel: float, model: ForceModel, pole, ephemeris) -> list:  # fmt: skip
    """At the start of a coast long enough for it, the eccentricity the debris will have at
    the arrival, turned back by the apsides' rotation on the coast (first-order J2 rate
    of the coast orbit, ``d(omega)/dt``, in the frame of each plane's node: the RAANs meet
    at the arrival), then the coast's radius again (the arcs leave a little ``da``).
    Matching the eccentricity takes days at low thrust, ``pi V |de| / (4 f)``; done on the
    coast it delays nothing, and what is left is closed after the arrival."""
    r_d, v_d = debris_orbit(ephemeris, leg, phased.arrive, model)
    goal = in_node_frame(np.mean(eccentricity_vector(r_d, v_d, mu=model.mu), axis=0),
                         goal_orbit.normal, pole)  # fmt: skip
    rate = secular_rates(phased.a_drift, 0.0, phased.inc_drift, j2=model.j2, mu=model.mu,
                         r_eq=model.r_eq).argp  # fmt: skip

    def wanted(t):
        turn = -rate * (phased.arrive - t)
        x, y = (np.cos(turn) * goal[0] - np.sin(turn) * goal[1],
                np.sin(turn) * goal[0] + np.cos(turn) * goal[1])
        normal = track.normal
        node = np.cross(pole, normal)
        node /= np.linalg.norm(node)
        return x * node + y * np.cross(normal, node)

    # the change from the vehicle's own eccentricity, not from a circle: a vehicle that
    # leaves an eccentric debris may need twice the debris' (the coast then ran out, and
    # the arcs went on past it: a GTOC9 leg arrived 2.3 deg of RAAN off)
    size = float(np.linalg.norm(eccentricity_change(track, wanted, model, pole)))
    needed = np.pi * circular_speed(phased.a_drift, mu=model.mu) * size / (4.0 * accel)
    room = phased.coast_end - COAST_MARGIN_S
    if room - track.t < needed:
        return []  # no room: after the arrival
    done = thrust_eccentricity(track, leg, ephemeris, leg, accel, model, pole, wanted=wanted,
                               until=room)  # fmt: skip
    return done + thrust_semi_major_axis(track, leg, ephemeris, leg, accel, model, pole,
                                         goal_m=phased.a_drift)


def _coast(track: Track, leg: int, t_leave: float, rest, ephemeris, model: ForceModel,
           pole) -> list:  # fmt: skip
    """Coast to ``t_leave`` [s], trimming the mean motion on the way
    (:data:`~sdc_cvx.flight.corrections.TRIMS`) so
    that the vehicle meets debris ``leg`` at the end of ``rest`` (the thrust arcs after the
    coast).  At each trim the rest of the leg is flown ahead on a copy of the track: the
    angle from the vehicle to the debris in its plane at that arrival ``t_a``, ``gap``, is
    closed by ``d(n) = gap / (t_a - t)``, i.e. a tangential impulse ``dv = v da / (2 a)``
    with ``da = -2/3 a d(n) / n`` (the offset in radius lasts until the arrival: the plane
    change keeps it, spiral D starts and ends that much later).  The thrust arcs' own
    errors, where a model of their argument of latitude would miss by a tenth of a
    radian, are then flown, not modelled."""
    trims = []
    for t_trim in trim_epochs(track.t, t_leave):
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
        trims.append(trim(track, leg, da, now.a))
    track.coast(t_leave, model, pole)
    return trims


def impulse_note(maneuvers, accel: float) -> str:
    """What the impulses of a low-thrust flight stand for: their ΔV and thrust time."""
    dv = sum(m.dv_mps for m in maneuvers if m.end_s is None)
    return (f"low thrust: the trims and arrivals ({dv:.3f} m/s) are flown as impulses; at "
            f"{accel:g} m/s^2 they take {dv / accel:.0f} s of thrust in all")  # fmt: skip
