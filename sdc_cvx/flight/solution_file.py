"""The plan a run folder's ``solution.json`` holds, checked before it is flown.

``fly RUN_DIR`` reads a file a user may have edited or truncated: every field it uses is
checked here (type, range, and that the legs chain into the path), and a fault is a
:class:`~sdc_cvx.flight.plan.FlightError` naming the file, the leg and the field (exit 2),
never a traceback.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pandas as pd

from ..errors import InputError
from ..physics.orbits import R_EARTH

CHAIN_TOL_DAYS = 1e-6
"""How far a leg may leave before the previous one arrives (rounding) [days]."""
MAX_DAYS = 3652.5
"""The latest a leg may leave or last [days]: the longest mission planned (10 years,
``inputs.mission.MAX_TMAX_DAYS``, not imported: a flight needs no mission module here)."""


class SolutionFileError(InputError):
    """``solution.json`` does not hold a plan that can be flown (the message says where)."""


def checked_solution(data, path: Path) -> dict:
    """``data`` (parsed ``solution.json``) with every field ``fly`` uses checked.

    Returns
    -------
    dict
        ``legs`` (a list of dicts of typed fields), ``tmax_days``, ``drift_altitude_km``,
        ``total_duration_days``, ``start`` (``pd.Timestamp`` or None), ``mission``,
        ``debris`` (the path's debris as planned; empty in an earlier version's file).

    Raises
    ------
    SolutionFileError
    """
    def fail(where: str, what: str):
        raise SolutionFileError(f"{path}: {where}: {what}")

    if not isinstance(data, dict):
        fail("the file", f"expected a JSON object (a solution), got {type(data).__name__}")
    mission, legs = data.get("mission"), data.get("legs")
    if not isinstance(legs, list) or not isinstance(mission, dict):
        fail("the file", "not a solution of this version (no 'legs' list or 'mission' object)")
    tmax = _number(mission.get("tmax_days"), lambda v: 0 < v <= MAX_DAYS)
    if tmax is None:
        fail("mission.tmax_days", f"expected a number in (0, {MAX_DAYS:g}], got "
                                  f"{mission.get('tmax_days')!r}")  # fmt: skip
    band = mission.get("drift_altitude_km")
    if not (isinstance(band, list | tuple) and len(band) == 2
            and all(_number(v, lambda v: v > 0) is not None for v in band)):  # fmt: skip
        fail("mission.drift_altitude_km", f"expected [low, high] in km, got {band!r}")
    total = _number(data.get("total_duration_days"), lambda v: 0 <= v <= 2 * MAX_DAYS)
    if total is None:
        fail("total_duration_days", f"expected a number in [0, {2 * MAX_DAYS:g}], got "
                                    f"{data.get('total_duration_days')!r}")  # fmt: skip
    start = None
    if data.get("start"):
        try:
            start = pd.Timestamp(data["start"])
        except (ValueError, TypeError):
            fail("start", f"expected an ISO-8601 date, got {data['start']!r}")
    checked = []
    for k, leg in enumerate(legs, start=1):
        where = f"legs[{k - 1}] (leg {k})"
        if not isinstance(leg, dict):
            fail(where, f"expected an object, got {leg!r}")
        fields = {}
        for name in ("from", "to"):
            if not isinstance(leg.get(name), str | int) or not str(leg.get(name)).strip():
                fail(f"{where}.{name}", f"expected a debris id, got {leg.get(name)!r}")
            fields[name] = str(leg[name])
        for name, rule, said in (
                ("departure_day", lambda v: 0 <= v <= MAX_DAYS, f"in [0, {MAX_DAYS:g}] [days]"),
                ("duration_days", lambda v: 0 <= v <= MAX_DAYS, f"in [0, {MAX_DAYS:g}] [days]"),
                ("drift_a_km", lambda v: v > R_EARTH / 1e3, f"> {R_EARTH / 1e3:g} [km]"),
                ("drift_inc_deg", lambda v: 0 <= v <= 180, "in [0, 180] [deg]"),
                ("dv_mps", lambda v: v >= 0, ">= 0 [m/s]")):  # fmt: skip
            fields[name] = _number(leg.get(name), rule)
            if fields[name] is None:
                fail(f"{where}.{name}", f"expected a number {said}, got {leg.get(name)!r}")
        side, laps = leg.get("side"), leg.get("laps", 0)
        if side not in (1, -1, 1.0, -1.0):
            fail(f"{where}.side", f"expected 1 or -1, got {side!r}")
        if not (isinstance(laps, int | float) and not isinstance(laps, bool) and laps >= 0
                and float(laps).is_integer()):  # fmt: skip
            fail(f"{where}.laps", f"expected a whole number >= 0, got {laps!r}")
        fields |= {"side": int(side), "laps": int(laps)}
        if checked:
            before = checked[-1]
            if before["to"] != fields["from"]:
                fail(where, f"leaves {fields['from']!r}, but leg {k - 1} arrived at "
                            f"{before['to']!r}: the legs do not chain")  # fmt: skip
            arrived = before["departure_day"] + before["duration_days"]
            if fields["departure_day"] < arrived - CHAIN_TOL_DAYS:
                fail(f"{where}.departure_day", f"{fields['departure_day']:g} is before leg "
                                               f"{k - 1} arrives ({arrived:g})")  # fmt: skip
        checked.append(fields)
    path_ids = data.get("path")
    flown = [checked[0]["from"]] + [leg["to"] for leg in checked] if checked else []
    if path_ids is not None and [str(p) for p in path_ids] != flown:
        fail("path", f"{path_ids!r} is not the legs' path {flown!r}")
    planned = data.get("debris", [])  # absent from the files of earlier versions
    if not (isinstance(planned, list) and all(isinstance(entry, dict) for entry in planned)):
        fail("debris", f"expected a list of objects (the debris as planned), got {planned!r}")
    return {"legs": checked, "tmax_days": tmax, "drift_altitude_km": tuple(map(float, band)),
            "total_duration_days": total, "start": start, "mission": mission,
            "debris": planned}


def _number(value, rule) -> float | None:
    """``value`` as a finite float that satisfies ``rule``, or None."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    value = float(value)
    return value if math.isfinite(value) and rule(value) else None


