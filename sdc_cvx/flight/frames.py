"""Reference frames of a flown plan: SGP4's TEME to the GCRF, and the Earth's pole in it.

SGP4 gives positions and velocities in TEME, the *true equator, mean equinox* of date
(Spacetrack Report #3; Vallado et al. [2]_ Appendix C).  A numerical replay of a plan
(issue 26) compares the spacecraft and the debris in one inertial frame, the GCRF, and
measures inclinations and RAANs from the Earth's true equator.

TEME to GCRF (Vallado [1]_ §3.7, [2]_ §"TEME"), IAU-76/FK5 route::

    r_TOD   = R3(-eqeq) r_TEME       equation of the equinoxes, 1982 form
    r_MOD   = N80^T r_TOD            nutation, IAU 1980      (erfa.nutm80)
    r_J2000 = P76^T r_MOD            precession, IAU 1976    (erfa.pmat76)
    r_GCRF  = B^T r_J2000            frame bias, IAU 2000    (erfa.bp00)

``R3(a)`` is the frame rotation about z by ``a`` (ERFA's ``rz``).  The equation of the
equinoxes is the 1982 one, ``eqeq = dpsi_80 cos(eps_mean_80)``, without the two
"kinematic" terms the IAU added in 1997 (``erfa.eqeq94`` has them): TEME is tied to
SGP4's Greenwich mean sidereal time of 1982, and Vallado's ``teme2eci`` rotates through
these "geometric terms" only.  The kinematic terms are at most 2.7 mas, 9 cm at 7,000 km
(with them, the difference to skyfield below shrinks by 0.04 m).

The time argument is TT (UTC + TAI-UTC + 32.184 s, ``erfa.utctai`` then ``erfa.taitt``);
UT1 is not needed: TEME and the GCRF are both celestial frames, and no Earth rotation
angle enters the rotation between them.  Past the end of ERFA's leap-second table
(e.g. GTOC9's 2060 epochs) TAI-UTC is held at its last value: a TT wrong by a minute
moves the matrix by < 1e-9 rad (precession and nutation drift < 100 "/yr).

Accuracy: the IAU 1976/1980 pole lies about 31 mas from the IAU 2006/2000A Celestial
Intermediate Pole (the celestial pole offsets of the old model, not applied here), and
the rotation differs from skyfield's TEME (GMST 1982 to the pseudo-Earth-fixed frame,
then IAU 2006/2000A) by 30-36 mas over 2020-2021: 1.3 m and 1.3 mm/s on a 7,200 km
orbit, measured in ``tests/flight/test_frames.py``.

Units: lengths in m, velocities in m/s, angles in rad.

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §3.7 (IAU-76/FK5 reduction) and §3.7.4 (TEME).
.. [2] D. A. Vallado, P. Crawford, R. Hujsak and T. S. Kelso, "Revisiting Spacetrack
   Report #3", AIAA/AAS Astrodynamics Specialist Conference, AIAA 2006-6753, 2006.
.. [3] IERS Conventions (2010), IERS Technical Note 36, ch. 5 (frame bias, CIP).
"""

from __future__ import annotations

import warnings

import erfa
import numpy as np
import pandas as pd

__all__ = [
    "earth_pole_gcrf",
    "equatorial_basis",
    "julian_dates",
    "teme_to_gcrf",
    "teme_to_gcrf_matrix",
]

_UNIX_EPOCH_JD = 2440587.5
"""Julian date of 1970-01-01 00:00 UTC."""
_NS_PER_DAY = 86_400 * 10**9


def julian_dates(epochs) -> tuple[np.ndarray, np.ndarray]:
    """Two-part UTC Julian dates of ``epochs``, to the nanosecond.

    Parameters
    ----------
    epochs : pandas.Timestamp, pandas.DatetimeIndex or array_like of Timestamps
        UTC dates (tz-aware; naive ones are taken as UTC).

    Returns
    -------
    jd1, jd2 : numpy.ndarray
        Shape (m,) (``(1,)`` for one Timestamp): ``jd1`` the Julian date of the day's
        0 h UTC (an integer + 0.5) [day], ``jd2`` the fraction of the day in [0, 1)
        [day], from the integer nanoseconds (no rounding beyond the float of ``jd2``,
        ~1e-17 day).  ERFA's quasi-JD convention for UTC.
    """
    index = _index(epochs)
    days, rest = np.divmod(index.as_unit("ns").asi8, _NS_PER_DAY)
    return _UNIX_EPOCH_JD + days.astype(float), rest / _NS_PER_DAY


def _index(epochs) -> pd.DatetimeIndex:
    """``epochs`` as a UTC DatetimeIndex."""
    if isinstance(epochs, pd.Timestamp | str) or np.ndim(epochs) == 0:
        epochs = [pd.Timestamp(epochs)]
    index = pd.DatetimeIndex(epochs)
    return index.tz_localize("UTC") if index.tz is None else index.tz_convert("UTC")


def _tt(epochs) -> tuple[np.ndarray, np.ndarray]:
    """Two-part TT Julian dates of UTC ``epochs`` (TAI-UTC held past ERFA's table)."""
    utc1, utc2 = julian_dates(epochs)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", erfa.ErfaWarning)  # "dubious year": see module doc
        tai1, tai2 = erfa.utctai(utc1, utc2)
    return erfa.taitt(tai1, tai2)


def _transpose(matrices: np.ndarray) -> np.ndarray:
    return np.swapaxes(matrices, -1, -2)


