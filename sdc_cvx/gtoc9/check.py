"""Validate GTOC9 mission files as the competition did (issue 47, item 4).

:func:`check_folder` re-checks every ``mission_*.txt`` of a folder (or of its ``gtoc9/``
sub-folder) and :func:`check_mission` one mission:

- **format** - each line has the 11 fields of :mod:`.mission_file`; epochs never decrease
  (**order**); ids are GTOC9 debris (**debris**);
- **sequence** - a mission starts with an arrival at a debris (the launch delivers the
  spacecraft there), each arrival at a debris is followed by the departure from it (its
  id again) and the mission ends with a departure; deep-space manoeuvres (``-1``) only
  between a departure and the next arrival;
- **stay** - no impulse between an arrival and its departure (the spacecraft co-orbits the
  debris), and the departure at least ``t_w`` = 5 days after the arrival;
- **rendezvous** - at the arrival the position and the velocity after the impulse, at the
  departure the position and the velocity before it, coincide with the debris' GTOC9
  ephemeris (:class:`~sdc_cvx.flight.gtoc9_ephemeris.Gtoc9Ephemeris`) within
  ``ε_r`` = 100 m and ``ε_v`` = 1 m/s;
- **arc** - each arc (from an event's state plus its impulse to the next event) is
  propagated in GTOC9's dynamics (:mod:`.dynamics`); the state it ends in coincides with
  the next line's within ``ε_r`` and ``ε_v``;
- **perigee** - the osculating perigee radius stays >= 6600 km at every integration step
  of every arc (the stays are on the debris' own orbits, all above it);
- **dt-r** - consecutive rendezvous of a mission at most ``Δt_R`` = 30 days apart;
- **window** - the first event at or after MJD2000 23467, the last at or before 26419;
- **dt-m** - a mission's launch at least ``Δt_M`` = 30 days after every earlier mission's end;
- **propellant** - the launch mass ``m0`` from the mass chain, ``m0 - m_dry <= 5000 kg``;
- **once** - no debris removed twice in the folder; **all** (``require_all``) - each of
  the 123 removed.

Readings where GTOC9's statement is ambiguous
----------------------------------------------
- *Stays.*  GTOC9's equations page says that between an arrival and a departure the
  spacecraft co-orbits the debris, its state not given by the ODE: a stay is checked at its
  two events only (both against the ephemeris), never propagated.  (Propagating a debris'
  state 5 days in two-body + J2 does not stay on GTOC9's secular ephemeris: the osculating
  and mean elements differ by kilometres.)
- *Δt_R.*  "Consecutive rendezvous" is read from one arrival to the next by default
  (stay included: the stricter reading, so a file it accepts is accepted by the
  transfer-time reading too); ``Gtoc9Rules(dt_r_from="departure")`` measures the transfer
  alone (departure to the next arrival).
- *Mass.*  Backward from ``m_dry`` after the last event: each impulse multiplies the mass
  by ``exp(|ΔV| / (Isp g0))`` and each stay adds the package ``m_de`` = 30 kg, so the mass
  just after the last arrival is ``m_dry + m_de`` (with no ΔV at the last departure) and
  ``m0`` is the mass before the first event.  The propellant bound is read as
  ``m0 - m_dry <= m_p`` (packages counted in: stricter than ``m0 - m_dry - N m_de <= m_p``).
- *Perigee.*  The osculating Keplerian perigee radius ``p / (1 + e)`` of the spacecraft's
  state along each arc (checked at every DOP853 step, not only at the impulses).
- *Arc continuity* uses the rendezvous tolerances ``ε_r``, ``ε_v``.
- *Cost.*  ``C_i = c + α (m0_i - m_dry)^2`` with the constant ``c = c_M = 55`` MEUR (the
  convention since the competition, whose ``c_i`` grew with the submission date).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from itertools import pairwise
from pathlib import Path

import numpy as np

from .debris import DebrisTable
from .dynamics import perigee_radius, propagate
from .mission_file import Event, read_mission_file
from .rules import DEBRIS_COUNT, DEFAULT_RULES, Gtoc9Rules

DAY = 86400.0


@dataclass(frozen=True)
class Violation:
    """A rule broken: the file, its line (0: the whole file or folder), the rule's name
    (module docstring) and what was found against what was expected."""

    file: str
    line: int
    rule: str
    message: str

    def __str__(self) -> str:
        return f"{self.file}:{self.line}: {self.rule}: {self.message}"


@dataclass
class MissionReport:
    """One mission checked: its debris (in visit order), total ΔV [m/s], launch mass
    ``m0`` [kg], cost [MEUR], first and last epochs [MJD2000], and its violations."""

    file: str
    debris: list[int] = field(default_factory=list)
    arrivals: list[Event] = field(default_factory=list)
    dv_mps: float = 0.0
    m0_kg: float = math.nan
    cost_meur: float = math.nan
    start: float = math.nan
    end: float = math.nan
    violations: list[Violation] = field(default_factory=list)
    unreadable: bool = False


@dataclass
class FolderReport:
    """Every mission of a folder checked, the violations across them, and ``J`` [MEUR]."""

    missions: list[MissionReport]
    violations: list[Violation]

    @property
    def all_violations(self) -> list[Violation]:
        return [v for m in self.missions for v in m.violations] + self.violations

    @property
    def valid(self) -> bool:
        return not self.all_violations

    @property
    def unreadable(self) -> bool:
        return any(m.unreadable for m in self.missions)

    @property
    def cost_meur(self) -> float:
        """``J``, the sum of the missions' costs [MEUR]."""
        return float(sum(m.cost_meur for m in self.missions))


