"""The certified search: the mission's optimum bracketed by a lower bound and the best plan.

The loop (dynamic discretisation discovery, Boland et al. 2018, over the drift
transfer model of Part III):

1. every ordered pair of candidate debris is an edge (no heuristic filter: an edge
   leaves only when a bound proves it cannot be on a plan better than the incumbent);
2. each debris' dates [0, T_max] are split into cells; the time-expanded relaxation
   (:mod:`~sdc_cvx.relaxation`) priced by exact box bounds is a MILP whose optimum is a
   lower bound of the mission;
3. the relaxation's path is optimised globally as a fixed path
   (:func:`~sdc_cvx.fixed_path.solve_path`): a plan that flies, i.e. an upper bound, and
   a certified lower bound of that path alone, after which a no-good row removes it
   from the relaxation;
4. the cells the relaxation's path used are halved and arcs that cannot be on a plan
   better than the incumbent are dropped (walk bounds over the network);
5. until the best plan is within the requested gap of the lower bound
   ``min(relaxation, lower bounds of the removed paths)``, or a limit stops the search,
   which then reports the plan with its gap.

Plans from other sources (the paper's sequential linearisation, a beam search over the
network) enter as incumbents: they prune, they are never taken as proven.

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

import heapq
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..milp.types import SolverOptions
from ..network.dominance import path_cost_floor
from ..physics.leg_bounds import LegCosts, leg_box_bound
from .fixed_path import PathProblem, PathSchedule, solve_path
from .relaxation import Arcs, solve_relaxation

INITIAL_CELLS = 8
DEFAULT_GAP_REL = 1e-3
PATH_TOL_MPS = 0.01
SEED_PATHS = 12
BEAM_WIDTH = 1000
MILP_STEP_S = 10.0
"""First time limit of each relaxation MILP [s], doubled whenever one reaches it: a MILP
stopped early still proves its dual bound and usually holds a path to refine around."""


@dataclass(frozen=True)
class CertifiedNodes:
    """The mission as the certified search needs it (positions into the catalog).

    Attributes
    ----------
    legs : int
        Transfers on a path.
    ops_days, cost_mps : ndarray
        Operations time [days] and cost [m/s] at each node.
    first : int or None
    must_visit, excluded : tuple of int
    tmax_days, tmin_days : float
    rule : str
    j2 : float
    """

    legs: int
    ops_days: np.ndarray
    cost_mps: np.ndarray
    first: int | None
    must_visit: tuple[int, ...]
    excluded: tuple[int, ...]
    tmax_days: float
    tmin_days: float
    rule: str
    j2: float


@dataclass(frozen=True)
class CertifiedResult:
    """Best plan found and what is proven about the optimum.

    Attributes
    ----------
    path : tuple of int
        Node positions (empty when no plan was found).
    schedule : PathSchedule or None
    upper_mps : float
        Total ΔV of the plan (transfers and operations) [m/s]; ``inf`` without a plan.
    lower_mps : float
        No plan costs less [m/s] (``inf``: proven infeasible).
    status : {"optimal", "feasible", "infeasible", "no_plan"}
        ``optimal``: within the requested gap; ``feasible``: a limit stopped the search;
        ``infeasible``: proven that no plan exists; ``no_plan``: stopped before any plan.
    log : list of dict
    """

    path: tuple[int, ...]
    schedule: PathSchedule | None
    upper_mps: float
    lower_mps: float
    status: str
    log: list
    milp_solves: int
    cells: int
    seconds: float
    notes: tuple[str, ...] = ()
    edges: int = 0
    paths_certified: int = 0

    @property
    def gap_mps(self) -> float:
        return self.upper_mps - self.lower_mps

    @property
    def gap_rel(self) -> float:
        if not np.isfinite(self.upper_mps) or self.upper_mps == 0:
            return np.inf if not np.isfinite(self.upper_mps) else 0.0
        return max(self.gap_mps, 0.0) / self.upper_mps


class _Partitions:
    """Date cells of every debris, each a sorted list of [lo, hi] with a version counter."""

    def __init__(self, n_debris, start, stop, count):
        self.lo = [np.linspace(start[i], stop, count + 1)[:-1] for i in range(n_debris)]
        self.hi = [np.linspace(start[i], stop, count + 1)[1:] for i in range(n_debris)]

    def split(self, debris: int, cell: int, pieces: int = 2):
        lo, hi = self.lo[debris][cell], self.hi[debris][cell]
        edges = np.linspace(lo, hi, pieces + 1)
        self.lo[debris] = np.r_[self.lo[debris][:cell], edges[:-1], self.lo[debris][cell + 1 :]]
        self.hi[debris] = np.r_[self.hi[debris][:cell], edges[1:], self.hi[debris][cell + 1 :]]

    def count(self) -> int:
        return sum(len(c) for c in self.lo)


class _Network:
    """Time-expanded network over the current partitions: node ids, arcs and their bounds."""

    def __init__(self, nodes: CertifiedNodes, legs_table: LegCosts, edge_from, edge_to,
                 parts: _Partitions, alive_edges):  # fmt: skip
        n = len(nodes.ops_days)
        self.n_debris = n
        # node ids: starts 0..n-1, then the cells of each debris in order
        self.offset = np.cumsum([n] + [len(parts.lo[i]) for i in range(n)])[:-1]
        self.n_nodes = int(self.offset[-1] + len(parts.lo[n - 1])) if n else 0
        self.node_debris = np.r_[np.arange(n), np.concatenate(
            [np.full(len(parts.lo[i]), i) for i in range(n)])].astype(int)  # fmt: skip
        self.node_lo = np.r_[nodes.ops_days, np.concatenate(parts.lo)]
        self.node_hi = np.r_[nodes.ops_days, np.concatenate(parts.hi)]
        self.node_cell = np.r_[np.full(n, -1), np.concatenate(
            [np.arange(len(parts.lo[i])) for i in range(n)])].astype(int)  # fmt: skip
        tails, heads, edges = [], [], []
        for e in np.flatnonzero(alive_edges):
            i, j = int(edge_from[e]), int(edge_to[e])
            t_ids = np.r_[i, self.offset[i] + np.arange(len(parts.lo[i]))]
            h_ids = self.offset[j] + np.arange(len(parts.lo[j]))
            tt, hh = np.meshgrid(t_ids, h_ids, indexing="ij")
            tt, hh = tt.ravel(), hh.ravel()
            ok = self.node_hi[hh] - nodes.ops_days[j] - self.node_lo[tt] >= nodes.tmin_days
            tails.append(tt[ok])
            heads.append(hh[ok])
            edges.append(np.full(int(ok.sum()), e))
        tail = np.concatenate(tails) if tails else np.empty(0, dtype=int)
        head = np.concatenate(heads) if heads else np.empty(0, dtype=int)
        edge = np.concatenate(edges) if edges else np.empty(0, dtype=int)
        j = edge_to[edge]
        bound = leg_box_bound(legs_table, edge, self.node_lo[tail], self.node_hi[tail],
                              self.node_lo[head] - nodes.ops_days[j],
                              self.node_hi[head] - nodes.ops_days[j], rule=nodes.rule,
                              j2=nodes.j2, t_min=nodes.tmin_days)  # fmt: skip
        finite = np.isfinite(bound)
        self.edge = edge[finite]
        self.arcs = Arcs(tail[finite], head[finite], edge_from[self.edge], edge_to[self.edge],
                         bound[finite] + nodes.cost_mps[edge_to[self.edge]])  # fmt: skip

    def pruned(self, nodes: CertifiedNodes, start_allowed, upper: float):
        """Arcs that can lie on a plan within ``upper``, and the walk bound [m/s].

        Leg 0 leaves a start node (its operations cost added to the arc), later legs
        leave cells.  ``F_k`` (cheapest walk of k legs to a node) and ``B_k`` (cheapest
        walk of k legs from it) bound every path through arc a as leg k by
        ``F_k + c_a + B_{L-1-k}``; arcs above ``upper`` as every leg leave.
        """
        a = self.arcs
        L = nodes.legs
        from_start = a.tail < self.n_debris
        cost0 = a.cost + nodes.cost_mps[a.debris_from]
        forward = [np.full(self.n_nodes, np.inf)]
        forward[0][: self.n_debris] = np.where(start_allowed, 0.0, np.inf)
        backward = [np.zeros(self.n_nodes)]
        for k in range(L):
            f = np.full(self.n_nodes, np.inf)
            leg_ok = from_start if k == 0 else ~from_start
            cost = cost0 if k == 0 else a.cost
            np.minimum.at(f, a.head[leg_ok], forward[-1][a.tail[leg_ok]] + cost[leg_ok])
            forward.append(f)
            b = np.full(self.n_nodes, np.inf)
            inner = ~from_start
            np.minimum.at(b, a.tail[inner], a.cost[inner] + backward[-1][a.head[inner]])
            backward.append(b)
        best = np.full(len(a), np.inf)
        for k in range(L):
            leg_ok = from_start if k == 0 else ~from_start
            cost = cost0 if k == 0 else a.cost
            through = forward[k][a.tail] + cost + backward[L - 1 - k][a.head]
            best = np.minimum(best, np.where(leg_ok, through, np.inf))
        keep = best <= upper + 1e-9
        priced = Arcs(a.tail, a.head, a.debris_from, a.debris_to, np.where(from_start, cost0,
                                                                           a.cost))  # fmt: skip
        return priced.take(keep), float(np.min(forward[L]))


def certify(orbits, nodes: CertifiedNodes, a_low: float, a_high: float, *,
            solver: SolverOptions | None = None, gap_rel: float = DEFAULT_GAP_REL,
            time_limit_s: float | None = None, seeds=(),
            progress: Callable[[str], None] | None = None,
            on_iteration: Callable[[dict], None] | None = None,
            max_iterations: int = 500, initial_cells: int = INITIAL_CELLS,
            split_pieces: int = 2) -> CertifiedResult:  # fmt: skip
    """Minimum-ΔV plan of the mission with a certified lower bound (see module docstring).

    Parameters
    ----------
    orbits : NodeOrbits
        Every node's orbit (catalog order, injection orbit last when there is one).
    nodes : CertifiedNodes
    a_low, a_high : float
        Drift radius bounds [m].
    solver : SolverOptions
        MILP backend for the relaxation (its fallback chain is used).
    gap_rel : float
        Stop when (plan - bound) <= gap_rel * plan (and at most 0.01 m/s is always enough).
    time_limit_s : float, optional
        Wall-clock limit of the whole search [s]; the best plan is then returned with its gap.
    seeds : sequence of sequence of int
        Paths to optimise first (e.g. the paper method's answer), as incumbents.
    progress : callable, optional
        Receives one line of text per step.
    on_iteration : callable, optional
        Receives each relaxation's row (bound, plan, arcs, cells, seconds) when known.
    max_iterations : int
        Relaxations solved at most.

    Returns
    -------
    CertifiedResult
    """
    clock = time.perf_counter()
    solver = SolverOptions() if solver is None else solver
    say = progress or (lambda line: None)
    deadline = np.inf if time_limit_s is None else clock + time_limit_s
    n = len(nodes.ops_days)
    excluded = np.zeros(n, dtype=bool)
    excluded[list(nodes.excluded)] = True
    start_allowed = ~excluded
    if nodes.first is not None:
        start_allowed = np.arange(n) == nodes.first
    ii, jj = np.nonzero(~np.eye(n, dtype=bool))
    usable = ~excluded[ii] & ~excluded[jj]
    if nodes.first is not None:
        usable &= jj != nodes.first
    edge_from, edge_to = ii[usable], jj[usable]
    legs_table = LegCosts.build(orbits.take(edge_from), orbits.take(edge_to), a_low, a_high)
    say(f"certified search: {n} debris, {len(edge_from)} edges, {nodes.legs} legs")

    def path_problem(path):
        index = {(int(a), int(b)): k for k, (a, b) in enumerate(zip(edge_from, edge_to,
                                                                   strict=True))}  # fmt: skip
        edges = tuple(index[(a, b)] for a, b in zip(path[:-1], path[1:], strict=True))
        return PathProblem(legs_table, edges, tuple(float(nodes.ops_days[k]) for k in path),
                           nodes.tmax_days, nodes.tmin_days, nodes.rule, nodes.j2)  # fmt: skip

    best = {"upper": np.inf, "path": (), "schedule": None}
    settled: dict[tuple, float] = {}

    def node_total(path):
        return float(np.sum(nodes.cost_mps[list(path)]))

    def try_path(path, why):
        path = tuple(int(k) for k in path)
        if path in settled:
            return
        cutoff = best["upper"] - node_total(path)
        remaining = max(deadline - time.perf_counter(), 0.1)
        schedule = solve_path(path_problem(path), tol_mps=PATH_TOL_MPS, cutoff_mps=cutoff,
                              time_limit_s=remaining)  # fmt: skip
        settled[path] = schedule.lower_mps + node_total(path)
        total = schedule.upper_mps + node_total(path)
        if total < best["upper"]:
            best.update(upper=total, path=path, schedule=schedule)
            say(f"  plan {'-'.join(map(str, path))}: {total:.2f} m/s ({why})")

    for seed in seeds:
        if len(seed) == nodes.legs + 1:
            try_path(seed, "seed")

    edge_floor = legs_table.floor(np.arange(len(edge_from)))
    parts = _Partitions(n, nodes.ops_days, nodes.tmax_days, initial_cells)
    rows: list[dict] = []
    cycles: list[tuple[int, ...]] = []
    step_limit = MILP_STEP_S
    relax_lower, milp_solves, status, notes = -np.inf, 0, "feasible", []
    proven = -np.inf  # the best lower bound so far: every bound found stays valid
    for iteration in range(max_iterations + 1):
        started = time.perf_counter()
        # an edge on no walk of L legs cheaper than the plan at any date leaves
        alive_edges = (
            path_cost_floor(
                edge_from, edge_to, edge_floor, nodes.cost_mps, nodes.legs, first=nodes.first
            )
            <= best["upper"] + 1e-9
        )
        net = _Network(nodes, legs_table, edge_from, edge_to, parts, alive_edges)
        arcs, walk_lower = net.pruned(nodes, start_allowed, best["upper"])
        proven = max(proven, min(walk_lower, best["upper"]))
        candidates = _beam(arcs, n, nodes, start_allowed, exclude=settled,
                           count=SEED_PATHS if iteration == 0 else 1)  # fmt: skip
        if iteration == 0:  # cheap plans first: they prune every relaxation after
            for _, path, _ in candidates:
                try_path(path, "beam")
            continue
        if len(arcs) == 0 or not np.isfinite(walk_lower):
            relax_lower = np.inf  # no walk of L legs at all, or none below the best plan
            break
        remaining = deadline - time.perf_counter()
        if remaining <= 0:
            notes.append(f"time limit ({time_limit_s:g} s) reached")
            break
        options = _with_limit(solver, min(remaining, step_limit))
        result = solve_relaxation(arcs, n_nodes=net.n_nodes, n_debris=n, legs=nodes.legs,
                                  solver=options, must_visit=nodes.must_visit,
                                  cuts=list(settled), cycles=cycles, solver_gap=gap_rel / 4,
                                  start=candidates[0][2] if candidates else None)  # fmt: skip
        milp_solves += 1
        notes += [msg for msg in result.report.fallbacks if msg not in notes]
        if result.cycles:  # a subtour beside the path: forbid it and solve again
            cycles.extend(result.cycles)
            continue
        stopped = result.report.status.value in ("time_limit", "no_solution")
        if stopped and time.perf_counter() < deadline:
            step_limit *= 2  # a MILP stopped at its step limit: its dual bound still counts
        if result.lower_mps is None:
            if stopped and time.perf_counter() < deadline:
                continue
            notes.append(f"relaxation MILP failed: {result.report.message}")
            break
        relax_lower = result.lower_mps
        if result.path and np.isfinite(relax_lower):
            try_path(result.path, "relaxation")
        proven = max(proven, min(relax_lower, min(settled.values(), default=np.inf)))
        lower = proven
        row = dict(iteration=iteration, path=result.path, relaxation_mps=relax_lower,
                   lower_mps=lower, upper_mps=best["upper"], arcs=len(arcs),
                   cells=parts.count(), nodes=result.report.nodes,
                   solve_seconds=result.report.solve_seconds, backend=result.report.backend,
                   cvxpy_seconds=result.report.overhead_seconds,
                   seconds=time.perf_counter() - started)  # fmt: skip
        rows.append(row)
        if on_iteration is not None:
            on_iteration(row)
        say(f"  bound {lower:.2f}, plan {best['upper']:.2f} m/s ({len(arcs)} arcs, "
            f"{parts.count()} cells, MILP {result.report.solve_seconds:.1f} s, "
            f"{result.report.nodes} nodes)")  # fmt: skip
        if not np.isfinite(relax_lower) or _within(best["upper"], lower, gap_rel):
            break
        if stopped and time.perf_counter() >= deadline:
            notes.append(f"time limit ({time_limit_s:g} s) reached during a MILP")
            break
        _refine(parts, net, arcs, result.arcs, split_pieces)
    else:
        notes.append(f"iteration limit ({max_iterations}) reached")
    lower = max(proven, min(relax_lower, min(settled.values(), default=np.inf)))
    if not np.isfinite(best["upper"]):
        status = "infeasible" if lower == np.inf else "no_plan"
    elif _within(best["upper"], lower, gap_rel):
        status = "optimal"
    lower = min(lower, best["upper"])
    return CertifiedResult(best["path"], best["schedule"], best["upper"], lower, status, rows,
                           milp_solves, parts.count(), time.perf_counter() - clock,
                           tuple(notes), edges=int(len(edge_from)),
                           paths_certified=len(settled))  # fmt: skip


def _within(upper, lower, gap_rel) -> bool:
    allowed = max(gap_rel * abs(upper), PATH_TOL_MPS) * (1 + 1e-9)
    return bool(np.isfinite(upper) and upper - lower <= allowed)


def _with_limit(solver: SolverOptions, remaining: float) -> SolverOptions:
    from dataclasses import replace

    return replace(solver, time_limit_s=max(remaining, 1.0))


def _refine(parts: _Partitions, net: _Network, arcs: Arcs, chosen, pieces: int = 2):
    """Halve the date cells the relaxation's arcs leave from and arrive in."""
    cells = set()
    for a in chosen:
        for node in (arcs.tail[a], arcs.head[a]):
            if net.node_cell[node] >= 0:
                cells.add((int(net.node_debris[node]), int(net.node_cell[node])))
    for debris, cell in sorted(cells, key=lambda dc: (dc[0], -dc[1])):
        parts.split(debris, cell, pieces)


def _beam(
    arcs: Arcs,
    n_debris: int,
    nodes: CertifiedNodes,
    start_allowed,
    *,
    exclude=(),
    width: int = BEAM_WIDTH,
    count: int = 1,
) -> list[tuple[float, tuple, tuple]]:
    """Cheapest simple paths under the arc bounds, leg by leg (a beam search).

    Returns up to ``count`` distinct debris paths not in ``exclude`` that visit
    ``must_visit``, as ``(cost, debris path, rows of arcs)``, cheapest first.
    """
    by_tail: dict[int, list[int]] = {}
    for row in range(len(arcs)):
        by_tail.setdefault(int(arcs.tail[row]), []).append(row)
    beam = [(0.0, (int(i),), int(i), ()) for i in np.flatnonzero(start_allowed)]
    for _ in range(nodes.legs):
        grown = [(cost + arcs.cost[r], path + (int(arcs.debris_to[r]),), int(arcs.head[r]),
                  rows + (r,))
                 for cost, path, node, rows in beam for r in by_tail.get(node, ())
                 if arcs.debris_to[r] not in path]  # fmt: skip
        beam = heapq.nsmallest(width, grown)
    required, excluded = set(nodes.must_visit), set(exclude)
    out, seen = [], set()
    for cost, path, _, rows in sorted(beam):
        if path not in seen and path not in excluded and required <= set(path):
            seen.add(path)
            out.append((float(cost), path, rows))
        if len(out) >= count:
            break
    return out
