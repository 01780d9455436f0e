"""Debris catalogs: read, validate and hold the orbits of the candidate debris.

A :class:`Catalog` is a validated table with one row per debris, in the units people
read (km, deg, deg/day), and SI accessors (m, rad) for the physics.  The RAANs it
holds are those at the mission start date: when the rows carry epochs, each RAAN is
propagated from its epoch to the start with its own J2 secular rate (paper Eq. 7,
``Omega(t) = Omega(t0) + dOmega/dt (t - t0)``).

Input comes from a CSV file, a DataFrame, or the paper's Table 5 bundled with the
package.  Bad input never produces a pandas or numpy traceback: every problem of a file
is collected and reported at once in a :class:`CatalogError` that names the file, the
row, the line and the field.  The text is read by :mod:`~sdc_cvx.inputs.catalog_text`,
the rows checked and built by :mod:`~sdc_cvx.inputs.catalog_rows`.

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

import dataclasses
import io
import math
import numbers
import os
from collections.abc import Iterable
from dataclasses import dataclass
from importlib import resources

import numpy as np
import pandas as pd

from ..errors import MAX_REPORTED, CatalogError, listing
from ..physics.orbits import J2, SECONDS_PER_DAY, raan_rate
from .catalog_rows import (
    MAX_A_KM,
    MAX_PROPAGATION_DAYS,
    MIN_PERIGEE_KM,
    ON_INVALID,
    R_EARTH_KM,
    validate,
    wrap_deg,
)
from .catalog_text import (
    DERIVED_COLUMNS,
    KNOWN_COLUMNS,
    OPTIONAL_COLUMNS,
    REQUIRED_COLUMNS,
    csv_delimiter,
    header_problems,
    read_csv_records,
    read_text,
    show_value,
)

__all__ = [
    "DERIVED_COLUMNS",
    "KNOWN_COLUMNS",
    "MAX_A_KM",
    "MAX_PROPAGATION_DAYS",
    "MIN_PERIGEE_KM",
    "ON_INVALID",
    "OPTIONAL_COLUMNS",
    "PAPER_SOURCE",
    "RAAN_RATES",
    "R_EARTH_KM",
    "REQUIRED_COLUMNS",
    "Catalog",
    "CatalogError",
    "csv_delimiter",
    "read_text",
]

PAPER_SOURCE = "paper Table 5"
"""``Catalog.source`` of :meth:`Catalog.paper_case`."""

RAAN_RATES = ("j2", "sgp4")
"""Where a catalog's RAAN rates come from (``Catalog.raan_rates``)."""


