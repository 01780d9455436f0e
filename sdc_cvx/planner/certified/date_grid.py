"""Cheap plans from a grid of dates: the certified search's first incumbents.

The certified search (:mod:`~sdc_cvx.planner.certified`) proves faster the better the plan
it holds: every arc and cell above the plan leaves its networks.  Its own relaxation
finds the optimum eventually, but with a poor plan in hand the first relaxation MILPs
carry thousands of arcs (lg8 of the reference cases: 46 s for the first one against 2 s
once the optimum is held).  This module finds near-optimal plans before any MILP.

Every leg is priced exactly (``LegCosts.cost_at``) between
the dates of one grid over ``[0, T_max]``; a debris sequence then has a cheapest
schedule on the grid by a dynamic programme over the dates (a min-plus product per
leg).  A beam search grows sequences leg by leg, each carrying that programme's vector
(the cheapest cost of arriving at its last debris on each grid date), ranked by it plus
the cheapest grid *walk* of the legs left (another dynamic programme, backwards over
(debris, date)).  The schedules flown on the grid are real ones, so the sequences found
are plans; the certified search then optimises each over continuous dates
(:func:`~sdc_cvx.planner.fixed_path.solve_path`) and holds the best as an incumbent.
Nothing here is a bound: a plan from the grid prunes, it proves nothing.

Measured on the reference cases lg7, lg8, lg8b, rb08 and syn05 (a grid of 113 dates, a
beam of 1000): the optimal sequence is the grid's best in each, in 1-4 s.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013 (Eq. 10: a drift leg's dates fix its drift orbit).
.. [2] D. Izzo et al., "Automated asteroid selection for a 'grand tour' mission",
   IAC-07-C1.7.07, 2007 (beam search over sequences of targets).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ...physics.leg_bounds import LegCosts

GRID_POINTS = 1_200_000
"""Leg costs evaluated for the grid at most (about 2 s): the dates per debris are fewer
when the edges are many."""
MAX_DATES = 113
"""Grid dates at most (4 days apart over 450 days)."""
MIN_DATES = 48
"""Grid dates at least (15 days apart over two years); with more edges than this allows
(N above about 33), no grid: a coarser one found poor plans (GTOC9, n = 8: 440 m/s, the
optimum 342) at a cost of 20 s."""
BEAM_WIDTH = 1000
"""Partial sequences kept per leg (lg7 needs about 1000 to keep its optimum's prefix)."""


@dataclass(frozen=True)
class GridPlan:
    """A debris sequence and its cheapest schedule on the grid.

    Attributes
    ----------
    path : tuple of int
        Node positions, length L + 1.
    cost_mps : float
        Transfers and node costs of the grid schedule [m/s] (the continuous dates of
        :func:`~sdc_cvx.planner.fixed_path.solve_path` do at least as well).
    """

    path: tuple[int, ...]
    cost_mps: float


def grid_plans(
    legs: LegCosts,
    edge_from,
    edge_to,
    nodes,
    *,
    count: int = 4,
    width: int = BEAM_WIDTH,
    max_points: int = GRID_POINTS,
    deadline: float = np.inf,
) -> list[GridPlan]:
    """The ``count`` cheapest debris sequences a beam search finds on a grid of dates.

    Parameters
    ----------
    legs : LegCosts
        Cost tables of the edges ``edge_from[e] -> edge_to[e]``.
    edge_from, edge_to : ndarray of int
        The edges a plan may fly (node positions).
    nodes : CertifiedNodes
        The mission (legs, operations times and node costs, first, must_visit,
        T_max, T_min, inclination rule, J2).
    count : int
        Sequences returned at most.
    width : int
        Beam width.
    max_points : int
        Leg costs evaluated at most (sets the grid's dates, see :data:`GRID_POINTS`).
    deadline : float
        ``time.perf_counter()`` past which the grid is given up (no plans).

    Returns
    -------
    list of GridPlan
        Cheapest first; empty when no sequence flies on the grid, or when the edges are
        too many for a grid of :data:`MIN_DATES` dates within ``max_points``.
    """
    edge_from, edge_to = np.asarray(edge_from), np.asarray(edge_to)
    n, L = len(nodes.ops_days), nodes.legs
    if len(edge_from) * MIN_DATES * (MIN_DATES + 1) // 2 > max_points:
        return []
    dates = np.linspace(0.0, nodes.tmax_days, _date_count(len(edge_from), max_points))
    table = _leg_table(legs, np.arange(len(edge_from)), edge_from, dates, nodes, deadline)
    if table is None:
        return []
    origin, target = edge_from, edge_to
    ops, node_cost = np.asarray(nodes.ops_days), np.asarray(nodes.cost_mps)
    ends = np.where(dates[None, :] + ops[:, None] <= nodes.tmax_days, 0.0, np.inf)
    rest = _walks_left(table, origin, target, node_cost, ends, L, n)
    by_origin = {int(i): np.flatnonzero(origin == i) for i in np.unique(origin)}
    starts = np.arange(n) if nodes.first is None else np.array([nodes.first])
    starts = starts[np.isin(starts, origin)]
    paths = starts[:, None]
    vectors = np.full((len(starts), len(dates)), np.inf)
    vectors[:, 0] = node_cost[starts]
    required = np.zeros(n, dtype=bool)
    required[list(nodes.must_visit)] = True
    for k in range(L):
        paths, vectors, rank = _grow(paths, vectors, by_origin, table, target, node_cost,
                                     rest[L - 1 - k], required, L - 1 - k)  # fmt: skip
        keep = _best(rank, width)
        paths, vectors, rank = paths[keep], vectors[keep], rank[keep]
    final = np.min(vectors + ends[paths[:, -1]], axis=1) if len(paths) else np.empty(0)
    order = np.argsort(final, kind="stable")
    return [GridPlan(tuple(int(v) for v in paths[s]), float(final[s]))
            for s in order[:count] if np.isfinite(final[s])]  # fmt: skip


def _date_count(edges: int, max_points: int) -> int:
    """Grid dates such that the upper triangles of ``edges`` tables hold ``max_points``."""
    dates = int(np.sqrt(2.0 * max_points / max(edges, 1)))
    return int(np.clip(dates, MIN_DATES, MAX_DATES))


def _leg_table(legs: LegCosts, edges, origin, dates, nodes, deadline) -> np.ndarray | None:
    """``table[k, p, q]``: exact cost [m/s] of edge ``edges[k]`` leaving its origin ready at
    ``dates[p]`` plus its operations and arriving at ``dates[q]`` (``inf`` if no drift
    orbit does it); None past the deadline."""
    m = len(dates)
    p, q = np.triu_indices(m)
    table = np.full((len(edges), m, m), np.inf)
    ops = np.asarray(nodes.ops_days)
    for k, e in enumerate(edges):
        if time.perf_counter() > deadline:
            return None
        table[k, p, q] = legs.cost_at(np.full(len(p), e), dates[p] + ops[origin[k]], dates[q],
                                      rule=nodes.rule, j2=nodes.j2, t_min=nodes.tmin_days).cost
    return table


def _walks_left(table, origin, target, node_cost, ends, legs: int, n: int) -> list[np.ndarray]:
    """``rest[r][v, q]``: the cheapest grid walk of r legs from debris v reached on
    ``dates[q]`` (node costs of the debris reached included, ``rest[0]``: the end)."""
    rest = [ends]
    for _ in range(1, legs):
        ahead = rest[-1][target] + node_cost[target][:, None]  # (E, m) on arrival
        step = np.min(table + ahead[:, None, :], axis=2)  # (E, m) on leaving
        best = np.full((n, table.shape[1]), np.inf)
        np.minimum.at(best, origin, step)
        rest.append(best)
    return rest


def _grow(paths, vectors, by_origin, table, target, node_cost, rest, required, left: int):
    """Every one-leg extension of the beam: new paths, their vectors and their ranks."""
    new_paths, new_vectors = [], []
    last = paths[:, -1]
    for i, edges in by_origin.items():
        rows = np.flatnonzero(last == i)
        if not len(rows):
            continue
        for k in edges:
            j = target[k]
            fresh = rows[~(paths[rows] == j).any(axis=1)]
            if not len(fresh):
                continue
            reach = (
                np.concatenate(
                    [  # (states, m, m) temporaries of at most 256 states
                        np.min(vectors[part][:, :, None] + table[k][None], axis=1)
                        for part in np.array_split(fresh, -(-len(fresh) // 256))
                    ]
                )
                + node_cost[j]
            )
            new_paths.append(np.column_stack([paths[fresh], np.full(len(fresh), j)]))
            new_vectors.append(reach)
    if not new_paths:
        m = vectors.shape[1]
        return np.empty((0, paths.shape[1] + 1), int), np.empty((0, m)), np.empty(0)
    paths, vectors = np.concatenate(new_paths), np.concatenate(new_vectors)
    rank = np.min(vectors + rest[paths[:, -1]], axis=1)
    missing = required.sum() - required[paths].sum(axis=1)  # must_visit debris not yet in
    rank = np.where(missing <= left, rank, np.inf)
    return paths, vectors, rank


def _best(rank, width: int) -> np.ndarray:
    """The ``width`` best-ranked rows whose rank is finite."""
    order = np.argsort(rank, kind="stable")[:width]
    return order[np.isfinite(rank[order])]
