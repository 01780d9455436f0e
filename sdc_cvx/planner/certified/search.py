"""The certified search: the mission's optimum bracketed by a lower bound and the best plan.

The loop (dynamic discretisation discovery, Boland et al. 2018, over the drift
transfer model of Part III):

1. every ordered pair of candidate debris is an edge (no heuristic filter: an edge
   leaves only when a bound proves it cannot be on a plan better than the incumbent);
   the first plans come from a beam search over a grid of dates
   (:mod:`~sdc_cvx.planner.certified.date_grid`);
2. each debris' dates [0, T_max] are split into cells; the time-expanded network
   (:mod:`~sdc_cvx.planner.certified.network`) prices each arc by the exact lower bound
   of its leg over its box of dates, and its relaxation (the cheapest path of L legs
   that is none of the settled paths) is a lower bound of the mission.  Labels solve
   it exactly (:func:`~sdc_cvx.network.path_bounds.cheapest_path`); where too many,
   ng-route labels (:mod:`~sdc_cvx.network.ng_routes`); a MILP where both give up;
3. the relaxation's path is optimised globally as a fixed path
   (:func:`~sdc_cvx.planner.fixed_path.solve_path`): a plan that flies, i.e. an upper
   bound, and a certified lower bound of that path alone; it is then settled (excluded
   from the relaxation);
4. the cells the relaxation's path used are halved and arcs that cannot be on a plan
   better than the incumbent are dropped (the cheapest walk through each arc:
   :mod:`~sdc_cvx.network.path_bounds`); before each relaxation, the cells of the paths
   a beam search over the network finds under the plan (more than the gap below it)
   are halved too, and the best of them certified, until it finds none;
5. until the best plan is within the requested gap of the lower bound
   ``min(relaxation, lower bounds of the settled paths)``, or a limit stops the search,
   which then reports the plan with its gap.

Plans from other sources (the paper's sequential linearisation, the beam searches)
enter as incumbents: they prune, they are never taken as proven.

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

import time
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ...milp.types import SolveReport, SolverOptions, Status
from ...network.dominance import path_cost_floor
from ...physics.leg_bounds import LegCosts
from ..fixed_path import PathProblem, PathSchedule, solve_path
from .date_grid import grid_plans
from .greedy import find_greedy, greedy_result
from .network import CellNetwork, DateCells, OutOfTime, beam_paths, cost_table_clock, refine_cells
from .relaxation import RelaxationResult, solve_relaxation
from .results import CertifiedNodes, CertifiedPath, CertifiedResult, allowed_gap, within_gap

INITIAL_CELLS = 8
DEFAULT_GAP_REL = 1e-3
PATH_TOL_MPS = 0.01
SEED_PATHS = 4
FIRST_ARCS = 1.5e6
"""About the most arcs of the first network (before a plan prunes edges): the initial
cells per debris are fewer when the edges are many."""
CANDIDATES = 40  # beam paths whose cells are refined together before a relaxation MILP
MAX_REFINE_ROUNDS = 30  # before a MILP at most (each certifies one path and splits cells)
GRID_LEGS = 6
"""Legs from which the first plans come from a grid of dates too (n >= 7): below, the
network's beam finds the optimum about as soon, and the grid's second or two would weigh
on short runs (the paper case) and on campaigns, which price many short missions."""
LABELS = "labels"
"""The ``backend`` of a relaxation solved by labels rather than by a MILP."""
MILP_STEP_S = 60.0
"""First time limit of each relaxation MILP [s], doubled whenever one reaches it: a MILP
stopped early still proves its dual bound and usually holds a path to refine around.
Measured: 10 s cost rb08 75 s (two MILPs stopped, then one proved) against 35 s."""


class _Search:
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


def certify(orbits, nodes: CertifiedNodes, a_low: float, a_high: float, *,
            solver: SolverOptions | None = None, gap_rel: float = DEFAULT_GAP_REL,
            time_limit_s: float | None = None, seeds=(),
            progress: Callable[[str], None] | None = None,
            on_iteration: Callable[[dict], None] | None = None, names=None,
            max_iterations: int = 500, initial_cells: int = INITIAL_CELLS,
            split_pieces: int = 2, gap_abs_mps: float = PATH_TOL_MPS,
            stop_above_mps: float = np.inf, ceiling_mps: float = -np.inf,
            known=None, path_tol_rel: float | None = None, date_grid: bool | None = None,
            stop: Callable[[], bool] | None = None,
            fallback: bool = False) -> CertifiedResult:  # fmt: skip
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
        Stop when ``plan - bound <= max(gap_rel * abs(plan), gap_abs_mps)``.
    time_limit_s : float, optional
        Wall-clock limit of the whole search [s]; the best plan is then returned with its gap.
    seeds : sequence of sequence of int
        Paths to optimise first (e.g. the paper method's answer), as incumbents.
    progress : callable, optional
        Receives one line of text per step.
    on_iteration : callable, optional
        Receives each relaxation's row (bound, plan, arcs, cells, seconds) when known.
    names : sequence of str, optional
        The nodes' names in progress lines (default their positions).
    max_iterations : int
        Relaxations solved at most.
    initial_cells, split_pieces : int
        Date cells per debris at the start (fewer when the edges are many, see
        ``FIRST_ARCS``), and pieces a used cell is split into.
    gap_abs_mps : float
        Absolute gap that is always enough [m/s] (0.01 by default).
    stop_above_mps : float
        Stop as soon as no plan can cost less than this [m/s] (a campaign's pricing:
        no mission of negative reduced cost is left); the result's bound says so.
    ceiling_mps : float
        Enumerate: certify every path whose lower bound is under this [m/s] (they are
        in ``paths``), and stop when the relaxation proves that no other path is; the
        plan and bound are then those of the cheapest, as usual.
    known : dict, optional
        Schedules certified before, by path (node positions): a path is not solved again
        when its schedule is within the tolerance of its bound, or its bound is above
        what could matter (a campaign prices the same launch many times; a path's
        schedule does not depend on the node costs).
    path_tol_rel : float, optional
        Relative tolerance of each path's schedule (default ``gap_rel / 2``: a path
        needs no finer certificate than the mission's).
    date_grid : bool, optional
        Seed the search with the best plans of a beam search over a grid of dates
        (:mod:`~sdc_cvx.planner.certified.date_grid`): a few seconds that make the first
        relaxations small.  Default: from :data:`GRID_LEGS` legs on.
    stop : callable, optional
        Asked between steps; True ends the search as a time limit does (the best plan
        with its gap): the command line's Ctrl-C.
    fallback : bool
        When the time limit cannot cover the edge cost tables, stop them early and
        return a greedy plan that flies (:mod:`~sdc_cvx.planner.certified.greedy`),
        ``feasible`` with the bound every plan has (its node costs' least sum), rather
        than no plan.  For a single mission; a campaign's pricing leaves it off.

    Notes
    -----
    Node costs (``nodes.cost_mps``) may be negative, e.g. a campaign's prize for a
    debris it must remove.  Every rule of the search compares a whole path (or a
    partial path of k legs with the cheapest completion of the L - k legs left) to a
    plan of L legs, and every such sum counts exactly L + 1 node costs: adding a
    constant to every node cost changes both sides of every comparison by the same
    amount.  So the search with any node costs is the search with non-negative ones
    (all raised by the same constant), and each pruning rule stays valid
    (``docs/design.md`` §10).

    Returns
    -------
    CertifiedResult
    """
    clock = time.perf_counter()
    solver = SolverOptions() if solver is None else solver
    deadline = np.inf if time_limit_s is None else clock + time_limit_s
    stop = stop or (lambda: False)
    try:
        search = _Search(orbits, nodes, a_low, a_high, deadline=deadline,
                         say=progress or (lambda line: None), initial_cells=initial_cells,
                         names=names, gap_abs_mps=gap_abs_mps,
                         path_tol_rel=gap_rel / 2 if path_tol_rel is None else path_tol_rel,
                         ceiling_mps=ceiling_mps, known=known, stop=stop,
                         fallback=fallback)  # fmt: skip
    except OutOfTime as err:
        if err.plan is not None and not stop():
            return greedy_result(nodes, err.plan, clock, str(err))
        return CertifiedResult((), None, np.inf, -np.inf, "no_plan", [], 0, 0,
                               time.perf_counter() - clock, (str(err),),
                               complete=False)  # fmt: skip
    enumerating = np.isfinite(ceiling_mps)
    rows: list[dict] = []
    step_limit, milp_solves = MILP_STEP_S, 0
    try:  # a network of date cells bounded past the time limit ends the search
        for seed in seeds:
            if len(seed) == nodes.legs + 1:
                search.try_path(seed, "seed")
        if fallback and search.greedy is None and 3 * time.perf_counter() > deadline + 2 * clock:
            search.find_greedy()  # past a third of the limit: the first network may not end
        if search.greedy is not None:
            search.try_path(search.greedy[0], "greedy")
        use_grid = nodes.legs >= GRID_LEGS if date_grid is None else date_grid
        if use_grid:  # near-optimal plans before any network: they prune
            search.say("  cheap plans from a grid of dates (a beam search)")
            for plan in grid_plans(search.legs, search.edge_from, search.edge_to, nodes,
                                   deadline=deadline):  # fmt: skip
                search.try_path(plan.path, "date grid")
        # cheap plans first, from a beam search over the first network: they prune the rest
        _, arcs, _ = search.network()
        search.try_paths([path for _, path, _ in search.candidates(arcs, SEED_PATHS)], "beam")
        for iteration in range(1, max_iterations + 1):
            started = time.perf_counter()
            net, arcs, network_lower = search.network()
            if search.proven >= stop_above_mps:
                break
            beam = []  # the uncut beam paths of the current arcs, cheapest first
            for _ in range(MAX_REFINE_ROUNDS):  # cheap first: cells along the beam's open paths
                if len(arcs) == 0 or time.perf_counter() >= deadline or stop():
                    break
                beam = search.candidates(arcs, CANDIDATES)
                open_paths = search.open_paths(beam, gap_rel)
                if not open_paths:
                    break
                for _, path, _ in open_paths if enumerating else open_paths[:1]:
                    search.try_path(path, "network")
                chosen = np.concatenate([rows for *_, rows in open_paths])
                refine_cells(search.parts, net, arcs, chosen, split_pieces)
                search.say(f"  refine the cells of {len(open_paths)} paths whose bounds (from "
                           f"{open_paths[0][0]:.2f} m/s) are under the plan's "
                           f"{search.upper:.2f} m/s: {search.parts.count()} cells")  # fmt: skip
                net, arcs, network_lower = search.network()
                beam = []
            if len(arcs) == 0 or not np.isfinite(network_lower):
                search.prove(np.inf)  # no path of L legs at all, or none below the plan held
                break
            remaining = deadline - time.perf_counter()
            if stop() and np.isfinite(search.upper):
                search.notes.append("interrupted: the best plan so far")
                search.limited = True
                break
            if remaining <= 0:
                search.notes.append(f"time limit ({time_limit_s:g} s) reached")
                search.limited = True
                break
            result = search.exact_relaxation()  # by labels; None: a MILP solves it
            if result is None:
                start = beam[:1] or search.candidates(arcs, 1)  # the MILP's first incumbent
                search.say(
                    f"  relaxation MILP {milp_solves + 1}: {len(arcs)} arcs over "
                    f"{search.parts.count()} date cells (limit {min(remaining, step_limit):.0f} s)"
                )
                result = solve_relaxation(
                    arcs, n_nodes=net.n_nodes, n_debris=search.n, legs=nodes.legs,
                    solver=replace(solver, time_limit_s=max(min(remaining, step_limit), 1.0)),
                    must_visit=nodes.must_visit, cuts=list(search.settled),
                    solver_gap=gap_rel / 10, start=start[0][2] if start else None)  # fmt: skip
                milp_solves += 1
            search.notes += [m for m in result.report.fallbacks if m not in search.notes]
            stopped = result.report.status.value in ("time_limit", "no_solution")
            out_of_time = time.perf_counter() >= deadline
            if stopped and not out_of_time:
                step_limit *= 2  # a MILP stopped at its step limit: its dual bound still counts
            if result.lower_mps is None:
                if stopped and not out_of_time:
                    continue
                search.notes.append(f"relaxation MILP failed: {result.report.message}")
                search.limited = True
                break
            if result.path and np.isfinite(result.lower_mps):
                search.try_path(result.path, "relaxation")
            lower = search.prove(result.lower_mps)
            row = dict(iteration=iteration, path=result.path, plan_path=search.path,
                       relaxation_mps=result.lower_mps,
                       lower_mps=lower, upper_mps=search.upper, arcs=len(arcs),
                       cells=search.parts.count(), nodes=result.report.nodes,
                       solve_seconds=result.report.solve_seconds, backend=result.report.backend,
                       cvxpy_seconds=result.report.overhead_seconds,
                       seconds=time.perf_counter() - started,
                       elapsed=time.perf_counter() - clock)  # fmt: skip
            rows.append(row)
            if on_iteration is not None:
                on_iteration(row)
            how = (
                f"labels {result.report.solve_seconds:.1f} s"
                if result.report.backend == LABELS
                else f"MILP {result.report.solve_seconds:.1f} s, {result.report.nodes} nodes"
            )
            search.say(f"  bound {lower:.2f}, plan {search.upper:.2f} m/s ({len(arcs)} arcs, "
                       f"{search.parts.count()} cells, {how})")  # fmt: skip
            if enumerating:
                if result.lower_mps > ceiling_mps:  # every path under the ceiling is settled
                    break
            elif not np.isfinite(result.lower_mps) or search.within(lower, gap_rel):
                break
            if lower >= stop_above_mps:
                break
            if stopped and out_of_time:
                search.notes.append(f"time limit ({time_limit_s:g} s) reached during a MILP")
                search.limited = True
                break
            if stop() and np.isfinite(search.upper):
                search.notes.append("interrupted: the best plan so far")
                search.limited = True
                break
            refine_cells(search.parts, net, arcs, result.arcs, split_pieces)
        else:
            search.notes.append(f"iteration limit ({max_iterations}) reached")
            search.limited = True
    except OutOfTime as err:
        search.notes.append(str(err))
        search.limited = True
    status = search.status(gap_rel)
    if status == "feasible" and not search.limited:  # not a limit: the bounds' resolution
        search.notes.append("the bounds cannot be refined further (their resolution)")
    lower = max(min(search.proven, search.upper), nodes.least_cost())  # never -inf
    return CertifiedResult(search.path, search.schedule, search.upper, lower, status, rows,
                           milp_solves, search.parts.count(), time.perf_counter() - clock,
                           tuple(search.notes), edges=int(len(search.edge_from)),
                           paths_certified=len(search.settled),
                           paths=search.certified_paths(), complete=not search.limited,
                           trace=tuple((t - clock, b, u) for t, b, u in search.trace))  # fmt: skip


def _settles(schedule: PathSchedule, cutoff: float, tol_rel: float) -> bool:
    """A schedule certified before serves again: within the tolerance of its own bound,
    or with a bound above the cutoff (the path cannot matter)."""
    tol = max(PATH_TOL_MPS, tol_rel * schedule.upper_mps) if schedule.feasible else PATH_TOL_MPS
    return schedule.upper_mps - schedule.lower_mps <= tol * (1 + 1e-9) or \
        schedule.lower_mps > cutoff  # fmt: skip
