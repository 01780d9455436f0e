"""The physics of the independent replay (issue 46, "How we will know"), none of it sdc_cvx's.

Everything a flown folder is checked against is computed here from the files and public
definitions, never by importing ``sdc_cvx``: a mistake in the package's physics, frames or
ephemerides then shows as a difference instead of cancelling out.

- a CCSDS OEM (KVN) reader: header, frame, one segment per arc;
- two-body + J2 about a given pole, ``U = mu/r - mu J2 R^2 / (2 r^3) (3 z^2/r^2 - 1)``,
  integrated by scipy's DOP853 at ``rtol = 1e-12``;
- the Earth's pole of date in the GCRS and TEME -> GCRS by skyfield (IAU 2000A nutation,
  IAU 2006 precession: another implementation than the package's IAU 1976/1980 one);
- SGP4 by the ``sgp4`` library on TLE lines read here;
- GTOC9's ephemeris as its equations page defines it: osculating elements advanced by the
  mean motion ``n = sqrt(mu/a^3)`` and the secular J2 rates
  ``dOmega/dt = -3/2 J2 (r_eq/p)^2 n cos i``, ``domega/dt = 3/4 J2 (r_eq/p)^2 n (5 cos^2 i - 1)``
  (``p = a (1 - e^2)``; a, e, i fixed), then converted as Keplerian elements; the epochs in
  MJD2000 (day 0 = 2000-01-01T00:00); the frame is GTOC9's, J2 about its z axis.

Constants: GTOC9's (its constants page), ``mu = 398600.4418e9 m^3/s^2``,
``r_eq = 6378137 m``, ``J2 = 1.08262668e-3``.  Units: m, m/s, s, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

MU = 398600.4418e9  # m^3/s^2
R_EQ = 6378137.0  # m
J2 = 1.08262668e-3
RTOL, ATOL = 1e-12, 1e-7
"""DOP853's tolerances (relative; absolute in m and m/s)."""
MJD2000 = pd.Timestamp("2000-01-01T00:00:00Z")


# -- files ---------------------------------------------------------------------------------
@dataclass
class Oem:
    """An OEM's comments, frame and segments: ``times`` [s] after ``epoch0`` and
    ``states`` (m, 6) [m, m/s] per segment."""

    epoch0: pd.Timestamp
    frame: str
    comments: list[str]
    times: list[np.ndarray]
    states: list[np.ndarray]


def read_oem(path: Path) -> Oem:
    """Read a KVN OEM (km, km/s) into :class:`Oem` (SI units)."""
    frames, comments, stamps, rows = set(), [], [], []
    in_data = False
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "COMMENT":
            comments.append(line[8:].strip())
        elif words[0] == "META_START":
            in_data = False
            stamps.append([])
            rows.append([])
        elif words[0] == "META_STOP":
            in_data = True
        elif not in_data:
            if words[0] == "REF_FRAME":
                frames.add(words[-1])
        elif len(words) >= 7:
            stamps[-1].append(words[0])
            rows[-1].append([float(w) for w in words[1:7]])
    if len(frames) != 1:
        raise ValueError(f"{path}: REF_FRAME {sorted(frames)}, expected one frame")
    epochs = [utc(s) for s in stamps]
    epoch0 = epochs[0][0]
    times = [(e - epoch0).total_seconds().to_numpy() for e in epochs]
    states = [np.array(r) * 1e3 for r in rows]
    return Oem(epoch0, frames.pop(), comments, times, states)


def utc(stamps) -> pd.DatetimeIndex:
    """ISO stamps (naive ones read as UTC) as a UTC DatetimeIndex."""
    index = pd.DatetimeIndex(pd.to_datetime(list(stamps), utc=True))
    return index


