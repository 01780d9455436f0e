"""The plan a run folder's ``solution.json`` holds, checked before it is flown.

``fly RUN_DIR`` reads a file a user may have edited or truncated: every field it uses is
checked here (type, range, and that the legs chain into the path), and a fault is a
:class:`~sdc_cvx.flight.plan.FlightError` naming the file, the leg and the field (exit 2),
never a traceback.
"""

from __future__ import annotations

import math
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
