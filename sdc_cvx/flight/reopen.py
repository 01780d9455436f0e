"""A flight reopened from the files :meth:`Flight.save <sdc_cvx.flight.result.Flight.save>`
wrote (``RUN_DIR/flight/``): :meth:`Flight.load <sdc_cvx.flight.result.Flight.load>`.

The plan is the run folder's ``solution.json``
(:func:`~sdc_cvx.flight.solution_file.solution_fields`: the path's debris as planned), the
manoeuvres ``maneuvers.csv``, the rendezvous ``rendezvous.csv``, the trajectory
``trajectory.oem`` and the rest ``flight.json``: the totals, status and tables of the
loaded flight are those saved (to the files' digits: 10 significant digits, epochs to the
microsecond, positions to 0.1 mm).
"""

from __future__ import annotations

import dataclasses
import json
import os
from pathlib import Path

import numpy as np
import pandas as pd

from ..report.out_folder import FLIGHT_FOLDER
from .plan import FlightError, FlightPlan, PlannedLeg, PlannedTank
from .propagation import ForceModel
from .solution_file import solution_fields


def read_flight(folder, flight_cls, maneuver_cls, rendezvous_cls):
    """The flight of a run folder (``folder/flight/``), or of the flight folder itself.

    Raises
    ------
    FlightError
        No flight there, or a file that is not what ``Flight.save`` writes (the file and
        the field named).
    SolutionFileError
        The run folder's ``solution.json`` is missing or not what ``save`` writes.
    """
    if isinstance(folder, bytes) or not isinstance(folder, str | os.PathLike):
        raise FlightError(f"Flight.load(folder): folder must be a path (a str or os.PathLike), "
                          f"got {folder!r}")  # fmt: skip
    folder = Path(folder)
    flown = folder if (folder / "flight.json").exists() else folder / FLIGHT_FOLDER
    if not (flown / "flight.json").exists():
        raise FlightError(f"{folder}: no {FLIGHT_FOLDER}/flight.json: not a flown run folder "
                          f"(python -m sdc_cvx fly {folder} flies it)")  # fmt: skip
    summary = _json(flown / "flight.json")
    try:
        start = pd.Timestamp(summary["start"])
        force = ForceModel(**{f.name: summary["force"][f.name]
                              for f in dataclasses.fields(ForceModel)})  # fmt: skip
        rates, seconds = str(summary["rates"]), float(summary["seconds"])
        notes, frame = tuple(summary.get("notes") or ()), str(summary.get("frame", "GCRF"))
    except (KeyError, TypeError, ValueError) as err:
        raise FlightError(f"{flown / 'flight.json'}: not a flight of this version "
                          f"({type(err).__name__}: {err})") from None  # fmt: skip
    plan = _plan(solution_fields(flown.parent), start)

    def seconds_of(stamps) -> np.ndarray:
        return (pd.DatetimeIndex(pd.to_datetime(stamps, utc=True)) - start).total_seconds() \
            .to_numpy()  # fmt: skip

    path = flown / "maneuvers.csv"
    try:
        table = pd.read_csv(path, keep_default_na=False)
        arcs = "end_utc" in table.columns
        epochs = seconds_of(table["epoch_utc"])
        ends = [seconds_of([end])[0] if arcs and end else None
                for end in (table["end_utc"] if arcs else [""] * len(table))]  # fmt: skip
        maneuvers = tuple(maneuver_cls(
            epoch_s=float(t), leg=int(row["leg"]), kind=str(row["kind"]),
            dv_gcrf=np.array([row["dv_x_mps"], row["dv_y_mps"], row["dv_z_mps"]], dtype=float),
            dv_rtn=np.array([row["dv_r_mps"], row["dv_t_mps"], row["dv_n_mps"]], dtype=float),
            end_s=end, accel_mps2=float(row["accel_mps2"]) if end is not None else None,
            law=str(row["law"]) if end is not None else None)
            for t, end, (_, row) in zip(epochs, ends, table.iterrows(), strict=True))  # fmt: skip
        path = flown / "rendezvous.csv"
        table = pd.read_csv(path, dtype={"target": str})
        epochs = seconds_of(table["epoch_utc"])
        rendezvous = tuple(rendezvous_cls(
            epoch_s=float(t), target=str(row["target"]),
            **{f.name: float(row[f.name]) for f in dataclasses.fields(rendezvous_cls)
               if f.name not in ("epoch_s", "target", "in_time")},
            in_time=str(row["in_time"]).strip().lower() == "true")
            for t, (_, row) in zip(epochs, table.iterrows(), strict=True))  # fmt: skip
        path = flown / "trajectory.oem"
        segments = tuple((seconds_of(stamps), r, v) for stamps, r, v in read_oem(path))
    except (OSError, KeyError, TypeError, ValueError, pd.errors.ParserError) as err:
        raise FlightError(f"{path}: not what Flight.save writes ({type(err).__name__}: "
                          f"{err})") from None  # fmt: skip
    return flight_cls(plan=plan, maneuvers=maneuvers, rendezvous=rendezvous, segments=segments,
                      force=force, rates=rates, seconds=seconds, notes=notes, frame=frame)


