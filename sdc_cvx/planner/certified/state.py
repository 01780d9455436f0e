"""What the certified search holds, and its steps: :class:`SearchState`.

The edges and their cost tables, the best plan, the settled paths (each certified by
:func:`~sdc_cvx.planner.fixed_path.solve_path`) with their lower bounds, the date cells
and the best bound so far, with one method per step of the loop that
:func:`~sdc_cvx.planner.certified.search.certify` runs: certify a path, build the
network and its bound, take the relaxation the labels solved, find the beam's open
paths, say how the search ends.
"""

from __future__ import annotations

import time

import numpy as np

from ...milp.types import SolveReport, Status
from ...network.dominance import path_cost_floor
from ...physics.leg_bounds import LegCosts
from ..fixed_path import PathProblem, PathSchedule, solve_path
from .clock import cost_table_clock
from .greedy import find_greedy
from .network import CellNetwork, DateCells, beam_paths
from .relaxation import RelaxationResult
from .results import CertifiedNodes, CertifiedPath, allowed_gap, within_gap

PATH_TOL_MPS = 0.01
"""Absolute tolerance of each path's certificate, and the gap always enough [m/s]."""
FIRST_ARCS = 1.5e6
"""About the most arcs of the first network (before a plan prunes edges): the initial
cells per debris are fewer when the edges are many."""
LABELS = "labels"
"""The ``backend`` of a relaxation solved by labels rather than by a MILP."""


