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

This module is the loop's order; what the search holds and each step are
:class:`~sdc_cvx.planner.certified.state.SearchState`'s, and the cost tables' clock
:mod:`~sdc_cvx.planner.certified.clock`'s.

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

from ...milp.types import SolverOptions
from .clock import OutOfTime
from .date_grid import grid_plans
from .greedy import greedy_result
from .network import refine_cells
from .relaxation import solve_relaxation
from .results import CertifiedNodes, CertifiedResult
from .state import LABELS, PATH_TOL_MPS, SearchState

INITIAL_CELLS = 8
DEFAULT_GAP_REL = 1e-3
SEED_PATHS = 4
CANDIDATES = 40  # beam paths whose cells are refined together before a relaxation MILP
MAX_REFINE_ROUNDS = 30  # before a MILP at most (each certifies one path and splits cells)
GRID_LEGS = 6
"""Legs from which the first plans come from a grid of dates too (n >= 7): below, the
network's beam finds the optimum about as soon, and the grid's second or two would weigh
on short runs (the paper case) and on campaigns, which price many short missions."""
MILP_STEP_S = 60.0
"""First time limit of each relaxation MILP [s], doubled whenever one reaches it: a MILP
stopped early still proves its dual bound and usually holds a path to refine around.
Measured: 10 s cost rb08 75 s (two MILPs stopped, then one proved) against 35 s."""


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
        search = SearchState(orbits, nodes, a_low, a_high, deadline=deadline,
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