def _plan(fields: dict, start: pd.Timestamp) -> FlightPlan:
    """The plan flown: the run folder's legs over the path's debris as planned
    (:func:`~sdc_cvx.flight.solution_file.solution_fields`)."""
    catalog, plan, data, mission = fields["catalog"], fields["plan"], fields["data"], \
        fields["mission"]  # fmt: skip
    if catalog is None:
        raise FlightError(f"{fields['path']}: no debris as planned (a file of an earlier "
                          "version): fly the folder again")  # fmt: skip
    if catalog.start is None:
        catalog = dataclasses.replace(catalog, start=start)
    legs = tuple(PlannedLeg(leg["from"], leg["to"], leg["departure_day"], leg["duration_days"],
                            leg["drift_a_km"], leg["drift_inc_deg"], leg["side"], leg["dv_mps"],
                            leg["laps"])
                 for leg in plan["legs"])  # fmt: skip
    notes = [note for note in data.get("notes") or () if isinstance(note, str)]
    over = notes[-1] if data.get("status") == "over_capacity" and notes else None
    accel = mission.transfer_model().describe().get("accel_mps2")
    return FlightPlan(legs, catalog, float(mission.tmax_days),
                      tuple(map(float, mission.drift_altitude_km)),
                      float(sum(leg.dv_mps for leg in legs)), plan["total_duration_days"],
                      None if accel is None else float(accel), over_capacity=over,
                      tank=PlannedTank.of(mission.vehicle, data.get("vehicle"),
                                          data.get("operations"), catalog.ids))  # fmt: skip


def read_oem(path) -> list[tuple[pd.DatetimeIndex, np.ndarray, np.ndarray]]:
    """The segments of an OEM (KVN) :func:`~sdc_cvx.flight.oem.write_oem` wrote: ``(epochs
    (UTC), r [m], v [m/s])`` each, as they were given to it (to the file's digits)."""
    segments, rows, in_meta = [], None, False
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line == "META_START":
            in_meta = True
            if rows:
                segments.append(rows)
            rows = []
        elif line == "META_STOP":
            in_meta = False
        elif line and not in_meta and rows is not None and not line.startswith("COMMENT"):
            stamp, *values = line.split()
            if len(values) != 6:
                raise ValueError(f"a data line of {len(values) + 1} fields, not 7: {line[:60]}")
            rows.append((stamp, [float(v) for v in values]))
    if rows:
        segments.append(rows)
    if not segments:
        raise ValueError("no segment")
    out = []
    for rows in segments:
        epochs = pd.DatetimeIndex(pd.to_datetime([stamp for stamp, _ in rows], utc=True))
        states = np.array([values for _, values in rows]) * 1e3  # km, km/s -> m, m/s
        out.append((epochs, states[:, :3], states[:, 3:]))
    return out


def _json(path: Path) -> dict:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise FlightError(f"{path}: unreadable ({err})") from None
    if not isinstance(data, dict):
        raise FlightError(f"{path}: expected a JSON object, got {type(data).__name__}")
    return data