class SearchState:
    """What the certified search holds: the edges, the best plan, the settled paths, the
    date cells and the best bound so far, with one method per step of the loop."""

    def __init__(self, orbits, nodes: CertifiedNodes, a_low, a_high, *, deadline, say,
                 initial_cells, names=None, path_tol_rel=0.0, gap_abs_mps=PATH_TOL_MPS,
                 ceiling_mps=-np.inf, known=None, stop=None, fallback=False):  # fmt: skip
        n = len(nodes.ops_days)
        self.stop = stop or (lambda: False)  # asked by the cost tables' chunks too
        self.fallback = fallback  # late tables: a greedy plan first (find_greedy)
        self.greedy = None  # (path, schedule) of that plan
        self.names = [str(k) for k in range(n)] if names is None else [str(v) for v in names]
        # no finer than the model's box bounds resolve a mission (low thrust: mm/s a leg)
        self.path_tol_rel = path_tol_rel
        self.gap_abs = max(gap_abs_mps, 2.0 * nodes.legs * nodes.model.bound_tol_mps)
        self.ceiling = ceiling_mps  # enumeration: every path whose bound is under it
        self.nodes, self.n, self.deadline, self.say = nodes, n, deadline, say
        excluded = np.zeros(n, dtype=bool)
        excluded[list(nodes.excluded)] = True
        self.start_allowed = ~excluded
        if nodes.first is not None:
            self.start_allowed = np.arange(n) == nodes.first
        ii, jj = np.nonzero(~np.eye(n, dtype=bool))
        usable = ~excluded[ii] & ~excluded[jj]
        if nodes.first is not None:
            usable &= jj != nodes.first  # nothing flies back to the start
        self.edge_from, self.edge_to = ii[usable], jj[usable]
        self.edge_index = {(int(a), int(b)): k for k, (a, b) in
                           enumerate(zip(self.edge_from, self.edge_to, strict=True))}  # fmt: skip
        say(f"certified search: {n} debris, {len(self.edge_from)} edges, {nodes.legs} legs; "
            "cost tables of every edge")  # fmt: skip
        self.find_greedy = lambda: find_greedy(self, orbits, a_low, a_high)
        ends = self.edge_from, self.edge_to
        self.legs = LegCosts.build(*(orbits.take(k) for k in ends), a_low, a_high,
                                   model=nodes.model, on_chunk=cost_table_clock(self),
                                   eccentricity=nodes.edge_eccentricity(*ends))  # fmt: skip
        self.edge_floor = self.legs.floor(np.arange(len(self.edge_from)))
        # the first network holds every edge: fewer cells when they are many (481 TLE
        # fragments: 230 880 edges, 2 cells each instead of 8 keeps it near 1.4 M arcs)
        cells = max(2, min(initial_cells, int(np.sqrt(FIRST_ARCS / max(len(self.edge_from), 1)))))
        self.parts = DateCells(n, nodes.ops_days, nodes.tmax_days, cells)
        self.upper, self.path, self.schedule = np.inf, (), None
        self.settled: dict[tuple, float] = {}  # path -> its certified lower bound [m/s]
        self.schedules: dict[tuple, PathSchedule] = {}  # path -> its best schedule
        self.known = dict(known or {})  # path -> a schedule certified before (a campaign's)
        self.proven = -np.inf  # the best lower bound so far: every bound found stays valid
        self.trace: list[tuple[float, float, float]] = []  # (clock, bound, plan) on a change
        # network()'s: each node's cheapest walks, the labels' relaxation, route neighbourhoods
        self.completion, self.exact, self.neighbourhoods = None, None, None
        self.notes: list[str] = []
        self.limited = False  # a limit, not the search's own criterion, ended it

    def label(self, path) -> str:
        return "-".join(self.names[k] for k in path)

    def node_cost(self, path) -> float:
        return float(np.sum(self.nodes.cost_mps[list(path)]))

    @property
    def level(self) -> float:
        """Arcs and paths above this cannot matter [m/s]: the plan held, or the ceiling
        of an enumeration when it is higher."""
        return max(self.upper, self.ceiling)

    def allowed(self, upper: float, gap_rel: float) -> float:
        return allowed_gap(upper, gap_rel, self.gap_abs)

    def within(self, lower: float, gap_rel: float) -> bool:
        return within_gap(self.upper, lower, gap_rel, self.gap_abs)

    def try_path(self, path, why: str) -> None:
        """Certify one path (its best schedule and its lower bound), and hold it if better."""
        path = tuple(int(k) for k in path)
        if path in self.settled:
            return
        problem = self.path_problem(path)
        remaining = max(self.deadline - time.perf_counter(), 0.1)
        cutoff = self.level - self.node_cost(path)
        schedule = self.known.get(path)
        if schedule is None or not _settles(schedule, cutoff, self.path_tol_rel):
            # no finer than the model's box bounds resolve a path (low thrust: mm/s a leg)
            tol = max(PATH_TOL_MPS, 2.0 * len(path) * self.legs.model.bound_tol_mps)
            schedule = solve_path(problem, tol_mps=tol, tol_rel=self.path_tol_rel,
                                  time_limit_s=remaining, cutoff_mps=cutoff)  # fmt: skip
        self.settled[path] = schedule.lower_mps + self.node_cost(path)
        self.schedules[path] = schedule
        total = schedule.upper_mps + self.node_cost(path)
        if total < self.upper:
            self.upper, self.path, self.schedule = total, path, schedule
            self.trace.append((time.perf_counter(), self.proven, self.upper))
            self.say(f"  plan {self.label(path)}: {total:.2f} m/s ({why})")

    def try_paths(self, paths, why: str) -> None:
        """Certify ``paths``, cheapest quick schedule (one round of :func:`solve_path`,
        a plan that flies; a known schedule's plan) first: the best plan is held first and
        the others' certificates stop as soon as their bounds pass it (the paper case's
        schedules: 0.98 s -> 0.64 s)."""
        paths = [tuple(int(k) for k in path) for path in paths]
        if len(paths) > 1:
            fresh = [path for path in paths if path not in self.settled]
            quick = {path: (self.known.get(path) or solve_path(self.path_problem(path),
                                                               max_rounds=1)).upper_mps
                     + self.node_cost(path) for path in fresh}  # fmt: skip
            paths.sort(key=lambda path: quick.get(path, np.inf))
        for path in paths:
            self.try_path(path, why)

    def path_problem(self, path) -> PathProblem:
        """The schedule problem of one path of debris (node indices)."""
        nodes = self.nodes
        return PathProblem(
            self.legs, tuple(self.edge_index[(a, b)] for a, b in zip(path[:-1], path[1:],
                                                                     strict=True)),
            tuple(float(nodes.ops_days[k]) for k in path), nodes.tmax_days, nodes.tmin_days,
            nodes.rule, nodes.j2)  # fmt: skip

    def network(self):
        """Arcs that could be on a plan better than the one held, and the bound they prove
        (the relaxation over them when the labels solve it, else the network's cheapest
        path: :meth:`CellNetwork.pruned`)."""
        alive = path_cost_floor(self.edge_from, self.edge_to, self.edge_floor,
                                self.nodes.cost_mps, self.nodes.legs,
                                first=self.nodes.first) <= self.level + 1e-9  # fmt: skip
        net = CellNetwork(self.nodes, self.legs, self.edge_from, self.edge_to, self.parts, alive,
                       self.deadline)  # fmt: skip
        started = time.perf_counter()
        arcs, exact, network_lower = net.pruned(self.nodes, self.start_allowed, self.level,
                                                self.settled, self.neighbourhoods)  # fmt: skip
        self.neighbourhoods = net.neighbourhoods
        self.prove(min(network_lower, self.upper))
        self.completion = net.completion
        self.exact = None if exact is None else (len(self.settled), exact,
                                                 time.perf_counter() - started)  # fmt: skip
        return net, arcs, network_lower

    def prove(self, relaxation_bound: float) -> float:
        """Raise the bound: every plan is on a settled path or above the relaxation's."""
        settled = min(self.settled.values(), default=np.inf)
        proven = max(self.proven, min(relaxation_bound, settled))
        if proven > self.proven:
            self.trace.append((time.perf_counter(), proven, self.upper))
        self.proven = proven
        return self.proven

    def exact_relaxation(self) -> RelaxationResult | None:
        """The relaxation of the last network solved exactly by labels (its cheapest path
        that is not a settled one), or None when its labels were too many or paths were
        settled since (the MILP then solves it)."""
        if self.exact is None or self.exact[0] != len(self.settled):
            return None
        _, found, seconds = self.exact
        report = SolveReport(Status.OPTIMAL, found.cost, found.cost, 0.0, 0, seconds, 0.0,
                             LABELS, "cheapest path by labels")  # fmt: skip
        return RelaxationResult(report, found.cost, found.debris, found.rows)

    def candidates(self, arcs, count: int):
        return beam_paths(arcs, self.n, self.nodes, self.start_allowed, exclude=self.settled,
                     count=count, completion=self.completion)  # fmt: skip

    def open_paths(self, beam, gap_rel: float):
        """The beam's paths whose arc bounds could beat the plan by more than the gap
        (in an enumeration: whose arc bounds are under the ceiling)."""
        target = self.upper - self.allowed(self.upper, gap_rel) if np.isfinite(self.upper) \
            else np.inf  # fmt: skip
        target = max(target, self.ceiling)
        return [c for c in beam if c[0] < target]

    def status(self, gap_rel: float) -> str:
        if not np.isfinite(self.upper):
            return "infeasible" if self.proven == np.inf else "no_plan"
        return "optimal" if self.within(self.proven, gap_rel) else "feasible"

    def certified_paths(self) -> tuple[CertifiedPath, ...]:
        """Every settled path that flies, cheapest first."""
        out = [CertifiedPath(path, schedule, schedule.upper_mps + self.node_cost(path),
                             self.settled[path])
               for path, schedule in self.schedules.items() if schedule.feasible]  # fmt: skip
        return tuple(sorted(out, key=lambda c: c.upper_mps))


def _settles(schedule: PathSchedule, cutoff: float, tol_rel: float) -> bool:
    """A schedule certified before serves again: within the tolerance of its own bound,
    or with a bound above the cutoff (the path cannot matter)."""
    tol = max(PATH_TOL_MPS, tol_rel * schedule.upper_mps) if schedule.feasible else PATH_TOL_MPS
    return schedule.upper_mps - schedule.lower_mps <= tol * (1 + 1e-9) or \
        schedule.lower_mps > cutoff  # fmt: skip
