"""Two- and three-line element sets (TLE, 3LE) with their checksums (see :mod:`._common`
for the semi-major axis convention)."""

from __future__ import annotations

import calendar
import functools
import math
import os
import re

import pandas as pd
from sgp4.api import Satrec

from ..catalog import Catalog, read_text
from ..sgp4_sets import brouwer_a_km
from ._common import (
    _a_problem,
    _catalog,
    _duplicates,
    _element_row,
    _fail,
    _lines,
    _sgp4_problem,
    _short,
    kozai_a_km,
)

TLE_LINE_LENGTH = 69


# ---------------------------------------------------------------------- TLE
def tle_checksum(line: str) -> int:
    """TLE checksum of a line: digits of columns 1-68 summed, each '-' counting 1, mod 10."""
    body = _NOT_COUNTED.sub("", line[:68]).replace("-", "1")
    return (sum(body.encode("ascii")) - 48 * len(body)) % 10  # '0' is byte 48


_NOT_COUNTED = re.compile(r"[^0-9-]")


_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)\Z")


def _tle_satnum(text: str):
    stripped = text.strip()
    if stripped.isdigit() and stripped.isascii():
        return int(stripped), None
    if re.fullmatch(r"[A-HJ-NP-Z]\d{4}", text):
        return (10 + _ALPHA5.index(text[0])) * 10000 + int(text[1:]), None
    return None, "a catalog number (up to 5 digits, or Alpha-5: a letter and 4 digits)"


def _tle_number(low=-math.inf, high=math.inf, *, positive=False):
    def parse(text: str):
        stripped = text.strip()
        if not _DECIMAL.match(stripped):
            return None, "a number"
        value = float(stripped)
        if positive and value <= 0.0:
            return None, "a number > 0"
        if not low <= value <= high:
            return None, f"a number in [{low:g}, {high:g}]"
        return value, None

    return parse


def _tle_exponent(text: str):
    """Field such as ' 11455-2' or '-11606-4': sign, 5 digits after an assumed '0.', exponent."""
    sign, mantissa, exponent = text[0], text[1:6].replace(" ", "0"), text[6:8]
    if sign in " +-" and mantissa.isdigit() and re.fullmatch(r"[+ -]\d", exponent):
        value = float(f"0.{mantissa}e{exponent.replace(' ', '+')}")
        return (-value if sign == "-" else value), None
    return None, "a number with an assumed decimal point and an exponent, such as ' 12345-4'"


def _tle_eccentricity(text: str):
    digits = text.replace(" ", "0")
    if digits.isdigit() and digits.isascii():
        return float("0." + digits), None
    return None, "7 digits after an assumed '0.', such as '0012345'"


def _tle_epoch(text: str):
    """Epoch field 'YYDDD.DDDDDDDD' -> UTC Timestamp (exact to the nanosecond)."""
    year_text, day_text = text[:2], text[2:].strip()
    expected = "an epoch YYDDD.DDDDDDDD (2-digit year, day of the year from 1)"
    if not (year_text.isdigit() and re.fullmatch(r"\d{1,3}(?:\.\d*)?", day_text)):
        return None, expected
    year = int(year_text)
    year += 1900 if year >= 57 else 2000  # the TLE convention (Sputnik, 1957)
    whole, _, fraction = day_text.partition(".")
    days_in_year = 366 if calendar.isleap(year) else 365
    # exact integer arithmetic (as Decimal, half to even), then one Timestamp
    scale = 10 ** len(fraction)
    numerator = (int(whole) * scale + int(fraction or "0") - scale) * 86_400_000_000_000
    nanoseconds, rest = divmod(numerator, scale)
    if 2 * rest > scale or (2 * rest == scale and nanoseconds % 2):
        nanoseconds += 1
    if not 0 <= numerator < days_in_year * 86_400_000_000_000 * scale:
        return None, f"{expected}; day {day_text} is not in [1, {days_in_year + 1})"
    return pd.Timestamp(_year_start_ns(year) + nanoseconds, tz="UTC"), None


@functools.cache
def _year_start_ns(year: int) -> int:
    """1 January of ``year``, 00:00 UTC, in nanoseconds since 1970."""
    return pd.Timestamp(year=year, month=1, day=1, tz="UTC").value


