"""The debris of a catalog as SGP4 propagates them, in the GCRF (issue 26, a plan that flies).

:class:`DebrisEphemeris` holds one SGP4 element set (``sgp4.api.Satrec``, WGS72, opsmode
``'i'``, initialised by ``sgp4init``) per row of a :class:`~sdc_cvx.inputs.catalog.Catalog`
and gives each debris's GCRF position and velocity at any time after the catalog's start
(SGP4 output in TEME, rotated by :func:`~sdc_cvx.flight.frames.teme_to_gcrf`).

Element sets
------------
* TLE and OMM rows: the file's own mean elements (epoch, Kozai mean motion, e, i, RAAN
  at the epoch, argument of perigee, mean anomaly) and B* drag term (``bstar``, 0 when
  absent): the same element set as ``Satrec.twoline2rv`` of the file's lines.  The
  mean-motion derivatives are left 0: SGP4 does not use them.
* CSV and GTOC9 rows (no mean motion): ``bstar = 0`` (or the row's ``bstar``, when a
  CSV catalog gives one) and the Kozai mean motion whose SGP4 Brouwer ("un-Kozai'd")
  semi-major axis is the catalog's ``a_km``, the convention by which the TLE reader
  computes ``a_km`` (:func:`sdc_cvx.inputs.formats.brouwer_a_km`), found by a secant
  iteration on ``sgp4init`` (3-4 initialisations to 1 micrometre).  The phase is
  ``argp_deg`` and ``mean_anomaly_deg``, or ``argp = 0`` and ``M = arglat_deg``
  (argument of latitude) when only that is given.  GTOC9's osculating elements are
  taken as SGP4 mean elements: SGP4's mean radius then lies 4-6 km above their ``a``
  (the mean of the short-period J2 terms, ``3/4 J2 R^2/p (1 - 3 cos^2 i)``).
* The epoch is the row's ``epoch``, or the catalog's start when the catalog has none.

A row whose position on its orbit is unknown (no argument of perigee and mean anomaly,
no ``arglat_deg``), or a catalog without epochs nor start date, cannot be flown:
:meth:`DebrisEphemeris.from_catalog` raises a :class:`~sdc_cvx.errors.CatalogError`
saying what to add (:func:`missing_phase`).

Units inside are SI: m, m/s, rad, s.

References
----------
.. [1] F. R. Hoots and R. L. Roehrich, "Spacetrack Report No. 3: Models for Propagation of
   NORAD Element Sets", 1980 (SGP4; Kozai and Brouwer mean motions).
.. [2] D. A. Vallado, P. Crawford, R. Hujsak and T. S. Kelso, "Revisiting Spacetrack
   Report #3", AIAA 2006-6753, 2006 (``sgp4init``, WGS72, TEME).
.. [3] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §9.6 (secular J2 rates).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from sgp4.api import SGP4_ERRORS, WGS72, Satrec

from ..errors import CatalogError
from ..inputs.catalog import Catalog
from ..inputs.formats import brouwer_a_km
from ..physics.elements import secular_rates
from ..physics.orbits import J2, MU_EARTH, R_EARTH, SECONDS_PER_DAY
from .frames import teme_to_gcrf

__all__ = ["DebrisEphemeris", "kozai_for_brouwer_a", "missing_phase"]

_SGP4_EPOCH = pd.Timestamp("1949-12-31T00:00:00Z")
"""Day 0 of ``sgp4init``'s epoch argument."""
_MINUTES_PER_REV_DAY = 2.0 * math.pi / 1440.0
"""rev/day -> rad/min."""
_SHOWN_IDS = 5
"""Ids named in the message of :func:`missing_phase`."""
_A_TOLERANCE_M = 1e-6
"""The Kozai inversion stops when the Brouwer ``a`` is this close to the catalog's [m]."""
_MAX_ITERATIONS = 20


def _numbers(frame: pd.DataFrame, column: str) -> np.ndarray:
    """``frame[column]`` as floats (NaN where absent or not a number; CSV text included)."""
    if column not in frame.columns:
        return np.full(len(frame), np.nan)
    return pd.to_numeric(frame[column], errors="coerce").to_numpy(dtype=float)


def _row_epochs(catalog: Catalog) -> pd.DatetimeIndex | None:
    """Each row's epoch (UTC), the catalog's start where a row has none; None if neither."""
    frame = catalog.frame
    if "epoch" in frame.columns:
        epochs = pd.DatetimeIndex(frame["epoch"])
        epochs = epochs.tz_localize("UTC") if epochs.tz is None else epochs.tz_convert("UTC")
        if catalog.start is not None:
            epochs = epochs.fillna(catalog.start)
        return None if epochs.hasnans else epochs
    if catalog.start is None:
        return None
    return pd.DatetimeIndex([catalog.start] * len(frame))


def _phase_known(frame: pd.DataFrame) -> np.ndarray:
    elements = np.isfinite(_numbers(frame, "argp_deg") + _numbers(frame, "mean_anomaly_deg"))
    return elements | np.isfinite(_numbers(frame, "arglat_deg"))


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
    known = _phase_known(frame)
    lacking = [str(ident) for ident, ok in zip(frame["id"], known, strict=True) if not ok]
    parts = []
    if lacking:
        shown = ", ".join(lacking[:_SHOWN_IDS]) + (", ..." if len(lacking) > _SHOWN_IDS else "")
        parts.append(
            f"{len(lacking)} of {len(frame)} debris have no position on their orbit (no "
            f"argp_deg and mean_anomaly_deg, no arglat_deg): id(s) {shown}; add an "
            f"arglat_deg column (argument of latitude [deg] at the row's epoch, or at the "
            f"start date when the catalog has no epochs), or read the debris from a TLE, "
            f"OMM or GTOC9 file"
        )
    if _row_epochs(catalog) is None:
        parts.append(
            "the catalog has no epochs and no start date; give the start date the elements "
            "refer to (start=... when reading it, --start on the command line)"
        )
    if not parts:
        return None
    return f"{catalog.source}: cannot fly the debris: " + "; ".join(parts)


