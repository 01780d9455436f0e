"""The most valuable campaign: each mission within its ΔV budget and range of debris.

``objective = "max-value"`` (:data:`~sdc_cvx.inputs.campaign.OBJECTIVES`, issue 27): the
campaign that removes the most value, each mission k flying between ``n_min`` and ``n``
debris for a total ΔV (operations included) of at most its budget ``B_k``; among
campaigns of equal value, the least ΔV.  When each mission's vehicle has a tank
(:attr:`~sdc_cvx.inputs.campaign.Campaign.tank_limited`), ``B_k`` is at most the ΔV
the tank can fly at all (a relaxation: the bound stays a proof) and each mission must
also fit the tank with its schedule's propellant (:func:`tank_fits`); a path whose
least-ΔV schedule does not is undecided, counted by the value bound.

How it is solved and why the answer is certified.  For every launch and every count n of
its range, the certified search enumerates every path of n debris whose lower bound is
under the budget (``certify``'s ``ceiling_mps``: it certifies each such path's best
schedule and proves, by its relaxation, that every other path costs more than ``B_k``).
A path whose schedule is within the budget is a mission that flies (a *column*); one
whose bound is under the budget but whose best schedule is above it, within the path
tolerance, is *undecided*.  The exact master then chooses one column per launch, each
debris removed at most once: first the most value (an integer program), then, holding
that value, the least ΔV.  The same master over the columns *and* the undecided paths,
at their bounds, gives the most value any campaign could have and the least ΔV it could
cost: the answer is ``optimal`` when the two agree within the gap.

First, where plane changes no budget pays split the debris into groups that never share a
mission (:mod:`~sdc_cvx.campaign.plane_bound`), the most any campaign is worth may force
its debris: the min-ΔV campaign that removes exactly them, certified, is then the answer
if its missions fit their budgets (no enumeration).

The enumeration grows with the number of paths under the budget: it is exact for the
small and medium catalogs a programme is screened on.  When it does not end within
:data:`PLAIN_SHARE` of the time limit (the McKnight top 50 under 1 km/s a mission), rounds
of column generation on the value (:mod:`~sdc_cvx.campaign.value_bound`) give a bound that
holds whatever happens next and good campaigns, and the enumeration starts again narrowed
to the missions that can beat the best of them.  A limit then still leaves the best
campaign found and the value bound (``feasible``, with its value gap).

References
----------
.. [1] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

import time
from dataclasses import replace
from functools import partial

import numpy as np

from ..errors import MissionError, MissionInfeasible, SdcError, SolverFailure
from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..inputs.vehicle import propellant_budget
from ..milp.types import SolverOptions
from ..planner.nodes import MissionNodes
from ..solution import OPTIMAL_GAP_MPS, RunStatus
from .few import FEWEST_SEARCHED, price_counts, used_launches
from .plane_bound import campaign_plane_bound
from .pricing import Column, Launch, Pricing, mission_solution
from .result import CampaignSolution, GreedyCampaign, tank_status
from .value_bound import cardinality_narrowing, counts_of, lagrangian_bound
from .value_pool import VALUE_TOL, _priced, best_value, pareto_front
from .value_start import high_value_start, in_catalog, shared_out

PLAIN_SHARE = 0.15
"""Share of the time limit the plain enumeration (every mission within budget) may take
before the Lagrangian rounds (:mod:`~sdc_cvx.campaign.value_bound`) take over."""
BOUND_SHARE = 0.6
"""Share of the time left then that the Lagrangian rounds may take before the narrowed
enumeration."""
START_SHARE = 0.25
"""Share of the time left then that the first campaign of high value may take
(:func:`~sdc_cvx.campaign.value_start.high_value_start`)."""
FORCED_SHARE = 0.5
"""Share of the time left the min-ΔV campaign of the debris the plane-change bound forces
may take (:func:`_forced`)."""
PATH_GAP_REL = 1e-4
"""Relative tolerance of each enumerated path's schedule (undecided paths lie within it
of their budget)."""


def enumerate_missions(launches: list[Launch], campaign: Campaign, *, solver: SolverOptions,
                       deadline: float, say, stop, run, narrowed=None, found=(),
                       exclude=(), fits=None) -> tuple[list, list, bool]:  # fmt: skip
    """Every mission of every launch within its budget (columns), the undecided paths, and
    whether the enumeration is complete (no limit stopped it).

    Per (launch, debris set) only the cheapest is kept: the master needs no other.  The
    searches run on ``run`` (the campaign's
    :class:`~sdc_cvx.campaign.pricing_runs.PricingRuns`: this process, a local pool or a
    Dask cluster), every launch's at once for each count above its fewest: the fewest
    first, then one more, and so on.  ``narrowed`` (``{(launch, count): (prices,
    ceiling)}``, :meth:`~sdc_cvx.campaign.value_bound.ValueBound.narrowing`) enumerates
    under prices and a ceiling instead: only the missions a campaign worth at least the
    best found can hold (a count not in it has none), and ``exclude`` leaves out the debris
    such a campaign cannot hold
    (:func:`~sdc_cvx.campaign.value_bound.cardinality_narrowing`).  ``found``: missions
    within budget found before, kept as columns.  ``fits(column)``: whether a mission fits
    its vehicle's tank (:func:`tank_fits`); one within budget that does not is undecided
    (another schedule of its path might fit: the value bound counts it).
    """
    columns: dict[tuple, Column] = {(c.launch, c.debris): c for c in sorted(
        found, key=lambda c: c.dv_mps, reverse=True)}  # the cheapest order of each set
    undecided: dict[tuple, Column] = {}
    # per (launch, set): the least bound of any of its orders the enumeration certified (a
    # mission found before keeps its own: the rounds certify only the best to TOL_MPS)
    floor: dict[tuple, float] = {}
    complete = True
    # the fewest debris of every launch first: a limit then leaves a campaign to return
    steps = sorted((n - campaign.fewest(k), k, n) for k, n in counts_of(launches, campaign))
    done: dict[tuple, Pricing] = {}
    waves: set[int] = set()
    for extra, k, n in steps:
        launch, budget = launches[k], float(campaign.dv_budget_mps[k])
        if extra not in waves:  # the first of its count: every launch's at once
            waves.add(extra)
            left = deadline - time.perf_counter()
            if left <= 0 or stop():
                complete = False
                break
            wave = [(j, m) for e, j, m in steps if e == extra
                    and (narrowed is None or (j, m) in narrowed)]  # fmt: skip
            tasks = [(j, m, dict(solver=solver, gap_rel=PATH_GAP_REL, path_tol_rel=PATH_GAP_REL,
                                 time_limit_s=None if not np.isfinite(left) else left,
                                 exclude=tuple(int(i) for i in exclude),
                                 sent_at=time.time())  # a task waiting for a worker has less
                      | _under(narrowed, j, m, float(campaign.dv_budget_mps[j])))
                     for j, m in wave]  # fmt: skip
            done.update(zip(wave, price_counts(run, launches, tasks), strict=True))
        if (k, n) not in done:  # narrowed away: proven to hold no mission that matters
            done[(k, n)] = Pricing(k, (), np.inf, np.inf, "optimal", 0.0)
        pricing = done[(k, n)]
        complete &= pricing.complete or pricing.status == "infeasible"
        within = 0
        for column in pricing.columns:
            key = (k, column.debris)
            floor[key] = min(floor.get(key, np.inf), column.lower_mps)
            if column.dv_mps <= budget and (fits is None or fits(column)):
                within += 1
                if key not in columns or column.dv_mps < columns[key].dv_mps:
                    columns[key] = column
            elif column.lower_mps <= budget and (
                    key not in undecided or column.lower_mps < undecided[key].lower_mps):
                undecided[key] = column
        if narrowed is not None and (k, n) not in narrowed:
            say(f"  {launch.label()}, n = {n}: no mission worth the best campaign (the bound "
                "proves it)")  # fmt: skip
        else:
            say(f"  {launch.label()}, n = {n}: {within} missions within {budget:g} m/s "
                f"({len(pricing.columns)} paths certified)")  # fmt: skip
    undecided = {key: c for key, c in undecided.items() if key not in columns}
    # the set kept through its cheapest order, bounded by its least bound of any order
    columns = {key: replace(c, lower_mps=floor.get(key, c.lower_mps))
               for key, c in columns.items()}  # fmt: skip
    undecided = {key: replace(c, lower_mps=floor[key]) for key, c in undecided.items()}
    return list(columns.values()), list(undecided.values()), complete


def tank_fits(launches: list[Launch]):
    """``fits(column)``: the propellant of the column's schedule (its legs' and its
    operations' ΔV, :func:`~sdc_cvx.inputs.vehicle.propellant_budget`, kits left at each
    debris) fits its launch's tank; a launch unused (no debris) flies no vehicle."""
    operations = {}

    def fits(column: Column) -> bool:
        launch = launches[column.launch]
        if column.launch not in operations:
            operations[column.launch] = MissionNodes.of(launch.catalog, launch.mission).cost_mps
        return not column.nodes or propellant_budget(
            launch.mission.vehicle, column.schedule.dv_mps,
            operations[column.launch][list(column.nodes)],
            kit_at_start=launch.mission.injection is None).fits  # fmt: skip

    return fits