def mission_files(folder: str | os.PathLike) -> list[Path]:
    """``mission_*.txt`` of ``folder/gtoc9/`` if that folder exists, else of ``folder``."""
    folder = Path(folder)
    where = folder / "gtoc9" if (folder / "gtoc9").is_dir() else folder
    return sorted(where.glob("mission_*.txt"))


def check_folder(folder, debris: DebrisTable, rules: Gtoc9Rules = DEFAULT_RULES, *,
                 require_all: bool = False) -> FolderReport:  # fmt: skip
    """Check every mission file of ``folder`` (:func:`mission_files`) and the rules across
    them (**dt-m**, **once**, **all**)."""
    files = mission_files(folder)
    missions = [check_mission(path, debris, rules) for path in files]
    across: list[Violation] = []
    if not files:
        across.append(Violation(str(folder), 0, "format", "no mission_*.txt file in the folder "
                                "(nor in its gtoc9/ sub-folder)"))  # fmt: skip
    readable = [m for m in missions if m.arrivals]
    latest = None  # the mission that ends last among those launched before
    for mission in sorted(readable, key=lambda m: m.start):
        if latest is not None and mission.start - latest.end < rules.dt_m_days:
            across.append(Violation(mission.file, mission.arrivals[0].line, "dt-m",
                f"launch at MJD2000 {mission.start:.6f}, {mission.start - latest.end:.4f} days "
                f"after the end of {Path(latest.file).name} (MJD2000 {latest.end:.6f}); expected "
                f">= {rules.dt_m_days:g} days (Δt_M)"))  # fmt: skip
        if latest is None or mission.end > latest.end:
            latest = mission
    removed: dict[int, tuple[str, int]] = {}
    for mission in readable:
        for event in mission.arrivals:
            if event.ident in removed:
                file, line = removed[event.ident]
                across.append(Violation(mission.file, event.line, "once",
                    f"debris {event.ident} removed twice (first at {Path(file).name} line "
                    f"{line}); expected each debris at most once"))  # fmt: skip
            else:
                removed[event.ident] = (mission.file, event.line)
    if require_all:
        missing = sorted(set(range(DEBRIS_COUNT)) - set(removed))
        if missing:
            across.append(Violation(str(folder), 0, "all",
                f"{len(missing)} of the {DEBRIS_COUNT} debris never removed: "
                f"{' '.join(map(str, missing))}; expected all exactly once"))  # fmt: skip
    return FolderReport(missions, across)


