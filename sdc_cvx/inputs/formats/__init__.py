"""Real debris catalogs: TLE, CCSDS OMM and the GTOC9 debris file.

Every reader returns a :class:`~sdc_cvx.catalog.Catalog` built with
:meth:`Catalog.from_frame`, so validation and the propagation of each RAAN from its
epoch to the mission start (default: the latest epoch, paper Eq. 7) are the catalog's.
Bad input never gives a traceback: every problem of a file is collected and raised at
once in a :class:`~sdc_cvx.catalog.CatalogError` that names the file, the line (or the
record) and what was expected.

Semi-major axis convention (TLE and OMM)
----------------------------------------
A TLE or OMM mean motion is an SGP4 *Kozai* mean motion.  SGP4 itself first converts
it to the *Brouwer* (un-Kozai'd) mean motion ``no_unkozai`` and works with that, so
``a_km`` here is the semi-major axis that gives the Brouwer mean motion with this
package's gravity constant: ``a = (MU_EARTH / n_brouwer**2) ** (1/3)``, MU_EARTH =
3.986e14 m^3/s^2.  With this choice ``n = sqrt(mu / a^3)`` in the J2 rate (Eq. 7)
is the SGP4 mean motion again.  ``n_brouwer`` is read from sgp4 as
``1 / (satrec.tumin * satrec.a ** 1.5)`` [rad/min], which is exactly sgp4's
``no_unkozai`` (the compiled ``Satrec`` does not expose ``no_unkozai`` itself).

Measured on the 81 sun-synchronous rocket bodies of ``sso_rb.tle`` (600-900 km,
i ~ 98-100 deg): the Brouwer ``a`` is 2.76-2.97 km (mean 2.88 km) *below* the
``a = (mu / n_kozai**2) ** (1/3)`` of the raw TLE mean motion; sgp4's own
``satrec.a`` (WGS72, mu = 398600.8 km^3/s^2) is about 5 m above ours (mu differs).

Elements other than ``a`` (e, inclination, RAAN, argument of perigee, mean anomaly)
are the file's mean elements as written, not converted.
"""

from __future__ import annotations

import csv
import functools
import io
import json
import math
import os
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable
from datetime import datetime
from decimal import Decimal, InvalidOperation
from pathlib import Path

import pandas as pd
from sgp4 import omm
from sgp4.api import SGP4_ERRORS, Satrec

from ...physics.orbits import MU_EARTH
from ..catalog import R_EARTH_KM, Catalog, CatalogError, read_text

__all__ = [
    "FORMATS",
    "brouwer_a_km",
    "read_catalog",
    "read_gtoc9",
    "read_omm",
    "read_tle",
    "sniff_format",
    "tle_checksum",
]

FORMATS = ("csv", "tle", "omm", "gtoc9")
"""Catalog formats :func:`read_catalog` reads."""

TLE_LINE_LENGTH = 69

_MJD2000 = pd.Timestamp("2000-01-01T00:00:00Z")
"""MJD2000 = 0, i.e. JD 2451544.5, as in the GTOC9 data."""


# ---------------------------------------------------------------------- shared
def brouwer_a_km(satrec) -> float:
    """Semi-major axis [km] of an initialised sgp4 ``Satrec`` (see the module docstring).

    ``a = (MU_EARTH / n**2) ** (1/3)`` with ``n`` the Brouwer mean motion sgp4 derives
    from the Kozai mean motion of the element set (``no_unkozai``).
    """
    n_rad_per_min = 1.0 / (satrec.tumin * satrec.a**1.5)
    n = n_rad_per_min / 60.0
    return (MU_EARTH / n**2) ** (1.0 / 3.0) / 1000.0


def _lines(text: str) -> list[str]:
    """Lines of ``text`` without their ends; line k of the file is item k - 1."""
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