def _under(narrowed, k: int, n: int, budget: float) -> dict:
    """The enumeration's prices and ceiling of launch ``k`` and count ``n``: every mission
    within the budget, or the narrowed ones."""
    prices, ceiling = (None, None) if narrowed is None else narrowed[(k, n)]
    if prices is None:
        return dict(ceiling_mps=budget + OPTIMAL_GAP_MPS)
    return dict(prices=prices, ceiling_mps=ceiling + OPTIMAL_GAP_MPS)


def _share(share: float, deadline: float) -> float:
    """The ``time.perf_counter()`` at which ``share`` of the time to ``deadline`` is gone."""
    now = time.perf_counter()
    return now + share * (deadline - now) if np.isfinite(deadline) else deadline


def solve_max_value(catalog: Catalog, campaign: Campaign, *, solver: SolverOptions, gap: float,
                    deadline: float, say, stop, run, shortcut: bool = True):  # fmt: skip
    """The most valuable campaign (see the module docstring).

    ``shortcut``: where the plane-change bound forces the debris of the most valuable
    campaigns (:mod:`~sdc_cvx.campaign.plane_bound`), prove it by the min-ΔV search over
    them alone (:func:`_forced`), without the enumeration (whose missions a Pareto front
    needs: ``--pareto`` runs without it).

    Returns
    -------
    dict
        ``plan`` (columns, launch order), ``launches``, ``value`` and ``value_bound``
        (no campaign removes more), ``dv_mps`` and ``dv_bound_mps`` (no campaign of that
        value costs less), ``status``, ``columns`` (missions found), ``notes``.

    Raises
    ------
    MissionInfeasible
        A launch has no mission within its budget, or no campaign removes each debris
        once (proven: the enumeration was complete).
    """
    launches = Launch.all_of(campaign, catalog)
    values = campaign.value_of(catalog.ids)
    say(f"campaign: the most value, {len(launches)} launches, {len(catalog)} candidates; "
        "every mission within its budget")  # fmt: skip
    price = campaign.price_per_value_mps if campaign.objective == "value-per-dv" else None
    fits = tank_fits(launches) if campaign.tank_limited else None
    if fits is not None:
        say("  each mission must fit its vehicle's tank: budgets "
            f"{', '.join(f'{b:.2f}' for b in campaign.dv_budget_mps)} m/s"
            f"{' (the most ΔV each tank flies)' if campaign.budgets_from_tank else ''}, then "
            "each mission's propellant")  # fmt: skip
    enumerate_all = partial(enumerate_missions, launches, campaign, solver=solver, say=say,
                            stop=stop, run=run, fits=fits)  # fmt: skip
    plane = campaign_plane_bound(catalog, campaign, values)
    if price is None and shortcut and plane.forced is not None:
        forced = _forced(catalog, campaign, launches, values, plane, solver=solver, gap=gap,
                         deadline=deadline, say=say, stop=stop, run=run, fits=fits)  # fmt: skip
        if forced is not None:
            return forced
    upper, priced = plane.value, len(counts_of(launches, campaign))
    proven_from = -np.inf  # the pool holds every mission of a campaign worth at least this
    # every mission within budget, if that ends in a share of the time (small programmes)
    columns, undecided, complete = enumerate_all(
        deadline=deadline if price is not None else _share(PLAIN_SHARE, deadline))
    if not complete and price is None and not stop():
        # a bound and good campaigns first, then the missions that can beat them
        say("  the enumeration does not end in its share of the time: a value bound and "
            "campaigns first, then only the missions that can beat them")  # fmt: skip
        start = high_value_start(catalog, campaign, values, columns, solver=solver,
                                 deadline=_share(START_SHARE, deadline), say=say, stop=stop,
                                 run=run, fits=fits)  # fmt: skip
        bound = lagrangian_bound(
            launches, campaign, values, solver=solver, deadline=_share(BOUND_SHARE, deadline),
            say=say, stop=stop, run=run, best_value=lambda cs: best_value(
                cs, values, len(launches), len(catalog), solver=solver)[1],
            columns=tuple(columns) + tuple(start))  # fmt: skip
        found, upper = tuple(bound.columns.values()) + tuple(columns), min(bound.proven, upper)
        found = tuple(c for c in found if fits is None or fits(c))  # missions that fly
        priced += (bound.rounds + 1) * len(counts_of(launches, campaign))
        best = best_value(list(found), values, len(launches), len(catalog), solver=solver)[1]
        narrowed, excluded = None, ()
        if np.isfinite(best):  # what a campaign worth more than it must have
            excluded, fewest = cardinality_narrowing(
                values, [launch.mission.n for launch in launches], best)
            budgets = campaign.dv_budget_mps
            narrowed = bound.narrowing(values, budgets, best) or {
                (k, n): (None, budgets[k]) for k, n in counts_of(launches, campaign)}
            narrowed = {(k, n): how for (k, n), how in narrowed.items() if n >= fewest[k]}
            say(f"  to beat {best:g}: {len(excluded)} debris ruled out by their value, "
                f"{len(narrowed)} of {len(counts_of(launches, campaign))} counts left")
            proven_from = best
        columns, undecided, complete = enumerate_all(deadline=deadline, found=found,
                                                     narrowed=narrowed, exclude=excluded)
    if price is None:
        plan, value = best_value(columns, values, len(launches), len(catalog), solver=solver)
    else:
        plan, value = _priced(columns, values, price, len(launches), len(catalog), solver)
    over_tank = [c for c in undecided if fits is not None and not fits(c)
                 and c.dv_mps <= campaign.dv_budget_mps[c.launch]]  # fmt: skip
    if plan is None:
        if complete and over_tank and len(over_tank) == len(undecided):
            return dict(plan=None, launches=launches, notes=(
                f"no campaign found: the least-ΔV schedules of the {len(over_tank)} missions "
                "within budget need more propellant than their tanks hold (a schedule of "
                "more ΔV, spent later on a lighter vehicle, might need less and is not "
                "searched); give a larger tank or fewer debris",))  # fmt: skip
        if complete and not undecided:
            empty = [launch.label() for launch in launches
                     if not any(c.launch == launch.index for c in columns)]  # fmt: skip
            limit = ("its tank's ΔV" if getattr(campaign, "budgets_from_tank", False)
                     else "its ΔV budget")  # fmt: skip
            raise_ = ("give a larger tank (propellant_kg)"
                      if getattr(campaign, "budgets_from_tank", False) else "raise dv_budget_mps")
            why = (f"no mission of {', '.join(empty)} fits {limit}" if empty else
                   "the missions within budget cannot remove each debris once")  # fmt: skip
            raise MissionInfeasible(f"proven: {why} (every path enumerated); {raise_}, "
                                    "lower n_min or lengthen tmax_days")
        return dict(plan=None, launches=launches, notes=(
            "the limit stopped the enumeration before a campaign was found",))
    chosen = [columns[c] for c in plan.chosen]
    dv = float(sum(c.dv_mps for c in chosen))
    # the most any campaign could be worth, and the least that value could cost
    everything = columns + undecided
    lows = np.array([c.lower_mps for c in everything])
    if price is None:
        floor_plan, value_bound = best_value(everything, values, len(launches), len(catalog),
                                             solver=solver, costs=lows)  # fmt: skip
        dv_bound = floor_plan.value if value_bound <= value + VALUE_TOL * max(1.0, value) \
            else 0.0  # fmt: skip
    else:  # no campaign's ΔV - price · value is below the same over every path's bound
        floor_plan, _ = _priced(everything, values, price, len(launches), len(catalog), solver,
                                lows)  # fmt: skip
        value_bound = value  # not what is proven here: the priced objective is
        dv_bound = dv - max((dv - price * value) - floor_plan.value, 0.0)
    if price is None:  # the Lagrangian bound holds whether the enumeration ended or not
        value_bound = min(value_bound, upper) if complete else upper
    allowed = max(gap * dv, OPTIMAL_GAP_MPS * len(launches))
    proven = complete and value_bound <= value + VALUE_TOL * max(1.0, value) \
        and dv - dv_bound <= allowed * (1 + 1e-9)  # fmt: skip
    notes = []
    if not complete:
        notes.append("a limit stopped the enumeration: missions within budget may be missing")
    if len(undecided) > len(over_tank) and value_bound > value:
        notes.append(f"{len(undecided) - len(over_tank)} paths within the path tolerance of "
                     "their budget are undecided: the value bound counts them")  # fmt: skip
    if over_tank and value_bound > value:
        notes.append(f"{len(over_tank)} missions within budget need more propellant than "
                     "their tank holds on their least-ΔV schedule (another schedule might "
                     "not): the value bound counts them")  # fmt: skip
    status = RunStatus.OPTIMAL if proven else RunStatus.FEASIBLE
    return dict(plan=chosen, launches=launches, value=value,
                value_bound=value_bound if price is None and np.isfinite(value_bound)
                else None, dv_mps=dv, pricings=priced,
                dv_bound_mps=dv_bound if complete else None, status=status,
                columns=len(columns), notes=tuple(notes), complete=complete,
                pool=(columns, undecided, values), proven_from=proven_from)  # fmt: skip


