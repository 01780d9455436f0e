"""The integer programs a max-value campaign solves over a pool of columns (missions
already priced): the most value and, of that value, the least ΔV; the least ΔV less a
price on the value; and the front of value against ΔV (the ε-constraint method), each
point with the bound of the same program over every path at its lower bound.

The pool comes from :mod:`~sdc_cvx.campaign.value`'s enumeration; each program is the
master's set packing (:func:`~sdc_cvx.campaign.master.solve_ip`).

References
----------
.. [1] Y. Y. Haimes, L. S. Lasdon, D. A. Wismer, "On a Bicriterion Formulation of the
   Problems of Integrated System Identification and System Optimization", IEEE
   Transactions on Systems, Man, and Cybernetics 1(3), 296-297, 1971 (the ε-constraint
   method).
"""

from __future__ import annotations

import numpy as np

from ..milp.types import SolverOptions
from .master import solve_ip

VALUE_TOL = 1e-9
"""Relative tolerance on a campaign's value when it is held while the ΔV is minimised."""
TIE_MPS = 1e-7
"""ΔV each debris adds when the least ΔV of the most value is chosen [m/s]: of equal ΔV, the
fewest debris (a launch unused, not sent to a debris worth nothing at 0 m/s)."""


def _worth(columns: list, values: np.ndarray) -> np.ndarray:
    """The value each column (mission) removes."""
    return np.array([values[list(c.debris)].sum() for c in columns])


def best_value(columns: list, values: np.ndarray, launches: int, debris: int, *,
               solver: SolverOptions, costs=None):  # fmt: skip
    """The most valuable campaign of ``columns``, then its least ΔV: (plan, value) or
    (None, -inf) when no campaign can be made of them.  ``costs`` (default the columns'
    ΔV) are what the second stage minimises."""
    worth = _worth(columns, values)
    most = solve_ip(columns, launches, debris, solver=solver, costs=-worth)
    if most is None:
        return None, -np.inf
    value = -most.value
    hold = value - VALUE_TOL * max(1.0, abs(value))
    if costs is None:  # of equal ΔV, the fewest debris (TIE_MPS)
        costs = np.array([c.dv_mps + TIE_MPS * len(c.debris) for c in columns])
    plan = solve_ip(columns, launches, debris, solver=solver, costs=costs,
                    at_least=(worth, hold))  # fmt: skip
    return plan, value


def _priced(columns: list, values: np.ndarray, price: float, launches: int, debris: int,
            solver: SolverOptions, costs=None):  # fmt: skip
    """The campaign of ``columns`` least in ``Σ cost − price · Σ value`` (``costs``:
    default the columns' ΔV): (plan, its value) or (None, -inf).  The plan's ``value``
    is the priced objective [m/s]."""
    worth = _worth(columns, values)
    costs = np.array([c.dv_mps for c in columns]) if costs is None else np.asarray(costs)
    plan = solve_ip(columns, launches, debris, solver=solver, costs=costs - price * worth)
    return (None, -np.inf) if plan is None else (plan, float(worth[list(plan.chosen)].sum()))


def pareto_front(columns: list, undecided: list, values: np.ndarray, launches: int,
                 debris: int, points: int, *, solver: SolverOptions, proven: bool = True,
                 proven_from: float = -np.inf) -> tuple[dict, ...]:  # fmt: skip
    """Campaigns of value against ΔV, each the cheapest of at least a target value.

    The targets run evenly from the value of the cheapest campaign to the most value
    (``points`` of them; a campaign met twice is kept once).  Each point's ``dv_bound_mps``
    is the same program over every path at its bound: no campaign of at least that value
    costs less (the ε-constraint method: every point is on the front, within the bound);
    None for every point unless ``proven`` (the enumeration of the missions within budget
    was complete: else a mission it missed might make a campaign cheaper), and None for a
    target below ``proven_from`` (the narrowed enumeration holds every mission of a
    campaign worth at least that value, not the missions of a cheaper, less valuable one).
    """
    everything = columns + undecided
    worth = _worth(columns, values)
    worth_all = _worth(everything, values)
    lows = np.array([c.lower_mps for c in everything])
    cheapest = solve_ip(columns, launches, debris, solver=solver)
    _, most = best_value(columns, values, launches, debris, solver=solver)
    if cheapest is None:
        return ()
    least = float(worth[list(cheapest.chosen)].sum())
    rows, seen = [], set()
    for target in np.linspace(least, most, max(points, 2)):
        hold = target - VALUE_TOL * max(1.0, abs(target))
        plan = solve_ip(columns, launches, debris, solver=solver, at_least=(worth, hold))
        covered = proven and target >= proven_from - VALUE_TOL * max(1.0, abs(proven_from))
        floor = None if not covered else solve_ip(everything, launches, debris, solver=solver,
                                                  costs=lows, at_least=(worth_all, hold))
        if plan is None or plan.chosen in seen:
            continue
        seen.add(plan.chosen)
        rows.append(dict(target_value=float(target), value=float(worth[list(plan.chosen)].sum()),
                         dv_mps=plan.value, dv_bound_mps=None if floor is None else floor.value,
                         missions=[columns[c].nodes for c in plan.chosen]))  # fmt: skip
    return tuple(rows)