def _sgp4_epoch_days(epoch: pd.Timestamp) -> float:
    """Days since 1949-12-31 00:00 UTC (``sgp4init``'s epoch), from the nanoseconds."""
    return (epoch - _SGP4_EPOCH).value / (SECONDS_PER_DAY * 1e9)


def _satnum(ident: str) -> int:
    return int(ident) if ident.isdigit() and int(ident) <= 339_999 else 0


def _init(satnum, epoch_days, bstar, e, argp, inc, mean_anomaly, no_kozai, raan) -> Satrec:
    satrec = Satrec()
    satrec.sgp4init(WGS72, "i", satnum, epoch_days, bstar, 0.0, 0.0, e, argp, inc,
                    mean_anomaly, no_kozai, raan)  # fmt: skip
    return satrec


def kozai_for_brouwer_a(a_m: float, init) -> tuple[Satrec, int]:
    """The element set whose SGP4 Brouwer semi-major axis is ``a_m``, by a secant method.

    Parameters
    ----------
    a_m : float
        Target Brouwer ``a`` [m], in the convention of
        :func:`sdc_cvx.inputs.formats.brouwer_a_km` (``MU_EARTH``).
    init : callable
        ``init(no_kozai)`` -> ``Satrec`` initialised with the Kozai mean motion
        ``no_kozai`` [rad/min] and the other elements fixed.

    Returns
    -------
    satrec : sgp4.api.Satrec
        Within ``_A_TOLERANCE_M`` (1 micrometre) of ``a_m``.
    calls : int
        ``sgp4init`` calls made.

    References
    ----------
    Hoots and Roehrich [1]_ (SGP4's recovery of the Brouwer mean motion).
    """
    target = math.sqrt(MU_EARTH / a_m**3) * 60.0  # Brouwer mean motion [rad/min]

    def brouwer_n(satrec) -> float:
        return 1.0 / (satrec.tumin * satrec.a**1.5)

    x0, s0 = target, init(target)
    x1 = x0 * target / brouwer_n(s0)  # n_kozai / n_brouwer is nearly constant
    s1, calls = init(x1), 2
    while abs(brouwer_a_km(s1) * 1000.0 - a_m) > _A_TOLERANCE_M and calls < _MAX_ITERATIONS:
        f0, f1 = brouwer_n(s0) - target, brouwer_n(s1) - target
        if f1 == f0:
            break
        x0, s0, x1 = x1, s1, x1 - f1 * (x1 - x0) / (f1 - f0)
        s1, calls = init(x1), calls + 1
    return s1, calls


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
        frame = catalog.frame
        epochs = _row_epochs(catalog)
        ids = tuple(str(ident) for ident in frame["id"])
        a_m, e, inc = catalog.a_m, catalog.e, catalog.inc_rad
        raan_column = "raan_epoch_deg" if "raan_epoch_deg" in frame.columns else "raan_deg"
        raan = np.radians(_numbers(frame, raan_column))
        argp = np.radians(_numbers(frame, "argp_deg"))
        mean_anomaly = np.radians(_numbers(frame, "mean_anomaly_deg"))
        arglat = np.radians(_numbers(frame, "arglat_deg"))
        elements = np.isfinite(argp + mean_anomaly)
        argp = np.where(elements, argp, 0.0)
        mean_anomaly = np.where(elements, mean_anomaly, arglat)
        mean_motion = _numbers(frame, "mean_motion_rev_per_day") * _MINUTES_PER_REV_DAY
        bstar = np.nan_to_num(_numbers(frame, "bstar"))
        satrecs, calls = [], []
        for k, ident in enumerate(ids):
            fixed = (_satnum(ident), _sgp4_epoch_days(epochs[k]), float(bstar[k]), e[k],
                     argp[k], inc[k], mean_anomaly[k])  # fmt: skip

            def init(no_kozai, fixed=fixed, k=k):
                return _init(*fixed, no_kozai, raan[k])

            if np.isfinite(mean_motion[k]):
                satrec, count = init(mean_motion[k]), 0
            else:
                satrec, count = kozai_for_brouwer_a(a_m[k], init)
            if satrec.error:
                reason = SGP4_ERRORS.get(satrec.error, "unknown")
                raise CatalogError(f"{catalog.source}: debris {ident}: sgp4 rejects the "
                                   f"elements (error {satrec.error}: {reason})")  # fmt: skip
            satrecs.append(satrec)
            calls.append(count)
        return cls(ids=ids, epochs=epochs, start=catalog.start, source=catalog.source,
                   satrecs=tuple(satrecs), a_m=a_m, e=e, inc_rad=inc,
                   arglat_epoch_rad=np.mod(argp + mean_anomaly, 2.0 * np.pi),
                   kozai_calls=tuple(calls))  # fmt: skip

    def __len__(self) -> int:
        return len(self.ids)

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
        Vallado et al. [2]_ (SGP4 in TEME); :func:`sdc_cvx.flight.frames.teme_to_gcrf`.
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
        Vallado [3]_ Eq. 9-41.
        """
        rate = secular_rates(self.a_m, self.e, self.inc_rad, j2=J2, mu=MU_EARTH,
                             r_eq=R_EARTH).arglat  # fmt: skip
        elapsed = (self.start - self.epochs).total_seconds().to_numpy()
        return np.mod(self.arglat_epoch_rad + rate * elapsed, 2.0 * np.pi)
