"""The greedy campaign, the baseline a campaign's answer is measured against.

One mission at a time, in launch order: the cheapest mission of the debris the earlier
missions left, then its debris removed.  Where debris must be removed (``must_remove``,
``remove_all``), each mission takes as many of those left as it can (a prize on each, so
the search prefers them), and as many debris as the later missions could not take
(``n`` within its range).  Greedy is not optimal (``docs/design.md`` §10): an early
mission can take a debris a later one needed.
"""

from __future__ import annotations

import numpy as np

from .pricing import Column, Pricing
from .result import GreedyCampaign

PRIZE_FACTOR = 10.0
"""A debris that must be removed is worth this many times the dearest launch alone [m/s]:
more than any mission's ΔV difference, so the search takes as many as it can."""
REPAIR_PASSES = 6
"""Greedy passes at most after greedy, where it found no campaign (:func:`repair`)."""
REPAIR_BOOST = 0.5
"""Prize added on a debris (in units of the base prize) each time a pass leaves it over."""


def greedy_campaign(search, alone: list[Pricing]) -> GreedyCampaign:
    """The greedy campaign of ``search`` (a :class:`~sdc_cvx.campaign.min_dv.CampaignSearch`),
    each launch's missions priced alone in ``alone`` (one per launch, its cheapest count).

    Returns
    -------
    GreedyCampaign
        ``dv_mps`` None where a launch found no mission with the debris left, or
        required debris are left over (``why`` says which).
    """
    return _greedy_pass(search, alone, np.ones(len(search.catalog)))


def repair(search, alone: list[Pricing], greedy: GreedyCampaign,
           tries: int = REPAIR_PASSES) -> None:  # fmt: skip
    """Greedy passes again, until the pool holds a campaign, where debris must be removed.

    Where greedy fails (a launch finds no mission among the debris the earlier ones
    left), each new pass puts more prize on the debris the passes before left over
    (squeaky wheel: Joslin and Clements, 1999), so that earlier missions take them.  Every
    pass's missions join the pool, and the integer master may combine missions of
    several passes: it is asked after each.  Before each new pass, the pass that failed
    at the last launch is mended by exchanges (:func:`swap_in`).  Stops at the first
    campaign, after ``tries`` passes, or at the time limit.

    References
    ----------
    .. [1] D. E. Joslin and D. P. Clements, "Squeaky wheel optimization", Journal of
       Artificial Intelligence Research, 10, 353-373, 1999.
    """
    weight = np.ones(len(search.catalog))
    failed = greedy
    for attempt in range(2, tries + 3):
        if search.plan is not None or not failed.left_over or search.out_of_time():
            return
        swap_in(search, alone, failed)
        if search.plan is not None or attempt == tries + 2:
            return
        left_over = list(failed.left_over)
        weight[left_over] += REPAIR_BOOST
        ids = ", ".join(search.catalog.ids[i] for i in left_over)
        search.say(f"  no campaign yet: greedy pass {attempt}, more prize on the debris the "
                   f"pass before left over ({ids})")  # fmt: skip
        failed = _greedy_pass(search, alone, weight, quiet=True)
        search.master_plan()


