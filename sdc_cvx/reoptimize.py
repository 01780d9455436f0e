"""Nonlinear re-optimisation of a fixed path in the true model (paper Part IV-D).

With the debris order fixed, the drift radii are optimised with the true cost and
duration (Eq. 10-13) so that the mission ends by T_max.  Sides and inclinations
stay as the sequential linearisation left them; each radius stays strictly on its
side of the duration asymptote and inside the altitude band.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.optimize import minimize

from .orbits import circular_a_for_raan_rate
from .solution import PlanEvaluation, evaluate_plan
from .transfer import NodeOrbits, drift_rate

KM = 1e3
ASYMPTOTE_MARGIN = 1e-6  # relative distance kept from the asymptote


class Reoptimized(NamedTuple):
    """Outcome of the re-optimisation."""

    a_drift: np.ndarray
    evaluation: PlanEvaluation
    improved_by_mps: float
    message: str


def side_bounds(orbits: NodeOrbits, path, side, inc_drift, a_low, a_high, *, j2):
    """Radius bounds [m] of each leg: its side of the asymptote, within the altitude band."""
    targets = orbits.take(np.asarray(path)[1:])
    asymptote = circular_a_for_raan_rate(targets.rate, inc_drift, j2=j2)
    low_is_on_side = side * (drift_rate(a_low, inc_drift, j2=j2) - targets.rate) > 0
    asymptote = np.where(np.isnan(asymptote), np.where(low_is_on_side, a_high, a_low), asymptote)
    lo = np.where(low_is_on_side, a_low, np.maximum(a_low, asymptote * (1 + ASYMPTOTE_MARGIN)))
    hi = np.where(low_is_on_side, np.minimum(a_high, asymptote * (1 - ASYMPTOTE_MARGIN)), a_high)
    return lo, hi


def reoptimize(orbits: NodeOrbits, path, side, inc_drift, a_start, *, tmax_days, deorbit_days,
               a_low, a_high, j2, not_before=None) -> Reoptimized:  # fmt: skip
    """Minimise the true total ΔV of a fixed path subject to the true end date <= T_max.

    Parameters
    ----------
    orbits : NodeOrbits
    path : sequence of int
        Debris positions in visiting order.
    side, inc_drift : array_like
        Side (+1/-1) and drift inclination [rad] of each leg.
    a_start : array_like
        Starting drift radii [m] (the last linearised solution).
    tmax_days, deorbit_days : float
    a_low, a_high : float
        Drift radius bounds [m].
    not_before : array_like, optional
        Planned earliest departures [days] (waits chosen by the linear model).

    Returns
    -------
    Reoptimized
        The better of the start and the optimiser's point among those that meet T_max.
    """
    lo, hi = side_bounds(
        orbits, path, np.asarray(side), np.asarray(inc_drift), a_low, a_high, j2=j2
    )
    start = np.clip(np.asarray(a_start, dtype=float), lo, hi)

    def plan(x_km):
        return evaluate_plan(orbits, path, x_km * KM, inc_drift, deorbit_days=deorbit_days,
                             not_before=not_before, j2=j2)  # fmt: skip

    def total_dv(x_km):
        return float(plan(x_km).dv_mps.sum())

    def slack_days(x_km):
        end = plan(x_km).end_day
        return tmax_days - end if np.isfinite(end) else -1e6

    x0 = start / KM
    result = minimize(
        total_dv, x0, method="SLSQP", bounds=list(zip(lo / KM, hi / KM, strict=True)),
        constraints=[{"type": "ineq", "fun": slack_days}],
        options={"maxiter": 200, "ftol": 1e-9},
    )  # fmt: skip
    candidates = [(x0, "start")]
    if np.all(np.isfinite(result.x)):
        candidates.append((np.clip(result.x, lo / KM, hi / KM), f"SLSQP: {result.message}"))
    feasible = [(total_dv(x), x, why) for x, why in candidates if slack_days(x) >= -1e-6]
    if not feasible:  # neither meets T_max: report the start as is
        return Reoptimized(start, plan(x0), 0.0, "no point meets T_max; kept the linear solution")
    best_dv, best_x, why = min(feasible, key=lambda item: item[0])
    return Reoptimized(best_x * KM, plan(best_x), total_dv(x0) - best_dv, why)
