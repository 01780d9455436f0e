"""A plan that flies without the cost tables, for a time limit too short to build them.

The certified search starts by tabulating every edge's cost over the drift band (about
15 s for the 230 880 edges of 481 TLE fragments).  When the tables are projected to take
most of the time limit, :func:`greedy_plan` first finds a plan without them: chains of
Part IV-B's pre-optimised leg (the cheapest drift transfer of each edge from the date the
vehicle is there, within a share of the time left), started from the cheapest first
legs and extended to the cheapest next debris; each chain's schedule is then optimised
in the true model on its own edges (:func:`~sdc_cvx.planner.fixed_path.solve_path`), so
the plan flies and ends by T_max.  The tables then go on: if they finish, the plan is
the search's first incumbent; if the limit stops them, :func:`greedy_result` is the
answer, ``feasible`` with the bound every plan has (nothing more is proven).

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013 (Part IV-B, the pre-optimised transfer of each edge).
"""

from __future__ import annotations

import time

import numpy as np

from ...physics.leg_bounds import LegCosts
from ...physics.orbits import SECONDS_PER_DAY
from ..fixed_path import PathProblem, PathSchedule, solve_path
from .results import CertifiedNodes, CertifiedResult

STARTS = 8
"""Chains grown, one from each of the cheapest first legs."""
FIRST_SHARE = 0.4
"""Share of the time left the first legs may take: they leave the debris in an order
spread over the catalog and stop there (low thrust, every pair of 481 debris: 28 s)."""
CHUNK = 4_000
"""Edges pre-optimised at once (the deadline is read between chunks)."""


def greedy_plan(orbits, nodes: CertifiedNodes, a_low: float, a_high: float, *,
                deadline: float) -> tuple[tuple[int, ...], PathSchedule] | None:  # fmt: skip
    """The cheapest of a few greedy chains of pre-optimised legs, scheduled exactly.

    Parameters
    ----------
    orbits : NodeOrbits
        Every node's orbit.
    nodes : CertifiedNodes
        The mission; its ``must_visit`` debris are not sought (None is returned when
        there are some).
    a_low, a_high : float
        Drift radius bounds [m].
    deadline : float
        ``time.perf_counter()`` past which no more work starts.

    Returns
    -------
    (path, schedule) or None
        Node positions and their schedule (transfers only); None when no chain flies
        or the time ran out first.
    """
    if nodes.must_visit:
        return None
    n = len(nodes.ops_days)
    allowed = np.ones(n, dtype=bool)
    allowed[list(nodes.excluded)] = False
    starts = np.asarray([nodes.first] if nodes.first is not None else np.flatnonzero(allowed))
    starts = starts[np.argsort((np.arange(len(starts)) * 0.6180339887) % 1.0)]  # spread
    ii, jj = np.meshgrid(starts, np.flatnonzero(allowed), indexing="ij")
    ii, jj = ii[ii != jj], jj[ii != jj]
    if nodes.first is not None:
        allowed[nodes.first] = False  # nothing flies back to the start
    budget = _leg_budget(nodes, float(np.max(nodes.ops_days[ii], initial=0.0)), nodes.legs)
    soon = time.perf_counter() + FIRST_SHARE * (deadline - time.perf_counter())
    first = _cheapest_legs(orbits, nodes, ii, jj, nodes.ops_days[ii], budget, a_low, a_high,
                           deadline, enough=soon)  # fmt: skip
    if first is None:
        return None
    best = None
    for k in np.argsort(first[0])[:STARTS]:
        if not np.isfinite(first[0][k]) or time.perf_counter() >= deadline:
            break
        path = _grow(orbits, nodes, [int(ii[k]), int(jj[k])], float(first[1][k]), allowed,
                     a_low, a_high, deadline)  # fmt: skip
        if path is None:
            continue
        schedule = _schedule(orbits, nodes, path, a_low, a_high, deadline)
        if schedule is not None and (best is None or schedule.upper_mps < best[1].upper_mps):
            best = (tuple(path), schedule)
    return best


def find_greedy(search, orbits, a_low: float, a_high: float) -> None:
    """``search.greedy``: a plan that flies without the cost tables, said on the search's
    log (the tables will take most of the time; ``search`` is the certified search)."""
    search.greedy = greedy_plan(orbits, search.nodes, a_low, a_high, deadline=search.deadline)
    if search.greedy is not None:
        path, schedule = search.greedy
        cost = schedule.upper_mps + search.node_cost(path)
        search.say(f"  greedy plan {search.label(path)}: {cost:.2f} m/s; the tables go on")


