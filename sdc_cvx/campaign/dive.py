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
   once it is fixed, is least (its artificial columns at their cost: the least repair
   first) is fixed (strong diving: a look one step ahead, an LP of the pool each); and
   so on until :data:`FINISH` launches are left;
4. those launches share out the debris left by the same search as the whole
   (:class:`~sdc_cvx.campaign.min_dv.CampaignSearch`, over the debris left), its best
   campaign ending the dive: the last missions of a dive cost the most, and the pool's
   LP prices them worst.  Where the launches left have no campaign (the residual LP
   needs its artificial columns after step 2, or that search finds none, or none in its
   time), the last mission fixed is undone and barred, and the dive goes on
   (:data:`BACKTRACKS` times at most).

Its campaign becomes the plan if it is cheaper; the bound is untouched (the dive adds
missions that fly, never a proof).  It dives again while the time left is at least the
last dive's (:data:`DIVES`), each from the pool the ones before grew.  From the state of a
whole GTOC9-all search where its dive starts (2384 columns, the plan 9560.46 m/s, 656 s
left): three dives in 506 s, 11383.79, 8933.41 and 9826.74 m/s, so the plan becomes
8933.41 m/s, as the whole search then did in 1587 s of 1800 (bound 5477.34 m/s); a single
dive is one greedy path through an LP whose integer gap is 43 %, and where it ends depends
on the pool (``docs/design.md`` §10).

References
----------
.. [1] R. Sadykov, F. Vanderbeck, A. Pessoa, I. Tahiri and E. Uchoa, "Primal heuristics
   for branch and price: the assets of diving methods", INFORMS Journal on Computing
   31(2), 251-267, 2019.
.. [2] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from ..errors import SdcError
from .master import MasterLP, solve_lp
from .pricing import Column, renumbered

CANDIDATES = 8
"""Missions the LP holds most that are tried, each by its residual LP, at each step."""
REPAIR_ROUNDS = 3
"""Pricing rounds at most in one step while the residual LP needs its artificial columns."""
REPAIR_SHARE = 0.5
"""Share of the time left that a repair's pricings may take, each from when it starts."""
WEIGHT_TOL = 1e-6
"""An LP weight (or artificial weight) below this is 0."""
FINISH = 4
"""Launches left that step 4 shares out by a search of their own (as many as the SL-16
cluster's programme: 18 debris, four missions, certified in a minute)."""
FINISH_SHARE = 0.5
"""Share of the time left that step 4's search may take."""
DIVES = 3
"""Dives at most (:func:`dive`)."""
BACKTRACKS = 5
"""Missions undone at most, each where the launches left have no campaign: the residual
LP needs its artificial columns after the repair, or step 4's search finds none."""


def dive(search) -> None:
    """Dive from ``search``'s pool (a :class:`~sdc_cvx.campaign.min_dv.CampaignSearch`
    whose column generation has run); its plan improves if a dive's campaign is cheaper.

    Dives again (:data:`DIVES` at most) while the time left is at least the last dive's:
    each from the pool the dives before it grew (their repairs' and step 4's missions),
    its first mission another than theirs.  A dive ends early, with a note saying why, at
    the time limit or where the missions fixed leave no campaign the pricing can find.
    """
    firsts: set[tuple] = set()
    for _ in range(DIVES):
        started = time.perf_counter()
        first = _dive_once(search, firsts)
        left = search.remaining()
        if first is None or (left is not None and left < time.perf_counter() - started):
            return
        firsts.add(first)