def _sgp4_problem(satrec) -> str | None:
    """Why sgp4 rejects an initialised element set, or None."""
    if satrec.error:
        return f"sgp4 rejects the element set: {SGP4_ERRORS.get(satrec.error, satrec.error)}"
    if not (math.isfinite(satrec.a) and satrec.a > 0.0):
        return "sgp4 rejects the element set: no finite semi-major axis"
    return None


def _a_problem(a_km: float, mean_motion: float) -> str | None:
    if a_km > R_EARTH_KM:
        return None
    return (
        f"mean motion {mean_motion:g} rev/day gives a = {a_km:.1f} km, not above the "
        f"Earth's radius {R_EARTH_KM} km"
    )


def _catalog(rows: list[dict], source: str, start, problems: list[str], what: str) -> Catalog:
    """Validated catalog of ``rows``, or every problem raised."""
    if not rows and not problems:
        problems.append(f"{source}: no {what} found")
    if problems:
        raise CatalogError.collect(source, _by_line(problems, source))
    frame = pd.DataFrame(rows)
    if "name" in frame.columns and not frame["name"].astype(bool).any():
        frame = frame.drop(columns="name")
    return Catalog.from_frame(frame, source=source, start=start)


def _by_line(problems: list[str], source: str) -> list[str]:
    """Problems sorted by their line number (stable; those without one last)."""

    def line(problem: str) -> float:
        found = re.match(r", line (\d+)", problem[len(source) :])
        return int(found.group(1)) if found else math.inf

    return sorted(problems, key=line)


def _duplicates(rows, where, source, problems, noun="catalog number") -> None:
    """Report ids given twice; ``where[k]`` locates row k."""
    first: dict[str, int] = {}
    for k, row in enumerate(rows):
        if row["id"] in first:
            problems.append(
                f"{source}, {where[k]}: {noun} {row['id']} again (first at "
                f"{where[first[row['id']]]}); expected one element set per object"
            )
        first.setdefault(row["id"], k)


def _element_row(norad, name, epoch, a_km, fields: dict, intl: str) -> dict:
    return {
        "id": str(norad),
        "name": name or "",
        "a_km": a_km,
        "e": fields["e"],
        "inc_deg": fields["inc_deg"],
        "raan_deg": fields["raan_deg"],
        "epoch": epoch,
        "argp_deg": fields["argp_deg"],
        "mean_anomaly_deg": fields["mean_anomaly_deg"],
        "mean_motion_rev_per_day": fields["mean_motion"],
        "intl_designator": intl,
    }


def _format_hint(fmt: str):
    """Decorate a reader: when it fails on a file whose content looks like another
    format, say so first (e.g. a GTOC9 ``.txt`` file read as TLE)."""

    def decorate(reader):
        @functools.wraps(reader)
        def read(path, *args, **kwargs):
            try:
                return reader(path, *args, **kwargs)
            except CatalogError as err:
                guess = sniff_format(path)
                if guess is None or guess == fmt:
                    raise
                source = os.fspath(path)
                hint = (f"{source}: the content looks like a {guess!r} catalog, not {fmt!r}; "
                        f"read it with format {guess!r}")  # fmt: skip
                raise CatalogError.collect(source, [hint, *err.problems]) from None

        return read

    return decorate


# ---------------------------------------------------------------------- TLE
def tle_checksum(line: str) -> int:
    """TLE checksum of a line: digits of columns 1-68 summed, each '-' counting 1, mod 10."""
    body = line[:68]
    return (sum(int(char) for char in body if char in "0123456789") + body.count("-")) % 10


_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)\Z")
_ALPHA5 = "ABCDEFGHJKLMNPQRSTUVWXYZ"  # Alpha-5: I and O are not used


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
    try:
        day = Decimal(day_text)
    except InvalidOperation:
        return None, expected
    first = pd.Timestamp(year=year, month=1, day=1, tz="UTC")
    days_in_year = 366 if first.is_leap_year else 365
    if not 1 <= day < days_in_year + 1:
        return None, f"{expected}; day {day_text} is not in [1, {days_in_year + 1})"
    nanoseconds = int(((day - 1) * 86_400_000_000_000).to_integral_value())
    return first + pd.Timedelta(nanoseconds, unit="ns"), None


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