def teme_to_gcrf_matrix(epochs) -> np.ndarray:
    """Rotation matrices taking TEME vectors to the GCRF (module docstring).

    Parameters
    ----------
    epochs : pandas.Timestamp, pandas.DatetimeIndex or array_like of Timestamps
        UTC dates (see :func:`julian_dates`).

    Returns
    -------
    numpy.ndarray
        Shape (m, 3, 3): ``r_gcrf = M[k] @ r_teme`` at ``epochs[k]``.  ``M[k][:, 2]``
        is TEME's z-axis, the true pole of date, in the GCRF.

    References
    ----------
    Vallado [1]_ §3.7 and Eq. 3-90; Vallado et al. [2]_ Appendix C.
    """
    tt1, tt2 = _tt(epochs)
    dpsi, _ = erfa.nut80(tt1, tt2)
    eqeq = dpsi * np.cos(erfa.obl80(tt1, tt2))  # 1982 form: no kinematic terms
    r3 = erfa.rz(-eqeq, np.broadcast_to(np.eye(3), (len(tt1), 3, 3)))  # TEME -> TOD
    nutation = erfa.nutm80(tt1, tt2)  # MOD -> TOD
    precession = erfa.pmat76(tt1, tt2)  # J2000 -> MOD
    bias = erfa.bp00(tt1, tt2)[0]  # GCRS -> J2000
    return _transpose(bias) @ _transpose(precession) @ _transpose(nutation) @ r3


def teme_to_gcrf(r, v, epochs) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity in TEME rotated into the GCRF.

    The velocity is rotated like the position: the term ``omega x r`` of the frame's
    slow rotation is left out.  TEME turns relative to the GCRF by precession and
    nutation only, ``|omega| <= 1.1e-11 rad/s`` (70 "/yr, measured over 2020-2021 by
    differencing the matrices): ``omega x r`` is at most 0.08 mm/s at 7,200 km and
    0.5 mm/s at geostationary radius, against the ~1 m/s of the plan's manoeuvres.

    Parameters
    ----------
    r : array_like
        Positions in TEME, shape (m, 3) or (3,) [any length unit, kept].
    v : array_like
        Velocities in TEME, shape (m, 3) or (3,) [any velocity unit, kept].
    epochs : pandas.Timestamp, pandas.DatetimeIndex or array_like of Timestamps
        UTC dates of the states, m of them, or one for all.

    Returns
    -------
    r_gcrf, v_gcrf : numpy.ndarray
        Shape (m, 3), in the units of ``r`` and ``v``.

    References
    ----------
    Vallado et al. [2]_ Appendix C (``teme2eci``).
    """
    r, v = (np.atleast_2d(np.asarray(value, dtype=float)) for value in (r, v))
    matrix = teme_to_gcrf_matrix(epochs)
    return np.einsum("mij,mj->mi", matrix, r), np.einsum("mij,mj->mi", matrix, v)


def earth_pole_gcrf(epochs) -> np.ndarray:
    """Unit vector of the Earth's rotation axis (the J2 symmetry axis) in the GCRF.

    TEME's z-axis, the true pole of date of the IAU 1976/1980 models (third column of
    :func:`teme_to_gcrf_matrix`): the axis SGP4's zonal harmonics are symmetric about,
    so inclinations measured from it are SGP4's.  It lies about 31 mas (1.5e-7 rad)
    from the IAU 2006/2000A Celestial Intermediate Pole (``erfa.xy06``), and about
    0.11-0.12 deg from the GCRF z-axis in 2020-2021 (precession since J2000, ~20 "/yr).

    Parameters
    ----------
    epochs : pandas.Timestamp, pandas.DatetimeIndex or array_like of Timestamps
        UTC dates.

    Returns
    -------
    numpy.ndarray
        Shape (m, 3), unit vectors [-].

    References
    ----------
    Vallado [1]_ §3.7; IERS Conventions [3]_ §5.4.4 (the CIP).
    """
    pole = teme_to_gcrf_matrix(epochs)[:, :, 2]
    return pole / np.linalg.norm(pole, axis=-1, keepdims=True)


def equatorial_basis(pole) -> np.ndarray:
    """Right-handed basis of the equator of ``pole``, in the GCRF.

    Parameters
    ----------
    pole : array_like
        Rotation axis, shape (3,) or (m, 3) (normalised here) [-].

    Returns
    -------
    numpy.ndarray
        Shape (3, 3) (or (m, 3, 3)): rows ``x, y, z`` with ``z`` the unit pole, ``x``
        the GCRF x-axis projected on the equator plane and normalised, ``y = z x x``.
        ``basis @ r_gcrf`` gives the components in this frame, in which the inclination
        and the RAAN of an orbit are those from the true equator.  The RAAN is counted
        from the projected GCRF x-axis, not from the equinox of date: TEME's x-axis (the
        mean equinox of date) lies at -0.256 deg in this basis on 2020-01-01 and -0.282
        deg on 2022-01-01 (precession in right ascension, ~46 "/yr since J2000), so a
        RAAN here is SGP4's (TEME) RAAN minus 0.26-0.28 deg in 2020-2021.

    References
    ----------
    Vallado [1]_ §3.7 (the equator and equinox of date).
    """
    z = np.asarray(pole, dtype=float)
    z = z / np.linalg.norm(z, axis=-1, keepdims=True)
    x = np.zeros_like(z)
    x[..., 0] = 1.0
    x = x - z[..., :1] * z
    x /= np.linalg.norm(x, axis=-1, keepdims=True)
    y = np.cross(z, x)
    return np.stack([x, y, z], axis=-2)
