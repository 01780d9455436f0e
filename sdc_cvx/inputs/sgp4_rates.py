"""RAAN rates fitted to SGP4: each debris' node as SGP4 flies it over the mission window.

The planner's first-order J2 rate (Eq. 7, :func:`sdc_cvx.physics.orbits.raan_rate`) is
not the rate at which the debris precess as SGP4 propagates them: SGP4's secular node
rate adds J2^2 and J4 terms, and its drag term moves the node quadratically with time
(a few 1e-3 deg/day at 600-900 km, a few tenths of a percent; over a 100-day leg a few
tenths of a degree of RAAN, days of the leg's duration).  :func:`sgp4_raan` measures the
rate on SGP4 itself (issue 26, item 4, "close the loop"):

1. the element sets of :func:`sdc_cvx.inputs.sgp4_sets.satrecs` (``phase_needed=False``:
   the node does not depend on the phase), propagated in TEME, whose z axis is the pole
   SGP4's zonal terms are about;
2. two windows of one nodal period ``2 pi / (dM/dt + domega/dt)`` (SGP4's own secular
   rates of the element set), one starting at the catalog's start, one ending ``days``
   later, each sampled at :data:`SAMPLES` times uniform over the period, so that the
   short-period terms (harmonics of the argument of latitude) average out;
3. the mean RAAN of a window: the RAAN of the mean direction of the angular momentum
   ``h = r x v`` over its samples (``atan2(h_x, -h_y)``), which is the RAAN at the
   window's mean time (the secular drift is linear within one period);
4. the rate: the difference of the two mean RAANs (unwrapped by the number of turns
   the first-order J2 rate makes between them) over the time between the windows'
   middles; the RAAN at the start: the first window's, carried back to t = 0.

A secant of the node over the window: the drag's quadratic term makes it the mean rate
of the window (and the slope of a least-squares line through the node over it), which
is what the planner's linear model ``Omega(t) = Omega(0) + rate t`` needs.

:meth:`sdc_cvx.inputs.catalog.Catalog.with_sgp4_rates` puts these in a catalog
(``raan_rates = "sgp4"``).

References
----------
.. [1] D. A. Vallado, P. Crawford, R. Hujsak and T. S. Kelso, "Revisiting Spacetrack
   Report #3", AIAA 2006-6753, 2006 (SGP4 in TEME, its secular rates and drag terms).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from sgp4.api import SGP4_ERRORS

from ..errors import CatalogError
from ..physics.orbits import raan_rate
from .sgp4_sets import NOMINAL_EPOCH, CatalogRows, satrecs

__all__ = ["SAMPLES", "sgp4_raan"]

SAMPLES = 32
"""States per window of one nodal period (harmonics of the argument of latitude up to
the 31st average out; SGP4's short-period node terms are of order 2)."""
_MINUTES_PER_DAY = 1440.0


def sgp4_raan(catalog: CatalogRows, days: float) -> tuple[np.ndarray, np.ndarray]:
    """Each debris' RAAN at the start and its RAAN rate, fitted to SGP4 (module docstring).

    Parameters
    ----------
    catalog : Catalog
        The debris (any format; CSV and GTOC9 rows need no phase).  A catalog without
        epochs nor start flies from :data:`~sdc_cvx.inputs.sgp4_sets.NOMINAL_EPOCH`.
    days : float
        The window [days after ``catalog.start``]: the mission's ``tmax_days`` (a
        campaign's last launch day plus its ``tmax_days``).  More than two orbital
        periods.

    Returns
    -------
    raan : numpy.ndarray
        Shape (N,): mean RAAN at the start (t = 0) of the fitted line [rad], in [0, 2 pi).
    rate : numpy.ndarray
        Shape (N,): RAAN rate [rad/s].

    Raises
    ------
    CatalogError
        sgp4 rejects a row's elements, or cannot propagate rows over the window (decayed,
        ...): every such debris named, with the date and SGP4's reason, and what to do.
    ValueError
        ``days`` is not a finite number longer than two orbital periods of every row.
    """
    sets = satrecs(catalog, phase_needed=False)
    start = NOMINAL_EPOCH if catalog.start is None else catalog.start
    days = float(days)
    span_min = days * _MINUTES_PER_DAY
    ids = [str(ident) for ident in catalog.frame["id"]]
    n = len(ids)
    raan = np.empty((n, 2))
    middle = np.empty((n, 2))  # [min after the start]
    grid = np.arange(SAMPLES) / SAMPLES
    problems, failed = [], []
    for k, satrec in enumerate(sets.satrecs):
        period = 2.0 * np.pi / (satrec.mdot + satrec.argpdot)  # nodal period [min]
        if not np.isfinite(span_min) or span_min <= 2.0 * period:
            raise ValueError(f"the window of the SGP4 rates must be longer than two orbital "
                             f"periods ({2.0 * period / _MINUTES_PER_DAY:.3f} days for debris "
                             f"{ids[k]}), got {days!r} days")  # fmt: skip
        minutes = np.concatenate([grid * period, span_min - period + grid * period])
        since_epoch = (start - sets.epochs[k]).value / 60e9 + minutes
        fraction = satrec.jdsatepochF + since_epoch / _MINUTES_PER_DAY
        errors, r, v = satrec.sgp4_array(np.full(minutes.shape, satrec.jdsatepoch), fraction)
        if np.any(errors):
            first = int(np.flatnonzero(errors)[0])
            code = int(errors[first])
            when = start + pd.Timedelta(minutes=float(minutes[first]))
            failed.append(ids[k])
            problems.append(
                f"debris {ids[k]}: SGP4 cannot propagate its element set (epoch "
                f"{sets.epochs[k].isoformat()}) to {when.isoformat()}: error {code} "
                f"({SGP4_ERRORS.get(code, 'unknown')})"
            )
            continue
        h = np.cross(r, v)
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        mean_h = h.reshape(2, SAMPLES, 3).mean(axis=1)
        raan[k] = np.arctan2(mean_h[:, 0], -mean_h[:, 1])
        middle[k] = minutes.reshape(2, SAMPLES).mean(axis=1)
    if problems:
        shown = ", ".join(f'"{ident}"' for ident in failed)
        raise CatalogError.collect(catalog.source, problems, (
            f"{len(failed)} debris cannot be flown by SGP4 over the {days:g} days of the "
            f"fitted RAAN rates: leave them out ([selection] exclude_ids = [{shown}], "
            '--exclude-ids) or plan with the J2 rates (raan_rates = "j2")'))  # fmt: skip
    elapsed_s = (middle[:, 1] - middle[:, 0]) * 60.0
    first_order = raan_rate(catalog.a_m, catalog.e, catalog.inc_rad)  # [rad/s]
    turned = first_order * elapsed_s  # the whole turns between the windows, from Eq. 7
    change = turned + np.angle(np.exp(1j * (raan[:, 1] - raan[:, 0] - turned)))
    rate = change / elapsed_s
    at_start = np.mod(raan[:, 0] - rate * middle[:, 0] * 60.0, 2.0 * np.pi)
    return at_start, rate