# -- two-body + J2 -------------------------------------------------------------------------
def j2_rhs(pole):
    """``d(r, v)/dt`` under two-body + J2 about the unit vector ``pole``.

    ``grad U = -mu r / r^3 - (3/2) mu J2 R^2 / r^5 [(1 - 5 z^2/r^2) r + 2 z pole]``,
    ``z = r . pole``: with pole = (0, 0, 1) it is GTOC9's equations of motion.
    """
    px, py, pz = (float(c) for c in np.asarray(pole, dtype=float) / np.linalg.norm(pole))
    k = 1.5 * MU * J2 * R_EQ**2

    def rhs(t, y):
        x, yy, z, vx, vy, vz = y
        r2 = x * x + yy * yy + z * z
        r = math.sqrt(r2)
        zp = x * px + yy * py + z * pz
        c = MU / (r2 * r)
        d = k / (r2 * r2 * r)
        f = c + d * (1.0 - 5.0 * zp * zp / r2)
        g = 2.0 * d * zp
        return [vx, vy, vz, -f * x - g * px, -f * yy - g * py, -f * z - g * pz]

    return rhs


def moving_pole_rhs(poles_at):
    """``d(r, v)/dt`` under two-body + J2 about ``poles_at(t)``, a pole moving with time."""
    k = 1.5 * MU * J2 * R_EQ**2

    def rhs(t, y):
        px, py, pz = poles_at(t)
        x, yy, z, vx, vy, vz = y
        r2 = x * x + yy * yy + z * z
        r = math.sqrt(r2)
        zp = x * px + yy * py + z * pz
        d = k / (r2 * r2 * r)
        f = MU / (r2 * r) + d * (1.0 - 5.0 * zp * zp / r2)
        g = 2.0 * d * zp
        return [vx, vy, vz, -f * x - g * px, -f * yy - g * py, -f * z - g * pz]

    return rhs


def integrate(y0, t0: float, t1: float, rhs, t_eval=None):
    """Integrate ``y0`` from ``t0`` to ``t1`` [s] under ``rhs`` (:func:`j2_rhs`); (state at
    t1, states (m, 6) at ``t_eval`` or None)."""
    y0 = np.asarray(y0, dtype=float)
    if t1 <= t0:
        return y0.copy(), None if t_eval is None else np.tile(y0, (len(t_eval), 1))
    arc = solve_ivp(rhs, (t0, t1), y0, method="DOP853", rtol=RTOL, atol=ATOL,
                    dense_output=t_eval is not None)  # fmt: skip
    if not arc.success:
        raise RuntimeError(f"DOP853 failed from {t0} s to {t1} s: {arc.message}")
    at = None if t_eval is None else arc.sol(np.clip(np.asarray(t_eval, float), t0, t1)).T
    return arc.y[:, -1].copy(), at


# -- frames: skyfield ----------------------------------------------------------------------
def _times(epochs: pd.DatetimeIndex):
    from skyfield.api import load

    ts = load.timescale(builtin=True)
    e = pd.DatetimeIndex(epochs)
    seconds = e.second + e.microsecond * 1e-6 + e.nanosecond * 1e-9
    return ts.utc(e.year.to_numpy(), e.month.to_numpy(), e.day.to_numpy(), e.hour.to_numpy(),
                  e.minute.to_numpy(), np.asarray(seconds, dtype=float))  # fmt: skip


def teme_to_gcrs(epochs: pd.DatetimeIndex) -> np.ndarray:
    """(m, 3, 3) rotations TEME -> GCRS at ``epochs`` (skyfield's, transposed)."""
    from skyfield.sgp4lib import TEME

    m = TEME.rotation_at(_times(epochs))  # GCRS -> TEME, (3, 3, m)
    return np.moveaxis(m, -1, 0).transpose(0, 2, 1)


def pole_of_date(epochs: pd.DatetimeIndex) -> np.ndarray:
    """(m, 3) the Earth's true pole of date (TEME's z axis) in the GCRS."""
    return teme_to_gcrs(epochs)[:, :, 2]