_ALPHA5 = "ABCDEFGHJKLMNPQRSTUVWXYZ"  # Alpha-5: I and O are not used


# (first column, last column) 1-based inclusive, key, label, parser
_LINE1_FIELDS = (
    ((3, 7), "norad", "catalog number", _tle_satnum),
    ((19, 32), "epoch", "epoch", _tle_epoch),
    ((34, 43), "ndot", "first derivative of the mean motion", _tle_number()),
    ((45, 52), "nddot", "second derivative of the mean motion", _tle_exponent),
    ((54, 61), "bstar", "BSTAR drag term", _tle_exponent),
)


_LINE2_FIELDS = (
    ((3, 7), "norad", "catalog number", _tle_satnum),
    ((9, 16), "inc_deg", "inclination [deg]", _tle_number(0.0, 180.0)),
    ((18, 25), "raan_deg", "RAAN [deg]", _tle_number(0.0, 360.0)),
    ((27, 33), "e", "eccentricity", _tle_eccentricity),
    ((35, 42), "argp_deg", "argument of perigee [deg]", _tle_number(0.0, 360.0)),
    ((44, 51), "mean_anomaly_deg", "mean anomaly [deg]", _tle_number(0.0, 360.0)),
    ((53, 63), "mean_motion", "mean motion [rev/day]", _tle_number(positive=True)),
)


def _tle_line(number: int, line: str, kind: str, source: str, checksum: bool, problems):
    """Fields of TLE line ``kind`` ('1' or '2') found at line ``number``, or None."""
    prefix = f"{source}, line {number}"
    if len(line) != TLE_LINE_LENGTH:
        hint = " (truncated?)" if len(line) < TLE_LINE_LENGTH else ""
        problems.append(
            f"{prefix}: expected {TLE_LINE_LENGTH} characters on TLE line {kind} (the last "
            f"one the checksum), got {len(line)}{hint}"
        )
        return None
    values, ok = {}, True
    for (first, last), key, label, parse in _LINE1_FIELDS if kind == "1" else _LINE2_FIELDS:
        text = line[first - 1 : last]
        value, expected = parse(text)
        if expected:
            problems.append(f"{prefix}, columns {first}-{last} ({label}): expected {expected}, "
                            f"got {text!r}")  # fmt: skip
            ok = False
        values[key] = value
    if checksum:
        digit, want = line[68], tle_checksum(line)
        if digit != str(want):
            problems.append(
                f"{prefix}, column 69 (checksum): expected {want} (digits of columns 1-68 "
                f"summed, '-' counting 1, modulo 10), got {digit!r}"
            )
            ok = False
    return values if ok else None


def _tle_sets(lines: list[str], source: str, problems: list[str]):
    """``(name line or None, (n1, line 1), (n2, line 2))`` of each element set."""
    sets = []
    title = first = None

    def unpaired(number, found):
        problems.append(
            f"{source}, line {number}: TLE line 1 is not followed by its line 2; expected a "
            f"line starting with '2 ' at line {number + 1}, {found}"
        )

    def lonely(number, text):
        problems.append(
            f"{source}, line {number}: name line {text!r} is not followed by an element set; "
            f"expected a line starting with '1 ' at line {number + 1}"
        )

    for number, raw in enumerate(lines, start=1):
        line = raw.rstrip()
        if not line.strip():
            continue
        if line.startswith("1 "):
            if first is not None:
                unpaired(first[0], f"found another line 1 at line {number}")
            first = (number, line)
        elif line.startswith("2 "):
            if first is None:
                problems.append(
                    f"{source}, line {number}: TLE line 2 without a line 1; expected a line "
                    f"starting with '1 ' just before it"
                )
            else:
                sets.append((title, first, (number, line)))
            title = first = None
        else:
            if first is not None:
                unpaired(first[0], f"found {_short(line)} at line {number}")
                first = None
            elif title is not None:
                lonely(*title)
            title = (number, line)
    if first is not None:
        unpaired(first[0], "found the end of the file")
    elif title is not None:
        lonely(*title)
    return sets


