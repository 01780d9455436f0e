"""Debris catalogs: read, validate and hold the orbits of the candidate debris.

A :class:`Catalog` is a validated table with one row per debris, in the units people
read (km, deg, deg/day), and SI accessors (m, rad) for the physics.  The RAANs it
holds are those at the mission start date: when the rows carry epochs, each RAAN is
propagated from its epoch to the start with its own J2 secular rate (paper Eq. 7,
``Omega(t) = Omega(t0) + dOmega/dt (t - t0)``).

Input comes from a CSV file, a DataFrame, or the paper's Table 5 bundled with the
package.  Bad input never produces a pandas or numpy traceback: every problem of a file
is collected and reported at once in a :class:`CatalogError` that names the file, the
row, the line and the field.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import csv
import io
import math
import numbers
import os
import warnings
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from datetime import datetime
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import MAX_REPORTED, CatalogError, CatalogWarning
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY, raan_rate

__all__ = [
    "DERIVED_COLUMNS",
    "OPTIONAL_COLUMNS",
    "PAPER_SOURCE",
    "REQUIRED_COLUMNS",
    "Catalog",
    "CatalogError",
]

REQUIRED_COLUMNS = ("id", "a_km", "e", "inc_deg", "raan_deg")
"""Columns every catalog must have."""

OPTIONAL_COLUMNS = ("name", "epoch")
"""Columns a catalog may have; any other column is kept untouched."""

DERIVED_COLUMNS = ("raan_rate_deg_per_day", "altitude_km", "raan_epoch_deg")
"""Columns computed by the catalog; input columns of these names are recomputed."""

PAPER_SOURCE = "paper Table 5"
"""``Catalog.source`` of :meth:`Catalog.paper_case`."""

R_EARTH_KM = R_EARTH / 1000.0
_EPOCH_EXPECTED = "expected an ISO-8601 UTC date such as 2020-05-24T12:00:00Z"


@dataclass(frozen=True, eq=False, repr=False)
class Catalog:
    """Validated debris orbits at the mission start date.

    Build it with :meth:`from_csv`, :meth:`from_frame` or :meth:`paper_case`.

    Attributes
    ----------
    frame : pandas.DataFrame
        One row per debris, index ``0..N-1``.  Columns: ``id`` (str), ``a_km``,
        ``e``, ``inc_deg``, ``raan_deg`` (RAAN at ``start``, in [0, 360)),
        ``raan_rate_deg_per_day`` (J2 secular rate, Eq. 7), ``altitude_km``
        (``a_km - R_T``); ``name`` (str) if given; ``epoch`` (UTC) and
        ``raan_epoch_deg`` (the RAAN at that epoch) if epochs are given; then any
        extra input column, untouched.
    start : pandas.Timestamp or None
        Mission start date (UTC) the RAANs refer to; None when there are no epochs
        and no start was given.
    source : str
        File path, ``"<DataFrame>"`` or ``"paper Table 5"``.
    """

    frame: pd.DataFrame
    start: pd.Timestamp | None
    source: str

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_csv(cls, path: str | os.PathLike, *, start=None) -> Catalog:
        """Read and validate a CSV catalog.

        Parameters
        ----------
        path : str or path-like
            UTF-8 CSV file with a header line.  Required columns ``id, a_km, e,
            inc_deg, raan_deg``; optional ``name`` and ``epoch`` (ISO-8601, UTC when
            naive); other columns are kept as strings.  Blank lines are skipped.
        start : str or datetime-like, optional
            Mission start date (UTC when naive).  Default: the latest epoch, or None
            without epochs.

        Returns
        -------
        Catalog

        Raises
        ------
        CatalogError
            The file is missing, unreadable, empty, or any row is invalid.
        """
        source, text = read_text(path)
        header, records = _read_csv(io.StringIO(text, newline=""), source)
        return cls._from_records(header, records, source, start)

    @classmethod
    def from_frame(cls, frame: pd.DataFrame, *, source: str = "<DataFrame>", start=None) -> Catalog:
        """Validate a DataFrame with the columns of a CSV catalog (see :meth:`from_csv`).

        Values may be strings (as read from a file) or numbers; ``epoch`` values may
        be strings or datetimes.  Integer ids become strings (``5`` -> ``"5"``).
        Problems name the 1-based row and the index label.

        Raises
        ------
        CatalogError
            Same validation as :meth:`from_csv`.
        """
        if not isinstance(frame, pd.DataFrame):
            kind = type(frame).__name__
            raise CatalogError.collect(source, [f"{source}: expected a DataFrame, got {kind}"])
        problems = _header_problems(list(frame.columns), source)
        if not problems and frame.empty:
            problems.append(f"{source}: no rows")
        if problems:
            raise CatalogError.collect(source, problems)
        labels = list(frame.index)

        def where(pos: int) -> str:
            return f"row {pos + 1} (index {_show(labels[pos])})"

        return cls._validated(frame, source, where, start)

    @classmethod
    def paper_case(cls) -> Catalog:
        """The 11 sun-synchronous debris of the paper's application case (Table 5).

        The RAANs are those at the mission start; the table has no epochs, so
        ``start`` is None.
        """
        text = (resources.files("sdc_cvx") / "data" / "paper_table5.csv").read_text("utf-8")
        header, records = _read_csv(text.splitlines(keepends=True), PAPER_SOURCE)
        return cls._from_records(header, records, PAPER_SOURCE, None)

    @classmethod
    def _from_records(cls, header, records, source, start) -> Catalog:
        """Validate the rows read by :func:`_read_csv`."""
        width = len(header)
        ragged = {
            pos: f"expected {width} fields as in the header, got {len(fields)}"
            for pos, (_, fields) in enumerate(records)
            if len(fields) != width
        }
        rows = [(fields + [""] * width)[:width] for _, fields in records]
        raw = pd.DataFrame(rows, columns=header, dtype=str)
        lines = [line for line, _ in records]

        def where(pos: int) -> str:
            return f"row {pos + 1} (line {lines[pos]})"

        return cls._validated(raw, source, where, start, ragged)

    @classmethod
    def _validated(cls, raw, source, where, start, broken=None) -> Catalog:
        """Check every row of ``raw`` and build the catalog, or raise all problems.

        ``broken`` maps the positions of rows that cannot be read to their problem.
        """
        problems: list[str] = []
        _warn_unknown_columns(list(raw.columns), source)
        columns = _check_rows(raw, source, where, problems, broken or {})
        start_ts = _parse_start(start, source, problems)
        if problems:
            raise CatalogError.collect(source, problems)
        frame = _build_frame(raw, columns)
        if columns.epochs is not None:
            start_ts = start_ts if start_ts is not None else max(columns.epochs)
            _propagate(frame, start_ts)
        return cls(frame=frame, start=start_ts, source=source)

    # ------------------------------------------------------------------ accessors
    @property
    def ids(self) -> tuple[str, ...]:
        """Debris ids, in catalog order."""
        return tuple(str(value) for value in self.frame["id"])

    @property
    def a_m(self) -> np.ndarray:
        """Semi-major axes [m]."""
        return self.frame["a_km"].to_numpy(dtype=float) * 1000.0

    @property
    def e(self) -> np.ndarray:
        """Eccentricities [-]."""
        return self.frame["e"].to_numpy(dtype=float, copy=True)

    @property
    def inc_rad(self) -> np.ndarray:
        """Inclinations [rad]."""
        return np.radians(self.frame["inc_deg"].to_numpy(dtype=float))

    @property
    def raan_rad(self) -> np.ndarray:
        """RAANs at the start date [rad], in [0, 2 pi)."""
        return np.radians(self.frame["raan_deg"].to_numpy(dtype=float))

    def __len__(self) -> int:
        return len(self.frame)

    def __repr__(self) -> str:
        start = "None" if self.start is None else self.start.isoformat()
        return f"Catalog({len(self)} debris from {self.source!r}, start={start})"

    def with_orbit(self, orbit_id: str, a_km, e, inc_deg, raan_deg) -> Catalog:
        """A copy with one more orbit, e.g. the launcher's injection orbit (Part II-C).

        The new row's RAAN is at the catalog's start date; the other rows are kept as
        they are (no second propagation of their epochs).
        """
        if str(orbit_id) in self.ids:
            raise CatalogError(f"{self.source}: id {orbit_id!r} is already in the catalog")
        row = Catalog.from_frame(
            pd.DataFrame({"id": [str(orbit_id)], "a_km": [a_km], "e": [e], "inc_deg": [inc_deg],
                          "raan_deg": [raan_deg]}),
            source=f"orbit {orbit_id!r}",
        ).frame  # fmt: skip
        frame = pd.concat([self.frame, row], ignore_index=True)
        return Catalog(frame, self.start, self.source)

    def subset(self, ids: Iterable[str] | str) -> Catalog:
        """Catalog restricted to ``ids``, kept in catalog order (not in the given order).

        Parameters
        ----------
        ids : iterable of str, or str
            Debris ids to keep; non-string ids are compared as ``str(id)``.

        Raises
        ------
        CatalogError
            An id is not in the catalog, or no id is given.
        """
        wanted = [ids] if isinstance(ids, str) else [str(value) for value in ids]
        known = self.ids
        unknown = [value for value in dict.fromkeys(wanted) if value not in known]
        if unknown:
            shown = ", ".join(repr(value) for value in unknown)
            listed = ", ".join(repr(value) for value in known[:MAX_REPORTED])
            more = ", ..." if len(known) > MAX_REPORTED else ""
            raise CatalogError(
                f"{self.source}: unknown debris id(s) {shown}; the catalog has {listed}{more}"
            )
        if not wanted:
            raise CatalogError(f"{self.source}: subset needs at least one debris id")
        keep = self.frame["id"].isin(set(wanted)).to_numpy()
        frame = self.frame.loc[keep].reset_index(drop=True)
        return Catalog(frame=frame, start=self.start, source=self.source)


# ---------------------------------------------------------------------- reading
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


def _read_csv(stream: Iterable[str], source: str):
    """Header and ``(first line, fields)`` records of a CSV text, blank lines skipped.

    Raises a :class:`CatalogError` at once for an empty file, a file without data rows,
    malformed CSV or a bad header (missing, duplicate or blank column names).
    """
    reader = csv.reader(stream)
    header = None
    records = []
    line = 0
    try:
        for fields in reader:
            first, line = line + 1, reader.line_num
            if all(not field.strip() for field in fields):
                continue
            if header is None:
                header = [field.strip() for field in fields]
            else:
                records.append((first, fields))
    except csv.Error as exc:
        message = f"{source}, line {reader.line_num}: not valid CSV ({exc})"
        raise CatalogError.collect(source, [message]) from None
    if header is None:
        raise CatalogError.collect(source, [f"{source}: empty file (no header line)"])
    problems = _header_problems(header, source)
    if not records:
        problems.append(f"{source}: header but no data rows")
    if problems:
        raise CatalogError.collect(source, problems)
    return header, records


def _header_problems(columns: list, source: str) -> list[str]:
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
            f"found {', '.join(map(repr, names))}"
        )
    return problems


# ---------------------------------------------------------------------- validation
@dataclass
class _Values:
    """Converted values of the required and optional columns, one entry per row."""

    ids: list[str]
    numbers: dict[str, np.ndarray]
    names: list[str] | None = None
    epochs: list[pd.Timestamp] | None = None


def _check_rows(raw: pd.DataFrame, source: str, where: Callable, problems, broken) -> _Values:
    """Convert and check every row; append problems to ``problems``.

    Rows in ``broken`` (position -> problem) are reported as such and not checked.
    """
    n = len(raw)
    values = _Values(ids=[""] * n, numbers={name: np.full(n, np.nan) for name in _CHECKS})
    if "name" in raw.columns:
        values.names = ["" if _is_missing(name) else str(name).strip() for name in raw["name"]]
    has_epoch = "epoch" in raw.columns
    epochs: list = [None] * n
    seen: dict[str, int] = {}
    for pos in range(n):
        prefix = f"{source}, {where(pos)}"
        if pos in broken:
            problems.append(f"{prefix}: {broken[pos]}")
            continue
        ident, error = _to_id(raw["id"].iat[pos])
        if not error and ident in seen:
            error = f"duplicate id {ident!r}, also in {where(seen[ident])}"
        seen.setdefault(ident, pos)
        values.ids[pos] = ident
        errors = {"id": error}
        for name, check in _CHECKS.items():
            values.numbers[name][pos], errors[name] = _to_float(raw[name].iat[pos], check)
        if not (errors["a_km"] or errors["e"]):
            errors["a_km"] = _check_domain(values.numbers["a_km"][pos], values.numbers["e"][pos])
        if has_epoch:
            epochs[pos], errors["epoch"] = _to_epoch(raw["epoch"].iat[pos])
        problems += [f"{prefix}, field '{f}': {msg}" for f, msg in errors.items() if msg]
    if has_epoch:
        values.epochs = _check_all_or_none(epochs, raw["epoch"], source, where, problems, broken)
    return values


def _check_all_or_none(epochs, column, source, where, problems, broken):
    """Epochs if every row has one, None if no row has one, else report the blank ones."""
    blank = [pos for pos, value in enumerate(column) if pos not in broken and _is_blank(value)]
    if len(blank) == len(column) - len(broken):
        return None
    for pos in blank:
        problems.append(
            f"{source}, {where(pos)}, field 'epoch': blank, but other rows have an epoch "
            f"({_EPOCH_EXPECTED}, or leave every epoch blank)"
        )
    return epochs


def _check_a(value: float) -> str | None:
    if value > R_EARTH_KM:
        return None
    side = "below" if value < R_EARTH_KM else "at"
    return (
        f"expected a number > {R_EARTH_KM}, got {{got}} ({side} the Earth's radius {R_EARTH_KM} km)"
    )


MIN_PERIGEE_KM = 150.0
"""Lowest perigee altitude of a catalog orbit [km]: below, an orbit decays within days."""
MAX_A_KM = 100_000.0
"""Largest semi-major axis of a catalog orbit [km] (GEO is 42,164 km; the Moon 384,400)."""
KNOWN_COLUMNS = (
    "id", "a_km", "e", "inc_deg", "raan_deg", "name", "epoch", "raan_rate_deg_per_day",
    "altitude_km", "raan_epoch_deg", "argp_deg", "mean_anomaly_deg",
    "mean_motion_rev_per_day", "intl_designator",
)  # fmt: skip
"""Columns a catalog reads or its readers write; any other draws a :class:`CatalogWarning`."""


def _check_domain(a_km: float, e: float) -> str | None:
    """Whether an orbit is one the package can plan with (README, "Physical domain")."""
    if a_km > MAX_A_KM:
        return (
            f"expected a semi-major axis of at most {MAX_A_KM:,.0f} km (an Earth orbit), "
            f"got {a_km:g}"
        )
    perigee = a_km * (1.0 - e) - R_EARTH_KM
    if perigee < MIN_PERIGEE_KM:
        return (
            f"expected a perigee altitude a_km * (1 - e) - {R_EARTH_KM} of at least "
            f"{MIN_PERIGEE_KM:g} km (lower orbits decay within days), got a_km = {a_km:g} "
            f"and e = {e:g}: perigee at {perigee:.1f} km"
        )
    return None


def _warn_unknown_columns(columns: list, source: str) -> None:
    """One :class:`CatalogWarning` per column the catalog does not read (a typo, likely)."""
    for column in columns:
        if str(column) in KNOWN_COLUMNS:
            continue
        hint = ""
        if "epoch" in str(column).lower():
            hint = f"; the epoch column is named 'epoch' ({_EPOCH_EXPECTED})"
        warnings.warn(
            f"{source}, header: unknown column {str(column)!r} is not used (kept as text); "
            f"the columns read are id, a_km, e, inc_deg, raan_deg and optional name, "
            f"epoch{hint}",
            CatalogWarning,
            stacklevel=4,
        )


def _check_e(value: float) -> str | None:
    return None if 0.0 <= value < 1.0 else "expected a number in [0, 1), got {got}"


def _check_inc(value: float) -> str | None:
    return None if 0.0 <= value <= 180.0 else "expected a number in [0, 180], got {got}"


MAX_ABS_RAAN_DEG = 36_000.0
"""Largest |RAAN| read [deg] (100 turns, wrapped into [0, 360)): beyond, a value is noise,
not an angle (1e308 % 360 "is" 296 deg)."""


def _check_raan(value: float) -> str | None:
    ok = -MAX_ABS_RAAN_DEG <= value <= MAX_ABS_RAAN_DEG
    return None if ok else "expected an angle in [-36000, 36000] deg (wrapped), got {got}"


_CHECKS = {
    "a_km": _check_a,
    "e": _check_e,
    "inc_deg": _check_inc,
    "raan_deg": _check_raan,
}


def _is_missing(value) -> bool:
    """None, NaN, NA or NaT (scalars only)."""
    return bool(pd.api.types.is_scalar(value) and pd.isna(value))


def _is_blank(value) -> bool:
    return _is_missing(value) or (isinstance(value, str) and not value.strip())


def _show(value) -> str:
    """Short quoted form of an input value for messages."""
    if isinstance(value, np.generic):
        value = value.item()
    text = repr(value)
    return text if len(text) <= 40 else text[:36] + "..." + text[-1]


def _to_id(value) -> tuple[str, str | None]:
    """Debris id as a string: integral numbers lose their ``.0``."""
    if _is_blank(value):
        return "", "expected a non-blank id, got a blank value"
    if isinstance(value, str):
        return value.strip(), None
    if isinstance(value, numbers.Integral) and not isinstance(value, bool | np.bool_):
        return str(int(value)), None
    if isinstance(value, numbers.Real) and float(value).is_integer():
        return str(int(value)), None
    return str(value).strip(), None


def _to_float(value, check) -> tuple[float, str | None]:
    """Finite float passing ``check``, or an error message."""
    if _is_blank(value):
        return math.nan, "expected a number, got a blank value"
    is_real = isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
    try:
        if not (is_real or isinstance(value, str)):
            raise TypeError
        number = float(value)
    except (ValueError, TypeError, OverflowError):
        return math.nan, f"expected a number, got {_show(value)}"
    if math.isnan(number):
        return math.nan, f"expected a number, got {_show(value)} (NaN)"
    if not math.isfinite(number):
        return math.nan, f"expected a finite number, got {_show(value)}"
    error = check(number)
    if error:
        return math.nan, error.format(got=_show(value))
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


def _to_epoch(value) -> tuple[pd.Timestamp | None, str | None]:
    """Epoch of a row: (timestamp, None), (None, None) when blank, or (None, error)."""
    if _is_blank(value):
        return None, None
    stamp = _to_timestamp(value)
    return stamp, None if stamp is not None else f"{_EPOCH_EXPECTED}, got {_show(value)}"


def _parse_start(start, source: str, problems: list[str]) -> pd.Timestamp | None:
    if start is None:
        return None
    stamp = _to_timestamp(start)
    if stamp is None:
        problems.append(f"{source}, argument 'start': {_EPOCH_EXPECTED}, got {_show(start)}")
    return stamp


# ---------------------------------------------------------------------- building
def _wrap_deg(angle: np.ndarray) -> np.ndarray:
    """Angle [deg] wrapped into [0, 360)."""
    wrapped = np.mod(angle, 360.0)
    return np.where(wrapped >= 360.0, wrapped - 360.0, wrapped)


def _build_frame(raw: pd.DataFrame, columns: _Values) -> pd.DataFrame:
    """Output frame from validated columns (RAANs at their epochs, if any)."""
    values = columns.numbers
    a_m = values["a_km"] * 1000.0
    rate = raan_rate(a_m, values["e"], np.radians(values["inc_deg"]))
    frame = pd.DataFrame({"id": columns.ids})
    if columns.names is not None:
        frame["name"] = columns.names
    for name in REQUIRED_COLUMNS[1:]:
        frame[name] = values[name]
    frame["raan_deg"] = _wrap_deg(values["raan_deg"])
    frame["raan_rate_deg_per_day"] = np.degrees(rate) * SECONDS_PER_DAY
    frame["altitude_km"] = values["a_km"] - R_EARTH_KM
    if columns.epochs is not None:
        frame["epoch"] = pd.Series(columns.epochs)
        frame["raan_epoch_deg"] = frame["raan_deg"]
    reserved = set(REQUIRED_COLUMNS) | set(OPTIONAL_COLUMNS) | set(DERIVED_COLUMNS)
    for name in raw.columns:
        if name not in reserved:
            frame[name] = raw[name].reset_index(drop=True)
    return frame


def _propagate(frame: pd.DataFrame, start: pd.Timestamp) -> None:
    """Move ``raan_deg`` from each row's epoch to ``start`` at the row's J2 rate (Eq. 7)."""
    elapsed_days = np.array(
        [(start - epoch).total_seconds() / SECONDS_PER_DAY for epoch in frame["epoch"]]
    )
    raan = frame["raan_epoch_deg"].to_numpy() + frame["raan_rate_deg_per_day"] * elapsed_days
    frame["raan_deg"] = _wrap_deg(np.asarray(raan, dtype=float))
