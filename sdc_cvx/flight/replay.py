"""Fly a plan: phase each leg, place its impulses, propagate the vehicle, meet the real debris.

For each leg (issue 26):

1. **Phasing** (:func:`~sdc_cvx.physics.phasing.phase_leg`): the departure node and the
   drift radius that bring the vehicle to the debris itself, in the mean-element model,
   arriving no later than the mission can spare.
2. **Impulses as vectors** (:mod:`~sdc_cvx.physics.impulses`), each computed from the
   vehicle's propagated state at its epoch: ``depart`` (onto the transfer orbit),
   ``drift`` (onto the drift orbit), ``trim`` (the drift's mean motion, so that the
   vehicle is at the node the phasing has at ``leave_drift``), ``leave_drift``,
   ``arrive`` (onto the target's orbit); each Hohmann transfer's plane change on its
   higher-radius impulse (Eq. 13).  ``drift`` and ``arrive`` aim at orbit-*averaged*
   semi-major axes (the drift's, then the debris' own as SGP4 flies it), by one-orbit
   shots: a mean element taken as an osculating one would miss by kilometres.  The two
   impulses of each transfer are unequal so that the eccentricity vector moves towards
   the target's on the way, at no cost within the transfer's ``|da/a|``
   (:func:`~sdc_cvx.flight.corrections.node_split`): the planner's circular model does
   not see eccentricities, which differ by up to 0.01 between debris.
3. **Rendezvous** (:mod:`~sdc_cvx.flight.corrections`): the ``correction`` impulses that
   close what is left, the eccentricity, the plane, then the along-track gap over a few
   orbits; the vehicle is then measured against the debris (SGP4, in GCRF): position and
   velocity miss, and the orbit-averaged differences of a, i and RAAN at the arrival.
4. The next leg leaves from where the vehicle is, when its corrections are done.

The flown ΔV is the sum of the impulses as flown.  Per leg, ``phasing_dv`` is the phased
leg's cost less the plan point's, both in the mean-element model of the flight, and
``correction_dv`` the rest: plan + phasing + correction = flown, leg by leg.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §6.6 (phasing), §9.6 (secular J2 effects).
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from ..physics.elements import secular_rates
from ..physics.impulses import (
    inclination,
    plane_towards,
    plane_with_inclination,
    with_horizontal_speed,
)
from ..physics.orbits import SECONDS_PER_DAY
from ..physics.phasing import MeanOrbit, leg_at, phase_leg
from . import thrust_legs
from .corrections import (
    aim_at,
    correct_eccentricity,
    correct_phase,
    correct_plane,
    debris_eccentricity,
    debris_orbit,
    eccentricity_vector,
    in_node_frame,
    mean_eccentricity,
    node_split,
    trim,
    trim_epochs,
)
from .ephemeris import DebrisEphemeris
from .frames import earth_pole_gcrf
from .plan import FlightPlan
from .propagation import ForceModel, averaged_orbit, orbit_average
from .rates import (
    RATE_MODES,
    SAMPLES,
    drift_factors,
    fitted_orbit,
    placed_orbit,
    propagated_mean_state,
)
from .result import Flight, Rendezvous
from .thrust_corrections import (
    thrust_eccentricity,
    thrust_phase,
    thrust_plane,
    thrust_semi_major_axis,
)
from .track import Track

CORRECTION_DAYS = 0.6
"""Time the corrections after an arrival take [days] (about 7 orbits): a leg followed by
less stay at its debris aims to arrive that much earlier."""
HOPELESS_DAYS = 30.0
"""A leg that cannot arrive within this many days after T_max is not flown."""


def fly(plan: FlightPlan, *, force: str = "j2", rates: str = "fitted", ephemeris=None,
        progress=None) -> Flight:  # fmt: skip
    """Fly ``plan`` through its phased impulses against the debris propagated by SGP4.

    Parameters
    ----------
    plan : FlightPlan
    force : {"j2", "j2-j4", "j2-j4-drag"}
        The vehicle's force model (:meth:`ForceModel.named`).
    rates : {"fitted", "model"}
        The mean rates the phasing uses (:mod:`~sdc_cvx.flight.rates`): measured on the
        debris' SGP4 states and a propagation of the drift orbit, or the first-order J2
        rates of the catalog's elements (the planner's).
    ephemeris : DebrisEphemeris, optional
        Where the debris are: default SGP4 from the catalog's elements; anything with
        its ``state(position, seconds)``, ``arglat_at_start()`` and ``a_m`` will do.
    progress : callable, optional
        Called with a line of text after each leg.

    Returns
    -------
    Flight
    """
    if rates not in RATE_MODES:
        raise ValueError(f"rates must be one of {RATE_MODES}, got {rates!r}")
    started = time.perf_counter()
    model = ForceModel.named(force)
    consts = dict(j2=model.j2, mu=model.mu, r_eq=model.r_eq)
    if ephemeris is None:
        ephemeris = DebrisEphemeris.from_catalog(plan.catalog)
    frame = plan.catalog.frame
    arglat0 = ephemeris.arglat_at_start()
    orbits = [MeanOrbit.from_elements(row.a_km * 1e3, row.e, np.radians(row.inc_deg),
                                      np.radians(row.raan_deg), arglat0[k], **consts)
              for k, row in enumerate(frame.itertuples())]  # fmt: skip
    ids = frame["id"].astype(str).tolist()
    bounds = tuple(model.r_eq + 1e3 * h for h in plan.drift_altitude_km)
    slack = max(plan.tmax_days - plan.plan_end_day, 0.0) * SECONDS_PER_DAY
    t0 = plan.legs[0].departure_day * SECONDS_PER_DAY
    r0, v0 = ephemeris.state(0, np.array([t0]))
    track = Track(t0, r0[0], v0[0])
    maneuvers, meetings = [], []
    delay = 0.0  # how much later than the plan the phased leg arrives [s]
    notes = list(plan.notes)  # first: the last note says why a flight is incomplete
    for k, leg in enumerate(plan.legs):
        t_ready = max(leg.departure_day * SECONDS_PER_DAY + delay, track.t)
        pole = _pole(plan, t_ready + 0.5 * leg.duration_days * SECONDS_PER_DAY)
        a_plan, i_plan = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
        # the plan's arrival, less the corrections' time where the plan has no operations to
        # hide them in; the mission's slack is spent only when that date cannot be kept
        # (spending it early, for a cheaper leg, leaves none to the legs after)
        stay = (plan.legs[k + 1].departure_day if k + 1 < len(plan.legs)
                else plan.plan_end_day) - leg.arrival_day  # fmt: skip
        on_time = (leg.arrival_day - max(CORRECTION_DAYS - stay, 0.0)) * SECONDS_PER_DAY
        latest = on_time + slack
        origin = _vehicle_orbit(track, orbits[k], model, pole)
        target, factors = placed_orbit(ephemeris, k + 1, t_ready, orbits[k + 1], model,
                                       pole), (1.0, 1.0)  # fmt: skip
        if rates == "fitted":
            target = fitted_orbit(ephemeris, k + 1, t_ready, latest + SECONDS_PER_DAY, target,
                                  model, pole)  # fmt: skip
            factors = drift_factors(a_plan, i_plan, t_ready, model, pole)
        consts["drift_factors"] = factors
        if plan.accel_mps2 is None:
            step = _phase(origin, target, t_ready, leg, bounds, on_time, latest, consts)
        else:
            step = thrust_legs.phase(origin, target, t_ready, leg, plan.accel_mps2, factors,
                                     bounds, on_time, latest, _physics(consts))  # fmt: skip
        if step["note"]:
            notes.append(f"leg {k + 1}: {step['note']}")
        if step["arrive"] > (plan.tmax_days + HOPELESS_DAYS) * SECONDS_PER_DAY:
            notes.append(f"leg {k + 1} ({ids[k]} -> {ids[k + 1]}) cannot arrive before day "
                         f"{step['arrive'] / SECONDS_PER_DAY:.0f} (T_max {plan.tmax_days:g}): "
                         "not flown, nor the legs after it")  # fmt: skip
            break
        flown = _fly_leg(track, k, step, origin, plan.accel_mps2, factors, ephemeris, model,
                         pole)  # fmt: skip
        maneuvers += flown["maneuvers"]
        meeting = flown["meeting"]
        # phasing: the phased leg's model cost less the plan point's (same model, same
        # orbits); correction: whatever else the flight took, so that plan + phasing +
        # correction = flown, leg by leg
        phasing = step["model_dv"] - step["point_dv"]
        correction = sum(m.dv_mps for m in flown["maneuvers"]) - leg.dv_mps - phasing
        # as flown: the arrive impulse against the plan's arrival, and the corrections
        # done by the plan's departure from the debris (the phasing's aim, step["in_time"])
        arrived = next(m.epoch_s for m in flown["maneuvers"] if m.kind == "arrive")
        late = (arrived - leg.arrival_day * SECONDS_PER_DAY) / SECONDS_PER_DAY
        on_schedule = meeting["epoch_s"] <= (leg.arrival_day + stay) * SECONDS_PER_DAY + 1.0
        meetings.append(Rendezvous(
            target=ids[k + 1], **meeting, correction_dv_mps=correction,
            phasing_shift_h=float(step["depart"] - t_ready) / 3600.0, phasing_dv_mps=phasing,
            delay_days=late, in_time=bool(on_schedule),
        ))  # fmt: skip
        # the next leg is ready the phased leg's delay after the plan's departure (a
        # low-thrust arrival flown hours to days off it leaves the plan's stay at the
        # debris as it was; the corrections' end bounds it anyway)
        delay = step["arrive"] - leg.arrival_day * SECONDS_PER_DAY
        if progress is not None:
            progress(f"leg {k + 1}/{len(plan.legs)} {ids[k]} -> {ids[k + 1]}: miss "
                     f"{meeting['miss_km']:.2f} km, phasing {phasing:+.2f} m/s, correction "
                     f"{correction:+.2f} m/s, {late:+.2f} d")  # fmt: skip
    end = track.t + 2.0 * np.pi / orbits[-1].arglat_rate  # one more orbit with the last debris
    track.coast(end, model, _pole(plan, end))
    if plan.accel_mps2 is not None:  # first: the last note says why a flight is incomplete
        notes.insert(0, thrust_legs.impulse_note(maneuvers, plan.accel_mps2))
    return Flight(plan=plan, maneuvers=tuple(maneuvers), rendezvous=tuple(meetings),
                  segments=tuple(track.segments), force=model, rates=rates, notes=tuple(notes),
                  seconds=time.perf_counter() - started)  # fmt: skip


def _physics(consts: dict) -> dict:
    return {name: consts[name] for name in ("j2", "mu", "r_eq")}


def _phase(origin: MeanOrbit, target: MeanOrbit, t_ready, leg, bounds, on_time, latest,
           consts) -> dict:  # fmt: skip
    """The phased impulsive leg: on the plan's date if it can; else within the mission's
    slack; else late (:func:`~sdc_cvx.physics.phasing.phase_leg`)."""
    a_plan, i_plan = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
    point = leg_at(origin, target, t_ready, a_plan, i_plan, 0, laps=leg.laps, **consts)
    # the phasing's extra ΔV is over the plan's point in the same model; where that point
    # does not arrive in time (a co-planar leg, whose RAANs the flight's model has a
    # hundredth of a degree on the other side: the plan's radius closes them years
    # later), over the plan's own ΔV
    point_dv = (float(point["impulses"].sum()) if point["epochs"][3] <= latest
                else leg.dv_mps)  # fmt: skip
    note = None
    try:
        phased, in_time = phase_leg(origin, target, t_ready, a_plan, i_plan, laps=leg.laps,
                                    a_bounds=bounds, latest_arrival=on_time, **consts)
        if not in_time and latest > on_time:
            phased, in_time = phase_leg(origin, target, t_ready, a_plan, i_plan,
                                        laps=leg.laps, a_bounds=bounds,
                                        latest_arrival=latest, **consts)  # fmt: skip
        epochs, a_drift, model_dv = phased.epochs, phased.a_drift, phased.dv
    except ValueError:  # no phasing found: the plan's point, unphased, flown as it is
        in_time, note = False, "no phasing found; flown unphased"
        epochs, a_drift, model_dv = point["epochs"], a_plan, float(point["impulses"].sum())
    return {"epochs": epochs, "a_drift": a_drift, "i_drift": i_plan, "in_time": in_time,
            "model_dv": model_dv, "point_dv": point_dv,
            "depart": float(epochs[0]), "arrive": float(epochs[3]), "note": note}  # fmt: skip


def _pole(plan: FlightPlan, t: float) -> np.ndarray:
    """Earth's rotation axis in GCRF at ``t`` [s after day 0] (constant over a leg: it
    moves about 1e-4 rad a year)."""
    return earth_pole_gcrf(plan.start + pd.to_timedelta([t], unit="s"))[0]


def _vehicle_orbit(track: Track, guess: MeanOrbit, model: ForceModel, pole) -> MeanOrbit:
    """Where the vehicle is: its mean orbit over the next revolution (first-order rates,
    which carry it only the few hours to its departure node)."""
    now = propagated_mean_state(track.r, track.v, track.t, model, pole)
    mine = MeanOrbit.from_elements(now.a, guess.e, now.inc, now.raan, now.arglat, j2=model.j2,
                                   mu=model.mu, r_eq=model.r_eq)  # fmt: skip
    return mine._replace(raan=now.raan - mine.raan_rate * now.t,
                         arglat=now.arglat - mine.arglat_rate * now.t)


def _tangential(track: Track, normal, a_to, a_from, de_along_node, model, pole):
    """The first impulse of a transfer from ``a_from`` to ``a_to`` [m] (mean), tangential,
    that also moves the eccentricity vector by ``de_along_node`` along the node line
    (:func:`~sdc_cvx.flight.corrections.node_split`); in the plane ``normal``."""
    r_hat = track.r / np.linalg.norm(track.r)
    radial = np.dot(track.v, r_hat)
    horizontal = np.linalg.norm(track.v - radial * r_hat)
    node = np.cross(pole, track.normal)
    sign = 1.0 if np.dot(r_hat, node) >= 0.0 else -1.0  # at the ascending node or not
    speed = np.linalg.norm(track.v)
    dv = speed * node_split((a_to - a_from) / a_from, de_along_node, sign)
    return with_horizontal_speed(track.r, track.v, normal, horizontal + dv)


def _drift(track: Track, leg: int, t_leave: float, factors, model: ForceModel,
           pole) -> list:  # fmt: skip
    """Coast on the drift orbit to ``t_leave`` [s], trimming its mean motion on the way so
    that the vehicle is at the node there, as the phasing has it
    (:data:`~sdc_cvx.flight.corrections.TRIMS`).

    At each trim the vehicle's mean state (one orbit averaged) and its measured rates
    predict its argument of latitude at ``t_leave``; a tangential impulse changes the
    semi-major axis by ``da = -2/3 a d(n) / n`` so that it reaches the nearest node
    (a multiple of pi) instead: millimetres per second, where an error of 1e-7 in the mean
    motion would put the vehicle 10 km off after half a year of coasting.
    """
    trims = []
    for t_trim in trim_epochs(track.t, t_leave):
        track.coast(t_trim, model, pole)
        now = propagated_mean_state(track.r, track.v, track.t, model, pole)
        rate = secular_rates(now.a, 0.0, now.inc, j2=model.j2, mu=model.mu,
                             r_eq=model.r_eq).arglat * factors[1]  # fmt: skip
        predicted = now.arglat + rate * (t_leave - now.t)
        error = np.pi * np.round(predicted / np.pi) - predicted
        da = -2.0 / 3.0 * now.a * (error / (t_leave - track.t)) / rate
        trims.append(trim(track, leg, da, now.a))
    track.coast(t_leave, model, pole)
    return trims


def _fly_leg(track: Track, k, step: dict, origin: MeanOrbit, accel, factors, ephemeris,
             model: ForceModel, pole) -> dict:  # fmt: skip
    """Leg ``k`` as ``step`` phased it (impulses, or thrust arcs when ``accel`` is given),
    the rendezvous and the correction."""
    # the target's orbit as SGP4 flies it, averaged over the orbit after the rendezvous
    r_goal, v_goal = debris_orbit(ephemeris, k + 1, step["arrive"], model)
    goal_orbit = orbit_average(r_goal, v_goal, mu=model.mu, pole=pole)
    if accel is None:
        goal_e = in_node_frame(np.mean(eccentricity_vector(r_goal, v_goal, mu=model.mu),
                                       axis=0), goal_orbit.normal, pole)  # fmt: skip
        out = _impulses(track, k + 1, step["epochs"], origin, step["a_drift"], step["i_drift"],
                        goal_orbit, goal_e, factors, model, pole)  # fmt: skip
    else:
        out = thrust_legs.fly_leg(track, k + 1, step["phased"], goal_orbit, accel, model, pole,
                                  ephemeris)  # fmt: skip
    return _rendezvous(track, k, out, goal_orbit, ephemeris, model, pole, accel)


def _impulses(track: Track, leg, epochs, origin: MeanOrbit, a_drift, i_drift, goal_orbit,
              goal_e, factors, model: ForceModel, pole) -> list:  # fmt: skip
    """The four impulses of an impulsive leg at ``epochs``, and the drift's trims."""
    out = []
    up_first = a_drift >= origin.a  # the plane change on the higher-radius impulse (Eq. 13)
    track.coast(epochs[0], model, pole)
    # the eccentricity: along the node line now, and along it again after the drift has
    # turned the apsides by `turn` (node_split: free within the transfers' room)
    turn = secular_rates(a_drift, 0.0, i_drift, j2=model.j2, mu=model.mu,
                         r_eq=model.r_eq).argp * (epochs[2] - epochs[1])  # fmt: skip
    now_e = in_node_frame(mean_eccentricity(track, model, pole), track.normal, pole)
    rotation = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]])
    wanted = goal_e - rotation @ now_e
    first_de = wanted[1] / np.sin(turn) if abs(np.sin(turn)) > 0.05 else 0.0
    plane = track.normal
    if not up_first:  # plane change now, to the drift inclination (its osculating offset kept)
        goal = inclination(track.r, track.v, pole) + (i_drift - origin.inc)
        plane = plane_with_inclination(track.r, track.v, pole, goal)
    out.append(track.impulse(leg, "depart", _tangential(
        track, plane, a_drift, origin.a, first_de, model, pole)))  # fmt: skip
    track.coast(epochs[1], model, pole)
    if up_first:
        goal = inclination(track.r, track.v, pole) + (i_drift - origin.inc)
        plane = plane_with_inclination(track.r, track.v, pole, goal)
    else:
        plane = plane_towards(track.r, track.v, plane)
    out.append(track.impulse(leg, "drift", aim_at(track, model, pole, a_drift, plane)))
    out += _drift(track, leg, epochs[2], factors, model, pole)
    plane = track.normal
    if goal_orbit.a < a_drift:  # going down: the plane change on this, higher, impulse
        plane = plane_towards(track.r, track.v, goal_orbit.normal)
    drift_e = in_node_frame(mean_eccentricity(track, model, pole), track.normal, pole)
    out.append(track.impulse(leg, "leave_drift", _tangential(
        track, plane, goal_orbit.a, a_drift, (goal_e - drift_e)[0], model, pole)))  # fmt: skip
    track.coast(epochs[3], model, pole)
    if goal_orbit.a >= a_drift:  # going up: the plane change on this impulse
        plane = plane_towards(track.r, track.v, goal_orbit.normal)
    else:
        plane = track.normal
    out.append(track.impulse(leg, "arrive", aim_at(track, model, pole, goal_orbit.a, plane)))
    return out