# -- debris: SGP4 on TLE lines read here ---------------------------------------------------
def tle_lines(path: Path) -> dict[str, tuple[str, str]]:
    """Catalog number -> (line 1, line 2) of a TLE file (the latest epoch of a number)."""
    found: dict[str, tuple[float, str, str]] = {}
    lines = [x.rstrip() for x in Path(path).read_text(encoding="utf-8").splitlines()]
    for one, two in zip(lines[:-1], lines[1:], strict=True):
        if one.startswith("1 ") and two.startswith("2 ") and one[2:7] == two[2:7]:
            ident = one[2:7].strip()
            epoch = float(one[18:32])
            year = int(epoch // 1000)
            key = (2000 + year if year < 57 else 1900 + year) * 1000 + epoch % 1000
            if ident not in found or key > found[ident][0]:
                found[ident] = (key, one, two)
    return {k: (v[1], v[2]) for k, v in found.items()}


def sgp4_gcrs(lines: tuple[str, str], epochs: pd.DatetimeIndex):
    """SGP4 of a TLE at ``epochs``, TEME -> GCRS: (r, v) (m, 3) [m, m/s]."""
    from sgp4.api import Satrec, jday

    satrec = Satrec.twoline2rv(*lines)
    e = pd.DatetimeIndex(epochs)
    r, v = np.empty((len(e), 3)), np.empty((len(e), 3))
    for k, when in enumerate(e):
        seconds = when.second + when.microsecond * 1e-6 + when.nanosecond * 1e-9
        jd, fraction = jday(when.year, when.month, when.day, when.hour, when.minute, seconds)
        error, r_teme, v_teme = satrec.sgp4(jd, fraction)
        if error:
            raise RuntimeError(f"SGP4 error {error} for {lines[0][2:7].strip()} at {when}")
        r[k], v[k] = np.array(r_teme) * 1e3, np.array(v_teme) * 1e3
    rot = teme_to_gcrs(e)
    return np.einsum("mij,mj->mi", rot, r), np.einsum("mij,mj->mi", rot, v)


# -- debris: GTOC9's ephemeris -------------------------------------------------------------
def gtoc9_rows(path: Path) -> dict[str, np.ndarray]:
    """GTOC9 debris id -> (t0 [MJD2000], a, e, i, Omega, omega, M) of ``debris_data.txt``
    (or GTOC9's ``debris.csv``, comma separated with a header line)."""
    rows = {}
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        words = line.replace(",", " ").split()
        if len(words) < 8:
            continue
        try:
            numbers = np.array([float(w) for w in words[:8]])
        except ValueError:  # a header line
            continue
        rows[str(int(numbers[0]))] = numbers[1:]
    return rows


def kepler_state(a, e, i, raan, argp, mean_anomaly):
    """Position and velocity [m, m/s] of Keplerian elements (``MU``)."""
    m = math.fmod(mean_anomaly, 2.0 * math.pi)
    big_e = m if e < 0.8 else math.pi
    for _ in range(50):  # Newton on Kepler's equation
        step = (big_e - e * math.sin(big_e) - m) / (1.0 - e * math.cos(big_e))
        big_e -= step
        if abs(step) < 1e-15:
            break
    cos_e, sin_e = math.cos(big_e), math.sin(big_e)
    root = math.sqrt(1.0 - e * e)
    r_p = np.array([a * (cos_e - e), a * root * sin_e, 0.0])  # perifocal
    r = a * (1.0 - e * cos_e)
    v_p = math.sqrt(MU * a) / r * np.array([-sin_e, root * cos_e, 0.0])
    co, so = math.cos(raan), math.sin(raan)
    cw, sw = math.cos(argp), math.sin(argp)
    ci, si = math.cos(i), math.sin(i)
    rot = np.array([[co * cw - so * sw * ci, -co * sw - so * cw * ci, so * si],
                    [so * cw + co * sw * ci, -so * sw + co * cw * ci, -co * si],
                    [sw * si, cw * si, ci]])  # fmt: skip
    return rot @ r_p, rot @ v_p


def gtoc9_state(row: np.ndarray, epochs: pd.DatetimeIndex):
    """GTOC9's debris ``row`` (:func:`gtoc9_rows`) at ``epochs``: (r, v) (m, 3)."""
    t0, a, e, i, raan0, argp0, m0 = row
    n = math.sqrt(MU / a**3)
    p = a * (1.0 - e * e)
    k = J2 * (R_EQ / p) ** 2 * n
    raan_rate = -1.5 * k * math.cos(i)
    argp_rate = 0.75 * k * (5.0 * math.cos(i) ** 2 - 1.0)
    dt = (pd.DatetimeIndex(epochs) - (MJD2000 + pd.to_timedelta(t0, unit="D"))).total_seconds()
    states = [kepler_state(a, e, i, raan0 + raan_rate * s, argp0 + argp_rate * s, m0 + n * s)
              for s in np.asarray(dt, dtype=float)]  # fmt: skip
    return np.array([s[0] for s in states]), np.array([s[1] for s in states])
