"""The vehicle's trajectory as a CCSDS Orbit Ephemeris Message, OEM version 2.0, KVN.

One segment per arc between impulses: consecutive segments share the impulse's epoch,
the state before the impulse ending one and the state after it beginning the next (a
reader never interpolates across a velocity jump).  Positions in km to 0.1 mm and
velocities in km/s to 1e-7 m/s (the standard's units), epochs ISO 8601 to the nanosecond
(pandas' resolution; the standard allows any number of digits, and a microsecond is 7 mm
along a LEO orbit), ``TIME_SYSTEM = UTC``, ``REF_FRAME = GCRF``, ``CENTER_NAME = EARTH``.

The keywords follow CCSDS 502.0-B-2 [1]_ §5 (OEM 2.0): header ``CCSDS_OEM_VERS``,
``CREATION_DATE``, ``ORIGINATOR`` (``COMMENT`` lines after the version line); in each
segment ``META_START``, ``OBJECT_NAME``, ``OBJECT_ID``, ``CENTER_NAME``, ``REF_FRAME``,
``TIME_SYSTEM``, ``START_TIME``, ``STOP_TIME`` (mandatory), ``INTERPOLATION``,
``INTERPOLATION_DEGREE`` (optional, written), ``META_STOP``, then the data lines
``epoch x y z x_dot y_dot z_dot``.  ``USEABLE_START_TIME``/``USEABLE_STOP_TIME`` are left
out: the whole segment is usable.  CCSDS 502.0-B-3 [2]_ (2023) defines OEM 3.0 with the
same mandatory keywords (adding optional header keywords, ``MESSAGE_ID`` among them); a
2.0 message is what most readers take.

References
----------
.. [1] CCSDS, *Orbit Data Messages*, Blue Book CCSDS 502.0-B-2, 2009, §5 (OEM).
.. [2] CCSDS, *Orbit Data Messages*, Blue Book CCSDS 502.0-B-3, 2023, §5 (OEM).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pandas as pd

from ..report.atomic import write_atomic

OEM_VERSION = "2.0"
OEM_DEGREE = 9
"""Lagrange interpolation degree written in the OEM (10 samples a window): see
:data:`OEM_STEP_S`."""
OEM_STEP_S = 240.0
"""Largest sample step of the OEM [s], with :data:`OEM_DEGREE` 9.

Measured (``python benchmarks/propagation.py``): the largest position error of Lagrange
interpolation between samples, against the propagation, on an 800 km circular orbit:

======  ==============  ==============  ==============  ==============
degree  120 s           180 s           240 s           300 s
======  ==============  ==============  ==============  ==============
5       0.15 / 0.68 m   1.7 / 7.6 m     9.3 / 42 m      35 / 154 m
7       0.001 / 0.012   0.023 / 0.26 m  0.22 / 2.2 m    1.3 / 9.7 m
9       2e-5 / 7e-4     0.001 / 0.036   0.015 / 0.55 m  0.12 / 4.3 m
11      6e-7 / 7e-5     6e-5 / 0.009    0.002 / 0.25 m  0.020 / 3.1 m
======  ==============  ==============  ==============  ==============