def _forced(catalog, campaign, launches, values, plane, *, solver, gap, deadline, say, stop,
            run, fits):  # fmt: skip
    """The most valuable campaign where ``plane`` forces its debris: the min-ΔV campaign
    that removes exactly them, if it is certified and its missions fit their budgets (and
    tanks); else None (the enumeration goes on)."""
    counts = [launch.mission.n for launch in launches]
    if len(plane.forced) != sum(counts) or min(values[list(plane.forced)]) <= 0:
        return None  # room for other debris of no value: not every campaign is these
    ids = tuple(catalog.ids[i] for i in plane.forced)
    say(f"  no mission removes debris {np.degrees(plane.max_turn_rad):.2f} deg apart (a plane "
        f"change of 2 v sin(dI/2) at {plane.v_min_mps / 1e3:.3f} km/s, the slowest speed "
        f"flown, would exceed every budget): {plane.groups} groups of debris, no campaign "
        f"worth more than {plane.value:g}, and only these {len(ids)} debris reach it; "
        "their least ΔV campaign:")  # fmt: skip
    try:  # a share of the time at most: the enumeration may follow
        search = shared_out(catalog, campaign, ids, solver, gap, _share(FORCED_SHARE, deadline),
                            run, stop)  # fmt: skip
    except SdcError as err:
        say(f"  none ({err}): every mission within budget is enumerated next")
        return None
    plan = in_catalog(search, catalog, ids)
    over = [c for c in plan if c.dv_mps > campaign.dv_budget_mps[c.launch] * (1 + 1e-12)
            or (fits is not None and not fits(c))]  # fmt: skip
    dv, dv_bound = float(sum(c.dv_mps for c in plan)), max(float(search.lower), 0.0)
    allowed = max(gap * dv, OPTIMAL_GAP_MPS * len(launches))
    if over or dv - dv_bound > allowed * (1 + 1e-9):
        say(f"  {'a mission over its budget' if over else 'its ΔV not proven'}: every "
            "mission within budget is enumerated next")  # fmt: skip
        return None
    return dict(plan=plan, launches=launches, value=plane.value, value_bound=plane.value,
                dv_mps=dv, pricings=search.pricings, dv_bound_mps=dv_bound,
                status=RunStatus.OPTIMAL, columns=len(search.pool), complete=True,
                notes=(f"the value bound is the plane changes' ({plane.groups} groups of debris "
                       "that may share a mission)",), pool=(plan, [], values))  # fmt: skip