def _leg_budget(nodes: CertifiedNodes, depart_days: float, legs_left: int) -> float:
    """An even share [days] of the time left after ``depart_days`` for each leg still to
    fly, less the longest operations at each debris still to reach."""
    left = nodes.tmax_days - depart_days - legs_left * float(np.max(nodes.ops_days))
    return max(left, 0.0) / max(legs_left, 1)


def _cheapest_legs(orbits, nodes, i, j, depart_days, budget_days, a_low, a_high, deadline,
                   enough=np.inf):  # fmt: skip
    """Pre-optimised legs i -> j leaving at ``depart_days``: (ΔV [m/s], arrival [days]),
    ``inf`` where none lasts at most ``budget_days`` (or past ``enough``: the legs not
    reached by then are left out); None when the time ran out."""
    dv, arrive = np.full(len(i), np.inf), np.full(len(i), np.inf)
    for start in range(0, len(i), CHUNK):
        if start and time.perf_counter() >= enough:
            break
        if time.perf_counter() >= deadline:
            return None
        rows = slice(start, start + CHUNK)
        choice = nodes.model.cheapest_transfer(
            orbits.take(i[rows]), orbits.take(j[rows]),
            np.asarray(depart_days, float)[rows] * SECONDS_PER_DAY,
            budget_days * SECONDS_PER_DAY, a_low, a_high, inclination=nodes.rule,
            j2=nodes.j2)  # fmt: skip
        dv[rows] = choice.dv
        arrive[rows] = np.asarray(depart_days, float)[rows] + choice.duration / SECONDS_PER_DAY
    return dv, arrive


def _grow(orbits, nodes, path, arrived_days, allowed, a_low, a_high, deadline):
    """Extend ``path`` to ``nodes.legs`` legs, each to the cheapest debris not yet on it."""
    while len(path) <= nodes.legs:
        here = path[-1]
        free = allowed.copy()
        free[path] = False
        targets = np.flatnonzero(free)
        if not len(targets):
            return None
        depart = arrived_days + nodes.ops_days[here]
        budget = _leg_budget(nodes, depart, nodes.legs + 1 - len(path))
        found = _cheapest_legs(orbits, nodes, np.full(len(targets), here), targets,
                               np.full(len(targets), depart), budget, a_low, a_high,
                               deadline)  # fmt: skip
        if found is None or not np.isfinite(found[0]).any():
            return None
        k = int(np.argmin(found[0]))
        path.append(int(targets[k]))
        arrived_days = float(found[1][k])
    return path


def _schedule(orbits, nodes, path, a_low, a_high, deadline) -> PathSchedule | None:
    """The path's best schedule in the true model (its own edges' cost tables only)."""
    origin, target = np.asarray(path[:-1]), np.asarray(path[1:])
    legs = LegCosts.build(orbits.take(origin), orbits.take(target), a_low, a_high,
                          model=nodes.model,
                          eccentricity=nodes.edge_eccentricity(origin, target))  # fmt: skip
    problem = PathProblem(legs, tuple(range(len(origin))),
                          tuple(float(nodes.ops_days[k]) for k in path), nodes.tmax_days,
                          nodes.tmin_days, nodes.rule, nodes.j2)  # fmt: skip
    remaining = deadline - time.perf_counter()
    if remaining <= 0:
        return None
    schedule = solve_path(problem, time_limit_s=remaining)
    return schedule if schedule.feasible else None


def greedy_result(nodes: CertifiedNodes, plan, clock: float, why: str) -> CertifiedResult:
    """The search's result when its tables could not be built in time: the greedy
    ``plan`` (path, schedule) found while they were, ``feasible``.

    Its bound is :meth:`CertifiedNodes.least_cost`; ``clock``
    is when the search started (``time.perf_counter()``), ``why`` what stopped the tables.
    """
    seconds = time.perf_counter() - clock
    lower = nodes.least_cost()
    path, schedule = plan
    upper = schedule.upper_mps + float(nodes.cost_mps[list(path)].sum())
    note = (f"{why}: a greedy plan (chains of pre-optimised legs, each scheduled exactly), "
            "with no useful bound; raise the time limit for a certified answer")
    return CertifiedResult(path, schedule, upper, lower, "feasible", [], 0, 0, seconds, (note,),
                           complete=False, trace=((seconds, lower, upper),))  # fmt: skip