def _rendezvous(track: Track, k, out: list, goal_orbit, ephemeris, model: ForceModel, pole,
                accel=None) -> dict:  # fmt: skip
    """The arrival measured, then the corrections that close what is left (a low-thrust
    vehicle's as thrust arcs, :mod:`~sdc_cvx.flight.thrust_corrections`)."""
    leg = k + 1
    differences = _differences(track, goal_orbit, model, pole)
    if accel is not None:
        for correct in (thrust_eccentricity, thrust_plane, thrust_semi_major_axis,
                        thrust_phase):  # fmt: skip
            out += correct(track, leg, ephemeris, k + 1, accel, model, pole)
    else:
        wanted = debris_eccentricity(ephemeris, k + 1, track.t, model)
        out += correct_eccentricity(track, leg, wanted, model, pole)
        out.append(correct_plane(track, leg, ephemeris, k + 1, model, pole))
        out += correct_phase(track, leg, ephemeris, k + 1, model, pole)
    r_d, v_d = ephemeris.state(k + 1, np.array([track.t]))
    meeting = differences | {
        "epoch_s": track.t,  # the rendezvous: the vehicle on the debris' orbit
        "miss_km": float(np.linalg.norm(track.r - r_d[0]) / 1e3),
        "miss_mps": float(np.linalg.norm(track.v - v_d[0])),
    }
    return {"maneuvers": [m for m in out if m is not None], "meeting": meeting}


def _differences(track: Track, goal_orbit, model, pole) -> dict:
    """The vehicle's orbit-averaged a, i and RAAN less the debris' (``goal_orbit``)."""
    mine = averaged_orbit(track.r, track.v, track.t, model, pole=pole, samples=SAMPLES)
    draan = np.mod(mine.raan - goal_orbit.raan + np.pi, 2.0 * np.pi) - np.pi
    return {
        "da_km": float(mine.a - goal_orbit.a) / 1e3,
        "di_deg": float(np.degrees(mine.inc - goal_orbit.inc)),
        "draan_deg": float(np.degrees(draan)),
    }