def value_campaign(catalog: Catalog, campaign: Campaign, *, solver: SolverOptions, gap: float,
                   deadline: float, say, stop, clock: float, run,
                   pareto: int = 0) -> CampaignSolution:  # fmt: skip
    """:func:`solve_max_value` as a :class:`CampaignSolution` (``solve_campaign``'s answer
    for ``objective = "max-value"``; its searches run on ``run``, as a min-dv campaign's
    pricing does), with ``pareto`` points of :func:`pareto_front` (none: 0)."""
    if not isinstance(pareto, int) or isinstance(pareto, bool) or pareto < 0:
        raise MissionError(f"pareto must be a number of campaigns >= 0, got {pareto!r}")
    if pareto and campaign.objective != "max-value":
        raise MissionError("pareto: value against ΔV needs objective = 'max-value' (with "
                           "each mission's dv_budget_mps)")  # fmt: skip
    found = solve_max_value(catalog, campaign, solver=solver, gap=gap, deadline=deadline,
                            say=say, stop=stop, run=run, shortcut=not pareto)  # fmt: skip
    front = ()
    if pareto and found["plan"] is not None:
        columns, undecided, values = found["pool"]
        proven_from = found.get("proven_from", -np.inf)
        front, catalog_ids = pareto_front(
            columns, undecided, values, len(campaign), len(catalog), pareto, solver=solver,
            proven=found["complete"], proven_from=proven_from), catalog.ids  # fmt: skip
        front = tuple(row | {"missions": [[catalog_ids[i] for i in path if i < len(catalog_ids)]
                                          for path in row["missions"]]}
                      for row in front)  # fmt: skip
        say(f"  value against ΔV: {len(front)} campaigns of the front")
        if not found["complete"]:
            found["notes"] += ("the front's ΔV bounds are not proven (a limit stopped the "
                               "enumeration of the missions within budget)",)
        elif any(row["dv_bound_mps"] is None for row in front):
            found["notes"] += (f"the front's ΔV bounds of values below {proven_from:g} are not "
                               "proven (the enumeration was narrowed to the missions of "
                               f"campaigns worth at least {proven_from:g})",)
    if found["plan"] is None:
        why = found["notes"][0]
        raise SolverFailure(why if why.startswith("no campaign") else f"{why}: allow more time")
    status = found["status"]
    plan, campaign, unused = used_launches(found["plan"], campaign)  # n_min = 0: left out
    found["notes"] += unused  # and a mission of one debris keeps its launch's Mission:
    sized = [replace(launch, mission=launch.mission.replace(n=len(c.debris)))
             if len(c.debris) >= FEWEST_SEARCHED else launch
             for launch, c in ((found["launches"][c.launch], c) for c in plan)]  # fmt: skip
    missions = tuple(mission_solution(launch, c, status, solver.backend)
                     for launch, c in zip(sized, plan, strict=True))  # fmt: skip
    status, notes = tank_status(missions, status, found["notes"])
    value, bound = (None if v is None else v + 0.0  # + 0.0: never "-0"
                    for v in (found["value"], found["value_bound"]))
    say(f"  value {value:g} (the most any campaign removes: "
        f"{'not proven' if bound is None else f'{bound:g}'}), {found['dv_mps']:.2f} m/s")
    return CampaignSolution(
        campaign=campaign, catalog=catalog, missions=missions,
        total_dv_mps=found["dv_mps"], lower_bound_mps=found["dv_bound_mps"], status=status,
        greedy=GreedyCampaign(None, why=f"not computed for objective = {campaign.objective!r}"),
        columns=found["columns"], pricings=found["pricings"],
        seconds=time.perf_counter() - clock, notes=notes, gap_requested=gap,
        history=(dict(step="the most value, its least ΔV", seconds=time.perf_counter() - clock,
                      lower_mps=found["dv_bound_mps"], upper_mps=found["dv_mps"], lp_mps=None,
                      columns=found["columns"], pricings=found["pricings"]),),
        value=value, value_bound=bound, pareto=front)  # fmt: skip