def check_mission(path, debris: DebrisTable, rules: Gtoc9Rules = DEFAULT_RULES) -> MissionReport:
    """Check one mission file (every rule of the module docstring but **dt-m**, **once**
    and **all**, which need the other missions)."""
    path = str(path)
    report = MissionReport(path)
    events, problems = read_mission_file(path)
    if problems:
        report.unreadable = True
        report.violations += [Violation(path, p.line, "format", p.message) for p in problems]
        return report
    bad = report.violations

    def flag(event: Event, rule: str, message: str) -> None:
        bad.append(Violation(path, event.line, rule, message))

    for before, after in pairwise(events):
        if after.epoch < before.epoch:
            flag(after, "order", f"epoch {after.epoch:.6f} before the previous line's "
                                 f"{before.epoch:.6f} (line {before.line}); expected time order")
    known = [e for e in events if e.is_dsm or debris.has(e.ident)]
    for event in events:
        if not (event.is_dsm or debris.has(event.ident)):
            flag(event, "debris", f"id {event.ident} is no debris of {debris.source} "
                                  f"(expected -1 or one of its ids)")
    if any(after.epoch < before.epoch for before, after in pairwise(events)):
        return report
    events = known
    if not events:
        return report
    stays = _sequence(events, rules, flag)
    for arrival, departure in stays:
        _rendezvous(arrival, debris, rules, flag, arriving=True)
        if departure is not None:
            _rendezvous(departure, debris, rules, flag, arriving=False)
    index = {id(e): k for k, e in enumerate(events)}
    stay_of = {}  # event position -> its stay (from an arrival to its departure, both in)
    for number, (arrival, departure) in enumerate(stays):
        if departure is not None:
            for k in range(index[id(arrival)], index[id(departure)] + 1):
                stay_of[k] = number
    for k, (before, after) in enumerate(pairwise(events)):  # an arc, unless co-orbiting
        if k not in stay_of or stay_of.get(k + 1) != stay_of[k]:
            _arc(before, after, rules, flag)
    report.arrivals = [a for a, _ in stays]
    report.debris = [a.ident for a in report.arrivals]
    for (a1, d1), (a2, _) in pairwise(stays):
        since = a1 if rules.dt_r_from == "arrival" or d1 is None else d1
        gap = a2.epoch - since.epoch
        if gap > rules.dt_r_days:
            flag(a2, "dt-r", f"{gap:.4f} days from the {rules.dt_r_from} at debris {a1.ident} "
                 f"(line {since.line}) to the arrival at debris {a2.ident}; expected <= "
                 f"{rules.dt_r_days:g} days (Δt_R, {rules.dt_r_from} to arrival)")  # fmt: skip
    report.start, report.end = events[0].epoch, events[-1].epoch
    if report.start < rules.start_mjd2000:
        flag(events[0], "window", f"launch at MJD2000 {report.start:.6f}; expected >= "
                                  f"{rules.start_mjd2000:g}")  # fmt: skip
    if report.end > rules.end_mjd2000:
        flag(events[-1], "window", f"mission end at MJD2000 {report.end:.6f}; expected <= "
                                   f"{rules.end_mjd2000:g}")  # fmt: skip
    _masses(report, events, stays, rules, flag)
    return report


