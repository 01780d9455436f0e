"""A GTOC9 campaign folder: ``gtoc9/mission_01.txt``, ... and ``campaign.json``.

:func:`write_campaign` writes one mission file per mission (:mod:`.mission_file`) and
``campaign.json``: each mission's file, debris (in visit order), arrival and departure
epochs [MJD2000], ΔV [m/s], launch mass ``m0`` [kg] and cost [MEUR], and ``J`` [MEUR],
with the rules' constants.  The masses follow :func:`launch_mass` (the chain of
:mod:`.check`); the files are not validated here (``sdc-cvx gtoc9-check FOLDER`` does).
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from ..errors import MissionError
from .mission_file import Event, write_mission_file
from .rules import DEFAULT_RULES, Gtoc9Rules

FOLDER = "gtoc9"
"""The sub-folder of a campaign folder holding the mission files."""
SUMMARY = "campaign.json"


def stays(events) -> list[tuple[Event, Event]]:
    """The ``(arrival, departure)`` pairs of a mission: a debris event followed by one of
    the same id (deep-space manoeuvres, ``-1``, are neither)."""
    pairs, previous = [], None
    for event in events:
        if event.is_dsm:
            previous = None
        elif previous is not None and previous.ident == event.ident:
            pairs.append((previous, event))
            previous = None
        else:
            previous = event
    return pairs


def launch_mass(events, rules: Gtoc9Rules = DEFAULT_RULES) -> float:
    """The launch mass ``m0`` [kg]: backward from ``m_dry`` after the last event, each
    impulse times ``exp(|ΔV| / (Isp g0))``, each stay (at its departure) ``+ m_de``."""
    departures = {id(d) for _, d in stays(events)}
    mass = rules.m_dry_kg
    for event in reversed(list(events)):
        mass *= math.exp(float(np.linalg.norm(event.dv)) / (rules.isp_s * rules.g0_mps2))
        mass += rules.m_de_kg if id(event) in departures else 0.0
    return mass


def mission_summary(events, file: str, rules: Gtoc9Rules = DEFAULT_RULES) -> dict:
    """A mission's entry of ``campaign.json`` (module docstring)."""
    events = list(events)
    pairs = stays(events)
    m0 = launch_mass(events, rules)
    return {
        "file": file,
        "debris": [a.ident for a, _ in pairs],
        "arrivals_mjd2000": [a.epoch for a, _ in pairs],
        "departures_mjd2000": [d.epoch for _, d in pairs],
        "dv_mps": float(sum(np.linalg.norm(e.dv) for e in events)),
        "m0_kg": m0,
        "cost_meur": rules.cost(m0),
    }


def write_campaign(folder: str | os.PathLike, missions, *,
                   rules: Gtoc9Rules = DEFAULT_RULES) -> Path:  # fmt: skip
    """Write ``missions`` (each a list of :class:`Event` in time order) as
    ``folder/gtoc9/mission_NN.txt`` and ``folder/campaign.json``; returns the json's path.

    Raises MissionError when ``folder/gtoc9/`` already holds mission files (a campaign
    is written whole, never mixed with an older one's files)."""
    folder = Path(folder)
    missions = [list(m) for m in missions]
    if not missions:
        raise MissionError(f"{folder}: a GTOC9 campaign needs at least one mission, got none")
    old = sorted((folder / FOLDER).glob("mission_*.txt"))
    if old:
        raise MissionError(f"{folder / FOLDER}: holds {len(old)} mission files already "
                           f"({old[0].name}, ...); expected an empty or new folder")  # fmt: skip
    entries = []
    for number, events in enumerate(missions, start=1):
        name = f"{FOLDER}/mission_{number:02d}.txt"
        write_mission_file(folder / name, events, comment=f"GTOC9 mission {number} (sdc_cvx)")
        entries.append(mission_summary(events, name, rules))
    summary = {
        "missions": entries,
        "J_meur": float(sum(e["cost_meur"] for e in entries)),
        "launch_cost_meur": rules.launch_cost_meur,
        "alpha_meur_per_kg2": rules.alpha_meur_per_kg2,
    }
    path = folder / SUMMARY
    path.write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    return path
