"""The debris of a catalog as SGP4 propagates them, in the GCRF (issue 26, a plan that flies).

:class:`DebrisEphemeris` holds one SGP4 element set (``sgp4.api.Satrec``, WGS72, opsmode
``'i'``, initialised by ``sgp4init``) per row of a :class:`~sdc_cvx.inputs.catalog.Catalog`
and gives each debris's GCRF position and velocity at any time after the catalog's start
(SGP4 output in TEME, rotated by :func:`~sdc_cvx.flight.frames.teme_to_gcrf`).

The element sets are those of :func:`sdc_cvx.inputs.sgp4_sets.satrecs` (TLE and OMM rows
as the file's; CSV and GTOC9 rows with the Kozai mean motion whose Brouwer ``a`` is the
catalog's ``a_km``; each row's epoch, or the catalog's start).

A row whose position on its orbit is unknown (no argument of perigee and mean anomaly,
no ``arglat_deg``), or a catalog without epochs nor start date, cannot be flown:
:meth:`DebrisEphemeris.from_catalog` raises a :class:`~sdc_cvx.errors.CatalogError`
saying what to add (:func:`missing_phase`).

Units inside are SI: m, m/s, rad, s.

References
----------
.. [1] D. A. Vallado, P. Crawford, R. Hujsak and T. S. Kelso, "Revisiting Spacetrack
   Report #3", AIAA 2006-6753, 2006 (``sgp4init``, WGS72, TEME).
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.6 (secular J2 rates).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from sgp4.api import SGP4_ERRORS, Satrec

from ..errors import CatalogError
from ..inputs.catalog import Catalog
from ..inputs.sgp4_sets import kozai_for_brouwer_a, row_epochs, satrecs, without_phase
from ..physics.elements import secular_rates
from ..physics.orbits import J2, MU_EARTH, R_EARTH, SECONDS_PER_DAY
from .frames import earth_pole_gcrf, teme_to_gcrf
from .gtoc9_ephemeris import Gtoc9Ephemeris

__all__ = ["DebrisEphemeris", "Gtoc9Ephemeris", "debris_ephemeris", "kozai_for_brouwer_a",
           "missing_phase"]  # fmt: skip


def missing_phase(catalog: Catalog) -> str | None:
    """Why the debris of ``catalog`` cannot be flown, in words, or None if they can.

    Parameters
    ----------
    catalog : Catalog
        The debris.

    Returns
    -------
    str or None
        Names the catalog's source, how many rows lack a position on their orbit (no
        ``argp_deg`` and ``mean_anomaly_deg``, no ``arglat_deg``), their first ids and
        what to add; and, for a catalog without epochs, the missing start date.
    """
    frame = catalog.frame
    lacking, shown = without_phase(frame)
    parts = []
    if lacking:
        parts.append(
            f"{lacking} of {len(frame)} debris have no position on their orbit (no "
            f"argp_deg and mean_anomaly_deg, no arglat_deg): id(s) {shown}; add an "
            f"arglat_deg column (argument of latitude [deg] at the row's epoch, or at the "
            f"start date when the catalog has no epochs), or read the debris from a TLE, "
            f"OMM or GTOC9 file"
        )
    if row_epochs(catalog) is None:
        parts.append(
            "the catalog has no epochs and no start date; give the start date the elements "
            "refer to (start=... when reading it, --start on the command line)"
        )
    if not parts:
        return None
    return f"{catalog.source}: cannot fly the debris: " + "; ".join(parts)


@dataclass(frozen=True, eq=False, repr=False)
class DebrisEphemeris:
    """The debris of a catalog as SGP4 propagates them (module docstring).

    Build it with :meth:`from_catalog`.

    Attributes
    ----------
    ids : tuple of str
        Debris ids, in the catalog's order.
    epochs : pandas.DatetimeIndex
        Epoch of each row's element set (UTC).
    start : pandas.Timestamp
        The catalog's start (UTC): time 0 of :meth:`state`.
    source : str
        The catalog's source, for the messages.
    satrecs : tuple of sgp4.api.Satrec
        One initialised element set per row.
    a_m, e, inc_rad : numpy.ndarray
        The catalog's Brouwer semi-major axis [m], eccentricity [-], inclination [rad].
    arglat_epoch_rad : numpy.ndarray
        Mean argument of latitude ``argp + M`` at each row's epoch [rad].
    kozai_calls : tuple of int
        ``sgp4init`` calls of each row's Kozai inversion (0 for TLE and OMM rows).
    """

    ids: tuple[str, ...]
    epochs: pd.DatetimeIndex
    start: pd.Timestamp
    source: str
    satrecs: tuple[Satrec, ...]
    a_m: np.ndarray
    e: np.ndarray
    inc_rad: np.ndarray
    arglat_epoch_rad: np.ndarray
    kozai_calls: tuple[int, ...]

    @classmethod
    def from_catalog(cls, catalog: Catalog) -> DebrisEphemeris:
        """One SGP4 element set per row of ``catalog`` (module docstring).

        Parameters
        ----------
        catalog : Catalog
            TLE, OMM, GTOC9 or CSV catalog (a CSV one with ``arglat_deg``, or
            ``argp_deg`` and ``mean_anomaly_deg``).

        Returns
        -------
        DebrisEphemeris

        Raises
        ------
        CatalogError
            A row has no phase, the catalog has no epochs nor start date
            (:func:`missing_phase`), or sgp4 rejects a row's elements.
        """
        problem = missing_phase(catalog)
        if problem:
            raise CatalogError(problem)
        sets = satrecs(catalog)
        return cls(ids=tuple(str(ident) for ident in catalog.frame["id"]), epochs=sets.epochs,
                   start=catalog.start, source=catalog.source, satrecs=sets.satrecs,
                   a_m=catalog.a_m, e=catalog.e, inc_rad=catalog.inc_rad,
                   arglat_epoch_rad=sets.arglat_epoch_rad,
                   kozai_calls=sets.kozai_calls)  # fmt: skip

    frame_name = "GCRF"

    def __len__(self) -> int:
        return len(self.ids)

    def pole_at(self, seconds: float) -> np.ndarray:
        """The Earth's rotation axis in the GCRF ``seconds`` after the start (TEME's z
        axis, :func:`~sdc_cvx.flight.frames.earth_pole_gcrf`)."""
        return earth_pole_gcrf(self.start + pd.to_timedelta([float(seconds)], unit="s"))[0]

    def __repr__(self) -> str:
        return f"DebrisEphemeris({len(self)} debris from {self.source!r}, start={self.start})"

    def state(self, position: int, seconds) -> tuple[np.ndarray, np.ndarray]:
        """GCRF position and velocity of one debris, ``seconds`` after the start.

        Parameters
        ----------
        position : int
            Row of ``catalog.frame`` (0-based).
        seconds : array_like
            Times after :attr:`start` [s], shape (m,) or scalar.

        Returns
        -------
        r, v : numpy.ndarray
            Shape (m, 3): position [m] and velocity [m/s] in the GCRF.

        Raises
        ------
        CatalogError
            SGP4 cannot propagate the element set to one of the dates (decayed, ...):
            names the debris and the first such date.

        References
        ----------
        Vallado et al. [1]_ (SGP4 in TEME); :func:`sdc_cvx.flight.frames.teme_to_gcrf`.
        """
        seconds = np.atleast_1d(np.asarray(seconds, dtype=float))
        satrec = self.satrecs[position]
        since_epoch_s = (self.start - self.epochs[position]).value / 1e9 + seconds
        jd = np.full(seconds.shape, satrec.jdsatepoch)
        fraction = satrec.jdsatepochF + since_epoch_s / SECONDS_PER_DAY  # exact tsince
        errors, r_km, v_kmps = satrec.sgp4_array(jd, fraction)
        if np.any(errors):
            k = int(np.flatnonzero(errors)[0])
            code = int(errors[k])
            when = self.start + pd.Timedelta(seconds=float(seconds[k]))
            raise CatalogError(
                f"{self.source}: debris {self.ids[position]}: SGP4 cannot propagate its "
                f"element set (epoch {self.epochs[position].isoformat()}) to "
                f"{when.isoformat()}, {seconds[k]:g} s after the start: error {code} "
                f"({SGP4_ERRORS.get(code, 'unknown')})"
            )
        dates = self.start + pd.to_timedelta(seconds, unit="s")
        return teme_to_gcrf(r_km * 1000.0, v_kmps * 1000.0, dates)

    def arglat_at_start(self) -> np.ndarray:
        """Mean argument of latitude ``argp + M`` of every debris at the start [rad].

        Carried from each row's epoch by the first-order secular J2 rate of the mean
        argument of latitude (:func:`sdc_cvx.physics.elements.secular_rates`), with the
        package's ``MU_EARTH``, ``J2`` and ``R_EARTH`` and the catalog's Brouwer ``a``:
        the planner's model.  SGP4's own secular rates add J2^2 and J4 terms, a few
        1e-3 of the J2 drift (~6 deg/day in sun-synchronous LEO).

        Returns
        -------
        numpy.ndarray
            Shape (N,), in [0, 2 pi) [rad].

        References
        ----------
        Vallado [2]_ Eq. 9-41.
        """
        rate = secular_rates(self.a_m, self.e, self.inc_rad, j2=J2, mu=MU_EARTH,
                             r_eq=R_EARTH).arglat  # fmt: skip
        elapsed = (self.start - self.epochs).total_seconds().to_numpy()
        return np.mod(self.arglat_epoch_rad + rate * elapsed, 2.0 * np.pi)


def debris_ephemeris(catalog: Catalog, *, low_thrust: bool = False):
    """Where the debris of ``catalog`` are, as its elements define them: GTOC9's own
    ephemeris for a GTOC9 catalog (:class:`Gtoc9Ephemeris`), SGP4 for the others
    (:class:`DebrisEphemeris`).  CatalogError as they raise it.

    A ``low_thrust`` flight of a GTOC9 catalog flies against SGP4 sets of its elements:
    it closes its rendezvous by co-orbiting the debris (:mod:`.thrust_corrections`), and a
    GTOC9 debris, a Keplerian orbit whose elements precess without J2's short-period
    terms, co-orbits with no J2 trajectory (measured: 470 km misses and +168 % of ΔV on
    README's low-thrust GTOC9 flight against GTOC9's ephemeris).
    """
    if getattr(catalog, "ephemeris", "sgp4") == "gtoc9" and not low_thrust:
        problem = missing_phase(catalog)
        if problem:
            raise CatalogError(problem)
        return Gtoc9Ephemeris.from_catalog(catalog)
    return DebrisEphemeris.from_catalog(catalog)
