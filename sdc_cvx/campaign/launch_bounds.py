"""The campaign search's bounds as it reports and combines them.

:func:`shown_bound`: a proven lower bound as reported (at least 0); :func:`sizes_bound`:
the least sum of the launches' bounds over the mission sizes of their ranges that remove
what must go (:mod:`~sdc_cvx.campaign.min_dv`).
"""

from __future__ import annotations

import numpy as np


def shown_bound(lower: float) -> float | None:
    """The bound as reported [m/s]: at least 0 (every mission's ΔV is, so 0 is always a
    bound, and an early master LP, priced against artificial columns, may prove less);
    None while none is proven (``-inf``)."""
    return max(float(lower), 0.0) if np.isfinite(lower) else None


def sizes_bound(bounds: dict[int, dict[int, float]], required: int) -> float:
    """The least sum of the launches' bounds over mission sizes that remove at least
    ``required`` debris in all [m/s] (a dynamic programme over launches and debris).

    ``bounds[k][n]``: no mission of launch k with n debris costs less [m/s].  Every
    campaign flies one mission per launch, no debris twice, and removes the debris that
    must go: its sizes add up to at least their number, and each mission costs at least
    its launch's bound for its size.  With nothing required, the sum of each launch's
    least bound.
    """
    if not all(bound > -np.inf for by_size in bounds.values() for bound in by_size.values()):
        return -np.inf  # a size with no bound proven
    best = np.full(required + 1, np.inf)
    best[0] = 0.0
    reached = np.arange(required + 1)
    for by_size in bounds.values():
        step = np.full(required + 1, np.inf)
        for size, bound in by_size.items():
            np.minimum.at(step, np.minimum(reached + size, required), best + bound)
        best = step
    return float(best[required])
