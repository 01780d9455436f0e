"""A campaign built by diving on the master LP, one mission at a time (strong diving).

Where the column generation has solved the master LP but the pool's best campaign is far
above it, the integer master over the pool finds nothing better: its LP mixes fractions
of missions that share debris, and its MILP finds no other campaign in minutes (GTOC9-all:
the LP 5489 m/s, the plan 9560 m/s, 2859 columns).  The dive builds one:

1. the *residual* master: the missions fixed so far, and the pool's missions of the
   other launches that share no debris with them; its LP;
2. where that LP needs its artificial columns (the pool holds no way to finish), the
   launches left are priced at its prices, the fixed debris left out, until it does not
   (:data:`REPAIR_ROUNDS` rounds at most);
3. of the missions the LP holds most (:data:`CANDIDATES`), the one whose residual LP,
   once it is fixed, is least is fixed (strong diving: a look one step ahead, an LP of the
   pool each); and so on until each launch has its mission.

Its campaign becomes the plan if it is cheaper; the bound is untouched (the dive adds
missions that fly, never a proof).  From a converged pool of GTOC9-all it finds 9056.50
m/s where the plan was 9560.46 m/s, in 171-263 s; within a whole search of 1800 s it has
found nothing cheaper so far (``docs/design.md`` §10).

References
----------
.. [1] R. Sadykov, F. Vanderbeck, A. Pessoa, I. Tahiri and E. Uchoa, "Primal heuristics
   for branch and price: the assets of diving methods", INFORMS Journal on Computing
   31(2), 251-267, 2019.
.. [2] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005.
"""

from __future__ import annotations

import numpy as np

from .master import MasterLP, solve_lp
from .pricing import Column

CANDIDATES = 8
"""Missions the LP holds most that are tried, each by its residual LP, at each step."""
REPAIR_ROUNDS = 3
"""Pricing rounds at most in one step while the residual LP needs its artificial columns."""
REPAIR_SHARE = 0.5
"""Share of the time left that a repair's pricings may take, each from when it starts."""
WEIGHT_TOL = 1e-6
"""An LP weight (or artificial weight) below this is 0."""


def dive(search) -> None:
    """Dive from ``search``'s pool (a :class:`~sdc_cvx.campaign.min_dv.CampaignSearch`
    whose column generation has run); its plan improves if the dive's campaign is
    cheaper.  Ends early, the plan unchanged and a note saying why, at the time limit or
    where the missions fixed leave no campaign the pricing can find."""
    launches = len(search.launches)
    search.say("  diving on the master LP, one mission at a time")
    fixed: dict[int, Column] = {}
    before = search.upper
    while len(fixed) < launches:
        if search.out_of_time():
            search.notes.append(f"{search.limit_reached()} during the dive, its campaign "
                                f"unfinished ({len(fixed)} of {launches} missions)")
            return
        lp, columns = _repaired(search, fixed)
        if lp.artificial > WEIGHT_TOL:
            search.notes.append(f"the dive ended with {len(fixed)} of {launches} missions "
                                "fixed: no campaign of the launches left was found")
            search.say(f"  {search.notes[-1]}")
            return
        column, value = _strongest(search, lp, columns, fixed)
        fixed[column.launch] = column
        left = (f"the LP left {value:.2f} m/s" if np.isfinite(value) else
                "the pool cannot finish it: the launches left are priced next")  # fmt: skip
        search.record(f"dive ({len(fixed)} of {launches} missions fixed, {left})",
                      value if np.isfinite(value) else None)  # fmt: skip
    value = float(sum(column.dv_mps for column in fixed.values()))
    if value < search.upper - 1e-9:
        search.upper, search.plan = value, [fixed[k] for k in range(launches)]
    search.say(f"  the dive's campaign: {value:.2f} m/s; the plan {before:.2f} -> "
               f"{search.upper:.2f} m/s")  # fmt: skip


def residual(columns, fixed: dict[int, Column]) -> list[Column]:
    """The fixed missions, and the missions of ``columns`` of the other launches that
    share no debris with them."""
    used = {i for column in fixed.values() for i in column.debris}
    return list(fixed.values()) + [c for c in columns
                                   if c.launch not in fixed and used.isdisjoint(c.debris)]


def _lp(search, columns: list[Column]) -> MasterLP:
    return solve_lp(columns, len(search.launches), len(search.catalog), search.must)


def _repaired(search, fixed: dict[int, Column]) -> tuple[MasterLP, list[Column]]:
    """Steps 1 and 2: the residual LP, the launches left priced at its prices while it
    needs its artificial columns and the pricing brings new ones."""
    columns = residual(search.pool.columns, fixed)
    lp = _lp(search, columns)
    used = sorted({i for column in fixed.values() for i in column.debris})
    free = len(search.catalog) - len(used)
    left = [v for v in search.variants if v.index not in fixed and v.mission.n <= free]
    for _ in range(REPAIR_ROUNDS):
        if lp.artificial <= WEIGHT_TOL or search.out_of_time():
            break
        tasks = [(v, dict(prices=lp.prices, tol_mps=search.tol, exclude=used,
                          stop_above_mps=lp.sigma[v.index] - search.tol))
                 for v in left]  # fmt: skip
        new = sum(search.pool.add(r.columns)
                  for r in search.price_all(tasks, round_share=REPAIR_SHARE))  # fmt: skip
        columns = residual(search.pool.columns, fixed)
        lp = _lp(search, columns)
        if new == 0:
            break
    return lp, columns


def _strongest(search, lp: MasterLP, columns: list[Column],
               fixed: dict[int, Column]) -> tuple[Column, float]:  # fmt: skip
    """Step 3: of the :data:`CANDIDATES` missions of the launches left that the LP holds
    most, the one whose residual LP is least once it is fixed, and that LP's value
    (``inf`` where the pool cannot finish any of them: then the most held, and the next
    step's pricing repairs)."""
    held = sorted((k for k, c in enumerate(columns)
                   if c.launch not in fixed and lp.weights[k] > WEIGHT_TOL),
                  key=lambda k: -lp.weights[k])[:CANDIDATES]  # fmt: skip
    best, best_value = columns[held[0]], np.inf
    for k in held:
        trial = fixed | {columns[k].launch: columns[k]}
        after = _lp(search, residual(columns, trial))
        value = after.value if after.artificial <= WEIGHT_TOL else np.inf
        if value < best_value:
            best, best_value = columns[k], value
    return best, best_value
