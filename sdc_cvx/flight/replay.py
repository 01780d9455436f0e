"""Fly a plan: each leg guided to its debris, the vehicle propagated, the real debris met.

For each leg, from the debris the vehicle is at (issue 46):

- an **impulsive** leg is flown by optimised closed-loop guidance
  (:class:`~sdc_cvx.flight.guidance.LegGuidance`): a multi-impulse rendezvous planned in
  mean elements (free epochs and vectors, seeded by the plan's leg), flown impulse by
  impulse with re-plans from the measured state, trimmed on long coasts, its approach
  targeted in the force model itself: the debris met within metres, its velocity matched;
- a **low-thrust** leg is phased and flown as thrust arcs
  (:mod:`~sdc_cvx.flight.thrust_legs`), then its rendezvous closed by correction arcs
  (:mod:`~sdc_cvx.flight.thrust_corrections`).

The schedule: a leg leaves when the vehicle is ready, at the plan's departure moved by
how early or late the previous arrival was (never before it); it arrives at the latest by
the plan's arrival plus what the mission's T_max leaves over; a leg of the plan shorter
than :data:`MIN_FLIGHT_DAYS` (RAANs that meet on the previous arrival's day: the plan's
zero-length legs) gets that long, the legs after it absorbing the delay.  Between a
rendezvous and the next departure (the plan's stay, at least :data:`MIN_STAY_S`) the
vehicle coasts in the force model: the proximity operations of a stay are not modelled,
and every arc of the trajectory files is one a J2 replay reproduces.

The flown ΔV is the sum of the impulses (and arcs) as flown.  Per leg, ``phasing_dv`` is
the guided leg's planned cost (impulsive: the mean-element rendezvous; low thrust: the
phased leg in the mean model) less the plan's, and ``correction_dv`` the rest: plan +
phasing + correction = flown, leg by leg.

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

from ..physics.orbits import SECONDS_PER_DAY
from ..physics.phasing import MeanOrbit
from . import thrust_legs
from .corrections import debris_orbit
from .ephemeris import debris_ephemeris
from .frames import earth_pole_gcrf, equatorial_basis
from .guidance import GuidanceError, LegGuidance, LegWindow
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
"""Time a low-thrust leg's corrections after its arrival take [days] (about 7 orbits): a
leg followed by less stay at its debris aims to arrive that much earlier."""
HOPELESS_DAYS = 30.0
"""A leg that cannot arrive within this many days after T_max is not flown."""
MIN_STAY_S = 60.0
"""A leg leaves at least this long [s] after the last arrival (the state at a rendezvous
epoch is the rendezvous', not the next departure's) or the flight's start (the
trajectory's first state is the debris', before any impulse)."""
MIN_FLIGHT_DAYS = 10.0
"""Flight time [days] a leg of the plan shorter than this gets (a zero-length leg's
rendezvous needs weeks to phase cheaply; measured in ``benchmarks/flight.py``)."""


def fly(plan: FlightPlan, *, force: str = "j2", rates: str = "fitted", ephemeris=None,
        progress=None) -> Flight:  # fmt: skip
    """Fly ``plan`` against its debris' ephemeris (module docstring).

    Parameters
    ----------
    plan : FlightPlan
    force : {"j2", "j2-j4", "j2-j4-drag"}
        The vehicle's force model (:meth:`ForceModel.named`).
    rates : {"fitted", "model"}
        The mean rates the guidance uses (:mod:`~sdc_cvx.flight.rates`): measured in the
        force model (the drift orbit's) and on the debris' ephemeris (the default), or the
        first-order J2 rates of the model (the planner's: the replay then shows what
        they miss).
    ephemeris : optional
        Where the debris are: default the catalog's own (:func:`debris_ephemeris`: SGP4,
        or GTOC9's); anything with ``state(position, seconds)``, ``arglat_at_start()``,
        ``a_m`` and ``pole_at(seconds)`` will do.
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
        ephemeris = debris_ephemeris(plan.catalog, low_thrust=plan.accel_mps2 is not None)
    ids = plan.catalog.frame["id"].astype(str).tolist()
    slack = max(plan.tmax_days - plan.plan_end_day, 0.0) * SECONDS_PER_DAY
    t0 = plan.legs[0].departure_day * SECONDS_PER_DAY
    r0, v0 = ephemeris.state(0, np.array([t0]))
    track = Track(t0, r0[0], v0[0])
    maneuvers, meetings = [], []
    delay = 0.0  # how much later than the plan the last leg arrived [s]
    notes = list(plan.notes)  # first: the last note says why a flight is incomplete
    if plan.accel_mps2 is not None and getattr(plan.catalog, "ephemeris", "") == "gtoc9":
        notes.append("a low-thrust flight meets GTOC9's debris as SGP4 sets of their elements "
                     "(it closes by co-orbiting, which GTOC9's ephemeris allows no J2 orbit)")
    for k, leg in enumerate(plan.legs):
        t_ready = max(leg.departure_day * SECONDS_PER_DAY + delay, track.t)
        if plan.accel_mps2 is None:  # never at an arrival's epoch (its state is the check),
            t_ready = max(t_ready, track.t + MIN_STAY_S)  # nor at the trajectory's first
        pole = _pole(plan, ephemeris, t_ready + 0.5 * leg.duration_days * SECONDS_PER_DAY)
        if plan.accel_mps2 is None:
            track.coast(t_ready, model, pole)  # the stay: proximity operations not modelled
        if plan.accel_mps2 is None:
            window = _window(plan, k, t_ready, slack)
            if window.latest > (plan.tmax_days + HOPELESS_DAYS) * SECONDS_PER_DAY:
                notes.append(_hopeless(k, ids, window.latest, plan))
                break
            try:
                flown = _guided(track, k, leg, window, ephemeris, model, pole, rates)
            except GuidanceError as err:
                notes.append(f"leg {k + 1} ({ids[k]} -> {ids[k + 1]}): {err}: not flown, nor "
                             "the legs after it")  # fmt: skip
                break
        else:
            flown = _thrust_leg(track, k, t_ready, plan, ephemeris, model, pole, rates, slack,
                                consts, notes)  # fmt: skip
            if flown is None:
                break
        maneuvers += flown["maneuvers"]
        meeting = flown["meeting"]
        phasing = flown["model_dv"] - flown["point_dv"]
        correction = sum(m.dv_mps for m in flown["maneuvers"]) - leg.dv_mps - phasing
        # as flown: the arrive impulse against the plan's arrival, and the rendezvous
        # done by the plan's departure from the debris
        arrived = next(m.epoch_s for m in flown["maneuvers"] if m.kind == "arrive")
        late = (arrived - leg.arrival_day * SECONDS_PER_DAY) / SECONDS_PER_DAY
        stay = (plan.legs[k + 1].departure_day if k + 1 < len(plan.legs)
                else plan.plan_end_day) - leg.arrival_day  # fmt: skip
        on_schedule = meeting["epoch_s"] <= (leg.arrival_day + stay) * SECONDS_PER_DAY + 1.0
        meetings.append(Rendezvous(
            target=ids[k + 1], **meeting, correction_dv_mps=correction,
            phasing_shift_h=float(flown["depart"] - t_ready) / 3600.0, phasing_dv_mps=phasing,
            delay_days=late, in_time=bool(on_schedule),
        ))  # fmt: skip
        delay = flown["arrive"] - leg.arrival_day * SECONDS_PER_DAY
        if progress is not None:
            progress(f"leg {k + 1}/{len(plan.legs)} {ids[k]} -> {ids[k + 1]}: miss "
                     f"{meeting['miss_km'] * 1e3:.1f} m, phasing {phasing:+.2f} m/s, "
                     f"correction {correction:+.2f} m/s, {late:+.2f} d")  # fmt: skip
    end = track.t + 2.0 * np.pi * np.sqrt(ephemeris.a_m[len(meetings)] ** 3 / model.mu)
    track.coast(end, model, _pole(plan, ephemeris, end))  # one more orbit with the last debris
    if plan.accel_mps2 is not None:  # first: the last note says why a flight is incomplete
        notes.insert(0, thrust_legs.impulse_note(maneuvers, plan.accel_mps2))
    return Flight(plan=plan, maneuvers=tuple(maneuvers), rendezvous=tuple(meetings),
                  segments=tuple(track.segments), force=model, rates=rates, notes=tuple(notes),
                  seconds=time.perf_counter() - started,
                  frame=getattr(ephemeris, "frame_name", "GCRF"))  # fmt: skip


def _window(plan: FlightPlan, k: int, t_ready: float, slack: float) -> LegWindow:
    """Leg ``k``'s window: ready at ``t_ready``, the rendezvous by the plan's arrival plus
    the mission's ``slack`` [s], and at least :data:`MIN_FLIGHT_DAYS` after ``t_ready``
    where the plan's leg is shorter or its arrival has passed; aimed at the plan's
    arrival, or that minimum."""
    leg = plan.legs[k]
    t_plan = leg.arrival_day * SECONDS_PER_DAY
    shortest = t_ready + MIN_FLIGHT_DAYS * SECONDS_PER_DAY
    aim = t_plan if t_plan - t_ready >= MIN_FLIGHT_DAYS * SECONDS_PER_DAY else shortest
    return LegWindow(t_ready, max(t_plan + slack, aim), aim)


def _hopeless(k: int, ids, latest: float, plan: FlightPlan) -> str:
    return (f"leg {k + 1} ({ids[k]} -> {ids[k + 1]}) cannot arrive before day "
            f"{latest / SECONDS_PER_DAY:.0f} (T_max {plan.tmax_days:g}): not flown, nor the "
            "legs after it")  # fmt: skip


def _guided(track: Track, k: int, leg, window: LegWindow, ephemeris, model: ForceModel, pole,
            rates: str) -> dict:  # fmt: skip
    """Impulsive leg ``k`` by :class:`~sdc_cvx.flight.guidance.LegGuidance`."""
    a_plan, i_plan = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
    factors = (drift_factors(a_plan, i_plan, window.t_ready, model, pole)
               if rates == "fitted" else (1.0, 1.0))  # fmt: skip
    guidance = LegGuidance(track, k + 1, leg, k + 1, window, ephemeris, model, pole,
                           equatorial_basis(pole), (factors[0], 1.0, factors[1]))  # fmt: skip
    flown = guidance.fly()
    meeting = _met(track, k, ephemeris, model, pole)
    return {"maneuvers": flown, "meeting": meeting, "model_dv": guidance.first.total_mps,
            "point_dv": leg.dv_mps, "depart": float(guidance.first.epochs[0]),
            "arrive": float(track.t)}  # fmt: skip


def _met(track: Track, k: int, ephemeris, model: ForceModel, pole) -> dict:
    """The rendezvous with debris ``k + 1`` as measured now: the distance and the velocity
    difference, and the orbit-averaged a, i and RAAN differences."""
    r_goal, v_goal = debris_orbit(ephemeris, k + 1, track.t, model)
    goal_orbit = orbit_average(r_goal, v_goal, mu=model.mu, pole=pole)
    r_d, v_d = ephemeris.state(k + 1, np.array([track.t]))
    return _differences(track, goal_orbit, model, pole) | {
        "epoch_s": track.t,
        "miss_km": float(np.linalg.norm(track.r - r_d[0]) / 1e3),
        "miss_mps": float(np.linalg.norm(track.v - v_d[0])),
    }


def _thrust_leg(track: Track, k: int, t_ready: float, plan: FlightPlan, ephemeris,
                model: ForceModel, pole, rates: str, slack: float, consts: dict,
                notes: list) -> dict | None:  # fmt: skip
    """Low-thrust leg ``k``, ready at ``t_ready`` [s]: phased, flown as thrust arcs, its
    rendezvous corrected; None (a note said why) when it cannot arrive near T_max."""
    leg = plan.legs[k]
    ids = plan.catalog.frame["id"].astype(str).tolist()
    arglat0 = ephemeris.arglat_at_start()
    rows = plan.catalog.frame.iloc[[k, k + 1]]
    orbits = [MeanOrbit.from_elements(row.a_km * 1e3, row.e, np.radians(row.inc_deg),
                                      np.radians(row.raan_deg), arglat0[k + j], **consts)
              for j, row in enumerate(rows.itertuples())]  # fmt: skip
    bounds = tuple(model.r_eq + 1e3 * h for h in plan.drift_altitude_km)
    a_plan, i_plan = leg.drift_a_km * 1e3, np.radians(leg.drift_inc_deg)
    stay = (plan.legs[k + 1].departure_day if k + 1 < len(plan.legs)
            else plan.plan_end_day) - leg.arrival_day  # fmt: skip
    on_time = (leg.arrival_day - max(CORRECTION_DAYS - stay, 0.0)) * SECONDS_PER_DAY
    latest = on_time + slack
    origin = _vehicle_orbit(track, orbits[0], model, pole)
    target, factors = placed_orbit(ephemeris, k + 1, t_ready, orbits[1], model, pole), (1.0, 1.0)
    if rates == "fitted":
        target = fitted_orbit(ephemeris, k + 1, t_ready, latest + SECONDS_PER_DAY, target,
                              model, pole)  # fmt: skip
        factors = drift_factors(a_plan, i_plan, t_ready, model, pole)
    step = thrust_legs.phase(origin, target, t_ready, leg, plan.accel_mps2, factors, bounds,
                             on_time, latest, consts)  # fmt: skip
    if step["note"]:
        notes.append(f"leg {k + 1}: {step['note']}")
    if step["arrive"] > (plan.tmax_days + HOPELESS_DAYS) * SECONDS_PER_DAY:
        notes.append(_hopeless(k, ids, step["arrive"], plan))
        return None
    r_goal, v_goal = debris_orbit(ephemeris, k + 1, step["arrive"], model)
    goal_orbit = orbit_average(r_goal, v_goal, mu=model.mu, pole=pole)
    out = thrust_legs.fly_leg(track, k + 1, step["phased"], goal_orbit, plan.accel_mps2, model,
                              pole, ephemeris)  # fmt: skip
    differences = _differences(track, goal_orbit, model, pole)
    for correct in (thrust_eccentricity, thrust_plane, thrust_semi_major_axis, thrust_phase):
        out += correct(track, k + 1, ephemeris, k + 1, plan.accel_mps2, model, pole)
    r_d, v_d = ephemeris.state(k + 1, np.array([track.t]))
    meeting = differences | {
        "epoch_s": track.t,  # the rendezvous: the vehicle on the debris' orbit
        "miss_km": float(np.linalg.norm(track.r - r_d[0]) / 1e3),
        "miss_mps": float(np.linalg.norm(track.v - v_d[0])),
    }
    return {"maneuvers": [m for m in out if m is not None], "meeting": meeting,
            "model_dv": step["model_dv"], "point_dv": step["point_dv"],
            "depart": step["depart"], "arrive": step["arrive"]}  # fmt: skip


def _pole(plan: FlightPlan, ephemeris, t: float) -> np.ndarray:
    """The axis J2 is about at ``t`` [s after day 0], held over a leg: the Earth's rotation
    axis in GCRF (it moves about 1e-4 rad a year), or GTOC9's z axis
    (``ephemeris.pole_at``; an ephemeris without one is in the GCRF)."""
    pole_at = getattr(ephemeris, "pole_at", None)
    if pole_at is None:
        return earth_pole_gcrf(plan.start + pd.to_timedelta([t], unit="s"))[0]
    return np.asarray(pole_at(t), dtype=float)


def _vehicle_orbit(track: Track, guess: MeanOrbit, model: ForceModel, pole) -> MeanOrbit:
    """Where the vehicle is: its mean orbit over the next revolution (first-order rates,
    which carry it only the few hours to its departure node)."""
    now = propagated_mean_state(track.r, track.v, track.t, model, pole)
    mine = MeanOrbit.from_elements(now.a, guess.e, now.inc, now.raan, now.arglat, j2=model.j2,
                                   mu=model.mu, r_eq=model.r_eq)  # fmt: skip
    return mine._replace(raan=now.raan - mine.raan_rate * now.t,
                         arglat=now.arglat - mine.arglat_rate * now.t)


def _differences(track: Track, goal_orbit, model, pole) -> dict:
    """The vehicle's orbit-averaged a, i and RAAN less the debris' (``goal_orbit``)."""
    mine = averaged_orbit(track.r, track.v, track.t, model, pole=pole, samples=SAMPLES)
    draan = np.mod(mine.raan - goal_orbit.raan + np.pi, 2.0 * np.pi) - np.pi
    return {
        "da_km": float(mine.a - goal_orbit.a) / 1e3,
        "di_deg": float(np.degrees(mine.inc - goal_orbit.inc)),
        "draan_deg": float(np.degrees(draan)),
    }
