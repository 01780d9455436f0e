"""The scan of each edge's transfer cost over the drift band for its possible minimisers.

A leg's cost against the drift radius (either transfer model) is piecewise smooth: its
minimum over any interval of radii is at an end, at a kink (the two debris radii) or at
an interior local minimum.  :func:`scanned_minimisers` finds those points for every edge
once (a grid of :data:`GRID_POINTS` radii, each local minimum refined by golden section),
and :class:`~sdc_cvx.physics.leg_bounds.LegCosts` minimises over intervals with them.

The scan depends on the edges' radii and inclinations, the band, mu and the model, not on
any date: a process keeps its last :data:`TABLES_KEPT` scans, so that a campaign, which
prices every launch again each round over the same debris, scans them once.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013 (Eq. 11-13, the cost against the drift radius).
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable

import numpy as np

from .transfer import NodeOrbits, minimize_on_interval

GRID_POINTS = 513
"""Radii per edge and inclination scanned for the interior local minima of the cost."""
MAX_MINIMA = 4
"""Interior local minima kept per edge and inclination (the cost has at most one per piece)."""


TABLES_KEPT = 8
"""Scans of :meth:`LegCosts.build` a process keeps (each a few MB at most): a campaign
prices each launch every round with the same debris radii and inclinations (GTOC9: 0.9 s
of a 3.5 s pricing), whatever its RAANs and prices."""
_TABLES: dict = {}


def _table_key(origin: NodeOrbits, target: NodeOrbits, a_low, a_high, mu, model) -> tuple:
    """What the scan of possible minimisers depends on: the ends' radii and inclinations,
    the band, mu and the transfer model (not the RAANs or rates: no date enters a cost)."""
    digest = hashlib.blake2b(digest_size=16)
    for values in (origin.a, origin.inc, target.a, target.inc):
        digest.update(np.ascontiguousarray(values, dtype=float).tobytes())
    return (digest.hexdigest(), float(a_low), float(a_high), float(mu), model)


def _possible_minimisers(origin: NodeOrbits, target: NodeOrbits, inc, a_low, a_high, mu, model):
    """Kinks and interior local minima of one inclination's cost over the band, (M, K)."""
    grid = np.linspace(a_low, a_high, GRID_POINTS)

    def cost(a):
        return model.leg_dv(origin.a[:, None], origin.inc[:, None], target.a[:, None],
                            target.inc[:, None], a, inc[:, None], mu=mu)  # fmt: skip

    values = cost(np.broadcast_to(grid, (len(inc), GRID_POINTS)))
    local = (values[:, 1:-1] < values[:, :-2]) & (values[:, 1:-1] <= values[:, 2:])
    out = np.full((len(inc), 2 + MAX_MINIMA), np.nan)
    kinks = np.stack([origin.a, target.a], axis=1)
    out[:, :2] = np.where((kinks >= a_low) & (kinks <= a_high), kinks, np.nan)
    step = grid[1] - grid[0]
    rows, cols = np.nonzero(local)
    rank = np.zeros(len(rows), dtype=int)
    if len(rows):
        first_of_row = np.r_[True, rows[1:] != rows[:-1]]
        run = np.cumsum(first_of_row) - 1
        rank = np.arange(len(rows)) - np.flatnonzero(first_of_row)[run]
    keep = rank < MAX_MINIMA
    rows, cols, rank = rows[keep], cols[keep], rank[keep]
    if len(rows):
        centre = grid[cols + 1]
        lo, hi = centre - step, centre + step
        sub = NodeOrbits(*(np.asarray(f)[rows] for f in origin))
        sub_t = NodeOrbits(*(np.asarray(f)[rows] for f in target))
        sub_inc = inc[rows]

        def sub_cost(a):
            return model.leg_dv(sub.a[:, None], sub.inc[:, None], sub_t.a[:, None],
                                sub_t.inc[:, None], a, sub_inc[:, None], mu=mu)  # fmt: skip

        a_min, _ = minimize_on_interval(sub_cost, lo, hi, n_grid=9, n_golden=40)
        out[rows, 2 + rank] = a_min
    return out


def scanned_minimisers(origin: NodeOrbits, target: NodeOrbits, a_low: float, a_high: float,
                       mu: float, model, *, chunk: int = 2048,
                       on_chunk: Callable[[int, int], None] | None = None):  # fmt: skip
    """Radii where each edge's cost may have a local minimum inside the band [m].

    Parameters
    ----------
    origin, target : NodeOrbits
        The edges' ends, shape (E,).
    a_low, a_high : float
        Drift radius bounds [m].
    mu : float
        Gravitational parameter [m^3/s^2].
    model : TransferModel
        Its ``leg_dv`` is scanned.
    chunk : int
        Edges scanned at once.
    on_chunk : callable, optional
        ``on_chunk(done, total)`` after each chunk (once, at the end, for a kept scan);
        it may raise to stop the scan.

    Returns
    -------
    ndarray
        Shape (E, 2, 2 + MAX_MINIMA), read-only: per edge and drift inclination (0: the
        origin's, 1: the target's), the two kinks then the interior minima (``nan``
        padding).
    """
    count = len(origin.a)
    key = _table_key(origin, target, a_low, a_high, mu, model)
    candidates = _TABLES.pop(key, None)
    if candidates is not None:  # scanned before in this process
        if on_chunk is not None:
            on_chunk(count, count)
    else:
        candidates = np.full((count, 2, 2 + MAX_MINIMA), np.nan)
        for start in range(0, count, chunk):
            rows = slice(start, min(count, start + chunk))
            o, t = origin.take(rows), target.take(rows)
            for c, inc in enumerate((o.inc, t.inc)):
                candidates[rows, c] = _possible_minimisers(o, t, inc, a_low, a_high, mu, model)
            if on_chunk is not None:
                on_chunk(rows.stop, count)
        candidates.setflags(write=False)  # shared by every table built from it
    _TABLES[key] = candidates  # the most recent last; the oldest go past TABLES_KEPT
    while len(_TABLES) > TABLES_KEPT:
        _TABLES.pop(next(iter(_TABLES)))
    return candidates
