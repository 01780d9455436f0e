"""One SGP4 element set per catalog row: the debris as SGP4 propagates them (issue 26).

:func:`satrecs` builds one ``sgp4.api.Satrec`` (WGS72, opsmode ``'i'``, initialised by
``sgp4init``) per row of a :class:`~sdc_cvx.inputs.catalog.Catalog` (what it reads of
one: :class:`CatalogRows`, so that the catalog, which fits its rates through this module,
is not imported back).  The flight replay
(:class:`sdc_cvx.flight.ephemeris.DebrisEphemeris`, which adds the TEME to GCRF rotation)
and the RAAN rates fitted to SGP4 (:mod:`sdc_cvx.inputs.sgp4_rates`) both fly these.

Element sets
------------
* TLE and OMM rows: the file's own mean elements (epoch, Kozai mean motion, e, i, RAAN
  at the epoch, argument of perigee, mean anomaly) and B* drag term (``bstar``, 0 when
  absent): the same element set as ``Satrec.twoline2rv`` of the file's lines.  The
  mean-motion derivatives are left 0: SGP4 does not use them.
* CSV and GTOC9 rows (no mean motion): ``bstar = 0`` (or the row's ``bstar``, when a
  CSV catalog gives one) and the Kozai mean motion whose SGP4 Brouwer ("un-Kozai'd")
  semi-major axis is the catalog's ``a_km``, the convention by which the TLE reader
  computes ``a_km`` (:func:`brouwer_a_km`), found by a secant
  iteration on ``sgp4init`` (3-4 initialisations to 1 micrometre).  The phase is
  ``argp_deg`` and ``mean_anomaly_deg``, or ``argp = 0`` and ``M = arglat_deg``
  (argument of latitude) when only that is given; with ``phase_needed=False``, a row
  with neither gets ``argp = M = 0`` (what needs no phase, e.g. the RAAN rate, may
  use it).  GTOC9's osculating elements are taken as SGP4 mean elements: SGP4's mean
  radius then lies 4-6 km above their ``a`` (the mean of the short-period J2 terms,
  ``3/4 J2 R^2/p (1 - 3 cos^2 i)``).
* The RAAN is ``raan_epoch_deg`` (the file's, at the row's epoch) when the catalog has
  that column, else ``raan_deg``.
* The epoch is the row's ``epoch``, or the catalog's start when the catalog has none;
  with ``phase_needed=False``, :data:`NOMINAL_EPOCH` when it has neither (SGP4's
  near-Earth model, periods under 225 minutes, does not depend on the date).

References
----------
.. [1] F. R. Hoots and R. L. Roehrich, "Spacetrack Report No. 3: Models for Propagation of
   NORAD Element Sets", 1980 (SGP4; Kozai and Brouwer mean motions).
.. [2] D. A. Vallado, P. Crawford, R. Hujsak and T. S. Kelso, "Revisiting Spacetrack
   Report #3", AIAA 2006-6753, 2006 (``sgp4init``, WGS72, TEME).
"""

from __future__ import annotations

import math
from typing import NamedTuple, Protocol

import numpy as np
import pandas as pd
from sgp4.api import SGP4_ERRORS, WGS72, Satrec

from ..errors import CatalogError
from ..physics.orbits import MU_EARTH, SECONDS_PER_DAY

__all__ = ["NOMINAL_EPOCH", "CatalogRows", "ElementSets", "brouwer_a_km", "kozai_for_brouwer_a",
           "numbers", "phase_known", "row_epochs", "satrecs", "without_phase"]  # fmt: skip

NOMINAL_EPOCH = pd.Timestamp("2000-01-01T12:00:00Z")
"""Epoch of the element sets of a catalog without epochs nor start (``phase_needed=False``)."""
_SGP4_EPOCH = pd.Timestamp("1949-12-31T00:00:00Z")
"""Day 0 of ``sgp4init``'s epoch argument."""
_MINUTES_PER_REV_DAY = 2.0 * math.pi / 1440.0
"""rev/day -> rad/min."""
_A_TOLERANCE_M = 1e-6
"""The Kozai inversion stops when the Brouwer ``a`` is this close to the catalog's [m]."""
_MAX_ITERATIONS = 20
_SHOWN_IDS = 5
"""Ids named by :func:`without_phase`."""


class CatalogRows(Protocol):
    """What the element sets are built from: a :class:`~sdc_cvx.inputs.catalog.Catalog`
    (its rows, start and source; the elements in SI units)."""

    @property
    def frame(self) -> pd.DataFrame: ...
    @property
    def start(self) -> pd.Timestamp | None: ...
    @property
    def source(self) -> str: ...
    @property
    def a_m(self) -> np.ndarray: ...
    @property
    def e(self) -> np.ndarray: ...
    @property
    def inc_rad(self) -> np.ndarray: ...


