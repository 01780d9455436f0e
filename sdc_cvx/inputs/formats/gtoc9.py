"""The GTOC9 debris file (``debris_data.txt``, or the official ``debris.csv``)."""

from __future__ import annotations

import dataclasses
import math
import os

import pandas as pd

from ..catalog import R_EARTH_KM, Catalog, read_text
from ._common import _MJD2000, _catalog, _duplicates, _lines, _short

# ---------------------------------------------------------------------- GTOC9
GTOC9_COLUMNS = ("id", "epoch [MJD2000]", "a [m]", "e", "i [rad]", "RAAN [rad]",
                 "argument of perigee [rad]", "mean anomaly [rad]")  # fmt: skip
"""The 8 columns of the GTOC9 debris file, in order."""


def _gtoc9_checks():
    r_m = R_EARTH_KM * 1000.0
    return (
        lambda v: None if v >= 0 and v.is_integer() else "a non-negative integer",
        lambda v: None,
        lambda v: None if v > r_m else f"a number > {r_m:g} (the Earth's radius)",
        lambda v: None if 0.0 <= v < 1.0 else "a number in [0, 1)",
        lambda v: None if 0.0 <= v <= math.pi else "a number in [0, pi]",
        lambda v: None,
        lambda v: None,
        lambda v: None,
    )


def read_gtoc9(path: str | os.PathLike, *, start=None, on_invalid: str = "raise") -> Catalog:
    """Read the GTOC9 debris file (``debris_data.txt``, or the official ``debris.csv``).

    One debris per line, 8 numbers separated by blanks or tabs (commas are accepted
    too): id, epoch [MJD2000], a [m], e, i [rad], RAAN [rad], argument of perigee
    [rad], mean anomaly [rad].  A first line that is not numeric (a header) and lines
    starting with ``#`` are skipped.  The epoch is UTC ``2000-01-01 00:00`` + MJD2000
    days (JD = MJD2000 + 2451544.5).  The elements are GTOC9's osculating elements,
    used as they are (GTOC9 itself propagates them with secular J2 rates only); the
    catalog's ``ephemeris`` is ``"gtoc9"``: a flight meets the debris where GTOC9 has
    them.

    Columns: ``id`` (the integer id as a string, ``"0"``..``"122"``), ``a_km``, ``e``,
    ``inc_deg``, ``raan_deg`` (at ``start``), ``epoch``, ``argp_deg``,
    ``mean_anomaly_deg``.

    Raises
    ------
    CatalogError
        Every problem at once, naming the file, the line and the column.
    """
    source, text = read_text(path)
    checks = _gtoc9_checks()
    problems: list[str] = []
    rows, where = [], []
    first = True
    for number, raw in enumerate(_lines(text), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        fields = line.replace(",", " ").split()
        numbers = [_gtoc9_float(field) for field in fields]
        if first and all(value is None for value in numbers):  # a header line
            first = False
            continue
        first = False
        prefix = f"{source}, line {number}"
        if len(fields) != len(GTOC9_COLUMNS):
            problems.append(f"{prefix}: expected {len(GTOC9_COLUMNS)} numbers "
                            f"({', '.join(GTOC9_COLUMNS)}), got {len(fields)} fields")  # fmt: skip
            continue
        bad = False
        for column, (field, value, check) in enumerate(zip(fields, numbers, checks, strict=True)):
            expected = "a number" if value is None else check(value)
            if expected:
                problems.append(f"{prefix}, column {column + 1} ({GTOC9_COLUMNS[column]}): "
                                f"expected {expected}, got {_short(field)}")  # fmt: skip
                bad = True
        if bad:
            continue
        ident, mjd2000, a_m, e, inc, raan, argp, mean_anomaly = numbers
        rows.append({
            "id": str(int(ident)),
            "a_km": a_m / 1000.0,
            "e": e,
            "inc_deg": math.degrees(inc),
            "raan_deg": math.degrees(raan),
            "epoch": _MJD2000 + pd.Timedelta(mjd2000, unit="D").round("us"),
            "argp_deg": math.degrees(argp),
            "mean_anomaly_deg": math.degrees(mean_anomaly),
        })  # fmt: skip
        where.append(f"line {number}")
    if not rows and not problems:
        problems.append(f"{source}: no GTOC9 debris lines (8 numbers each)")
    _duplicates(rows, where, source, problems)
    catalog = _catalog(rows, source, start, problems, "GTOC9 debris lines", where=where,
                       on_invalid=on_invalid, numbered=False)  # fmt: skip
    return dataclasses.replace(catalog, ephemeris="gtoc9")


def _gtoc9_float(text: str) -> float | None:
    if "_" in text:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None