@dataclass(frozen=True, eq=False, repr=False)
class Catalog:
    """Validated debris orbits at the mission start date.

    Build it with :meth:`from_csv`, :meth:`from_frame` or :meth:`paper_case`.

    Attributes
    ----------
    frame : pandas.DataFrame
        One row per debris, index ``0..N-1``.  Columns: ``id`` (str), ``a_km``,
        ``e``, ``inc_deg``, ``raan_deg`` (RAAN at ``start``, in [0, 360)),
        ``raan_rate_deg_per_day`` (its rate: the J2 secular rate, Eq. 7, or the rate
        fitted to SGP4, see ``raan_rates``), ``altitude_km`` (``a_km - R_T``); ``name``
        (str) if given; ``epoch`` (UTC) and ``raan_epoch_deg`` (the RAAN at that epoch)
        if epochs are given; then any extra input column, untouched.
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
    raan_rates : {"j2", "sgp4"}
        ``"j2"`` (as read): ``raan_deg`` carried from the epochs and
        ``raan_rate_deg_per_day`` by the first-order J2 rate of the mean elements (Eq.
        7), the planner's model.  ``"sgp4"`` (:meth:`with_sgp4_rates`): both fitted to
        each debris' SGP4 propagation over the mission window
        (:mod:`~sdc_cvx.inputs.sgp4_rates`); the planner then takes the debris' rates
        from ``raan_rate_deg_per_day``.  Kept by the methods that return catalogs, and
        by the candidate selection.
    ephemeris : {"sgp4", "gtoc9"}
        How the debris move when a plan is flown: ``"sgp4"``, the elements are SGP4's
        mean elements (TLE, OMM; CSV rows are given SGP4 sets,
        :mod:`~sdc_cvx.inputs.sgp4_sets`); ``"gtoc9"`` (the GTOC9 reader), GTOC9's
        osculating elements advanced by the mean motion and the secular J2 rates of the
        RAAN and the argument of perigee (:class:`sdc_cvx.flight.ephemeris.Gtoc9Ephemeris`).
    """

    frame: pd.DataFrame
    start: pd.Timestamp | None
    source: str
    invalid: pd.DataFrame | None = None
    raan_rates: str = "j2"
    ephemeris: str = "sgp4"

    def __post_init__(self):
        if self.raan_rates not in RAAN_RATES:
            raise ValueError(f"raan_rates must be one of {', '.join(RAAN_RATES)}, "
                             f"got {self.raan_rates!r}")  # fmt: skip

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
            the epochs.  Default: the latest epoch within :data:`MAX_PROPAGATION_DAYS` of
            the median epoch (a wrong epoch far from the others is named in a
            :class:`~sdc_cvx.errors.CatalogWarning`, not taken), or None without epochs.
        on_invalid : {"raise", "set aside"}
            Rows that are not orbits of this model (docs/guide/catalogues.md, "Physical domain"): a
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
        header, records = read_csv_records(stream, source, delimiter=csv_delimiter(text))
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
        problems = header_problems(list(frame.columns), source)
        if not problems and frame.empty:
            problems.append(f"{source}: no rows")
        if problems:
            raise CatalogError.collect(source, problems)
        labels = list(frame.index)

        def where(pos: int) -> str:
            return f"row {pos + 1} (index {show_value(labels[pos])})"

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
                              on_invalid=on_invalid, reader_problems=reader_problems,
                              units_known=True)  # fmt: skip

    @classmethod
    def paper_case(cls) -> Catalog:
        """The 11 sun-synchronous debris of the paper's application case (Table 5).

        The RAANs are those at the mission start; the table has no epochs, so
        ``start`` is None.
        """
        text = (resources.files("sdc_cvx") / "data" / "paper_table5.csv").read_text("utf-8")
        header, records = read_csv_records(text.splitlines(keepends=True), PAPER_SOURCE)
        return cls._from_records(header, records, PAPER_SOURCE, None)

    @classmethod
    def _from_records(cls, header, records, source, start, on_invalid="raise") -> Catalog:
        """Validate the rows read by :func:`read_csv_records`."""
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
                   on_invalid="raise", reader_problems=(),
                   units_known=False) -> Catalog:  # fmt: skip
        """Check every row of ``raw`` and build the catalog, or raise all problems
        (:func:`~sdc_cvx.inputs.catalog_rows.validate`)."""
        frame, start, invalid = validate(raw, source, where, start, broken, flagged=flagged,
                                         on_invalid=on_invalid, reader_problems=reader_problems,
                                         units_known=units_known)  # fmt: skip
        return cls(frame=frame, start=start, source=source, invalid=invalid)

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
        return dataclasses.replace(self, frame=frame, invalid=None)

    def advanced(self, days: float, *, j2: float = J2) -> Catalog:
        """The catalog ``days`` later: each RAAN carried by its own J2 rate (Eq. 7), or
        by ``raan_rate_deg_per_day`` when the rates are fitted to SGP4.

        A campaign's mission launched on day ``d`` plans from ``advanced(d)``: its day 0
        is the catalog's day ``d``, and its RAANs there are those a mission from day 0
        would meet on day ``d`` (the same rates, for the same ``j2``).

        Parameters
        ----------
        days : float
            [days] after ``start``.
        j2 : float
            Zonal coefficient of the J2 rates (the mission's; not used by SGP4 rates).

        Returns
        -------
        Catalog
            Same rows; ``raan_deg`` at the new date, ``start`` moved by ``days`` (None
            stays None).

        Raises
        ------
        CatalogError
            ``days`` is not a finite number within :data:`MAX_PROPAGATION_DAYS` (10
            years, as an epoch from the start), or ``j2`` is not a number > 0.
        """
        if not (_is_real(days) and abs(days) <= MAX_PROPAGATION_DAYS):
            raise CatalogError(f"{self.source}: Catalog.advanced(days): days must be a number "
                               f"in [-{MAX_PROPAGATION_DAYS:g}, {MAX_PROPAGATION_DAYS:g}] "
                               f"[days], got {days!r}")  # fmt: skip
        if not (_is_real(j2) and j2 > 0):
            raise CatalogError(f"{self.source}: Catalog.advanced(j2=...): j2 must be a number "
                               f"> 0, got {j2!r}")  # fmt: skip
        if days == 0:
            return self
        frame = self.frame.copy()
        if self.raan_rates == "sgp4":
            rate = frame["raan_rate_deg_per_day"].to_numpy(dtype=float)
        else:
            rate = np.degrees(raan_rate(self.a_m, self.e, self.inc_rad, j2=j2)) * SECONDS_PER_DAY
        frame["raan_deg"] = wrap_deg(frame["raan_deg"].to_numpy() + rate * days)
        start = None if self.start is None else self.start + pd.Timedelta(days=float(days))
        return dataclasses.replace(self, frame=frame, start=start, invalid=None)

    def with_sgp4_rates(self, days: float) -> Catalog:
        """A copy whose RAANs and RAAN rates are fitted to SGP4 over ``days`` from the start.

        Each debris' element set flown by SGP4 (:mod:`~sdc_cvx.inputs.sgp4_rates`): its
        mean node over one orbit at the start and one ending ``days`` later gives
        ``raan_rate_deg_per_day`` (the mean rate over the window) and ``raan_deg`` (the
        fitted line at the start: for a row whose epoch is the start, its own RAAN within
        1e-6 deg; for the others, the RAAN carried from the epoch by SGP4 instead of Eq.
        7).  About 0.1 ms per debris.

        Parameters
        ----------
        days : float
            The window [days]: the mission's ``tmax_days`` (a campaign's last launch day
            plus its ``tmax_days``).

        Returns
        -------
        Catalog
            ``raan_rates = "sgp4"``; same rows, ``start``, ``source`` and ``invalid``.

        Raises
        ------
        CatalogError
            The catalog has no date (no epochs, no start: the paper's Table 5): SGP4
            would fly element sets of an invented epoch, which neither the flight nor the
            user's orbits have; or SGP4 cannot propagate a row over the window (the row
            named).
        ValueError
            The rates are fitted already (fit the catalog as read), or ``days`` is not
            longer than two orbital periods.
        """
        from .sgp4_rates import sgp4_raan  # sgp4 only when asked; it imports no catalog

        if self.start is None:
            raise CatalogError(
                f'{self.source}: raan_rates = "sgp4" fits each debris\' RAAN rate to SGP4 '
                "flying its element set from its epoch, and the catalog has no epochs and no "
                "start: give a TLE or OMM file, a CSV with an 'epoch' column, or a start date "
                '(catalog.start, --start); or plan with raan_rates = "j2"')
        if self.raan_rates == "sgp4":
            raise ValueError(f"{self.source}: the RAAN rates are fitted to SGP4 already; "
                             "fit the catalog as read")  # fmt: skip
        raan, rate = sgp4_raan(self, days)
        frame = self.frame.copy()
        frame["raan_deg"] = wrap_deg(np.degrees(raan))
        frame["raan_rate_deg_per_day"] = np.degrees(rate) * SECONDS_PER_DAY
        return dataclasses.replace(self, frame=frame, raan_rates="sgp4")

    def subset(self, ids: Iterable[str] | str) -> Catalog:
        """Catalog restricted to ``ids``, kept in catalog order (not in the given order).

        Parameters
        ----------
        ids : iterable of str or int, or one str or int
            Debris ids to keep; integer ids are compared as ``str(id)`` (``subset(3)`` is
            ``subset(["3"])``).

        Raises
        ------
        CatalogError
            An id is not in the catalog, is neither a string nor an integer, or no id is
            given.
        """
        one = _is_id(ids)
        listed = [ids] if one else list(ids) if isinstance(ids, Iterable) else None
        wrong = [] if listed is None else [k for k in listed if not _is_id(k)]
        if listed is None or wrong:
            shown = repr(ids) if listed is None else listing(map(repr, wrong))
            raise CatalogError(f"{self.source}: Catalog.subset(ids): ids must be debris ids "
                               "(strings or integers) or a sequence of them, got "
                               f"{shown}")  # fmt: skip
        wanted = [str(value) for value in listed]
        known = self.ids
        unknown = [value for value in dict.fromkeys(wanted) if value not in known]
        if unknown:
            shown = listing(map(repr, unknown))
            raise CatalogError(f"{self.source}: unknown debris id(s) {shown}; the catalog has "
                               f"{listing(map(repr, known), MAX_REPORTED)}")  # fmt: skip
        if not wanted:
            raise CatalogError(f"{self.source}: subset needs at least one debris id")
        keep = self.frame["id"].isin(set(wanted)).to_numpy()
        frame = self.frame.loc[keep].reset_index(drop=True)
        return dataclasses.replace(self, frame=frame, invalid=None)


def _is_real(value) -> bool:
    """A finite real number (not a bool, not a string)."""
    return (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(value))  # fmt: skip


def _is_id(value) -> bool:
    """A debris id as the API takes one: a string, or an integer (``3`` is ``"3"``)."""
    return isinstance(value, str | numbers.Integral) and not isinstance(value, bool)