def _short(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:36] + "...")


@_format_hint("tle")
def read_tle(path: str | os.PathLike, *, start=None, checksum: bool = True) -> Catalog:
    """Read a file of two-line or three-line element sets (TLE / 3LE).

    Each element set is a line 1 and a line 2 (69 characters each), optionally after a
    name line (``"0 NAME"`` or a bare name).  Blank lines are skipped.

    Columns: ``id`` (NORAD catalog number, as a string without leading zeros;
    Alpha-5 numbers such as ``A0001`` become ``100001``), ``name`` (when any set has a
    name line), ``a_km`` (from the Brouwer mean motion, see the module docstring),
    ``e``, ``inc_deg``, ``raan_deg`` (RAAN at ``start``; the TLE's is
    ``raan_epoch_deg``), ``epoch`` (UTC, from the TLE epoch field), and
    ``argp_deg``, ``mean_anomaly_deg``, ``mean_motion_rev_per_day`` (the TLE's Kozai
    value), ``intl_designator``.

    Parameters
    ----------
    path : str or path-like
        The TLE file (UTF-8 or ASCII).
    start : str or datetime-like, optional
        Mission start date (UTC when naive); default the latest epoch.
    checksum : bool
        Check the checksum digit of every line (default True).

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
    rows, where = [], []
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
        a_km = None if problem else brouwer_a_km(satrec)
        problem = problem or _a_problem(a_km, two["mean_motion"])
        if problem:
            problems.append(f"{source}, line {n1} (catalog number {one['norad']}): {problem}")
            continue
        name = None
        if title is not None:
            name = title[1][2:] if title[1].startswith("0 ") else title[1]
        intl = line1[9:17].strip()
        rows.append(_element_row(one["norad"], name and name.strip(), one["epoch"], a_km,
                                 two, intl))  # fmt: skip
        where.append(f"line {n1}")
    _duplicates(rows, where, source, problems)
    return _catalog(rows, source, start, problems, "TLE element sets")


# ---------------------------------------------------------------------- OMM
_OMM_REQUIRED = ("NORAD_CAT_ID", "EPOCH", "MEAN_MOTION", "ECCENTRICITY", "INCLINATION",
                 "RA_OF_ASC_NODE", "ARG_OF_PERICENTER", "MEAN_ANOMALY")  # fmt: skip
_OMM_DEFAULTS = {
    "OBJECT_NAME": "",
    "OBJECT_ID": "",
    "CLASSIFICATION_TYPE": "U",
    "EPHEMERIS_TYPE": "0",
    "ELEMENT_SET_NO": "999",
    "REV_AT_EPOCH": "0",
    "BSTAR": "0",
    "MEAN_MOTION_DOT": "0",
    "MEAN_MOTION_DDOT": "0",
}
"""Fields sgp4 needs that do not change the elements read here: default when absent."""

_OMM_EPOCH = re.compile(
    r"(\d{4})-(?:(\d{2})-(\d{2})|(\d{3}))T(\d{2}):(\d{2}):(\d{2})(\.\d+)?Z?\Z"
)  # fmt: skip
_OMM_EPOCH_EXPECTED = "an epoch such as 2020-05-24T07:15:18.796032 (UTC)"


def _omm_epoch(value) -> pd.Timestamp | None:
    if not isinstance(value, str):
        return None
    match = _OMM_EPOCH.match(value.strip())
    if not match:
        return None
    year, month, day, doy, hour, minute, second, fraction = match.groups()
    try:
        if doy is not None:
            base = pd.Timestamp(year=int(year), month=1, day=1, tz="UTC")
            if not 1 <= int(doy) <= (366 if base.is_leap_year else 365):
                return None
            base += pd.Timedelta(days=int(doy) - 1)
        else:
            base = pd.Timestamp(year=int(year), month=int(month), day=int(day), tz="UTC")
        clock = datetime.strptime(f"{hour}:{minute}:{second}", "%H:%M:%S")
    except ValueError:
        return None
    nanoseconds = int((Decimal(fraction or "0") * 10**9).to_integral_value())
    offset = pd.Timedelta(hours=clock.hour, minutes=clock.minute, seconds=clock.second)
    return base + offset + pd.Timedelta(nanoseconds, unit="ns")


def _omm_float(value, low=-math.inf, high=math.inf, *, positive=False, below=None):
    """(float, None) or (None, expected)."""
    expected = "a number"
    if isinstance(value, bool) or not isinstance(value, int | float | str):
        return None, expected
    try:
        if isinstance(value, str) and "_" in value:
            raise ValueError
        number = float(value)
    except ValueError:
        return None, expected
    if not math.isfinite(number):
        return None, "a finite number"
    if positive and number <= 0.0:
        return None, "a number > 0"
    if below is not None and not low <= number < below:
        return None, f"a number in [{low:g}, {below:g})"
    if not low <= number <= high:
        return None, f"a number in [{low:g}, {high:g}]"
    return number, None


def _omm_int(value):
    if isinstance(value, bool):
        return None, "an integer"
    if isinstance(value, int):
        return value, None
    if isinstance(value, str) and value.strip().isdigit() and value.strip().isascii():
        return int(value.strip()), None
    if isinstance(value, float) and value.is_integer():
        return int(value), None
    return None, "an integer"


_OMM_CHECKS: dict[str, Callable] = {
    "NORAD_CAT_ID": _omm_int,
    "MEAN_MOTION": lambda v: _omm_float(v, positive=True),
    "ECCENTRICITY": lambda v: _omm_float(v, 0.0, below=1.0),
    "INCLINATION": lambda v: _omm_float(v, 0.0, 180.0),
    "RA_OF_ASC_NODE": _omm_float,
    "ARG_OF_PERICENTER": _omm_float,
    "MEAN_ANOMALY": _omm_float,
    "BSTAR": _omm_float,
    "MEAN_MOTION_DOT": _omm_float,
    "MEAN_MOTION_DDOT": _omm_float,
    "EPHEMERIS_TYPE": _omm_int,
    "ELEMENT_SET_NO": _omm_int,
    "REV_AT_EPOCH": _omm_int,
}


def _omm_records(text: str, source: str) -> tuple[str, list[tuple[str, dict | str]]]:
    """``(kind, [(where, fields or problem)])`` of an OMM text in XML, JSON, KVN or CSV."""
    stripped = text.lstrip()
    if stripped.startswith("<"):
        return "XML", _omm_xml(text, source)
    if stripped.startswith(("[", "{")):
        return "JSON", _omm_json(text, source)
    if any(line.strip().startswith("CCSDS_OMM_VERS") for line in _lines(stripped)[:20]):
        return "KVN", _omm_kvn(text)
    return "CSV", _omm_csv(text, source)


def _fail(source: str, message: str):
    raise CatalogError.collect(source, [f"{source}: {message}"])


def _omm_xml(text: str, source: str):
    try:
        records = list(omm.parse_xml(io.StringIO(text)))
    except ET.ParseError as exc:
        line, column = exc.position
        _fail(source, f"not valid XML (line {line}, column {column + 1}: {exc.msg})")
    except AttributeError:  # a <segment> without <metadata>, <data>, <meanElements>...
        _fail(source, "an OMM <segment> lacks <metadata>, <data>, <meanElements> or "
                      "<tleParameters>")  # fmt: skip
    return [(f"segment {k}", fields) for k, fields in enumerate(records, start=1)]


def _omm_json(text: str, source: str):
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        _fail(source, f"not valid JSON (line {exc.lineno}, column {exc.colno}: {exc.msg})")
    if isinstance(data, dict):
        data = [data]
    if not isinstance(data, list):
        _fail(source, "expected a JSON list of OMM objects (CelesTrak style)")
    records = []
    for k, item in enumerate(data, start=1):
        if not isinstance(item, dict):
            item = f"expected an OMM object (field names and values), got {_short(str(item))}"
        records.append((f"record {k}", item))
    return records


def _omm_kvn(text: str):
    records, fields, begin = [], {}, None
    for number, raw in enumerate(_lines(text), start=1):
        line = raw.strip()
        if not line or line.startswith("COMMENT") or "=" not in line:
            continue
        key, _, value = line.partition("=")
        key, value = key.strip(), re.sub(r"\s*\[[^\]]*\]\s*$", "", value.strip())
        if key == "CCSDS_OMM_VERS" and fields:
            records.append((f"record {len(records) + 1} (line {begin})", fields))
            fields = {}
        if not fields:
            begin = number
        fields[key] = value
    if fields:
        records.append((f"record {len(records) + 1} (line {begin})", fields))
    return records


def _omm_csv(text: str, source: str):
    reader = omm.parse_csv(io.StringIO(text))
    records = []
    try:
        for fields in reader:
            if not any(
                (value or "").strip() for value in fields.values() if isinstance(value, str)
            ):
                continue
            if None in fields:  # more values than the header has names
                width = len(reader.fieldnames or [])
                fields = (f"expected {width} fields as in the header, got "
                          f"{width + len(fields[None])}")  # fmt: skip
            records.append((f"line {reader.line_num}", fields))
    except csv.Error as exc:
        _fail(source, f"not valid CSV (line {reader.line_num}: {exc})")
    header = reader.fieldnames or []
    missing = [name for name in _OMM_REQUIRED if name not in header]
    if missing:
        _fail(source, f"header: missing OMM column(s) {', '.join(missing)}; found "
                      f"{', '.join(header) or 'no header'}")  # fmt: skip
    return records


def _omm_fields(fields: dict, prefix: str, problems: list[str]):
    """Checked fields as sgp4 strings plus the epoch, or None (problems appended).

    ``fields`` is a problem (str) for a record that cannot be read as fields.
    """
    if isinstance(fields, str):
        problems.append(f"{prefix}: {fields}")
        return None
    fields = {str(key).strip().upper(): value for key, value in fields.items()}
    missing = [key for key in _OMM_REQUIRED if _blank(fields.get(key))]
    if missing:
        problems.append(f"{prefix}: missing OMM field(s) {', '.join(missing)}")
    ok = not missing
    theory = fields.get("MEAN_ELEMENT_THEORY")
    if not _blank(theory) and "SGP4" not in str(theory).upper():
        problems.append(f"{prefix}, field 'MEAN_ELEMENT_THEORY': expected SGP4 mean elements, "
                        f"got {theory!r}")  # fmt: skip
        ok = False
    system = fields.get("TIME_SYSTEM")
    if not _blank(system) and str(system).strip().upper() != "UTC":
        problems.append(f"{prefix}, field 'TIME_SYSTEM': expected UTC, got {system!r}")
        ok = False
    values = dict(_OMM_DEFAULTS)
    values.update({key: value for key, value in fields.items() if not _blank(value)})
    checked = {}
    for key, check in _OMM_CHECKS.items():
        if key in missing:
            continue
        checked[key], expected = check(values[key])
        if expected:
            problems.append(f"{prefix}, field '{key}': expected {expected}, got "
                            f"{_short(str(values[key]))}")  # fmt: skip
            ok = False
    epoch = None
    if "EPOCH" not in missing:
        epoch = _omm_epoch(values["EPOCH"])
        if epoch is None:
            problems.append(f"{prefix}, field 'EPOCH': expected {_OMM_EPOCH_EXPECTED}, got "
                            f"{_short(str(values['EPOCH']))}")  # fmt: skip
            ok = False
    if not ok:
        return None
    strings = {key: str(value).strip() for key, value in values.items()}
    strings["EPOCH"] = epoch.strftime("%Y-%m-%dT%H:%M:%S.%f")
    return strings, checked, epoch


def _blank(value) -> bool:
    return value is None or (isinstance(value, str) and not value.strip())


@_format_hint("omm")
def read_omm(path: str | os.PathLike, *, start=None) -> Catalog:
    """Read CCSDS Orbit Mean-Elements Messages: CSV, XML, JSON (CelesTrak style) or KVN.

    The kind is told from the content: XML starts with ``<``, JSON with ``[`` or
    ``{`` (a list of objects, or one object), KVN with ``CCSDS_OMM_VERS``; anything else
    is read as CSV with a header line.  Field names are CelesTrak's / CCSDS's:
    ``NORAD_CAT_ID, EPOCH, MEAN_MOTION, ECCENTRICITY, INCLINATION, RA_OF_ASC_NODE,
    ARG_OF_PERICENTER, MEAN_ANOMALY`` are required; ``OBJECT_NAME, OBJECT_ID, BSTAR,
    MEAN_MOTION_DOT, ...`` optional.  ``MEAN_ELEMENT_THEORY`` and ``TIME_SYSTEM``, when
    given, must be SGP4 and UTC.  The elements go through ``sgp4.omm.initialize``,
    and ``a_km`` follows the same convention as :func:`read_tle` (module docstring),
    so an OMM and the TLE of the same element set give the same catalog.

    Columns are those of :func:`read_tle`; ``name`` is ``OBJECT_NAME`` and
    ``intl_designator`` is ``OBJECT_ID``.

    Raises
    ------
    CatalogError
        Every problem at once, naming the file and the record (``line N`` in CSV,
        ``segment k`` in XML, ``record k`` in JSON and KVN) and the field.
    """
    source, text = read_text(path)
    if not text.strip():
        _fail(source, "empty file (no OMM records)")
    kind, records = _omm_records(text, source)
    problems: list[str] = []
    rows, where = [], []
    for label, fields in records:
        prefix = f"{source}, {label}"
        checked = _omm_fields(fields, prefix, problems)
        if checked is None:
            continue
        strings, values, epoch = checked
        satrec = Satrec()
        try:
            omm.initialize(satrec, strings)
        except (ValueError, KeyError) as exc:
            problems.append(f"{prefix}: sgp4 cannot read the record ({exc})")
            continue
        problem = _sgp4_problem(satrec)
        a_km = None if problem else brouwer_a_km(satrec)
        problem = problem or _a_problem(a_km, values["MEAN_MOTION"])
        if problem:
            problems.append(f"{prefix} (catalog number {values['NORAD_CAT_ID']}): {problem}")
            continue
        elements = {
            "e": values["ECCENTRICITY"],
            "inc_deg": values["INCLINATION"],
            "raan_deg": values["RA_OF_ASC_NODE"],
            "argp_deg": values["ARG_OF_PERICENTER"],
            "mean_anomaly_deg": values["MEAN_ANOMALY"],
            "mean_motion": values["MEAN_MOTION"],
        }
        rows.append(_element_row(values["NORAD_CAT_ID"], strings["OBJECT_NAME"], epoch, a_km,
                                 elements, strings["OBJECT_ID"]))  # fmt: skip
        where.append(label)
    _duplicates(rows, where, source, problems)
    return _catalog(rows, source, start, problems, f"OMM records ({kind})")


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


@_format_hint("gtoc9")
def read_gtoc9(path: str | os.PathLike, *, start=None) -> Catalog:
    """Read the GTOC9 debris file (``debris_data.txt``, or the official ``debris.csv``).

    One debris per line, 8 numbers separated by blanks or tabs (commas are accepted
    too): id, epoch [MJD2000], a [m], e, i [rad], RAAN [rad], argument of perigee
    [rad], mean anomaly [rad].  A first line that is not numeric (a header) and lines
    starting with ``#`` are skipped.  The epoch is UTC ``2000-01-01 00:00`` + MJD2000
    days (JD = MJD2000 + 2451544.5).  The elements are GTOC9's osculating elements,
    used as they are (GTOC9 itself propagates them with secular J2 rates only).

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
    return _catalog(rows, source, start, problems, "GTOC9 debris lines")


def _gtoc9_float(text: str) -> float | None:
    if "_" in text:
        return None
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


# ---------------------------------------------------------------------- dispatch
def _sniff_text(text: str) -> str | None:
    """Catalog format told from the beginning of a text, or None."""
    stripped = text.lstrip()
    if not stripped:
        return None
    if stripped[0] == "<" or re.match(r"\{|\[\s*[{\]]", stripped):  # XML, JSON (not TOML)
        return "omm"
    lines = [line.rstrip() for line in _lines(stripped) if line.strip()][:12]
    if any(line.startswith("CCSDS_OMM_VERS") for line in lines):
        return "omm"
    if any(_tle_pair(a, b) for a, b in zip(lines, lines[1:], strict=False)):
        return "tle"
    header = {field.strip() for field in next(csv.reader([lines[0]]), [])}
    if {"NORAD_CAT_ID", "MEAN_MOTION"} <= {name.upper() for name in header}:
        return "omm"
    if {"id", "a_km"} <= header:
        return "csv"
    for line in lines[:2]:
        fields = line.replace(",", " ").split()
        if len(fields) == len(GTOC9_COLUMNS) and all(_gtoc9_float(f) is not None for f in fields):
            return "gtoc9"
    return None


def _tle_pair(line1: str, line2: str) -> bool:
    """Lines 1 and 2 of one TLE (loosely: the lengths may be wrong)."""
    return (
        line1.startswith("1 ")
        and line2.startswith("2 ")
        and min(len(line1), len(line2)) >= 60
        and line1[2:7] == line2[2:7]
    )


def sniff_format(path: str | os.PathLike) -> str | None:
    """Catalog format told from the content of a file, or None if it cannot be told.

    TLE: a line starting with ``"1 "`` followed by one starting with ``"2 "`` with the
    same catalog number; OMM:
    XML (``<``), JSON (``[``, ``{``), KVN (``CCSDS_OMM_VERS``) or a CSV header with
    ``NORAD_CAT_ID`` and ``MEAN_MOTION``; csv: a header with ``id`` and ``a_km``;
    gtoc9: 8 numbers on one of the first two lines.
    """
    try:
        with open(path, "rb") as stream:
            head = stream.read(65536)
    except OSError:
        return None
    return _sniff_text(head.decode("utf-8-sig", errors="replace"))


READERS: dict[str, Callable[..., Catalog]] = {
    "csv": _format_hint("csv")(Catalog.from_csv),
    "tle": read_tle,
    "omm": read_omm,
    "gtoc9": read_gtoc9,
}
"""Reader of each format; each takes ``(path, *, start=None)``."""


def read_catalog(path: str | os.PathLike, format: str | None = None, *, start=None) -> Catalog:
    """Read a debris catalog in any supported format.

    Parameters
    ----------
    path : str or path-like
        The catalog file.
    format : {"csv", "tle", "omm", "gtoc9"}, optional
        Default: told from the content (:func:`sniff_format`), else from the
        extension (``.csv``; ``.tle``, ``.3le``, ``.txt``; ``.xml``, ``.json``,
        ``.kvn``, ``.omm``).
    start : str or datetime-like, optional
        Mission start date (UTC when naive); default the latest epoch.

    Raises
    ------
    CatalogError
        Unknown format, a format that cannot be told, or any problem of the file.
    """
    source = os.fspath(path)
    if format is None:
        from ...study.scenario import EXTENSION_FORMATS  # scenario imports this module

        format = sniff_format(path) or EXTENSION_FORMATS.get(Path(source).suffix.lower())
        if format is None and Path(source).is_file():
            _fail(source, f"cannot tell the catalog format from the content or the extension; "
                          f"give one of {', '.join(FORMATS)}")  # fmt: skip
        format = format or "csv"  # a missing file: let the reader say so
    reader = READERS.get(str(format).lower())
    if reader is None:
        _fail(source, f"unknown catalog format {format!r}; expected one of {', '.join(FORMATS)}")
    return reader(path, start=start)
