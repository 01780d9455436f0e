"""``solve_campaign``: the cheapest (or most valuable) campaign, with a certified bound.

It checks the options, opens where the pricing problems run (this process, a local pool,
Dask or any executor) and hands the campaign to its objective's search: the min-ΔV
column generation (:mod:`~sdc_cvx.campaign.min_dv`, ``docs/design.md`` §10), or the
value search (:mod:`~sdc_cvx.campaign.value`).  It builds the
:class:`~sdc_cvx.campaign.result.CampaignSolution` of the min-ΔV one.

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

import time
import warnings
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ..errors import IgnoredOptionWarning, MissionError, SolverFailure
from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..milp.types import SolverOptions
from ..planner.size_guard import size_problem
from ..solution import OPTIMAL_GAP_MPS, OPTIMAL_GAP_REL, RunStatus
from .min_dv import CampaignSearch, shown_bound
from .pricing import Column, mission_solution
from .pricing_runs import (
    PricingRuns,
    check_options,
    guarded_workers,
    ignored_options,
    pricings_at_once,
)
from .result import CampaignSolution, GreedyCampaign, tank_status

DEFAULT_GAP_REL = 1e-3


def solve_campaign(catalog: Catalog, campaign: Campaign, *, solver: SolverOptions | None = None,
                   gap: float = DEFAULT_GAP_REL, time_limit_s: float | None = None,
                   workers: int | None = None, scheduler=None, executor=None,
                   log: Callable[[str], None] | None = None,
                   stop: Callable[[], bool] | None = None,
                   pareto: int = 0) -> CampaignSolution:  # fmt: skip
    """The cheapest campaign of ``campaign``'s missions over ``catalog``, with its bound.

    Parameters
    ----------
    catalog : Catalog
        Candidate debris, RAANs at day 0 (the campaign's start).
    campaign : Campaign
        Launch days and the mission flown from each.
    solver : SolverOptions, optional
        MILP backend of the pricing searches and of the integer master (HiGHS by
        default); the master LP is always HiGHS (its duals).
    gap : float
        Stop when plan - bound <= max(gap * plan, 0.01 m/s per mission) [-].
    time_limit_s : float, optional
        Wall-clock limit of the whole search [s]; the best campaign is then returned
        with its gap (status ``feasible``).
    workers : int, optional
        Processes of the local pool pricing the launches in parallel (default: the
        cores, at most one per launch; 1: in this process).
    scheduler : str or distributed.Client, optional
        A Dask scheduler to price on instead (``pip install 'sdc_cvx[dask]'``).
    executor : concurrent.futures.Executor, optional
        Any executor to price on instead.
    log : callable, optional
        Receives one line per step (each launch, the greedy campaign, each round's
        LP value, plan, bound and gap).
    stop : callable, optional
        Asked between steps (and by a pricing run in this process, between its own):
        True ends the search with the best campaign so far and its gap, status
        ``feasible`` (the command line's Ctrl-C).
    pareto : int
        ``objective = "max-value"``: also this many campaigns of value against ΔV
        (``CampaignSolution.pareto``; 0: none).

    Returns
    -------
    CampaignSolution

    Raises
    ------
    MissionError
        The campaign does not fit the catalog (unknown ids, too few candidates).
    MissionInfeasible
        A launch has no flyable mission, or the missions cannot share the debris.
    SolverFailure
        A backend failed, or the time limit came before any campaign.
    """
    if not isinstance(catalog, Catalog):
        raise TypeError(f"catalog must be a Catalog, got {type(catalog).__name__}")
    if not isinstance(campaign, Campaign):
        raise TypeError(f"campaign must be a Campaign, got {type(campaign).__name__}")
    solver = SolverOptions() if solver is None else solver
    check_options(solver, gap, time_limit_s, workers, scheduler, executor)
    for message in ignored_options(campaign, solver):
        warnings.warn(message, IgnoredOptionWarning, stacklevel=2)
    campaign.check_candidates(catalog)
    # one pricing per launch and count (a range of n prices each count; max-value
    # enumerates each count)
    tasks = sum(m.n - campaign.fewest(k) + 1 for k, m in enumerate(campaign.missions))
    workers = guarded_workers(workers, scheduler, executor, tasks)
    at_once = pricings_at_once(workers, scheduler, executor, tasks)
    if (problem := size_problem(len(catalog), at_once)) is not None:
        raise MissionError(problem)
    clock = time.perf_counter()
    deadline = np.inf if time_limit_s is None else clock + time_limit_s
    say = log or (lambda line: None)
    inline = executor is None and scheduler is None and (workers == 1 or tasks == 1)
    with PricingRuns(inline, executor, scheduler, workers, tasks, stop, say) as run:
        if campaign.objective != "min-dv" or pareto:
            from .value import value_campaign  # checks pareto too

            return value_campaign(catalog, campaign, solver=solver, gap=gap,
                                  deadline=deadline, say=say, stop=stop or (lambda: False),
                                  clock=clock, run=run, pareto=pareto)  # fmt: skip
        search = CampaignSearch(catalog, campaign, solver, gap, deadline, say, run, stop)
        search.at_once = 1 if inline else at_once
        greedy = search.solve()
    if search.plan is None:
        raise SolverFailure(
            "no campaign was found within the limits (the launches fly alone, but the pool "
            "of missions holds no disjoint set of them): allow more time"
        )
    return _solution(search, greedy, time.perf_counter() - clock)


def _status(search: CampaignSearch) -> RunStatus:
    """``optimal`` within 0.1 % (or 0.01 m/s per mission), ``within_gap`` within a wider
    requested gap, ``feasible`` when a limit stopped the search first."""
    if not search.within():
        return RunStatus.FEASIBLE
    optimal = max(OPTIMAL_GAP_REL * search.upper, OPTIMAL_GAP_MPS * len(search.launches))
    return RunStatus.OPTIMAL if search.upper - search.lower <= optimal * (1 + 1e-9) \
        else RunStatus.WITHIN_GAP  # fmt: skip


def _solution(search: CampaignSearch, greedy: GreedyCampaign, seconds: float) -> CampaignSolution:
    status = _status(search)
    missions = tuple(_mission_solution(search, column, status) for column in search.plan)
    status, notes = tank_status(missions, status, search.notes)
    greedy_paths = tuple(search.path_text(c) for c in greedy.missions)
    return CampaignSolution(
        campaign=search.campaign,
        catalog=search.catalog,
        missions=missions,
        total_dv_mps=float(sum(m.total_dv_mps for m in missions)),
        lower_bound_mps=shown_bound(min(search.lower, search.upper)),
        status=status,
        greedy=replace(greedy, paths=greedy_paths),
        history=tuple(search.history),
        columns=len(search.pool),
        pricings=search.pricings,
        seconds=seconds,
        notes=notes,
        gap_requested=search.gap_rel,
    )


def _mission_solution(search: CampaignSearch, column: Column, status: RunStatus):
    return mission_solution(search.variant(column.launch, len(column.debris)), column, status,
                            "+".join(sorted(search.backends)) or search.solver.backend)
