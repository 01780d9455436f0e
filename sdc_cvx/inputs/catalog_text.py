"""A catalog file's text read into values: the file, its CSV header and records, each field.

:func:`read_text` reads any catalog file (every format's reader starts there);
:func:`read_csv_records` splits a CSV text into its header and records; the ``to_*``
functions turn one field into a value, or say in words why they cannot.  The columns a
catalog requires, may have and computes are named here (:data:`REQUIRED_COLUMNS`,
:data:`OPTIONAL_COLUMNS`, :data:`DERIVED_COLUMNS`, :data:`KNOWN_COLUMNS`); a column it
does not read draws a :class:`~sdc_cvx.errors.CatalogWarning`.  Bad input never produces a
pandas or numpy traceback: a problem is a message naming the file, row, line and field.
"""

from __future__ import annotations

import csv
import math
import numbers
import os
import re
import warnings
from collections.abc import Iterable
from datetime import datetime
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import CatalogError, CatalogWarning, listing

REQUIRED_COLUMNS = ("id", "a_km", "e", "inc_deg", "raan_deg")
"""Columns every catalog must have."""
OPTIONAL_COLUMNS = ("name", "epoch")
"""Columns a catalog may have; any other column is kept untouched."""
DERIVED_COLUMNS = ("raan_rate_deg_per_day", "altitude_km", "raan_epoch_deg")
"""Columns computed by the catalog; input columns of these names are recomputed."""
KNOWN_COLUMNS = (
    "id", "a_km", "e", "inc_deg", "raan_deg", "name", "epoch", "raan_rate_deg_per_day",
    "altitude_km", "raan_epoch_deg", "argp_deg", "mean_anomaly_deg",
    "mean_motion_rev_per_day", "intl_designator", "arglat_deg", "bstar",
)  # fmt: skip
"""Columns a catalog reads or its readers write; any other draws a :class:`CatalogWarning`."""
EPOCH_EXPECTED = "expected an ISO-8601 UTC date such as 2020-05-24T12:00:00Z"
"""What an epoch must be, in the messages about one."""


# ---------------------------------------------------------------------- the file
def read_text(path: str | os.PathLike) -> tuple[str, str]:
    """``(source, text)`` of a UTF-8 file (BOM dropped), or a CatalogError saying why not."""
    source = os.fspath(path)
    file = Path(source)
    if not file.exists():
        raise CatalogError.collect(source, [f"{source}: file not found"])
    if file.is_dir():
        raise CatalogError.collect(source, [f"{source}: is a directory, not a file"])
    try:
        text = file.read_bytes().decode("utf-8-sig")
    except PermissionError:
        raise CatalogError.collect(
            source, [f"{source}: not readable (permission denied)"]
        ) from None
    except UnicodeDecodeError as exc:
        message = f"{source}: not a UTF-8 text file (undecodable byte at offset {exc.start})"
        raise CatalogError.collect(source, [message]) from None
    except OSError as exc:
        reason = exc.strerror or str(exc)
        raise CatalogError.collect(source, [f"{source}: not readable ({reason})"]) from None
    return source, text


def csv_delimiter(text: str) -> str:
    """The field separator of a CSV catalog: ``,`` unless the header line (the first that is
    not blank) has none and has ``;`` or a tab (a spreadsheet's export in some locales)."""
    for line in text.splitlines():
        if line.strip():
            if "," not in line:
                for other in (";", "\t"):
                    if other in line:
                        return other
            return ","
    return ","


def read_csv_records(stream: Iterable[str], source: str, delimiter: str = ","):
    """Header and ``(first line, fields)`` records of a CSV text, blank lines skipped.

    Column names that are known columns in another case (``ID``, ``A_KM``) are read as
    those columns.  Raises a :class:`CatalogError` at once for an empty file, a file
    without data rows, malformed CSV or a bad header (missing, duplicate or blank column
    names).
    """
    reader = csv.reader(stream, delimiter=delimiter)
    header = None
    records = []
    line = 0
    try:
        for fields in reader:
            first, line = line + 1, reader.line_num
            if all(not field.strip() for field in fields):
                continue
            if header is None:
                header = [_known_case(field.strip()) for field in fields]
            else:
                records.append((first, fields))
    except csv.Error as exc:
        message = f"{source}, line {reader.line_num}: not valid CSV ({exc})"
        raise CatalogError.collect(source, [message]) from None
    if header is None:
        raise CatalogError.collect(source, [f"{source}: empty file (no header line)"])
    problems = header_problems(header, source)
    if not records:
        problems.append(f"{source}: header but no data rows")
    if problems:
        raise CatalogError.collect(source, problems)
    return header, records


def _known_case(name: str) -> str:
    """``name`` as the known column it names in any case (``"A_KM"`` -> ``"a_km"``)."""
    lower = name.lower()
    return lower if lower != name and lower in KNOWN_COLUMNS else name


