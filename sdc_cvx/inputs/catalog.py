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

A row that is well formed but is not an orbit of this model (perigee below
:data:`MIN_PERIGEE_KM`, ``a`` above :data:`MAX_A_KM`, an epoch more than
:data:`MAX_PROPAGATION_DAYS` from the start, or, for TLE and OMM, elements sgp4 rejects)
is a problem too, unless the catalog is read with ``on_invalid="set aside"``: it then
goes to ``Catalog.invalid``, for the candidate filters to act first
(:func:`sdc_cvx.inputs.selection.select` reports only those it would keep).  A whole
public catalogue always holds a few such element sets.

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
import re
import warnings
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from datetime import datetime
from importlib import resources
from pathlib import Path

import numpy as np
import pandas as pd

from ..errors import MAX_REPORTED, CatalogError, CatalogWarning
from ..physics.orbits import J2, R_EARTH, SECONDS_PER_DAY, raan_rate

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
    invalid : pandas.DataFrame or None
        Rows set aside when read with ``on_invalid="set aside"``: element sets that are
        not orbits of this model (perigee below :data:`MIN_PERIGEE_KM`, ``a`` above
        :data:`MAX_A_KM`, rejected by sgp4, an epoch more than
        :data:`MAX_PROPAGATION_DAYS` from the start).  Columns ``id``, ``name`` (when
        the catalog has names), ``a_km``, ``e``, ``inc_deg``, ``altitude_km`` (as read,
        NaN when unreadable) and ``problem`` (file, line, catalogue number and reason, in
        words).  :func:`sdc_cvx.inputs.selection.select` reports those its filters keep
        and never mentions the others.  None when nothing was set aside.
    """

    frame: pd.DataFrame
    start: pd.Timestamp | None
    source: str
    invalid: pd.DataFrame | None = None

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_csv(cls, path: str | os.PathLike, *, start=None, on_invalid="raise") -> Catalog:
        """Read and validate a CSV catalog.

        Parameters
        ----------
        path : str or path-like
            UTF-8 CSV file with a header line.  Required columns ``id, a_km, e,
            inc_deg, raan_deg``; optional ``name`` and ``epoch`` (ISO-8601, UTC when
            naive); other columns are kept as strings.  Blank lines are skipped.  The
            column names are read whatever their case (``ID``, ``A_KM``), and the
            fields may be separated by ``;`` or tabs when the header line has no comma
            (:func:`csv_delimiter`); numbers take a decimal point.
        start : str or datetime-like, optional
            Mission start date (UTC when naive), within :data:`MAX_PROPAGATION_DAYS` of
            the epochs.  Default: the latest epoch, or None without epochs.
        on_invalid : {"raise", "set aside"}
            Rows that are not orbits of this model (README, "Physical domain"): a
            problem (default), or set aside in ``Catalog.invalid``.

        Returns
        -------
        Catalog

        Raises
        ------
        CatalogError
            The file is missing, unreadable, empty, or any row is invalid.
        """
        source, text = read_text(path)
        stream = io.StringIO(text, newline="")
        header, records = _read_csv(stream, source, delimiter=csv_delimiter(text))
        return cls._from_records(header, records, source, start, on_invalid)

    @classmethod
    def from_frame(cls, frame: pd.DataFrame, *, source: str = "<DataFrame>", start=None,
                   on_invalid="raise") -> Catalog:  # fmt: skip
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

        return cls._validated(frame, source, where, start, on_invalid=on_invalid)

    @classmethod
    def _from_rows(cls, frame, source, start, where_labels, *, flagged, on_invalid,
                   reader_problems) -> Catalog:  # fmt: skip
        """Validate the rows a format reader parsed (:mod:`sdc_cvx.inputs.formats`).

        ``where_labels[k]`` locates row k in the file (``"line 12 (catalog number
        25544)"``), ``flagged`` maps the rows the reader found not to be orbits of this
        model to ``": reason"``, and ``reader_problems`` are raised with this
        validation's in one error (sorted by line).
        """

        def where(pos: int) -> str:
            return where_labels[pos]

        return cls._validated(frame, source, where, start, flagged=flagged,
                              on_invalid=on_invalid, reader_problems=reader_problems)  # fmt: skip

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
    def _from_records(cls, header, records, source, start, on_invalid="raise") -> Catalog:
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

        return cls._validated(raw, source, where, start, ragged, on_invalid=on_invalid)

    @classmethod
    def _validated(cls, raw, source, where, start, broken=None, *, flagged=None,
                   on_invalid="raise", reader_problems=()) -> Catalog:  # fmt: skip
        """Check every row of ``raw`` and build the catalog, or raise all problems.

        ``broken`` maps the positions of rows that cannot be read to their problem;
        ``flagged`` those a reader found are not orbits of this model (sgp4 rejects
        them) to the reason.  With ``on_invalid="set aside"`` such rows, and those
        outside the physical domain (:func:`_check_domain`, :func:`_epoch_problem`), go
        to ``Catalog.invalid`` instead of being problems.  ``reader_problems`` (a
        reader's own, by line) are raised with this validation's, in one error.
        """
        if on_invalid not in ON_INVALID:
            raise ValueError(f"on_invalid must be one of {ON_INVALID}, got {on_invalid!r}")
        problems: list[str] = []
        _warn_unknown_columns(list(raw.columns), source)
        domain: dict[int, str] = dict(flagged or {})
        columns = _check_rows(raw, source, where, problems, broken or {}, domain)
        start_ts = _parse_start(start, source, problems)
        if columns.epochs is not None:  # also with other problems: one error says all
            usable = [e for pos, e in enumerate(columns.epochs)
                      if pos not in domain and e is not None]  # fmt: skip
            if start_ts is None and usable:
                start_ts = max(usable)
            _check_epochs(columns.epochs, start_ts, start is not None, source, domain, problems)
        aside = on_invalid == "set aside"
        if not aside:
            problems += [f"{source}, {where(pos)}{reason}" for pos, reason in domain.items()]
        problems = _by_location([*reader_problems, *problems], source)
        if problems:
            raise CatalogError.collect(source, problems)
        invalid = None
        if domain:
            invalid = _invalid_frame(raw, columns, domain, source, where)
            good = np.ones(len(raw), dtype=bool)
            good[list(domain)] = False
            raw = raw.loc[good].reset_index(drop=True)
            columns = columns.take(np.flatnonzero(good))
        frame = _build_frame(raw, columns)
        if columns.epochs is not None and len(frame):
            _propagate(frame, start_ts)
        return cls(frame=frame, start=start_ts, source=source, invalid=invalid)

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

    def advanced(self, days: float, *, j2: float = J2) -> Catalog:
        """The catalog ``days`` later: each RAAN carried by its own J2 rate (Eq. 7).

        A campaign's mission launched on day ``d`` plans from ``advanced(d)``: its day 0
        is the catalog's day ``d``, and its RAANs there are those a mission from day 0
        would meet on day ``d`` (the same rates, for the same ``j2``).

        Parameters
        ----------
        days : float
            [days] after ``start``.
        j2 : float
            Zonal coefficient of the rates (the mission's).

        Returns
        -------
        Catalog
            Same rows; ``raan_deg`` at the new date, ``start`` moved by ``days`` (None
            stays None).
        """
        if days == 0:
            return self
        frame = self.frame.copy()
        rate = raan_rate(self.a_m, self.e, self.inc_rad, j2=j2)  # rad/s
        frame["raan_deg"] = _wrap_deg(
            frame["raan_deg"].to_numpy() + np.degrees(rate) * SECONDS_PER_DAY * days
        )
        start = None if self.start is None else self.start + pd.Timedelta(days=float(days))
        return Catalog(frame=frame, start=start, source=self.source)

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


def _read_csv(stream: Iterable[str], source: str, delimiter: str = ","):
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
    problems = _header_problems(header, source)
    if not records:
        problems.append(f"{source}: header but no data rows")
    if problems:
        raise CatalogError.collect(source, problems)
    return header, records


def _known_case(name: str) -> str:
    """``name`` as the known column it names in any case (``"A_KM"`` -> ``"a_km"``)."""
    lower = name.lower()
    return lower if lower != name and lower in KNOWN_COLUMNS else name


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

    def take(self, positions) -> _Values:
        """The values of the rows at ``positions``, in that order."""
        return _Values(
            ids=[self.ids[k] for k in positions],
            numbers={name: values[positions] for name, values in self.numbers.items()},
            names=None if self.names is None else [self.names[k] for k in positions],
            epochs=None if self.epochs is None else [self.epochs[k] for k in positions],
        )


def _check_rows(raw: pd.DataFrame, source: str, where: Callable, problems, broken,
                domain) -> _Values:  # fmt: skip
    """Convert and check every row; append problems to ``problems``.

    Rows in ``broken`` (position -> problem) are reported as such and not checked.
    Rows in ``domain`` (position -> reason, a reader found them not to be orbits of this
    model) are converted as far as they can be and not checked; rows whose only fault
    is to be outside the physical domain (:func:`_check_domain`) are added to it, with
    the reason as ``", field 'a_km': ..."``.
    """
    n = len(raw)
    values = _Values(ids=[""] * n, numbers={name: np.full(n, np.nan) for name in _CHECKS})
    if "name" in raw.columns:
        values.names = ["" if _is_missing(name) else str(name).strip() for name in raw["name"]]
    has_epoch = "epoch" in raw.columns
    epochs: list = [None] * n
    seen: dict[str, int] = {}
    cells = {name: raw[name].tolist() for name in ("id", *_CHECKS)}  # .iat is slow
    epoch_cells = raw["epoch"].tolist() if has_epoch else None
    for pos in range(n):
        if pos in broken:
            problems.append(f"{source}, {where(pos)}: {broken[pos]}")
            continue
        ident, error = _to_id(cells["id"][pos])
        if not error and ident in seen:
            error = f"duplicate id {ident!r}, also in {where(seen[ident])}"
        seen.setdefault(ident, pos)
        values.ids[pos] = ident
        errors = {"id": error}
        flagged = pos in domain
        for name, check in _CHECKS.items():
            values.numbers[name][pos], errors[name] = _to_float(
                cells[name][pos], _no_check if flagged else check
            )
        if has_epoch:
            epochs[pos], errors["epoch"] = _to_epoch(epoch_cells[pos])
        if flagged:
            continue
        if not (errors["a_km"] or errors["e"]):
            outside = _check_domain(values.numbers["a_km"][pos], values.numbers["e"][pos])
            if outside:
                domain[pos] = f", field 'a_km': {outside}"
        if any(errors.values()):
            prefix = f"{source}, {where(pos)}"
            problems += [f"{prefix}, field '{f}': {msg}" for f, msg in errors.items() if msg]
    if has_epoch:
        values.epochs = _check_all_or_none(epochs, epoch_cells, source, where, problems, broken)
    return values


def _no_check(value: float) -> None:
    """The check of a value a reader already found is not an orbit of this model."""
    return None


MAX_PROPAGATION_DAYS = 3652.5
"""Largest time [days] between an element set's epoch and the mission start (10 years,
the longest mission, ``Mission.tmax_days``): the RAANs are moved to the start with J2
alone, without drag or decay, which is meaningless over decades (a 2-digit TLE year
read in the wrong century, a ``start`` typed with the wrong year)."""

ON_INVALID = ("raise", "set aside")
"""What to do with element sets that are not orbits of this model: raise a
:class:`CatalogError`, or set them aside in ``Catalog.invalid`` (the command line: the
candidate selection reports those it would keep)."""


def _check_epochs(epochs, start, given: bool, source, domain, problems) -> None:
    """Each epoch within :data:`MAX_PROPAGATION_DAYS` of ``start`` (others to ``domain``);
    a given ``start`` that is that far from every epoch is a problem of its own."""
    if start is None:
        return
    stamps = pd.DatetimeIndex(epochs)
    days = np.abs((stamps - start).total_seconds().to_numpy() / SECONDS_PER_DAY)
    usable = np.array([pos not in domain for pos in range(len(epochs))], dtype=bool)
    usable &= ~np.isnan(days)  # an unreadable epoch is reported as such
    if given and usable.any() and days[usable].min() > MAX_PROPAGATION_DAYS:
        nearest = stamps[usable][int(np.argmin(days[usable]))]
        problems.append(
            f"{source}, argument 'start': {start.isoformat()} is {days[usable].min():,.0f} "
            f"days ({days[usable].min() / 365.25:.1f} years) from the nearest epoch of the "
            f"catalog ({nearest.isoformat()}); expected a start within "
            f"{MAX_PROPAGATION_DAYS:g} days (10 years) of the epochs: the RAANs are moved "
            f"to the start with J2 alone (no drag, no decay)"
        )
        return
    for pos in np.flatnonzero(usable & (days > MAX_PROPAGATION_DAYS)):
        domain[int(pos)] = (
            f", field 'epoch': expected an epoch within {MAX_PROPAGATION_DAYS:g} days (10 "
            f"years) of the mission start {start.isoformat()}, got {stamps[pos].isoformat()} "
            f"({days[pos] / 365.25:.1f} years away: the RAAN would be moved with J2 alone)"
        )


def _invalid_frame(raw, columns: _Values, domain: dict, source: str, where) -> pd.DataFrame:
    """The rows set aside (``Catalog.invalid``), in file order."""
    positions = sorted(domain)
    frame = pd.DataFrame({"id": [columns.ids[k] for k in positions]})
    if columns.names is not None:
        frame["name"] = [columns.names[k] for k in positions]
    for name in ("a_km", "e", "inc_deg"):
        frame[name] = columns.numbers[name][positions]
    frame["altitude_km"] = frame["a_km"] - R_EARTH_KM
    frame["problem"] = [f"{source}, {where(k)}{domain[k]}" for k in positions]
    return frame


def _by_location(problems: list[str], source: str) -> list[str]:
    """Problems sorted by the row, line, record or segment they name (stable; the others,
    such as a bad ``start`` argument, last)."""

    def key(problem: str) -> float:
        found = re.match(r", (?:row|line|record|segment) (\d+)", problem[len(source) :])
        return int(found.group(1)) if found else math.inf

    return sorted(problems, key=key)


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
    if type(value) is float and math.isfinite(value):  # the readers' values: fast path
        error = check(value)
        return (math.nan, error.format(got=_show(value))) if error else (value, None)
    if _is_blank(value):
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
        return math.nan, f"expected a number, got {_show(value)}{hint}"
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
    if type(value) is pd.Timestamp and value.tz is not None and str(value.tz) == "UTC":
        return value, None  # the readers' epochs: fast path
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
    elapsed = start - pd.DatetimeIndex(frame["epoch"])
    elapsed_days = elapsed.total_seconds().to_numpy() / SECONDS_PER_DAY
    raan = frame["raan_epoch_deg"].to_numpy() + frame["raan_rate_deg_per_day"] * elapsed_days
    frame["raan_deg"] = _wrap_deg(np.asarray(raan, dtype=float))