def _dive_once(search, firsts: set[tuple]) -> tuple | None:
    """One dive, its first mission none of ``firsts`` (keys); the key of its first
    mission, or None where it fixed none."""
    launches = len(search.launches)
    search.say("  diving on the master LP, one mission at a time")
    fixed: dict[int, Column] = {}
    barred: set[tuple] = set()  # keys of missions undone: the launches left had none
    order: list[int] = []  # the launches in the order their missions were fixed
    backtracks = 0
    before = search.upper
    # a search over a part of a campaign (regroup's window, step 4's) does not finish
    # by a search of its own parts again
    finishes = search.regroups
    while len(fixed) < launches:
        if search.out_of_time():
            search.notes.append(f"{search.limit_reached()} during the dive, its campaign "
                                f"unfinished ({len(fixed)} of {launches} missions)")
            return None
        lp, columns = _repaired(search, fixed)
        if lp.artificial > WEIGHT_TOL:  # not even its LP: no campaign of the launches left
            failed = "no campaign of the launches left was found"
        elif finishes and fixed and launches - len(fixed) <= FINISH:
            rest = _finish(search, fixed)
            if rest is not None:
                fixed |= {column.launch: column for column in rest}
                search.record(f"dive (the {len(rest)} launches left shared out by their own "
                              f"search: {sum(c.dv_mps for c in rest):.2f} m/s)")
                break
            failed = "their own search found no campaign of the launches left"
        else:
            column, value = _strongest(search, lp, columns, fixed,
                                       barred if fixed else barred | firsts)  # fmt: skip
            if column is not None:
                fixed[column.launch] = column
                order.append(column.launch)
                left = (f"the LP left {value:.2f} m/s" if np.isfinite(value) else
                        "the pool cannot finish it: the launches left are priced next")
                search.record(f"dive ({len(fixed)} of {launches} missions fixed, {left})",
                              value if np.isfinite(value) else None)  # fmt: skip
                continue
            failed = "every mission left to fix was undone before"
        # where the launches left have no campaign, the mission fixed last is undone
        if not finishes or not order or backtracks == BACKTRACKS or search.out_of_time():
            undone = f" (after {backtracks} missions undone)" if backtracks else ""
            search.notes.append(f"the dive ended with {len(fixed)} of {launches} missions "
                                f"fixed: {failed}{undone}")  # fmt: skip
            search.say(f"  {search.notes[-1]}")
            return fixed[order[0]].key if order else None
        backtracks += 1
        barred.add(fixed.pop(order.pop()).key)
        search.say(f"  dive: {failed}; the last mission fixed is undone ({backtracks} of "
                   f"{BACKTRACKS})")  # fmt: skip
    value = float(sum(column.dv_mps for column in fixed.values()))
    if value < search.upper - 1e-9:
        search.upper, search.plan = value, [fixed[k] for k in range(launches)]
    search.say(f"  the dive's campaign: {value:.2f} m/s; the plan {before:.2f} -> "
               f"{search.upper:.2f} m/s")  # fmt: skip
    return fixed[order[0]].key if order else None


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


def _strongest(search, lp: MasterLP, columns: list[Column], fixed: dict[int, Column],
               barred=frozenset()) -> tuple[Column | None, float]:  # fmt: skip
    """Step 3: of the :data:`CANDIDATES` missions of the launches left that the LP holds
    most (none whose key is ``barred``), the one whose residual LP is least once it is
    fixed, and that LP's value (``inf`` where the pool alone cannot finish it: the next
    step's pricing repairs); None where the LP holds none.  A residual LP that needs its
    artificial columns counts them at their cost, so the least of those needs the least
    repair, and among equals costs least (not the most held: GTOC9-all's whole search
    fixed 13 missions that way, to 13109 m/s)."""
    held = sorted((k for k, c in enumerate(columns) if c.launch not in fixed
                   and lp.weights[k] > WEIGHT_TOL and c.key not in barred),
                  key=lambda k: -lp.weights[k])[:CANDIDATES]  # fmt: skip
    if not held:
        return None, np.inf
    best, best_lp = None, None
    for k in held:
        trial = fixed | {columns[k].launch: columns[k]}
        after = _lp(search, residual(columns, trial))
        if best_lp is None or after.value < best_lp.value:
            best, best_lp = columns[k], after
    return best, best_lp.value if best_lp.artificial <= WEIGHT_TOL else np.inf


def _finish(search, fixed: dict[int, Column]) -> list[Column] | None:
    """Step 4: the best campaign of the launches left over the debris left (the same
    search, :data:`FINISH_SHARE` of the time left), as columns of the whole; None where
    it finds none (none exists, or none in its time)."""
    catalog, campaign = search.catalog, search.campaign
    used = {i for column in fixed.values() for i in column.debris}
    rows = [i for i in range(len(catalog)) if i not in used]
    left = [k for k in range(len(search.launches)) if k not in fixed]
    ids = [catalog.ids[i] for i in rows]
    must = [catalog.ids[i] for i in search.must if i not in used]
    part = campaign.removing(ids, left)
    if len(must) < len(ids):  # not every debris left must go: those that must
        part = dataclasses.replace(part, must_remove=tuple(must))
    left_s = search.remaining()
    deadline = (search.deadline if left_s is None
                else time.perf_counter() + FINISH_SHARE * left_s)  # fmt: skip
    try:
        sub = type(search)(catalog.subset(ids), part, search.solver, search.gap_rel, deadline,
                           lambda line: None, search.run, search.stop)  # fmt: skip
        sub.regroups, sub.at_once = False, search.at_once  # no part within a part
        sub.solve()
    except SdcError:  # none exists, or none in its time
        return None
    if sub.plan is None:
        return None
    search.pool.add(renumbered(c, rows, len(ids), len(catalog), left)
                    for c in sub.pool.columns)  # fmt: skip
    return [renumbered(c, rows, len(ids), len(catalog), left) for c in sub.plan]