MASS_KEYS = ("propellant_kg", "mass_before_kg", "mass_after_kg", "burn_s")
"""The keys of a leg of ``solution.json`` that are its ``masses`` (``Leg.to_dict``); the
others beyond the leg's own fields are its ``phases``."""


def solution_fields(folder) -> dict:
    """What a run folder's ``solution.json`` holds, checked: its ``path`` (the file),
    ``data`` (as parsed), ``plan`` (:func:`checked_solution`'s), ``mission`` (validated
    again as :class:`~sdc_cvx.inputs.mission.Mission`) and ``catalog`` (the path's debris
    as planned, at ``start``; None in an earlier version's file, without them).

    Raises
    ------
    SolutionFileError
        No ``solution.json``, unreadable, or a field that is not what ``save`` writes
        (the message names the file and the field).
    """
    from ..inputs.mission import Mission

    if isinstance(folder, bytes) or not isinstance(folder, str | os.PathLike):
        raise SolutionFileError(f"Solution.load(folder): folder must be a path (a str or "
                                f"os.PathLike), got {folder!r}")  # fmt: skip
    path = Path(folder) / "solution.json"
    data = _read(path)
    plan = checked_solution(data, path)
    fail = _failing(path)
    mission = _built(Mission, "mission", fail, **plan["mission"])
    return {"path": path, "data": data, "plan": plan, "mission": mission,
            "catalog": _planned_catalog(plan, path, fail)}


