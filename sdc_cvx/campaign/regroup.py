"""A first campaign improved by sharing out again the debris of a few launches at a time.

Where the first campaign came from greedy mended (:func:`~sdc_cvx.campaign.greedy.repair`),
its later missions take whatever the earlier ones left, at a high ΔV.  The column
generation would improve it, but where its first rounds' prices are steep a round takes
minutes.  This step is a large neighbourhood search (Shaw, 1998) over that campaign:
for each window of :data:`GROUP` consecutive launches, the min-ΔV campaign of those
launches alone over the debris their missions remove (every one removed, each mission
within its range of counts) is solved by the same search
(:class:`~sdc_cvx.campaign.min_dv.CampaignSearch`), and every mission it priced joins
the pool.  The integer master then takes whichever missions make the campaign cheaper:
the plan can only improve, and the bound is untouched (the columns are missions that fly,
and the bound is proven by the pricing and closing steps alone).

References
----------
.. [1] P. Shaw, "Using constraint programming and local search methods to solve vehicle
   routing problems", Principles and Practice of Constraint Programming (CP98), LNCS
   1520, 417-431, 1998.
"""

from __future__ import annotations

import time

from ..errors import SdcError
from .pricing import renumbered

GROUP = 3
"""Consecutive launches shared out together (windows overlap by one launch)."""
REGROUP_SHARE = 0.25
"""Share of the time left that the windows take, all together."""


def regroup(search) -> None:
    """Share out again the debris of each window of launches of ``search``'s plan.

    ``search`` is a :class:`~sdc_cvx.campaign.min_dv.CampaignSearch` with a plan; each
    window's search is one of the same class over the window's debris and launches, with
    an equal share of :data:`REGROUP_SHARE` of the time left.
    """
    launches = len(search.launches)
    if search.plan is None or launches < 2:
        return
    windows = [list(range(start, min(start + GROUP, launches)))
               for start in range(0, launches - 1, GROUP - 1)]  # fmt: skip
    left = search.remaining()
    each = None if left is None else REGROUP_SHARE * left / len(windows)
    campaign, catalog = search.campaign, search.catalog
    before = search.upper
    for window in windows:
        if search.plan is None or search.out_of_time():
            break
        chosen = [c for c in search.plan if c.launch in window]
        rows = sorted(i for c in chosen for i in c.debris)
        ids = [catalog.ids[i] for i in rows]
        part = campaign.removing(ids, window)
        deadline = search.deadline if each is None else min(search.deadline,
                                                            time.perf_counter() + each)
        try:
            sub = type(search)(catalog.subset(ids), part, search.solver, search.gap_rel,
                               deadline, lambda line: None, search.run, search.stop)  # fmt: skip
            sub.regroups, sub.at_once = False, search.at_once  # no window within a window
            sub.solve()
        except SdcError:  # none better within its share: the plan stays
            continue
        search.pool.add(renumbered(c, rows, len(ids), len(catalog), window)
                        for c in sub.pool.columns)  # fmt: skip
        search.master_plan()
    if search.upper < before:
        search.say(f"  launches shared out again {GROUP} at a time: {before:.2f} -> "
                   f"{search.upper:.2f} m/s")  # fmt: skip
