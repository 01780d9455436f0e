"""A first campaign of high value, for the max-value search to narrow from.

The exact enumeration of a programme (:mod:`~sdc_cvx.campaign.value`) is narrowed to the
missions that can beat the best campaign in hand (:mod:`~sdc_cvx.campaign.value_bound`):
the better that campaign, the fewer missions remain.  On the McKnight top 50 the rounds of
column generation find good campaigns slowly, while the best one is plain to see: the
most valuable debris that can fly together, shared out among the launches.

So: take the debris by decreasing value, each one only if some mission within budget
already removes it with one taken before (a column found so far), until
there are as many as the missions can carry (``sum_k n_k``).  The min-ΔV campaign search
(:meth:`~sdc_cvx.campaign.min_dv.CampaignSearch.solve`, ``must_remove`` all of them, each
launch its largest count) then shares them out.  Its missions within their budget (and
tank) are columns of the full catalog: whatever it finds, the value search stays exact,
the start only makes it narrower.

References
----------
.. [1] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005 (primal heuristics before reduced-cost fixing).
"""

from __future__ import annotations

import itertools

import numpy as np

from ..errors import MissionError, SdcError, SolverFailure
from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..milp.types import SolverOptions
from .min_dv import CampaignSearch
from .pricing import Column
from .pricing import renumbered as _in_catalog

START_GAP = 0.05
"""Relative gap at which the min-ΔV search of the start stops (any campaign will do)."""


def pairable_by_value(values: np.ndarray, columns, count: int) -> list[int]:
    """Catalog rows by decreasing value, each paired within budget with one taken before.

    Parameters
    ----------
    values : ndarray
        Value of each debris (catalog order).
    columns : iterable of Column
        Missions within budget: two debris fly together if one removes both.
    count : int
        How many to take at most.

    Returns
    -------
    list of int
    """
    pairs = {frozenset(pair) for c in columns for pair in itertools.combinations(c.debris, 2)}
    chosen: list[int] = []
    for i in np.argsort(-values, kind="stable"):
        if len(chosen) == count or values[i] <= 0:
            break
        if not chosen or any(frozenset((int(i), j)) in pairs for j in chosen):
            chosen.append(int(i))
    return chosen


def high_value_start(catalog: Catalog, campaign: Campaign, values: np.ndarray, columns, *,
                     solver: SolverOptions, deadline: float, say, stop, run,
                     fits=None) -> list[Column]:  # fmt: skip
    """Missions of a campaign of high value (columns of ``catalog``; empty if none found).

    Parameters
    ----------
    catalog : Catalog
    campaign : Campaign
        A max-value campaign (budgets ``dv_budget_mps``).
    values : ndarray
    columns : iterable of Column
        Missions within budget found so far (their pairs guide the choice).
    solver : SolverOptions
    deadline : float
        ``time.perf_counter()`` at which the start must end.
    say, stop, run
        As :func:`~sdc_cvx.campaign.value.solve_max_value` has them.
    fits : callable, optional
        Whether a mission fits its vehicle's tank.

    Returns
    -------
    list of Column
    """
    counts = [mission.n for mission in campaign.missions]
    chosen = pairable_by_value(values, columns, sum(counts))
    if len(chosen) < sum(counts):
        say(f"  no first campaign: {len(chosen)} debris pair within budget, {sum(counts)} "
            "wanted")  # fmt: skip
        return []
    ids = tuple(catalog.ids[i] for i in chosen)
    say(f"  a first campaign: the {len(ids)} most valuable debris that pair within budget, "
        "shared out at least ΔV")  # fmt: skip
    try:
        search = shared_out(catalog, campaign, ids, solver, START_GAP, deadline, run, stop)
    except SdcError as err:  # no such campaign: the value search goes on without it
        say(f"  no first campaign ({err})")
        return []
    found = [c for c in in_catalog(search, catalog, ids)
             if c.dv_mps <= campaign.dv_budget_mps[c.launch] and (fits is None or fits(c))]
    say(f"  first campaign: {len(found)} of {len(counts)} missions within budget, worth "
        f"{sum(values[list(c.debris)].sum() for c in found):g}")  # fmt: skip
    return found


def shared_out(catalog: Catalog, campaign: Campaign, ids, solver: SolverOptions, gap: float,
               deadline: float, run, stop) -> CampaignSearch:  # fmt: skip
    """The min-ΔV search over the debris ``ids`` only, every one removed, each mission
    ``campaign``'s largest count (solved: its ``plan`` and bounds).

    Raises
    ------
    SdcError
        No such campaign (infeasible, or none before ``deadline``).
    """
    if any(m.must_include or m.first for m in campaign.missions):
        raise MissionError("a mission names debris it must remove or start from")
    shared = campaign.removing(ids, ranges=False)
    search = CampaignSearch(catalog.subset(ids), shared, solver, gap, deadline,
                            lambda line: None, run, stop)  # fmt: skip
    search.solve()
    if search.plan is None:
        raise SolverFailure("no campaign within the limit")
    return search


def in_catalog(search: CampaignSearch, catalog: Catalog, ids) -> list[Column]:
    """The plan of :func:`shared_out` as columns of ``catalog``."""
    rows = [catalog.ids.index(k) for k in ids]
    return [_in_catalog(c, rows, len(ids), len(catalog)) for c in search.plan]