def read_solution(folder, solution_cls, leg_cls, record_cls, status_cls):
    """The solution of a run folder (:meth:`Solution.load <sdc_cvx.solution.Solution.load>`,
    which gives its own classes: this module imports no solution), from
    :func:`solution_fields`.

    Raises
    ------
    SolutionFileError
        As :func:`solution_fields`, or a leg, an iteration or the status that is not what
        ``save`` writes.
    """
    fields = solution_fields(folder)
    data, plan = fields["data"], fields["plan"]
    fail = _failing(fields["path"])
    legs = tuple(_leg(leg_cls, entry, where, fail)
                 for where, entry in _entries(data, "legs", fail))  # fmt: skip
    initial = tuple(_leg(leg_cls, entry, where, fail)
                    for where, entry in _entries(data, "initial_legs", fail))  # fmt: skip
    records = tuple(_built(record_cls, where, fail, **(entry | {"path": tuple(
                        entry.get("path") or ())}))
                    for where, entry in _entries(data, "iterations", fail))  # fmt: skip
    status = _built(status_cls, "status", fail, data.get("status"))
    trace = tuple((e.get("seconds"), e.get("lower_bound_mps"), e.get("plan_mps"))
                  for _, e in _entries(data, "search_trace", fail))  # fmt: skip
    return _built(
        solution_cls, "the file", fail, path=tuple(map(str, data.get("path") or ())),
        legs=legs, total_dv_mps=_float(data, "total_dv_mps", fail),
        total_duration_days=plan["total_duration_days"], status=status,
        backend=str(data.get("backend", "")), mission=fields["mission"], iterations=records,
        initial_legs=initial, operations=dict(data.get("operations") or {}),
        catalog=fields["catalog"], model_size=dict(data.get("model_size") or {}),
        timings=dict(data.get("timings") or {}), notes=tuple(data.get("notes") or ()),
        method=str(data.get("method", "paper")), lower_bound_mps=data.get("lower_bound_mps"),
        gap_requested=data.get("gap_requested"), search_trace=trace,
        vehicle=data.get("vehicle"))  # fmt: skip


def _failing(path: Path):
    def fail(where: str, what) -> None:
        raise SolutionFileError(f"{path}: {where}: {what}")

    return fail


def _built(cls, where: str, fail, *args, **fields):
    """``cls(*args, **fields)``, or ``fail(where, why)``: an unknown or missing key, a
    value its class refuses."""
    try:
        return cls(*args, **fields)
    except (TypeError, ValueError) as err:
        fail(where, err)


def _read(path: Path):
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise SolutionFileError(f"{path.parent}: no {path.name}: not a run folder of sdc_cvx "
                                "(Solution.save and run --out write one)") from None  # fmt: skip
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise SolutionFileError(f"{path}: unreadable ({err})") from None


def _entries(data: dict, key: str, fail):
    """``(where, entry)`` of each object of the list ``data[key]`` (absent: none)."""
    entries = data.get(key) or []
    if not isinstance(entries, list):
        fail(key, f"expected a list, got {type(entries).__name__}")
    for k, entry in enumerate(entries):
        if not isinstance(entry, dict):
            fail(f"{key}[{k}]", f"expected an object, got {entry!r}")
        yield f"{key}[{k}]", entry


def _leg(cls, entry: dict, where: str, fail):
    """A :class:`~sdc_cvx.solution.Leg` from its ``to_dict()`` (phases and masses flat)."""
    own = {"from", "to", "departure_day", "duration_days", "drift_a_km", "drift_alt_km",
           "drift_inc_deg", "side", "dv_mps", "eccentricity_dv_mps"}  # fmt: skip
    missing = sorted(own - {"eccentricity_dv_mps"} - set(entry))
    if missing:
        fail(where, f"missing {', '.join(missing)}")
    extra = {k: v for k, v in entry.items() if k not in own}
    fields = {k: v for k, v in entry.items() if k in own}
    return cls(from_id=str(fields.pop("from")), to_id=str(fields.pop("to")), **fields,
               phases={k: v for k, v in extra.items() if k not in MASS_KEYS},
               masses={k: v for k, v in extra.items() if k in MASS_KEYS})  # fmt: skip


def _float(data: dict, key: str, fail) -> float:
    value = _number(data.get(key), lambda v: True)
    if value is None:
        fail(key, f"expected a number, got {data.get(key)!r}")
    return value


def _planned_catalog(plan: dict, path: Path, fail):
    """The path's debris as planned (``debris``, at ``start``), or None without them."""
    from ..errors import CatalogError
    from ..inputs.catalog import Catalog

    if not plan["debris"]:
        return None
    columns = ("id", "a_km", "e", "inc_deg", "raan_deg")
    try:
        frame = pd.DataFrame([{k: entry.get(k) for k in columns} for entry in plan["debris"]])
        catalog = Catalog.from_frame(frame, source=f"{path} (the path's debris as planned)",
                                     start=plan["start"])  # fmt: skip
    except CatalogError as err:
        fail("debris", str(err).replace("\n", " "))
    rates = [entry.get("raan_rate_deg_per_day") for entry in plan["debris"]]
    if all(_number(rate, lambda v: True) is not None for rate in rates):  # the plan's own
        catalog.frame["raan_rate_deg_per_day"] = [float(rate) for rate in rates]
    return catalog