def _sequence(events, rules, flag) -> list[tuple[Event, Event | None]]:
    """The stays ``(arrival, departure)`` of a mission (departure None when missing),
    every **sequence** and **stay** problem flagged."""
    stays: list[tuple[Event, Event | None]] = []
    current: Event | None = None  # the arrival of the stay under way
    for number, event in enumerate(events):
        if current is not None and event.ident == current.ident:
            stays[-1] = (current, event)
            days = event.epoch - current.epoch
            if days < rules.stay_days:
                flag(event, "stay", f"departure from debris {event.ident} {days:.6f} days after "
                     f"its arrival (line {current.line}); expected >= {rules.stay_days:g} days "
                     f"(t_w)")  # fmt: skip
            current = None
        elif current is not None:
            what = "an impulse (-1)" if event.is_dsm else f"an arrival at debris {event.ident}"
            flag(event, "stay", f"{what} during the stay at debris {current.ident} (arrived line "
                 f"{current.line}, no departure line yet); expected its departure (id "
                 f"{current.ident}) first")  # fmt: skip
            if not event.is_dsm:  # a new stay begins (the old one has no departure)
                current = event
                stays.append((event, None))
        elif event.is_dsm:
            if number == 0:
                flag(event, "sequence", "the mission starts with a deep-space manoeuvre; "
                     "expected the arrival at its first debris")  # fmt: skip
        else:
            current = event
            stays.append((event, None))
    if current is not None:
        flag(current, "sequence", f"no departure line after the arrival at debris "
             f"{current.ident}; expected the mission to end with it")  # fmt: skip
    elif events[-1].is_dsm:
        flag(events[-1], "sequence", "the mission ends with a deep-space manoeuvre; expected "
             "the departure from its last debris")  # fmt: skip
    return stays


def _rendezvous(event: Event, debris: DebrisTable, rules, flag, *, arriving: bool) -> None:
    r_d, v_d = debris.state(event.ident, event.epoch)
    r = np.array(event.r)
    v = np.array(event.v) + (np.array(event.dv) if arriving else 0.0)
    dr, dv = float(np.linalg.norm(r - r_d)), float(np.linalg.norm(v - v_d))
    what = "arrival at" if arriving else "departure from"
    after = "after" if arriving else "before"
    if dr > rules.eps_r_m or dv > rules.eps_v_mps:
        flag(event, "rendezvous", f"{what} debris {event.ident}: position {dr:.3f} m and "
             f"velocity ({after} the impulse) {dv:.4f} m/s from the debris' GTOC9 ephemeris; "
             f"expected <= {rules.eps_r_m:g} m and <= {rules.eps_v_mps:g} m/s")  # fmt: skip


def _arc(before: Event, after: Event, rules, flag) -> None:
    seconds = (after.epoch - before.epoch) * DAY
    v0 = np.array(before.v) + np.array(before.dv)
    r1, v1, states = propagate(before.r, v0, seconds)
    dr = float(np.linalg.norm(r1 - np.array(after.r)))
    dv = float(np.linalg.norm(v1 - np.array(after.v)))
    if dr > rules.eps_r_m or dv > rules.eps_v_mps:
        flag(after, "arc", f"the arc from line {before.line} propagated in GTOC9's dynamics ends "
             f"{dr:.3f} m and {dv:.4f} m/s from this line's state; expected <= "
             f"{rules.eps_r_m:g} m and <= {rules.eps_v_mps:g} m/s")  # fmt: skip
    rp = float(perigee_radius(states).min())
    if rp < rules.min_perigee_m:
        flag(before, "perigee", f"the arc to line {after.line} has a perigee radius of "
             f"{rp / 1e3:.3f} km; expected >= {rules.min_perigee_m / 1e3:g} km")  # fmt: skip


def _masses(report: MissionReport, events, stays, rules, flag) -> None:
    """The mass chain backward (module docstring), the ΔV, ``m0`` and the cost."""
    departures = {id(d) for _, d in stays if d is not None}
    c = rules.isp_s * rules.g0_mps2
    mass = rules.m_dry_kg
    total = 0.0
    for event in reversed(events):
        dv = float(np.linalg.norm(event.dv))
        total += dv
        mass *= math.exp(dv / c)
        if id(event) in departures:
            mass += rules.m_de_kg
    report.dv_mps, report.m0_kg, report.cost_meur = total, mass, rules.cost(mass)
    if mass - rules.m_dry_kg > rules.max_propellant_kg:
        flag(events[0], "propellant", f"launch mass m0 = {mass:.3f} kg for {total:.3f} m/s of ΔV "
             f"and {len(stays)} packages: m0 - m_dry = {mass - rules.m_dry_kg:.3f} kg; expected "
             f"<= {rules.max_propellant_kg:g} kg")  # fmt: skip
