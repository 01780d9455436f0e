"""A catalog's rows checked and built into its frame (:func:`validate`).

Every row is converted and checked, and every problem is collected before one
:class:`~sdc_cvx.errors.CatalogError` names them all.  A row that is well formed but is not
an orbit of this model (perigee below :data:`MIN_PERIGEE_KM`, ``a`` above
:data:`MAX_A_KM`, an epoch more than :data:`MAX_PROPAGATION_DAYS` from the start, or
elements a reader found sgp4 rejects) is a problem too, or is set aside
(:data:`ON_INVALID`).  The frame holds the RAANs at the mission start date: each RAAN is
propagated from its epoch with its own J2 secular rate (paper Eq. 7).
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..errors import CatalogError, CatalogWarning, listing
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY, raan_rate
from .catalog_text import (
    DERIVED_COLUMNS,
    EPOCH_EXPECTED,
    OPTIONAL_COLUMNS,
    REQUIRED_COLUMNS,
    is_blank,
    is_missing,
    parse_start,
    to_epoch,
    to_float,
    to_id,
    warn_unknown_columns,
)

R_EARTH_KM = R_EARTH / 1000.0

MIN_PERIGEE_KM = 150.0
"""Lowest perigee altitude of a catalog orbit [km]: below, an orbit decays within days."""
MAX_A_KM = 100_000.0
"""Largest semi-major axis of a catalog orbit [km] (GEO is 42,164 km; the Moon 384,400)."""
MAX_PROPAGATION_DAYS = 3652.5
"""Largest time [days] between an element set's epoch and the mission start (10 years,
the longest mission, ``Mission.tmax_days``): the RAANs are moved to the start with J2
alone, without drag or decay, which is meaningless over decades (a 2-digit TLE year
read in the wrong century, a ``start`` typed with the wrong year)."""
MAX_ABS_RAAN_DEG = 36_000.0
"""Largest |RAAN| read [deg] (100 turns, wrapped into [0, 360)): beyond, a value is noise,
not an angle (1e308 % 360 "is" 296 deg)."""
ON_INVALID = ("raise", "set aside")
"""What to do with element sets that are not orbits of this model: raise a
:class:`CatalogError`, or set them aside in ``Catalog.invalid`` (the command line: the
candidate selection reports those it would keep)."""


def validate(
    raw: pd.DataFrame,
    source: str,
    where: Callable[[int], str],
    start,
    broken=None,
    *,
    flagged=None,
    on_invalid="raise",
    reader_problems=(),
    units_known=False,
) -> tuple[pd.DataFrame, pd.Timestamp | None, pd.DataFrame | None]:
    """Check every row of ``raw`` and build the catalog's frame, or raise all problems.

    ``where(pos)`` locates row ``pos`` in the input (``"row 3 (line 4)"``).  ``broken``
    maps the positions of rows that cannot be read to their problem; ``flagged`` those a
    reader found are not orbits of this model (sgp4 rejects them) to the reason.  With
    ``on_invalid="set aside"`` such rows, and those outside the physical domain
    (:func:`_check_domain`, :func:`_check_epochs`), go to the ``invalid`` frame instead of
    being problems.  ``reader_problems`` (a reader's own, by line) are raised with this
    validation's, in one error.  ``units_known``: a format reader's rows, in degrees and
    kilometres by the format's definition (no look at their units, :func:`_check_units`).

    Returns
    -------
    frame : pandas.DataFrame
        The catalog's rows (``Catalog.frame``), RAANs at the start date.
    start : pandas.Timestamp or None
        The start date: ``start`` as given, else the latest epoch of the bulk
        (:func:`_bulk_start`), else None.
    invalid : pandas.DataFrame or None
        The rows set aside (``Catalog.invalid``), or None.

    Raises
    ------
    CatalogError
        Every problem of the input, sorted by the row, line, record or segment it names.
    """
    if on_invalid not in ON_INVALID:
        raise ValueError(f"on_invalid must be one of {ON_INVALID}, got {on_invalid!r}")
    problems: list[str] = []
    warn_unknown_columns(list(raw.columns), source)
    domain: dict[int, str] = dict(flagged or {})
    columns = _check_rows(raw, source, where, problems, broken or {}, domain)
    if not problems and not units_known:
        _check_units(columns.numbers, source, problems)
    start_ts = parse_start(start, source, problems)
    if columns.epochs is not None:  # also with other problems: one error says all
        usable = [e for pos, e in enumerate(columns.epochs)
                  if pos not in domain and e is not None]  # fmt: skip
        if start_ts is None and usable:
            start_ts = _bulk_start(columns.epochs, domain, source, where)
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
    return frame, start_ts, invalid


# ---------------------------------------------------------------------- checking
def _check_units(numbers: dict, source: str, problems: list[str]) -> None:
    """Values that look like other units than the columns'.

    Radians are refused (a problem): three rows or more, every inclination within
    [0, pi] and not all 0, every |RAAN| within 2 pi.  In degrees these are orbits within
    3.1 deg of the equator whose nodes all lie within 6.3 deg of each other, which no
    catalogue of debris holds; in radians they are any orbits (an SSO's 98 deg is 1.71 rad),
    and planned as degrees they were 1.7 deg orbits (issue 48: "optimal", 23.6 m/s for
    0.03 deg of plane change).  Equatorial rows (every inclination 0) are the same in both
    units.  A median semi-major axis above 100,000 km (metres?) draws a
    :class:`CatalogWarning`: each such row is refused or set aside by the domain check.
    """
    inc, raan, a_km = (np.asarray(numbers.get(k, []), dtype=float)
                       for k in ("inc_deg", "raan_deg", "a_km"))  # fmt: skip
    if (len(inc) >= 3 and np.nanmax(inc) <= np.pi and np.nanmax(inc) > 0
            and np.nanmax(np.abs(raan)) <= 2.0 * np.pi):  # fmt: skip
        problems.append(
            f"{source}, columns 'inc_deg' and 'raan_deg': every inclination is at most "
            f"{np.nanmax(inc):.4g} and every RAAN within {2.0 * np.pi:.4f} of 0 in all "
            f"{len(inc)} rows: radians? (degrees are expected: multiply by 180/pi = 57.2958)")
    if len(a_km) and np.nanmedian(a_km) > 1e5:
        warnings.warn(f"{source}: a_km: a median of {np.nanmedian(a_km):.6g}: metres? "
                      "(kilometres are expected)", CatalogWarning, stacklevel=5)  # fmt: skip


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
        values.names = ["" if is_missing(name) else str(name).strip() for name in raw["name"]]
    has_epoch = "epoch" in raw.columns
    epochs: list = [None] * n
    seen: dict[str, int] = {}
    cells = {name: raw[name].tolist() for name in ("id", *_CHECKS)}  # .iat is slow
    phases = {name: raw[name].tolist() for name in PHASE_NUMBERS if name in raw.columns}
    epoch_cells = raw["epoch"].tolist() if has_epoch else None
    for pos in range(n):
        if pos in broken:
            problems.append(f"{source}, {where(pos)}: {broken[pos]}")
            continue
        ident, error = to_id(cells["id"][pos])
        if not error and ident in seen:
            error = f"duplicate id {ident!r}, also in {where(seen[ident])}"
        seen.setdefault(ident, pos)
        values.ids[pos] = ident
        errors = {"id": error}
        flagged = pos in domain
        for name, check in _CHECKS.items():
            values.numbers[name][pos], errors[name] = to_float(
                cells[name][pos], _no_check if flagged else check
            )
        if has_epoch:
            epochs[pos], errors["epoch"] = to_epoch(epoch_cells[pos])
        for name, column in phases.items():  # optional, but a number where given
            if not is_blank(column[pos]):
                errors[name] = to_float(column[pos], _PHASE_CHECKS[name])[1]
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


def _bulk_start(epochs, domain, source: str, where: Callable[[int], str]) -> pd.Timestamp:
    """The default start: the latest epoch of the largest 10-year window of epochs.

    Each epoch counts the epochs within :data:`MAX_PROPAGATION_DAYS` before it (itself
    included); the start is the latest epoch of those counting the most (rows in
    ``domain`` and without an epoch left out).  In a catalogue the epochs lie days to
    months apart: the latest epoch counts them all and is the start, the freshest element
    set.  One wrong epoch (a 2-digit TLE year read in the wrong century: 2056 among sets of
    2020) counts only itself: it is not the start, which would leave every good set more
    than 10 years from it; the epochs later than the start by more than 10 years are named
    in a :class:`CatalogWarning` (and then by :func:`_check_epochs`, as too far from it).
    """
    positions = [pos for pos, e in enumerate(epochs) if pos not in domain and e is not None]
    stamps = pd.DatetimeIndex([epochs[pos] for pos in positions]).as_unit("ns")
    ns = np.sort(stamps.asi8)
    window = int(MAX_PROPAGATION_DAYS * SECONDS_PER_DAY * 1e9)
    counts = np.arange(len(ns)) - np.searchsorted(ns, ns - window, side="left") + 1
    start = pd.Timestamp(int(ns[np.flatnonzero(counts == counts.max())[-1]]), tz="UTC")
    later = [k for k in range(len(stamps)) if stamps[k].value - start.value > window]
    if later:
        named = listing(f"{where(positions[k])}: {stamps[k].isoformat()} "
                        f"({(stamps[k] - start).days / 365.25:.1f} years later)"
                        for k in later)  # fmt: skip
        warnings.warn(
            f"{source}: the start is {start.isoformat()}, the latest epoch of the most "
            f"epochs within {MAX_PROPAGATION_DAYS:g} days (10 years) of each other "
            f"({counts.max()} of {len(ns)}); {len(later)} epoch(s) more than 10 years later "
            f"are not taken as the start (a wrong year?): {named}", CatalogWarning,
            stacklevel=5)  # fmt: skip
    return start


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
    blank = [pos for pos, value in enumerate(column) if pos not in broken and is_blank(value)]
    if len(blank) == len(column) - len(broken):
        return None
    for pos in blank:
        problems.append(
            f"{source}, {where(pos)}, field 'epoch': blank, but other rows have an epoch "
            f"({EPOCH_EXPECTED}, or leave every epoch blank)"
        )
    return epochs


def _check_a(value: float) -> str | None:
    if value > R_EARTH_KM:
        return None
    side = "below" if value < R_EARTH_KM else "at"
    return (
        f"expected a number > {R_EARTH_KM}, got {{got}} ({side} the Earth's radius {R_EARTH_KM} km)"
    )


def _check_domain(a_km: float, e: float) -> str | None:
    """Whether an orbit is one the package can plan with (docs/guide/catalogues.md,
    "Physical domain")."""
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


def _check_e(value: float) -> str | None:
    return None if 0.0 <= value < 1.0 else "expected a number in [0, 1), got {got}"


def _check_inc(value: float) -> str | None:
    return None if 0.0 <= value <= 180.0 else "expected a number in [0, 180], got {got}"


def _check_angle(value: float) -> str | None:
    """An angle [deg] within :data:`MAX_ABS_RAAN_DEG` of 0 (a RAAN, a phase on the orbit)."""
    ok = -MAX_ABS_RAAN_DEG <= value <= MAX_ABS_RAAN_DEG
    return None if ok else "expected an angle in [-36000, 36000] deg (wrapped), got {got}"


PHASE_NUMBERS = ("arglat_deg", "argp_deg", "mean_anomaly_deg", "bstar")
"""Optional columns (where a debris is on its orbit, its drag term) that must be numbers
where a row gives them: a flight reads them (an 'abc' read as 'no arglat_deg' misled).
The angles take the RAAN's range (an arglat_deg of 1e12 is noise, not a phase)."""
_PHASE_CHECKS = {"arglat_deg": _check_angle, "argp_deg": _check_angle,
                 "mean_anomaly_deg": _check_angle, "bstar": _no_check}  # fmt: skip

_CHECKS = {
    "a_km": _check_a,
    "e": _check_e,
    "inc_deg": _check_inc,
    "raan_deg": _check_angle,
}


# ---------------------------------------------------------------------- building
def wrap_deg(angle: np.ndarray) -> np.ndarray:
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
    frame["raan_deg"] = wrap_deg(values["raan_deg"])
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
    frame["raan_deg"] = wrap_deg(np.asarray(raan, dtype=float))
