"""Missions of fewer than two debris in a value campaign's range: none, or one.

A max-value (or value-per-dv) campaign may let a mission remove between ``n_min`` and
``n`` debris with ``n_min`` as low as 0 (:class:`~sdc_cvx.inputs.campaign.Campaign`).
No search is needed for those counts, and the certified search does not take them (a
:class:`~sdc_cvx.inputs.mission.Mission` visits at least two debris):

* ``n = 0``: the launch is not used: no debris, 0 m/s;
* ``n = 1``: the vehicle is launched onto the debris' orbit (as every mission's first
  debris is, without an injection orbit), so its ΔV is the debris' operations alone
  (``operations_dv_mps``; 0 by default), within ``tmax_days`` if its operations are.

Each is exact: its ΔV is its bound.  :func:`price_few` answers such a count as the
pricing (:func:`~sdc_cvx.campaign.pricing.price`) answers the others, and
:func:`price_counts` sends the others to the campaign's runs.
"""

from __future__ import annotations

import dataclasses
from dataclasses import replace

import numpy as np

from ..errors import MissionInfeasible
from ..planner.fixed_path import PathSchedule
from ..planner.nodes import MissionNodes
from .pricing import Column, Launch, Pricing

FEWEST_SEARCHED = 2
"""The fewest debris the certified search takes (a mission's ``n``)."""


def no_legs(end_day: float) -> PathSchedule:
    """The schedule of a path without legs, ending at ``end_day`` [days]."""
    empty = np.zeros(0)
    return PathSchedule(0.0, 0.0, empty, empty, empty, empty, empty, empty, float(end_day),
                        0, 0, 0.0, np.zeros(0, dtype=int))  # fmt: skip


def price_few(launch: Launch, n: int, *, prices=None, ceiling_mps=None, exclude=(),
              **_search_options) -> Pricing:  # fmt: skip
    """Every mission of ``n`` (0 or 1) debris of ``launch``, cheapest first under
    ``prices`` (ΔV plus the prices of its debris), as a :class:`Pricing`.

    ``ceiling_mps``: only the missions under it under the prices (the enumeration's
    ceiling); ``exclude``: catalog rows left out.  The other options of a pricing (time
    limit, tolerances) mean nothing here: the answer is exact and immediate.
    """
    if n == 0:
        columns = [Column(launch.index, (), (), 0.0, 0.0, no_legs(0.0))]
        reduced = [0.0]
    else:
        nodes = MissionNodes.of(launch.catalog, launch.mission)
        left_out = set(nodes.excluded) | {int(k) for k in exclude}
        tmax = launch.mission.tmax_days
        rows = [i for i in range(len(launch.catalog))
                if i not in left_out and nodes.deorbit_days[i] <= tmax]  # fmt: skip
        priced = np.zeros(len(launch.catalog)) if prices is None else np.asarray(prices, float)
        columns = [Column(launch.index, (i,), (i,), float(nodes.cost_mps[i]),
                          float(nodes.cost_mps[i]), no_legs(nodes.deorbit_days[i]))
                   for i in rows]  # fmt: skip
        reduced = [c.dv_mps + float(priced[c.debris[0]]) for c in columns]
    order = np.argsort(reduced, kind="stable")
    kept = [(columns[j], reduced[j]) for j in order
            if ceiling_mps is None or reduced[j] <= ceiling_mps]  # fmt: skip
    lower = min(reduced) if reduced else np.inf
    status = "optimal" if columns else "infeasible"
    return Pricing(launch.index, tuple(c for c, _ in kept), float(lower), float(lower), status,
                   0.0)  # fmt: skip


def price_counts(run, launches: list[Launch], items) -> list[Pricing]:
    """The pricing of every ``(k, n, options)`` of ``items``: launch ``k`` with ``n``
    debris, the certified search's options; counts of fewer than
    :data:`FEWEST_SEARCHED` debris answered here (:func:`price_few`), the others on
    ``run`` (the campaign's :class:`~sdc_cvx.campaign.pricing_runs.PricingRuns`), all at
    once."""
    items = list(items)
    searched = [(replace(launches[k], mission=launches[k].mission.replace(n=n)), options)
                for k, n, options in items if n >= FEWEST_SEARCHED]  # fmt: skip
    answers = iter(run(searched) if searched else ())
    return [next(answers) if n >= FEWEST_SEARCHED else price_few(launches[k], n, **options)
            for k, n, options in items]  # fmt: skip


def used_launches(plan: list, campaign):
    """The missions of ``plan`` that remove debris (each column keeps its launch's index in
    ``campaign``), the campaign of their launches alone, and a note naming each launch
    left unused (``n_min = 0``): (columns, campaign, notes).

    Raises
    ------
    MissionInfeasible
        No launch is used.
    """
    used = [c for c in plan if c.debris]
    if len(used) == len(plan):
        return plan, campaign, ()
    if not used:
        raise MissionInfeasible("proven: the most valuable campaign uses no launch (no "
                                "mission within its budget removes any value); raise "
                                "dv_budget_mps or give values to the debris that fly")  # fmt: skip
    kept = [c.launch for c in used]
    unused = [f"{campaign.launch_days[c.launch]:g}" for c in plan if not c.debris]
    smaller = dataclasses.replace(
        campaign, launch_days=tuple(campaign.launch_days[k] for k in kept),
        missions=tuple(campaign.missions[k] for k in kept),
        dv_budget_mps=tuple(campaign.dv_budget_mps[k] for k in kept),
        n_min=tuple(campaign.fewest(k) for k in kept))  # fmt: skip
    note = (f"launch day{'s' * (len(unused) > 1)} {', '.join(unused)} left unused (n_min = 0: "
            "no mission there adds value within its budget); the campaign lists the "
            f"{len(used)} launches used")  # fmt: skip
    return used, smaller, (note,)