def swap_in(search, alone: list[Pricing], failed: GreedyCampaign) -> None:
    """Mend a greedy pass that left debris over for its last launch, by exchanges.

    The last launch takes its mission from every debris, as many of those left over as
    it can (a prize on each); some of the others it takes belong to earlier missions.  Each
    such mission is priced again with one debris left over in place of the one taken,
    for every pair.  All these missions join the pool: where the exchanges fit (each
    debris left over has a mission that takes it in place of one the last launch took),
    the integer master combines them with the pass's other missions into a campaign.
    This is an ejection chain of one step (Glover, 1996): where greedy's last launch is
    left a set no mission flies, most of that set and a few debris of earlier missions
    often fly.

    References
    ----------
    .. [1] F. Glover, "Ejection chains, reference structures and alternating path methods
       for traveling salesman problems", Discrete Applied Mathematics, 65, 223-253, 1996.
    """
    last = len(search.launches) - 1
    left = list(failed.left_over)
    if len(failed.missions) != last or not left or search.out_of_time():
        return
    if not search.campaign.fewest(last) <= len(left) <= search.launches[last].mission.n:
        return
    dearest = _dearest(alone)
    prices = np.zeros(len(search.catalog))
    prices[left] = -PRIZE_FACTOR * dearest
    taken = search.price_all([(search.variant(last, len(left)), search.unpriced(
        prices=prices, gap_rel=0.0, tol_mps=max(search.tol, search.gap_rel / 2 * dearest)))])[0]
    search.pool.add(taken.columns)
    if not taken.columns:
        return
    debris = taken.columns[0].debris
    owner = {i: column for column in failed.missions for i in column.debris}
    stolen = [i for i in debris if i in owner]  # the others: left over, or no one's
    rest = [i for i in left if i not in debris]
    tasks = []
    for e in stolen:
        for r in rest:  # e's mission with r in its place: those debris exactly
            column = owner[e]
            keep = (set(column.debris) - {e}) | {r}
            tasks.append((search.variant(column.launch, len(column.debris)), search.unpriced(
                exclude=[i for i in range(len(search.catalog)) if i not in keep])))  # fmt: skip
    ids = ", ".join(search.catalog.ids[i] for i in stolen)
    search.say(f"  {search.launches[last].label()} takes {len(left) - len(rest)} of the "
               f"{len(left)} debris left over and {ids} of earlier missions: "
               f"{len(tasks)} exchanges priced")  # fmt: skip
    for result in search.price_all(tasks):
        search.pool.add(result.columns)
    search.master_plan()


def _dearest(alone: list[Pricing]) -> float:
    """The dearest launch alone [m/s] (1 km/s where none has a plan): the scale of the
    prizes on debris that must be removed."""
    return max((p.upper_mps for p in alone if np.isfinite(p.upper_mps)), default=1e3)


def _greedy_pass(search, alone, weight, quiet: bool = False):
    """One greedy campaign, the prize on a required debris ``weight`` times the base one.

    Returns
    -------
    GreedyCampaign
    """
    removed: list[int] = []
    missions: list[Column] = []
    required = list(search.must)
    dearest = _dearest(alone)
    capacity = [launch.mission.n for launch in search.launches]
    say = (lambda line: None) if quiet else search.say
    for k, (launch, first) in enumerate(zip(search.launches, alone, strict=True)):
        if search.out_of_time():  # Ctrl-C or the limit: no greedy campaign, the pool stays
            return GreedyCampaign(None, tuple(missions), f"{search.limit_reached()} before "
                                  f"{launch.label()}")  # fmt: skip
        left = [i for i in required if i not in removed]
        count = min(max(len(left) - sum(capacity[k + 1:]), search.campaign.fewest(k)),
                    capacity[k])  # fmt: skip
        variant = search.variant(k, count)
        if not removed and not left and first.columns and len(first.columns[0].debris) == count:
            result = first  # the first launch alone is greedy's first mission
        else:
            options = dict(exclude=removed)
            if left:  # a prize on each: the gap is then in m/s, not relative to the prizes
                prices = np.zeros(len(search.catalog))
                prices[left] = -PRIZE_FACTOR * dearest * weight[left]
                options |= dict(prices=prices, gap_rel=0.0,
                                tol_mps=max(search.tol, search.gap_rel / 2 * dearest))
            result = search.price_all([(variant, search.unpriced(**options))])[0]
            search.pool.add(result.columns)
        if not result.columns:
            why = "time limit" if result.status == "no_plan" else "no mission flies"
            after = " with the debris the earlier missions left" if removed else ""
            say(f"  greedy stops at {launch.label()}: {why}{after}")
            return GreedyCampaign(None, tuple(missions), f"{launch.label()}: {why}{after}",
                                  left_over=tuple(left) if result.status != "no_plan" else ())
        missions.append(result.columns[0])
        removed += list(result.columns[0].debris)
    if any(i not in removed for i in required):
        return GreedyCampaign(None, tuple(missions), "must_remove debris left over",
                              left_over=tuple(i for i in required if i not in removed))
    total = float(sum(c.dv_mps for c in missions))
    say(f"  greedy campaign: {total:.2f} m/s")
    return GreedyCampaign(total, tuple(missions), "")
