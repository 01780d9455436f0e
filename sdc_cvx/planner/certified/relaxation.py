"""The time-expanded relaxation of Eq. 22, declared in CVXPY (the certified layer's MILP).

Nodes are (debris, date cell) pairs; an arc (i, I) -> (j, J) is the leg i -> j leaving
in cell I and ready to leave j in cell J, priced at the lower bound of its cost over
that box of dates (:func:`~sdc_cvx.leg_bounds.leg_box_bound`) plus the operations cost
at j.  Each debris also has a *start* node, the single date the vehicle is ready to
leave it when the mission starts there.  The program chooses L arcs:

- one leaves a start node (its operations cost is in the arc's price);
- flow: a cell is left at most as often as it is entered;
- each debris at most once (exactly once for ``must_include``), and at most one arc
  between two debris;
- no cycle beside the path (possible among cells whose dates overlap): Miller-Tucker-
  Zemlin order rows, a position per debris that rises along every chosen edge.  Measured
  against subtour rows added one by one when a cycle appears (each costing a solve):
  GTOC9 (N = 123) 24 s against 32-60 s, rb08 26 s against 35 s, 481 TLE fragments
  certified where one row at a time never ended.  A layered network (one copy of each
  arc per leg) forbids cycles too but was L times larger with the same LP bound;
- no-good rows removing paths already settled by their own certificate.

Every schedule of every path is a feasible point at no greater cost, so the optimum
is a lower bound on the mission's optimum.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
.. [2] N. Boland, M. Hewitt, M. Savelsbergh and D. M. Vu, "Solving the traveling
   salesman problem with time windows through dynamically generated time-expanded
   networks", CPAIOR 2017 / Operations Research 2018.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.sparse as sp

from ...milp.types import SolveReport, SolverOptions


@dataclass(frozen=True)
class Arcs:
    """Arcs of the time-expanded network.

    Attributes
    ----------
    tail, head : ndarray of int
        Network node (a debris' cell, or its start) each arc leaves and enters.
    debris_from, debris_to : ndarray of int
        The arc's debris.
    cost : ndarray
        Lower bound of the leg over the arc's box plus the operations cost at the head
        [m/s].
    """

    tail: np.ndarray
    head: np.ndarray
    debris_from: np.ndarray
    debris_to: np.ndarray
    cost: np.ndarray

    def __len__(self):
        return len(self.cost)

    def take(self, mask) -> Arcs:
        return Arcs(*(np.asarray(v)[mask] for v in (self.tail, self.head, self.debris_from,
                                                     self.debris_to, self.cost)))  # fmt: skip


@dataclass(frozen=True)
class RelaxationResult:
    """Outcome of one solve of the relaxation.

    Attributes
    ----------
    report : SolveReport
    lower_mps : float or None
        Proven lower bound [m/s]: ``inf`` if the relaxation is infeasible (so is the
        mission), None if the backend proved nothing.
    path : tuple of int
        Debris of the relaxation's path (empty without a solution).
    arcs : ndarray of int
        Arc of each leg of that path.
    """

    report: SolveReport
    lower_mps: float | None
    path: tuple[int, ...]
    arcs: np.ndarray


def solve_relaxation(arcs: Arcs, *, n_nodes: int, n_debris: int, legs: int,
                     solver: SolverOptions, must_visit=(), cuts=(),
                     solver_gap: float | None = None, start=None) -> RelaxationResult:  # fmt: skip
    """Declare and solve the relaxation; its optimum bounds every plan from below.

    Variable ``x[a]`` is 1 when arc ``a`` is on the path.  Arcs leaving a start node
    (node ids below ``n_debris``) are first legs, their price includes the start's
    operations cost; exactly one is chosen.  A cell is left at most as often as it is
    entered, ``legs`` arcs are chosen, each debris is visited at most once, and at most
    one arc joins any two debris (no back-and-forth).  Order rows (a position ``u_i``
    per debris, ``u_j >= u_i + 1`` on a chosen edge i -> j) leave no cycle beside the
    path, so the chosen arcs are the path.

    Parameters
    ----------
    arcs : Arcs
    n_nodes, n_debris : int
        Network nodes (starts, then cells), debris.
    legs : int
        Legs on a path (L).
    solver : SolverOptions
        Backend and settings; its fallback chain is used.
    must_visit : sequence of int
    cuts : sequence of tuple of int
        Debris paths excluded (their own certificates bound them).
    solver_gap : float, optional
        Relative MIP gap the backend may stop at (the bound used is its dual bound).
    start : sequence of int, optional
        Arcs forming a feasible path, given to the backend as its first incumbent
        (measured: with a good one, HiGHS proves the bound in a fraction of the time it
        otherwise spends looking for a solution).

    Returns
    -------
    RelaxationResult
    """
    import cvxpy as cp  # here: a run whose relaxations the labels solve never loads CVXPY

    from ...milp.solve import chain_of, solve_with_fallback

    m = len(arcs)
    x = cp.Variable(m, boolean=True)
    allowed = cp.Parameter(m, nonneg=True, value=np.ones(m))  # 0: arc barred (warm start)
    rows = np.arange(m)
    first = arcs.tail < n_debris
    constraints = [x <= allowed, cp.sum(x[np.flatnonzero(first)]) == 1, cp.sum(x) == legs]
    enter = sp.csr_matrix((np.ones(m), (arcs.head, rows)), shape=(n_nodes, m))
    leave = sp.csr_matrix((np.ones(m), (arcs.tail, rows)), shape=(n_nodes, m))
    cells = np.arange(n_debris, n_nodes)
    used = np.asarray(leave[cells, :].sum(axis=1)).ravel() > 0
    if used.any():
        constraints.append(leave[cells[used], :] @ x <= enter[cells[used], :] @ x)
    visit = sp.csr_matrix(
        (np.ones(m + int(first.sum())),
         (np.r_[arcs.debris_to, arcs.debris_from[first]], np.r_[rows, rows[first]])),
        shape=(n_debris, m))  # fmt: skip
    visited = np.flatnonzero(np.asarray(visit.sum(axis=1)).ravel() > 0)
    constraints.append(visit[visited, :] @ x <= 1)
    if len(must_visit):
        constraints.append(visit[list(must_visit), :] @ x == 1)
    # at most one arc between two debris: a path never goes back; this also cuts the
    # walks that go back and forth, which the LP would otherwise mix at weight 1/2
    pair = np.minimum(arcs.debris_from, arcs.debris_to) * n_debris + np.maximum(
        arcs.debris_from, arcs.debris_to
    )
    pairs, pair_of_arc, pair_count = np.unique(pair, return_inverse=True, return_counts=True)
    by_pair = sp.csr_matrix((np.ones(m), (pair_of_arc, rows)), shape=(len(pairs), m))
    shared = np.flatnonzero(pair_count > 1)
    if len(shared):
        constraints.append(by_pair[shared, :] @ x <= 1)
    for path in cuts:
        members = np.zeros(m, dtype=bool)
        for a, b in zip(path[:-1], path[1:], strict=True):
            members |= (arcs.debris_from == a) & (arcs.debris_to == b)
        if members.any():
            constraints.append(cp.sum(x[np.flatnonzero(members)]) <= legs - 1)
    # order rows: a position per debris that rises along every chosen edge (no cycle)
    edge_id = arcs.debris_from * n_debris + arcs.debris_to
    edges, edge_of_arc = np.unique(edge_id, return_inverse=True)
    on_edge = sp.csr_matrix((np.ones(m), (edge_of_arc, rows)), shape=(len(edges), m))
    position = cp.Variable(n_debris, nonneg=True)
    i, j = edges // n_debris, edges % n_debris
    big = legs + 1
    constraints += [position <= legs,
                    position[j] >= position[i] + 1 - big * (1 - on_edge @ x)]  # fmt: skip
    problem = cp.Problem(cp.Minimize(arcs.cost @ x), constraints)
    if solver_gap is not None:
        solver = replace(solver, mip_gap=max(solver.mip_gap or 0.0, solver_gap))
    if solver.presolve is None:
        solver = replace(solver, presolve=False)  # see SolverOptions.presolve
    warm = False
    if start is not None and len(start):
        # solve once restricted to the start path (trivial), so that the backend's
        # cache holds it as the incumbent of the real solve (CVXPY warm-starts HiGHS
        # from its previous result, not from variable values)
        only = np.zeros(m)
        only[np.asarray(start, dtype=int)] = 1.0
        allowed.value = only
        warm = solve_with_fallback(problem, chain_of(solver)).status.has_solution
        allowed.value = np.ones(m)
    report = solve_with_fallback(problem, chain_of(solver), warm_start=warm)
    if report.status.value == "infeasible":
        return RelaxationResult(report, np.inf, (), np.empty(0, dtype=int))
    if not report.status.has_solution:  # a limit before any solution: the bound may stand
        bound = report.dual_bound if report.status.value == "no_solution" else None
        bound = float(bound) if bound is not None and np.isfinite(bound) else None
        return RelaxationResult(report, bound, (), np.empty(0, dtype=int))
    lower = report.dual_bound
    if lower is None or not np.isfinite(lower):
        optimal = report.status.value == "optimal"
        gap = solver.mip_gap or 0.0
        lower = report.objective - gap * abs(report.objective) if optimal else None
    chosen = np.flatnonzero(x.value > 0.5)
    path, on_path = _trace(arcs, chosen, n_debris)
    return RelaxationResult(report, lower, path, on_path)


def _trace(arcs: Arcs, chosen, n_debris: int):
    """The path the chosen arcs trace from their start node (the order rows leave no other)."""
    leaving = {int(arcs.tail[a]): int(a) for a in chosen}
    first = [int(a) for a in chosen if arcs.tail[a] < n_debris]
    on_path = []
    node = int(arcs.tail[first[0]]) if first else -1
    while node in leaving and len(on_path) < len(chosen):
        a = leaving.pop(node)
        on_path.append(a)
        node = int(arcs.head[a])
    path = ()
    if on_path:
        path = (int(arcs.debris_from[on_path[0]]),) + tuple(int(arcs.debris_to[a])
                                                             for a in on_path)  # fmt: skip
    return path, np.array(on_path, dtype=int)