def header_problems(columns: list, source: str) -> list[str]:
    """Missing required, duplicate and blank column names."""
    problems = []
    if not columns:
        return [f"{source}: no columns"]
    names = [str(column) for column in columns]
    for number, name in enumerate(names, start=1):
        if not name.strip():
            problems.append(f"{source}, header: column {number} has no name")
    duplicated = sorted({name for name in names if name.strip() and names.count(name) > 1})
    for name in duplicated:
        problems.append(f"{source}, header: column {name!r} appears more than once")
    missing = [name for name in REQUIRED_COLUMNS if name not in columns]
    if missing:
        problems.append(
            f"{source}, header: missing required column(s) {', '.join(map(repr, missing))}; "
            f"found {listing(map(repr, names))}"
        )
    return problems


def warn_unknown_columns(columns: list, source: str) -> None:
    """One :class:`CatalogWarning` per column the catalog does not read (a typo, likely)."""
    for column in columns:
        if str(column) in KNOWN_COLUMNS:
            continue
        hint = ""
        if "epoch" in str(column).lower():
            hint = f"; the epoch column is named 'epoch' ({EPOCH_EXPECTED})"
        warnings.warn(
            f"{source}, header: unknown column {str(column)!r} is not used (kept as text); "
            f"the columns read are {', '.join(REQUIRED_COLUMNS)} and optional "
            f"{', '.join(c for c in KNOWN_COLUMNS if c not in REQUIRED_COLUMNS + DERIVED_COLUMNS)}"
            f"{hint}",
            CatalogWarning,
            stacklevel=5,  # the caller of Catalog.from_frame, or of a reader
        )


# ---------------------------------------------------------------------- one field
def is_missing(value) -> bool:
    """None, NaN, NA or NaT (scalars only)."""
    return bool(pd.api.types.is_scalar(value) and pd.isna(value))


def is_blank(value) -> bool:
    return is_missing(value) or (isinstance(value, str) and not value.strip())


def show_value(value) -> str:
    """Short quoted form of an input value for messages."""
    if isinstance(value, np.generic):
        value = value.item()
    text = repr(value)
    return text if len(text) <= 40 else text[:36] + "..." + text[-1]


def to_id(value) -> tuple[str, str | None]:
    """Debris id as a string: integral numbers lose their ``.0``."""
    if is_blank(value):
        return "", "expected a non-blank id, got a blank value"
    if isinstance(value, str):
        return value.strip(), None
    if isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_):
        return str(int(value)), None
    if isinstance(value, numbers.Real) and float(value).is_integer():
        return str(int(value)), None
    return str(value).strip(), None


def to_float(value, check) -> tuple[float, str | None]:
    """Finite float passing ``check``, or an error message."""
    if type(value) is float and math.isfinite(value):  # the readers' values: fast path
        error = check(value)
        return (math.nan, error.format(got=show_value(value))) if error else (value, None)
    if is_blank(value):
        return math.nan, "expected a number, got a blank value"
    is_real = isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
    try:
        if not (is_real or isinstance(value, str)):
            raise TypeError
        number = float(value)
    except (ValueError, TypeError, OverflowError):
        hint = ""
        if isinstance(value, str) and re.fullmatch(r"\s*[+-]?\d+,\d+\s*", value):
            hint = f" (a decimal comma? write {value.strip().replace(',', '.')})"
        return math.nan, f"expected a number, got {show_value(value)}{hint}"
    if math.isnan(number):
        return math.nan, f"expected a number, got {show_value(value)} (NaN)"
    if not math.isfinite(number):
        return math.nan, f"expected a finite number, got {show_value(value)}"
    error = check(number)
    if error:
        return math.nan, error.format(got=show_value(value))
    return number, None


def _to_timestamp(value) -> pd.Timestamp | None:
    """UTC timestamp from an ISO-8601 string or a datetime (naive means UTC), or None."""
    try:
        if isinstance(value, str):
            value = datetime.fromisoformat(value.strip())
        elif not isinstance(value, datetime | np.datetime64):
            return None
        stamp = pd.Timestamp(value)
    except (ValueError, TypeError, OverflowError):
        return None
    if stamp is pd.NaT:
        return None
    return stamp.tz_localize("UTC") if stamp.tzinfo is None else stamp.tz_convert("UTC")


def to_epoch(value) -> tuple[pd.Timestamp | None, str | None]:
    """Epoch of a row: (timestamp, None), (None, None) when blank, or (None, error)."""
    if type(value) is pd.Timestamp and value.tz is not None and str(value.tz) == "UTC":
        return value, None  # the readers' epochs: fast path
    if is_blank(value):
        return None, None
    stamp = _to_timestamp(value)
    return stamp, None if stamp is not None else f"{EPOCH_EXPECTED}, got {show_value(value)}"


def parse_start(start, source: str, problems: list[str]) -> pd.Timestamp | None:
    if start is None:
        return None
    stamp = _to_timestamp(start)
    if stamp is None:
        problems.append(f"{source}, argument 'start': {EPOCH_EXPECTED}, got {show_value(start)}")
    return stamp
