"""A flown mission as GTOC9 events (:func:`flight_events`), to write with
:func:`~sdc_cvx.gtoc9.mission_file.write_mission_file`.

A flight of GTOC9 debris (:func:`sdc_cvx.flight.fly` on a catalog read from GTOC9's file)
is in GTOC9's frame already (``flight.frame == "EME2000"``, the frame of its elements).
Its events:

- the launch: the arrival at the first leg's origin at the flight's start (the state the
  flight starts from, no impulse);
- each leg's ``depart`` impulse: the departure from the leg's origin; its ``arrive``
  impulse: the arrival at its target; every other impulse (``burn``, ``trim``,
  ``approach``, ``correction``): a deep-space manoeuvre (``-1``);
- the end: the departure from the last debris at the flight's end (no impulse).

The state before each impulse is the last sample of the trajectory segment that ends at
its epoch (a segment is an arc between impulses).  Whether the file is valid GTOC9 is
:mod:`.check`'s to say: a flight's trims at a debris are impulses during a stay, and its
stays last what its plan gave them.
"""

from __future__ import annotations

import numpy as np

from ..errors import MissionError
from .debris import MJD2000
from .mission_file import Event
from .rules import DSM

GTOC9_FLIGHT_FRAME = "EME2000"
"""The frame name a flight of GTOC9 debris carries (:mod:`sdc_cvx.flight.gtoc9_ephemeris`)."""


def flight_events(flight) -> list[Event]:
    """The GTOC9 events of a :class:`~sdc_cvx.flight.result.Flight` (module docstring).

    Raises
    ------
    MissionError
        The flight is not in GTOC9's frame, has a thrust arc (GTOC9's manoeuvres are
        impulses), or has an impulse no trajectory segment ends at.
    """
    if getattr(flight, "frame", None) != GTOC9_FLIGHT_FRAME:
        raise MissionError(f"flight in frame {getattr(flight, 'frame', None)!r}; expected "
                           f"{GTOC9_FLIGHT_FRAME!r} (a flight of GTOC9's debris file)")  # fmt: skip
    start = (flight.plan.start - MJD2000).total_seconds() / 86400.0
    legs = flight.plan.legs
    segments = [(np.asarray(t, float), np.asarray(r, float), np.asarray(v, float))
                for t, r, v in flight.segments]  # fmt: skip
    if not segments or not legs:
        raise MissionError("a flight with no trajectory or no leg has no GTOC9 events")

    def epoch(seconds: float) -> float:
        return start + seconds / 86400.0

    t0, r0, v0 = segments[0]
    events = [Event(epoch(t0[0]), r0[0], v0[0], (0.0, 0.0, 0.0), int(legs[0].from_id))]
    for maneuver in flight.maneuvers:
        if maneuver.end_s is not None:
            raise MissionError(f"leg {maneuver.leg}: a thrust arc ({maneuver.kind} at "
                               f"{maneuver.epoch_s:.3f} s); expected impulses only")  # fmt: skip
        leg = legs[maneuver.leg - 1]
        ident = {"depart": int(leg.from_id), "arrive": int(leg.to_id)}.get(maneuver.kind, DSM)
        ending = [s for s in segments if abs(s[0][-1] - maneuver.epoch_s) <= 1e-6]
        if not ending:
            raise MissionError(f"leg {maneuver.leg}: no trajectory segment ends at the "
                               f"{maneuver.kind} impulse ({maneuver.epoch_s:.6f} s)")  # fmt: skip
        _, r, v = ending[0]
        events.append(Event(epoch(maneuver.epoch_s), r[-1], v[-1], maneuver.dv_gcrf, ident))
    t1, r1, v1 = segments[-1]
    events.append(Event(epoch(t1[-1]), r1[-1], v1[-1], (0.0, 0.0, 0.0), int(legs[-1].to_id)))
    return events
