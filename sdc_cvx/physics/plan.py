"""A plan evaluated with the true physics (numpy only).

:func:`evaluate_plan` is the single place where a fixed path (debris order, drift
orbits, earliest departure dates) is turned into dates, durations and costs with
the nonlinear model of Part III: the sequential driver uses it for the true ΔV and
duration of every iteration (Table 7), the re-optimisation for its objective and
constraint, and :class:`~sdc_cvx.solution.Solution` reports its legs.

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

from .eccentricity import leg_cost
from .leg_bounds import IMPULSIVE
from .orbits import SECONDS_PER_DAY
from .transfer import NodeOrbits


class PlanEvaluation(NamedTuple):
    """True dates, durations and costs of the legs of a plan (arrays of length n - 1).

    Attributes
    ----------
    departure_day, duration_days, arrival_day : ndarray
        Leg departure date, coast duration and arrival date [days after t0].
    dv_mps : ndarray
        Leg cost [m/s] (the eccentricity priced, where it is).
    end_day : float
        Arrival at the last debris plus its operations [days]: the mission duration.
    """

    departure_day: np.ndarray
    duration_days: np.ndarray
    arrival_day: np.ndarray
    dv_mps: np.ndarray
    end_day: float
    eccentricity_dv_mps: np.ndarray | None = None
    """The part of ``dv_mps`` that prices each leg's eccentricity [m/s] (None: circular
    legs, :mod:`~sdc_cvx.physics.eccentricity`)."""


def evaluate_plan(orbits: NodeOrbits, path, a_drift, inc_drift, *, deorbit_days=0.0, j2,
                  model=None, laps=0, eccentricity=None) -> PlanEvaluation:  # fmt: skip
    """Chain the legs of ``path`` through the true model (Eq. 10-13, or another transfer model).

    The vehicle is at ``path[0]`` at t = 0; each leg leaves after the operations at
    its debris (``deorbit_days``, the paper's "as soon as possible", Part III-H),
    coasts on its drift orbit until the RAANs meet, and arrives.

    Parameters
    ----------
    orbits : NodeOrbits
        All debris.
    path : sequence of int
        Debris positions in visiting order (length n).
    a_drift, inc_drift : array_like
        Drift radius [m] and inclination [rad] of each leg (length n - 1).
    deorbit_days : float or array_like
        T_deorb [days]: one value, or one per debris of ``orbits`` (0 for an
        injection orbit).
    j2 : float
    model : TransferModel, optional
        The leg physics (:mod:`~sdc_cvx.physics.models`); default the impulsive drift leg.
    laps : int or array_like of int
        Relative laps of each leg's coast beyond the first that closes the RAAN gap.
    eccentricity : Eccentricities, optional
        Every debris' mean eccentricity vector: each leg's cost then prices it
        (:func:`~sdc_cvx.physics.eccentricity.leg_cost`).

    Returns
    -------
    PlanEvaluation
    """
    model = IMPULSIVE if model is None else model
    path = np.asarray(path, dtype=int)
    legs = len(path) - 1
    laps = np.broadcast_to(np.asarray(laps, dtype=int), (legs,))
    a_drift = np.broadcast_to(np.asarray(a_drift, dtype=float), (legs,))
    inc_drift = np.broadcast_to(np.asarray(inc_drift, dtype=float), (legs,))
    departure, duration, arrival = np.empty(legs), np.empty(legs), np.empty(legs)
    ops = np.broadcast_to(np.asarray(deorbit_days, dtype=float), np.shape(orbits.a))
    ready = float(ops[path[0]])  # operations at the first debris, reached at t = 0
    for k in range(legs):
        origin, target = orbits.take([path[k]]), orbits.take([path[k + 1]])
        departure[k] = ready
        seconds = model.leg_seconds(origin, target, a_drift[k], inc_drift[k],
                                    departure[k] * SECONDS_PER_DAY, laps=laps[k], j2=j2)
        duration[k] = seconds[0] / SECONDS_PER_DAY
        arrival[k] = departure[k] + duration[k]
        ready = arrival[k] + float(ops[path[k + 1]])
    origins, targets = orbits.take(path[:-1]), orbits.take(path[1:])
    dv = model.leg_dv(origins.a, origins.inc, targets.a, targets.inc, a_drift, inc_drift)
    if eccentricity is None:
        return PlanEvaluation(departure, duration, arrival, dv, float(ready))
    priced = leg_cost(eccentricity.take(path[:-1]), eccentricity.take(path[1:]), dv, origins.a,
                      a_drift, targets.a, inc_drift, departure * SECONDS_PER_DAY,
                      arrival * SECONDS_PER_DAY, j2=j2)  # fmt: skip
    return PlanEvaluation(departure, duration, arrival, priced, float(ready), priced - dv)