(metres; centred windows in the middle of a segment / one-sided ones in its first
interval).
Degree 9 every 240 s: 0.55 m at worst, 18 times under the 10 m goal, at 360 samples a
day (15 MB a year); at 400 km 1.6 m, on a 300 x 800 km transfer ellipse 5.4 m at a
segment's ends (0.2 m inside).  A segment needs ``degree + 1`` samples at this spacing
or closer for the bound to hold (:func:`sample_times`): 3 samples over 100 s, interpolated
at degree 2, are 63 m off."""


def sample_times(t0: float, t1: float, step: float = OEM_STEP_S,
                 degree: int = OEM_DEGREE) -> np.ndarray:  # fmt: skip
    """Uniform sample times of an arc for the OEM, both ends included.

    Parameters
    ----------
    t0, t1 : float
        The arc's start and end [s].
    step : float
        Largest spacing [s] (:data:`OEM_STEP_S`).
    degree : int
        Interpolation degree: at least ``degree + 1`` samples, so that a short arc keeps
        the error measured for :data:`OEM_STEP_S`.

    Returns
    -------
    ndarray
        Times [s], increasing (``[t0]`` alone when ``t1 <= t0``).
    """
    if not t1 > t0:
        return np.array([float(t0)])
    count = max(int(np.ceil((t1 - t0) / step)), int(degree))
    return np.linspace(float(t0), float(t1), count + 1)


def sample_epochs(t0, t1, step) -> pd.DatetimeIndex:
    """Epochs from ``t0`` to ``t1`` every ``step``, both ends included (UTC).

    Parameters
    ----------
    t0, t1 : datetime-like
        First and last epochs (naive ones are taken as UTC), ``t1 >= t0``.
    step : float or timedelta-like
        Spacing [s] (a number) or a timedelta; the last interval may be shorter.

    Returns
    -------
    pandas.DatetimeIndex
        Tz-aware UTC epochs.
    """
    t0, t1 = (_utc(pd.DatetimeIndex([t]))[0] for t in (t0, t1))
    step = pd.to_timedelta(step, unit="s") if np.isscalar(step) and not isinstance(
        step, str) else pd.to_timedelta(step)  # fmt: skip
    if step <= pd.Timedelta(0) or t1 < t0:
        raise ValueError("sample_epochs needs step > 0 and t1 >= t0")
    epochs = pd.date_range(t0, t1, freq=step)
    return epochs if epochs[-1] == t1 else epochs.append(pd.DatetimeIndex([t1]))


def _utc(epochs: pd.DatetimeIndex) -> pd.DatetimeIndex:
    epochs = pd.DatetimeIndex(epochs)
    return epochs.tz_localize("UTC") if epochs.tz is None else epochs.tz_convert("UTC")


def _iso(epochs: pd.DatetimeIndex) -> np.ndarray:
    """ISO 8601 strings to the nanosecond (pandas' resolution)."""
    naive = _utc(epochs).tz_convert(None)
    return np.datetime_as_string(naive.values.astype("datetime64[ns]"), unit="ns")


def _value(key: str, value) -> str:
    text = str(value)
    if not text or "\n" in text or "\r" in text:
        raise ValueError(f"OEM keyword {key}: {text!r} must be one non-empty line")
    return f"{key} = {text}"


def oem_text(
    segments: Sequence[tuple],
    *,
    object_name: str,
    object_id: str,
    center_name: str = "EARTH",
    ref_frame: str = "GCRF",
    time_system: str = "UTC",
    originator: str = "SDC_CVX",
    interpolation: str = "LAGRANGE",
    interpolation_degree: int = OEM_DEGREE,
    comments: Sequence[str] = (),
    creation_date=None,
) -> str:
    """The text of an OEM 2.0 (KVN) of ``segments`` (module docstring).

    Parameters
    ----------
    segments : sequence of (epochs, r, v)
        One per arc: ``epochs`` a pandas DatetimeIndex (UTC; naive ones are taken as
        UTC), strictly increasing; ``r`` [m] and ``v`` [m/s] arrays (m, 3).  A segment
        starts no earlier than the previous one stops.
    object_name, object_id : str
        ``OBJECT_NAME`` and ``OBJECT_ID`` (the standard recommends the international
        designator for the latter, ``YYYY-NNNP{PP}``, when there is one).
    center_name, ref_frame, time_system, originator : str
        The keywords of the same names.
    interpolation : str or None
        ``INTERPOLATION`` (None: neither it nor the degree is written).
    interpolation_degree : int
        ``INTERPOLATION_DEGREE``; a segment of fewer samples states ``samples - 1``.
    comments : sequence of str
        ``COMMENT`` lines of the header.
    creation_date : datetime-like, optional
        ``CREATION_DATE`` (default: now, UTC).

    Returns
    -------
    str
        The message, lines ending in ``\\n``.

    Raises
    ------
    ValueError
        No segment, a segment with no sample or mismatched shapes, epochs not increasing,
        segments out of order, a keyword value that is empty or spans lines.

    References
    ----------
    CCSDS 502.0-B-2 [1]_ §5.
    """
    if not segments:
        raise ValueError("an OEM needs at least one segment")
    created = pd.Timestamp.now(tz="UTC") if creation_date is None else creation_date
    lines = [_value("CCSDS_OEM_VERS", OEM_VERSION)]
    lines += [f"COMMENT {' '.join(str(c).split())}" for c in comments]
    lines += [_value("CREATION_DATE", _iso(pd.DatetimeIndex([created]))[0]),
              _value("ORIGINATOR", originator)]  # fmt: skip
    previous_stop = None
    for number, (epochs, r, v) in enumerate(segments, start=1):
        epochs = _utc(epochs)
        r = np.asarray(r, dtype=float) / 1e3
        v = np.asarray(v, dtype=float) / 1e3
        if len(epochs) == 0 or r.shape != (len(epochs), 3) or v.shape != r.shape:
            raise ValueError(f"OEM segment {number}: {len(epochs)} epochs, r {r.shape}, "
                             f"v {v.shape}: need (m, 3) arrays, m >= 1")  # fmt: skip
        if not epochs.is_monotonic_increasing or not epochs.is_unique:
            raise ValueError(f"OEM segment {number}: epochs not strictly increasing")
        if previous_stop is not None and epochs[0] < previous_stop:
            raise ValueError(f"OEM segment {number} starts before segment {number - 1} stops")
        previous_stop = epochs[-1]
        stamps = _iso(epochs)
        lines += ["", "META_START", _value("OBJECT_NAME", object_name),
                  _value("OBJECT_ID", object_id), _value("CENTER_NAME", center_name),
                  _value("REF_FRAME", ref_frame), _value("TIME_SYSTEM", time_system),
                  _value("START_TIME", stamps[0]), _value("STOP_TIME", stamps[-1])]  # fmt: skip
        if interpolation:
            degree = min(int(interpolation_degree), len(epochs) - 1)
            lines += [_value("INTERPOLATION", interpolation),
                      _value("INTERPOLATION_DEGREE", degree)]  # fmt: skip
        lines += ["META_STOP", ""]
        lines += [
            f"{stamp} {x:.7f} {y:.7f} {z:.7f} {vx:.10f} {vy:.10f} {vz:.10f}"
            for stamp, (x, y, z), (vx, vy, vz) in zip(stamps, r.tolist(), v.tolist(), strict=True)
        ]
    return "\n".join(lines) + "\n"


def write_oem(path, segments: Sequence[tuple], **keywords) -> None:
    """Write :func:`oem_text` of ``segments`` (and ``keywords``) to ``path``, atomically
    (:func:`sdc_cvx.report.atomic.write_atomic`)."""
    write_atomic(Path(path), oem_text(segments, **keywords))
