"""Nonlinear re-optimisation of a fixed path in the true model (paper Part IV-D).

With the debris order fixed, the drift orbits are optimised with the true cost and
duration (Eq. 10-13) so that the mission ends by T_max.

The true end date is not smooth: when a leg arrives just after the RAAN gap of the
next leg has closed, that gap wraps to a full turn and the mission jumps by years.
A gradient method stepping across such a cliff fails, so the main method is a
Lagrangian forward pass: for a price ``lam`` on time [m/s per day], each leg in turn,
departing when the previous one arrives, minimises ``dV + lam * T`` over its feasible
drift radii, on either side of its asymptote and with its allowed inclinations (a
robust bounded 1-D search, :func:`~sdc_cvx.physics.transfer.minimize_on_interval`).  The end
date falls as ``lam`` rises; bisection finds the cheapest plan that ends by T_max.
SLSQP then polishes the best plan with sides and inclinations fixed, kept only if it
is feasible and cheaper.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.optimize import minimize

from ...physics.leg_bounds import IMPULSIVE
from ...physics.orbits import SECONDS_PER_DAY, circular_a_for_raan_rate
from ...physics.plan import PlanEvaluation, evaluate_plan
from ...physics.transfer import NodeOrbits, drift_inclination, drift_rate, minimize_on_interval
from .linearize import KM

ASYMPTOTE_MARGIN = 1e-6  # relative distance kept from the asymptote
BISECTION_STEPS = 25


class Reoptimized(NamedTuple):
    """Outcome of the re-optimisation (arrays per leg)."""

    a_drift: np.ndarray
    inc_drift: np.ndarray
    side: np.ndarray
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


def forward_pass(orbits: NodeOrbits, path, price, *, tmax_days, deorbit_days, min_days,
                 a_low, a_high, inclination, j2, model=IMPULSIVE):  # fmt: skip
    """Legs chosen one after the other, each minimising ``dV + price * T`` [m/s, m/s/day].

    Each leg leaves when the previous one has arrived (plus the operations) and
    considers both sides of its asymptote with the allowed inclinations at once, in the
    transfer model ``model``.

    Returns
    -------
    a_drift, inc_drift, side : ndarray
        Per leg; ``nan`` radius when a leg cannot reach its target before T_max.
    """
    legs = len(path) - 1
    a_out, inc_out, side_out = np.full(legs, np.nan), np.zeros(legs), np.zeros(legs)
    ops = np.broadcast_to(np.asarray(deorbit_days, dtype=float), np.shape(orbits.a))
    ready = float(ops[path[0]])
    for k in range(legs):
        origin, target = orbits.take([path[k]]), orbits.take([path[k + 1]])
        remaining = tmax_days - float(ops[path[k + 1]]) - ready
        if remaining <= 0:
            break
        sides = np.array([1.0, -1.0] if inclination == "table3" else [1.0, 1.0, -1.0, -1.0])
        incs = (
            drift_inclination(origin.inc, target.inc, sides)
            if inclination == "table3"
            else np.concatenate([origin.inc, target.inc, origin.inc, target.inc])
        )
        t_depart = ready * SECONDS_PER_DAY
        lo, hi = model.duration_window(
            origin, target, sides, incs, t_depart, min_days * SECONDS_PER_DAY,
            remaining * SECONDS_PER_DAY, a_low, a_high, j2=j2,
        )  # fmt: skip

        def cost(a, origin=origin, target=target, incs=incs, t_depart=t_depart):
            dv = model.leg_dv(origin.a, origin.inc, target.a, target.inc, a, incs[:, None])
            seconds = model.leg_seconds(origin, target, a, incs[:, None], t_depart, j2=j2)
            return dv + price * seconds / SECONDS_PER_DAY

        kinks = np.broadcast_to(np.array([origin.a[0], target.a[0]]), (len(sides), 2))
        a_best, f_best = minimize_on_interval(cost, lo, hi, kinks)
        pick = int(np.argmin(f_best))
        if not np.isfinite(f_best[pick]):
            break
        a_out[k], inc_out[k], side_out[k] = a_best[pick], incs[pick], sides[pick]
        seconds = model.leg_seconds(origin, target, a_out[k], inc_out[k], t_depart, j2=j2)[0]
        ready += seconds / SECONDS_PER_DAY + float(ops[path[k + 1]])
    return a_out, inc_out, side_out


def reoptimize(orbits: NodeOrbits, path, side, inc_drift, a_start, *, tmax_days, deorbit_days,
               a_low, a_high, j2, inclination="table3", min_days=0.0,
               bisection_steps=BISECTION_STEPS, polish=True,
               model=IMPULSIVE) -> Reoptimized:  # fmt: skip
    """Minimise the true total ΔV of a fixed path subject to the true end date <= T_max.

    Parameters
    ----------
    orbits : NodeOrbits
    path : sequence of int
        Debris positions in visiting order.
    side, inc_drift, a_start : array_like
        Side (+1/-1), drift inclination [rad] and radius [m] of each leg in the last
        linearised solution (the starting point, kept if nothing better is found).
    tmax_days : float
    deorbit_days : float or array_like
        T_deorb [days], one value or one per debris.
    a_low, a_high : float
        Drift radius bounds [m].
    inclination : {"table3", "free"}
        Drift inclinations the forward pass may use.
    min_days : float
        Shortest allowed transfer T_min [days].
    bisection_steps : int
        Bisection steps on the price of time.
    polish : bool
        Polish the best plan with SLSQP (fewer steps and no polish: a quicker estimate).
    model : TransferModel
        The leg physics (:mod:`~sdc_cvx.physics.models`).

    Returns
    -------
    Reoptimized
        The cheapest plan found that ends by T_max (or the start if none does).
    """
    kwargs = dict(tmax_days=tmax_days, deorbit_days=deorbit_days, min_days=min_days,
                  a_low=a_low, a_high=a_high, j2=j2, model=model)  # fmt: skip

    def plan(a, inc):
        return evaluate_plan(orbits, path, a, inc, deorbit_days=deorbit_days, j2=j2, model=model)

    def feasible(evaluation):
        in_time = np.isfinite(evaluation.end_day) and evaluation.end_day <= tmax_days + 1e-6
        return in_time and bool(np.all(evaluation.duration_days >= min_days - 1e-6))

    side, inc_drift = np.asarray(side, dtype=float), np.asarray(inc_drift, dtype=float)
    start = np.asarray(a_start, dtype=float)
    candidates = [(start, inc_drift, side, "linear solution")]

    # Lagrangian forward pass, bisection on the price of time
    low_price, high_price = 0.0, 1.0
    plans = {}

    def attempt(price):
        a, inc, sides = forward_pass(orbits, path, price, inclination=inclination, **kwargs)
        ok = np.all(np.isfinite(a)) and feasible(plan(a, inc))
        plans[price] = (a, inc, sides, ok)
        return ok

    if not attempt(low_price):
        while not attempt(high_price) and high_price < 1e6:
            low_price, high_price = high_price, 10 * high_price
        if plans[high_price][3]:
            for _ in range(bisection_steps):
                middle = 0.5 * (low_price + high_price)
                if attempt(middle):
                    high_price = middle
                else:
                    low_price = middle
    for price, (a, inc, sides, ok) in plans.items():
        if ok:
            candidates.append((a, inc, sides, f"forward pass at {price:.4g} m/s per day"))

    best = min(
        (c for c in candidates if feasible(plan(c[0], c[1]))),
        key=lambda c: plan(c[0], c[1]).dv_mps.sum(),
        default=candidates[0],
    )
    polished = polish and _polish(orbits, path, best, plan, feasible, tmax_days, a_low, a_high, j2)
    if polished:
        best = polished
    a, inc, sides, message = best
    final, initial = plan(a, inc), plan(start, inc_drift)
    return Reoptimized(
        a, inc, sides, final, float(initial.dv_mps.sum() - final.dv_mps.sum()), message
    )


def _polish(orbits, path, candidate, plan, feasible, tmax_days, a_low, a_high, j2):
    """SLSQP on the radii with sides and inclinations fixed; None unless better and feasible."""
    a, inc, sides, message = candidate
    lo, hi = side_bounds(orbits, path, sides, inc, a_low, a_high, j2=j2)
    x0 = np.clip(a, lo, hi) / KM

    def total(x):
        return float(plan(x * KM, inc).dv_mps.sum())

    def slack(x):
        end = plan(x * KM, inc).end_day
        return tmax_days - end if np.isfinite(end) else -1e6

    if not feasible(plan(x0 * KM, inc)):
        return None
    result = minimize(
        total, x0, method="SLSQP", bounds=list(zip(lo / KM, hi / KM, strict=True)),
        constraints=[{"type": "ineq", "fun": slack}], options={"maxiter": 200, "ftol": 1e-9},
    )  # fmt: skip
    x = np.clip(result.x, lo / KM, hi / KM)
    if np.all(np.isfinite(x)) and feasible(plan(x * KM, inc)) and total(x) < total(x0) - 1e-6:
        return x * KM, inc, sides, f"{message}, polished by SLSQP"
    return None