class ElementSets(NamedTuple):
    """What :func:`satrecs` returns.

    Attributes
    ----------
    satrecs : tuple of sgp4.api.Satrec
        One initialised element set per row, in the catalog's order.
    epochs : pandas.DatetimeIndex
        Epoch of each element set (UTC).
    arglat_epoch_rad : numpy.ndarray
        Mean argument of latitude ``argp + M`` at each epoch, in [0, 2 pi) [rad] (0 for a
        row without phase, ``phase_needed=False``).
    kozai_calls : tuple of int
        ``sgp4init`` calls of each row's Kozai inversion (0 for TLE and OMM rows).
    """

    satrecs: tuple[Satrec, ...]
    epochs: pd.DatetimeIndex
    arglat_epoch_rad: np.ndarray
    kozai_calls: tuple[int, ...]


def brouwer_a_km(satrec) -> float:
    """Semi-major axis [km] of an initialised sgp4 ``Satrec``: the catalog's convention.

    ``a = (MU_EARTH / n**2) ** (1/3)`` with ``n`` the Brouwer mean motion sgp4 derives
    from the Kozai mean motion of the element set (``no_unkozai``, which the compiled
    ``Satrec`` does not expose: ``1 / (tumin * a**1.5)`` [rad/min] is exactly it); see
    :mod:`sdc_cvx.inputs.formats._common`.
    """
    n_rad_per_min = 1.0 / (satrec.tumin * satrec.a**1.5)
    n = n_rad_per_min / 60.0
    return (MU_EARTH / n**2) ** (1.0 / 3.0) / 1000.0


def numbers(frame: pd.DataFrame, column: str) -> np.ndarray:
    """``frame[column]`` as floats (NaN where absent or not a number; CSV text included)."""
    if column not in frame.columns:
        return np.full(len(frame), np.nan)
    return pd.to_numeric(frame[column], errors="coerce").to_numpy(dtype=float)


def row_epochs(catalog: CatalogRows) -> pd.DatetimeIndex | None:
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


def phase_known(frame: pd.DataFrame) -> np.ndarray:
    """Whether each row gives its position on its orbit (argp and M, or ``arglat_deg``)."""
    elements = np.isfinite(numbers(frame, "argp_deg") + numbers(frame, "mean_anomaly_deg"))
    return elements | np.isfinite(numbers(frame, "arglat_deg"))


def without_phase(frame: pd.DataFrame) -> tuple[int, str]:
    """How many rows have no phase (:func:`phase_known`), and their first ids in words."""
    lacking = [str(ident) for ident, ok in zip(frame["id"], phase_known(frame), strict=True)
               if not ok]  # fmt: skip
    shown = ", ".join(lacking[:_SHOWN_IDS]) + (", ..." if len(lacking) > _SHOWN_IDS else "")
    return len(lacking), shown


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
        :func:`brouwer_a_km` (``MU_EARTH``).
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


def satrecs(catalog: CatalogRows, *, phase_needed: bool = True) -> ElementSets:
    """One SGP4 element set per row of ``catalog`` (module docstring).

    Parameters
    ----------
    catalog : Catalog
        TLE, OMM, GTOC9 or CSV catalog.
    phase_needed : bool
        True (default): every row must give its phase (``argp_deg`` and
        ``mean_anomaly_deg``, or ``arglat_deg``) and the catalog its epochs or start
        date.  False: a row without phase gets argument of latitude 0, a catalog
        without epochs nor start the :data:`NOMINAL_EPOCH`.

    Returns
    -------
    ElementSets

    Raises
    ------
    CatalogError
        ``phase_needed`` and a row has no phase or the catalog no epochs nor start date;
        or sgp4 rejects a row's elements (the row named, with sgp4's reason).
    """
    frame = catalog.frame
    ids = tuple(str(ident) for ident in frame["id"])
    known = phase_known(frame)
    epochs = row_epochs(catalog)
    if phase_needed and (epochs is None or not known.all()):
        count, shown = without_phase(frame)
        what = (f"{count} debris without a position on their orbit ({shown})" if count
                else "no epochs nor start date")  # fmt: skip
        raise CatalogError(f"{catalog.source}: no SGP4 element sets with their phase: {what}")
    if epochs is None:
        epochs = pd.DatetimeIndex([NOMINAL_EPOCH] * len(frame))
    a_m, e, inc = catalog.a_m, catalog.e, catalog.inc_rad
    raan_column = "raan_epoch_deg" if "raan_epoch_deg" in frame.columns else "raan_deg"
    raan = np.radians(numbers(frame, raan_column))
    argp = np.radians(numbers(frame, "argp_deg"))
    mean_anomaly = np.radians(numbers(frame, "mean_anomaly_deg"))
    arglat = np.radians(numbers(frame, "arglat_deg"))
    elements = np.isfinite(argp + mean_anomaly)
    argp = np.where(elements, argp, 0.0)
    mean_anomaly = np.where(elements, mean_anomaly, np.where(known, arglat, 0.0))
    mean_motion = numbers(frame, "mean_motion_rev_per_day") * _MINUTES_PER_REV_DAY
    bstar = np.nan_to_num(numbers(frame, "bstar"))
    made, calls = [], []
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
        made.append(satrec)
        calls.append(count)
    return ElementSets(tuple(made), epochs, np.mod(argp + mean_anomaly, 2.0 * np.pi),
                       tuple(calls))  # fmt: skip