def read_tle(path: str | os.PathLike, *, start=None, checksum: bool = True,
             on_invalid: str = "raise") -> Catalog:  # fmt: skip
    """Read a file of two-line or three-line element sets (TLE / 3LE).

    Each element set is a line 1 and a line 2 (69 characters each), optionally after a
    name line (``"0 NAME"`` or a bare name).  Blank lines are skipped.

    Columns: ``id`` (NORAD catalog number, as a string without leading zeros;
    Alpha-5 numbers such as ``A0001`` become ``100001``), ``name`` (when any set has a
    name line), ``a_km`` (from the Brouwer mean motion, see the module docstring),
    ``e``, ``inc_deg``, ``raan_deg`` (RAAN at ``start``; the TLE's is
    ``raan_epoch_deg``), ``epoch`` (UTC, from the TLE epoch field), and
    ``argp_deg``, ``mean_anomaly_deg``, ``mean_motion_rev_per_day`` (the TLE's Kozai
    value), ``intl_designator``, ``bstar`` (the B* drag term [1/earth radii], as in
    columns 54-61 of line 1).

    Parameters
    ----------
    path : str or path-like
        The TLE file (UTF-8 or ASCII).
    start : str or datetime-like, optional
        Mission start date (UTC when naive); default the latest epoch.
    checksum : bool
        Check the checksum digit of every line (default True).
    on_invalid : {"raise", "set aside"}
        Element sets that are well formed but not orbits of this model (sgp4 rejects
        them, perigee below 150 km, ``a`` above 100,000 km, an epoch more than 10 years
        from the start): problems (default), or set aside in ``Catalog.invalid`` with
        their line and reason (the command line: the candidate filters decide).

    Raises
    ------
    CatalogError
        Every problem at once, each naming the file, the line number and the columns:
        a line of the wrong length, a field that is not a number, a bad checksum, a
        line 2 without its line 1 (or the reverse), catalog numbers of lines 1 and 2
        that differ, an object given twice, elements sgp4 rejects.
    """
    source, text = read_text(path)
    lines = _lines(text)
    if not any(line.startswith(("1 ", "2 ")) for line in lines):
        empty = "empty file: " if not text.strip() else ""
        _fail(source, f"{empty}no TLE element sets (pairs of lines starting with '1 ' and '2 ', "
                      "optionally after a name line)")  # fmt: skip
    problems: list[str] = []
    rows, where, flagged = [], [], {}
    for title, (n1, line1), (n2, line2) in _tle_sets(lines, source, problems):
        one = _tle_line(n1, line1, "1", source, checksum, problems)
        two = _tle_line(n2, line2, "2", source, checksum, problems)
        if one is None or two is None:
            continue
        if one["norad"] != two["norad"]:
            problems.append(
                f"{source}, line {n2}: catalog number {two['norad']} differs from "
                f"{one['norad']} on line 1 (line {n1}); expected line 2 of the same object"
            )
            continue
        satrec = Satrec.twoline2rv(line1, line2)
        problem = _sgp4_problem(satrec)
        a_km = kozai_a_km(two["mean_motion"]) if problem else brouwer_a_km(satrec)
        problem = problem or _a_problem(a_km, two["mean_motion"])
        if problem:
            flagged[len(rows)] = f": {problem}"
        name = None
        if title is not None:
            name = title[1][2:] if title[1].startswith("0 ") else title[1]
        intl = line1[9:17].strip()
        row = _element_row(one["norad"], name and name.strip(), one["epoch"], a_km, two, intl)
        row["bstar"] = one["bstar"]  # B* drag term [1/earth radii], for SGP4 (sdc_cvx.flight)
        rows.append(row)
        where.append(f"line {n1}")
    _duplicates(rows, where, source, problems)
    return _catalog(rows, source, start, problems, "TLE element sets", where=where,
                    flagged=flagged, on_invalid=on_invalid)  # fmt: skip


def _tle_pair(line1: str, line2: str) -> bool:
    """Lines 1 and 2 of one TLE (loosely: the lengths may be wrong)."""
    return (
        line1.startswith("1 ")
        and line2.startswith("2 ")
        and min(len(line1), len(line2)) >= 60
        and line1[2:7] == line2[2:7]
    )
