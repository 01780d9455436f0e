"""CCSDS Orbit Mean-Elements Messages: XML, JSON, KVN and CSV (see :mod:`._common` for the
semi-major axis convention)."""

from __future__ import annotations

import csv
import io
import json
import math
import os
import re
import xml.etree.ElementTree as ET
from collections.abc import Callable
from datetime import datetime
from decimal import Decimal

import pandas as pd
from sgp4 import omm
from sgp4.api import Satrec

from ...errors import listing
from ..catalog import Catalog, read_text
from ..sgp4_sets import brouwer_a_km
from ._common import (
    _a_problem,
    _blank,
    _catalog,
    _duplicates,
    _element_row,
    _fail,
    _lines,
    _sgp4_problem,
    _short,
    kozai_a_km,
)

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
    except RecursionError:  # lists within lists thousands deep: no OMM file is
        _fail(source, "JSON nested too deeply to be an OMM list (expected a list of objects)")
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
                      f"{listing(header) or 'no header'}")  # fmt: skip
    return records


_OMM_FIXED = {"TIME_SYSTEM": "UTC", "REF_FRAME": "TEME", "CENTER_NAME": "EARTH"}
"""OMM fields that, when given, must have these values for SGP4 mean elements."""


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
    for key, expected in _OMM_FIXED.items():  # SGP4's elements: UTC, TEME, the Earth
        given = fields.get(key)
        if not _blank(given) and str(given).strip().upper() != expected:
            problems.append(f"{prefix}, field '{key}': expected {expected}, got {given!r}")
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


def read_omm(path: str | os.PathLike, *, start=None, on_invalid: str = "raise") -> Catalog:
    """Read CCSDS Orbit Mean-Elements Messages: CSV, XML, JSON (CelesTrak style) or KVN.

    The kind is told from the content: XML starts with ``<``, JSON with ``[`` or
    ``{`` (a list of objects, or one object), KVN with ``CCSDS_OMM_VERS``; anything else
    is read as CSV with a header line.  Field names are CelesTrak's / CCSDS's:
    ``NORAD_CAT_ID, EPOCH, MEAN_MOTION, ECCENTRICITY, INCLINATION, RA_OF_ASC_NODE,
    ARG_OF_PERICENTER, MEAN_ANOMALY`` are required; ``OBJECT_NAME, OBJECT_ID, BSTAR,
    MEAN_MOTION_DOT, ...`` optional.  ``MEAN_ELEMENT_THEORY``, ``TIME_SYSTEM``,
    ``REF_FRAME`` and ``CENTER_NAME``, when given, must be SGP4, UTC, TEME and EARTH.
    The elements go through ``sgp4.omm.initialize``, and ``a_km`` follows the same
    convention as :func:`read_tle` (module docstring), so an OMM and the TLE of the same
    element set give the same catalog.

    Columns are those of :func:`read_tle`; ``name`` is ``OBJECT_NAME``,
    ``intl_designator`` is ``OBJECT_ID`` and ``bstar`` is ``BSTAR`` (0 when absent).

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
    rows, where, flagged = [], [], {}
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
        a_km = kozai_a_km(values["MEAN_MOTION"]) if problem else brouwer_a_km(satrec)
        problem = problem or _a_problem(a_km, values["MEAN_MOTION"])
        if problem:
            flagged[len(rows)] = f": {problem}"
        elements = {
            "e": values["ECCENTRICITY"],
            "inc_deg": values["INCLINATION"],
            "raan_deg": values["RA_OF_ASC_NODE"],
            "argp_deg": values["ARG_OF_PERICENTER"],
            "mean_anomaly_deg": values["MEAN_ANOMALY"],
            "mean_motion": values["MEAN_MOTION"],
        }
        row = _element_row(values["NORAD_CAT_ID"], strings["OBJECT_NAME"], epoch, a_km,
                           elements, strings["OBJECT_ID"])  # fmt: skip
        row["bstar"] = values["BSTAR"]  # B* drag term [1/earth radii], 0 when absent
        rows.append(row)
        where.append(label)
    _duplicates(rows, where, source, problems)
    return _catalog(rows, source, start, problems, f"OMM records ({kind})", where=where,
                    flagged=flagged, on_invalid=on_invalid)  # fmt: skip
