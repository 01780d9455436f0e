"""The most valuable campaign at programme scale: a Lagrangian bound, and the prices that
narrow the exact enumeration to the missions that can matter.

:mod:`~sdc_cvx.campaign.value` proves a max-value campaign by enumerating every mission
within its budget.  On a programme (the 50 most concerning derelicts, 1 km/s a mission)
that enumeration does not end in ten minutes.  Column generation on the value finds a
good campaign and a bound first, and tells the enumeration which missions it may skip.

The bound.  Let ``w_i`` be the value of debris i, ``W(c)`` the value a mission c removes
and ``y_i >= 0`` any prices on the debris.  A campaign flies one mission ``c_k`` per launch,
no debris twice, so::

    sum_k W(c_k) = sum_k [W(c_k) - y(c_k)] + sum_k y(c_k) <= sum_k U_k + sum_i y_i = UB,

where ``y(c)`` sums the prices of c's debris and ``U_k`` bounds the *reduced value*
``W(c) - y(c)`` of every mission of launch k within its budget ``B_k``.  Two bounds of
``U_k`` hold for every count n of the launch's range: the sum of the n largest
``max(w_i - y_i, 0)``, and, for any multiplier ``mu > 0`` [value per m/s]::

    W(c) - y(c) = mu * (ΔV(c) - [ΔV(c) + sum_{i in c} p_i]) <= mu * (B_k - L_k(mu)),
    p_i = -(w_i - y_i) / mu,

for every c with ``ΔV(c) <= B_k``, where ``L_k(mu)`` is the certified search's lower bound
of ``ΔV + sum p_i`` over every mission of the launch (the pricing of a min-dv campaign,
:func:`~sdc_cvx.campaign.pricing.price`, with these prices: a negative price is a prize).
Any ``y >= 0`` and ``mu > 0`` give a valid bound.  The rounds take ``y`` from the master
LP over the missions found (most value) and move each ``mu`` along the subgradient
``B_k - ΔV`` of the mission the pricing found best (a factor 2 at first, its square root
each time the direction turns).

A second bound needs no search: a campaign removes at most ``sum_k n_k`` debris, so it is
worth at most the sum of that many largest ``max(w_i, 0)``.  It is often the better of the
two on a programme (the Lagrangian bound decomposes by launch and loses that coupling);
the value bound reported is the least of the two, the narrowing uses ``UB``.  Used the
other way round (:func:`cardinality_narrowing`), it rules out, for a campaign worth at
least V, every debris j with ``w+_j <= s_S`` and ``w+_j + T - s_S < V`` (``T`` the sum of
the ``S = sum_k n_k`` largest, ``s_S`` the S-th: such a campaign holds j and at most S - 1
others) and every count n of launch k with ``top(n + S - n_k) < V`` (``top(m)``: the sum
of the m largest): the enumeration leaves those debris out of every search and skips
those counts.

The enumeration it narrows.  In a campaign worth at least V, mission ``c_k`` has
``W(c_k) - y(c_k) >= U_k - (UB - V)`` (the other launches and the prices give at most
``UB - U_k``), hence, within budget::

    ΔV(c_k) + sum_{i in c_k} p_i <= B_k - (U_k - (UB - V)) / mu.

The certified search's enumeration under that ceiling, at those prices, finds every such
mission (every path whose bound is under the ceiling), so the most valuable campaign, and
the least ΔV of that value, are among what it returns when V is a campaign already found.
A count whose ceiling is below the pricing's lower bound holds no such mission.  The
prices widen the ΔV a path may have (up to the ceiling minus its prizes): where that can
exceed the budget, the narrowed search is not a subset of the plain one (every path within
the budget), and the plain one is run instead — it holds every such mission too.

References
----------
.. [1] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005 (the Lagrangian bound, reduced-cost fixing).
.. [2] M. L. Fisher, "The Lagrangian relaxation method for solving integer programming
   problems", Management Science 27(1), 1-18, 1981 (the subgradient step).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..milp.types import SolverOptions
from .few import price_counts
from .master import solve_lp

TOL_MPS = 0.2
"""Gap each pricing closes [m/s]: a value slack of ``mu * TOL_MPS`` per launch."""
STALE_ROUNDS = 2
"""Rounds that find no better campaign and lower the bound by less than :data:`STALE_REL`
before the rounds stop."""
STALE_REL = 0.01
VALUE_SLACK = 1e-8
"""Relative slack [-] on the value to reach when debris and counts are ruled out by the
values alone (above the master's value tolerance: nothing it could hold is lost)."""
NARROW_ONLY_SUBSETS = True
"""Narrow a count by prices only where that is a subset of its plain enumeration (a speed
rule: the proof holds either way, and the tests run both)."""
FIRST_STEP = 2.0
"""First factor of a multiplier's step (its square root after each turn)."""


@dataclass
class ValueBound:
    """What the rounds proved and found.

    Attributes
    ----------
    upper : float
        No campaign is worth more (``inf``: no bound yet): the Lagrangian bound
        ``UB`` the narrowing is derived from.
    most : float
        The sum of the ``Σ_k n_k`` largest values: no campaign removes more debris
        than its missions' counts (a bound of its own; :attr:`proven` is the least).
    prices : ndarray
        The prices ``y_i`` of that bound, shape (N,).
    reduced : ndarray
        ``U_k`` of that bound, per launch.
    multipliers : dict
        ``mu`` [value per m/s] of each (launch, count) priced for that bound.
    lowers : dict
        The pricing's lower bound ``L_k(mu)`` [m/s] of each (launch, count) priced then.
    columns : dict
        Every mission found within its budget: ``{(launch, debris): Column}``, the
        cheapest order of each set.
    rounds : int
    """

    upper: float = np.inf
    most: float = np.inf
    prices: np.ndarray | None = None
    reduced: np.ndarray | None = None
    multipliers: dict = field(default_factory=dict)
    lowers: dict = field(default_factory=dict)
    columns: dict = field(default_factory=dict)
    rounds: int = 0

    @property
    def proven(self) -> float:
        """No campaign is worth more: the least of the two bounds."""
        return min(self.upper, self.most)

    def narrowing(self, values: np.ndarray, budgets, value: float) -> dict:
        """``{(launch, count): (prices, ceiling)}`` under which the enumeration finds every
        mission of a campaign worth at least ``value`` (see the module docstring); a count
        left out has none (its ceiling is below its proven lower bound).  ``prices`` is
        None where the narrowed search would not be a subset of the plain one (some path
        under its ceiling may be over budget): that count is enumerated under its budget.
        Empty when the bound is not finite."""
        if not np.isfinite(self.upper) or not np.all(np.isfinite(self.reduced)):
            return {}
        slack = max(self.upper - value, 0.0)
        narrowed = {}
        for (k, n), mu in self.multipliers.items():
            ceiling = float(budgets[k]) - (self.reduced[k] - slack) / mu + TOL_MPS
            if ceiling < self.lowers[(k, n)]:
                continue
            prices = -(values - self.prices) / mu
            # the most ΔV a path of n debris under the ceiling may have
            widest = ceiling - np.sort(prices)[:n].sum()
            subset = widest <= budgets[k] or not NARROW_ONLY_SUBSETS
            narrowed[(k, n)] = (prices if subset else None, ceiling)
        return narrowed


def cardinality_narrowing(values: np.ndarray, counts: list[int], value: float):
    """Debris and counts no campaign worth at least ``value`` can have, from the values
    alone (the module docstring's second bound, used the other way round).

    With ``S = sum(counts)`` and ``T`` the sum of the ``S`` largest ``w+ = max(w, 0)``
    (``s_S`` the S-th largest): a campaign holding debris j with ``w_j <= s_S`` is worth at
    most ``w+_j + T - s_S``; one of m debris at most the sum of the m largest, and launch
    k flying n debris makes m at most ``n + S - counts[k]``.

    Parameters
    ----------
    values : ndarray
        Value of each catalog row.
    counts : list of int
        Each launch's most debris.
    value : float
        The value to reach (a campaign in hand).

    Returns
    -------
    excluded : ndarray of int
        Rows no such campaign removes.
    fewest : list of int
        Per launch, the fewest debris such a campaign flies on it (0: no limit).
    """
    plus = np.maximum(np.asarray(values, dtype=float), 0.0)
    ranked = np.sort(plus)[::-1]
    total = sum(counts)
    if not np.isfinite(value) or total > len(ranked) or total == 0:
        return np.empty(0, dtype=int), [0] * len(counts)
    top = np.concatenate([[0.0], np.cumsum(ranked)])  # top[m]: the m largest
    need = value - VALUE_SLACK * max(1.0, abs(value))
    last = ranked[total - 1]
    excluded = np.flatnonzero((plus <= last) & (plus + top[total] - last < need))
    fewest = [int(np.searchsorted(top, need - 1e-12 * max(1.0, abs(need))))
              - (total - n) for n in counts]  # fmt: skip
    return excluded, [max(f, 0) for f in fewest]


def counts_of(launches, campaign) -> list[tuple[int, int]]:
    """``(launch, count)`` of every count in every launch's range of n."""
    return [(k, n) for k, launch in enumerate(launches)
            for n in range(campaign.fewest(k), launch.mission.n + 1)]  # fmt: skip


def _master_prices(columns: list, launches: int, values: np.ndarray, before=None):
    """Prices ``y`` of the debris: the duals of the LP of the most value over ``columns``
    (clipped to [0, w]: any y >= 0 bounds, above w_i it only weakens), or ``before`` (zeros)
    while some launch has no column."""
    if {c.launch for c in columns} != set(range(launches)):
        return np.zeros(len(values)) if before is None else before
    lp = solve_lp(columns, launches, len(values),
                  costs=-np.array([values[list(c.debris)].sum() for c in columns]))
    return np.clip(lp.prices, 0.0, values)


def _largest(reduced: np.ndarray, n: int) -> float:
    """The sum of the ``n`` largest of ``max(reduced, 0)``: no mission of n debris has
    more reduced value."""
    return float(np.sort(np.maximum(reduced, 0.0))[::-1][:n].sum())


def lagrangian_bound(launches, campaign, values: np.ndarray, *, solver: SolverOptions,
                     deadline: float, say, stop, run, best_value, columns=(),
                     max_rounds: int = 12, gap_rel: float = 1e-3) -> ValueBound:  # fmt: skip
    """Rounds of column generation on the value (see the module docstring).

    Parameters
    ----------
    launches : list of Launch
    campaign : Campaign
        Its ``dv_budget_mps`` and ranges of n.
    values : ndarray
        Value of each catalog row.
    solver : SolverOptions
    deadline : float
        ``time.perf_counter()`` at which the rounds stop.
    say, stop, run
        Progress lines; asked between rounds; runs a list of pricing tasks (the
        campaign's :class:`~sdc_cvx.campaign.pricing_runs.PricingRuns`).
    best_value : callable
        ``best_value(columns) -> value`` of the most valuable campaign they make
        (``-inf``: none).
    columns : sequence of Column
        Missions within budget found before (the first prices come from them).
    max_rounds : int
    gap_rel : float
        Stop once the best campaign found is within this of the bound (or after
        :data:`STALE_ROUNDS` rounds that find no better campaign and lower the bound by
        less than :data:`STALE_REL`).

    Returns
    -------
    ValueBound
        The least bound met and everything found.
    """
    budgets = np.asarray(campaign.dv_budget_mps, dtype=float)
    counts = counts_of(launches, campaign)
    mu = {(k, n): max(_largest(values, n), 1e-9) / budgets[k] for k, n in counts}
    step = dict.fromkeys(counts, FIRST_STEP)
    heading = dict.fromkeys(counts, 0)
    found = ValueBound(most=float(np.sort(np.maximum(values, 0.0))[::-1][:sum(
        launch.mission.n for launch in launches)].sum()))  # fmt: skip
    for column in sorted(columns, key=lambda c: c.dv_mps, reverse=True):
        found.columns[(column.launch, column.debris)] = column
    y = _master_prices(list(found.columns.values()), len(launches), values)
    value, stale = -np.inf, 0
    for round_ in range(max_rounds):
        left = deadline - time.perf_counter()
        if left <= 0 or stop():
            break
        tasks = [(k, n, dict(prices=-(values - y) / mu[(k, n)], solver=solver, tol_mps=TOL_MPS,
                             time_limit_s=left, sent_at=time.time()))
                 for k, n in counts]  # fmt: skip
        reduced = np.full(len(launches), -np.inf)
        lowers, before = {}, (found.proven, value)
        for (k, n), (_, _, task), pricing in zip(counts, tasks, price_counts(run, launches, tasks),
                                                 strict=True):  # fmt: skip
            prices = task["prices"]
            for column in pricing.columns:
                key = (k, column.debris)
                if column.dv_mps <= budgets[k] and (
                        key not in found.columns or column.dv_mps < found.columns[key].dv_mps):
                    found.columns[key] = column
            lowers[(k, n)] = pricing.lower_mps
            bound = _largest(values - y, n)
            if np.isfinite(pricing.lower_mps):
                bound = min(bound, mu[(k, n)] * (budgets[k] - pricing.lower_mps))
            elif pricing.status == "infeasible" and pricing.complete:
                bound = -np.inf  # no mission of n debris flies at all
            reduced[k] = max(reduced[k], bound)
            if pricing.columns:  # the subgradient at the mission the pricing found best
                best = min(pricing.columns, key=lambda c: c.dv_mps + prices[list(c.debris)].sum())
                heading_now = 1 if best.dv_mps > budgets[k] else -1
                if heading[(k, n)] and heading_now != heading[(k, n)]:
                    step[(k, n)] = max(step[(k, n)] ** 0.5, 1.01)
                heading[(k, n)] = heading_now
        upper = float(y.sum() + reduced.sum())
        if upper < found.upper:
            found.upper, found.prices, found.reduced = upper, y.copy(), reduced.copy()
            found.multipliers, found.lowers = dict(mu), lowers
        found.rounds = round_ + 1
        columns = list(found.columns.values())
        value = best_value(columns)
        say(f"  value bound, round {round_ + 1}: {len(columns)} missions within budget, best "
            f"campaign {value:g}, no campaign above {found.proven:g}")  # fmt: skip
        # stale: neither a better bound nor a better campaign (new missions or not)
        stale = stale + 1 if found.proven > (1 - STALE_REL) * before[0] and \
            value <= before[1] else 0  # fmt: skip
        if value >= found.proven - gap_rel * max(abs(found.proven), 1e-9) or not columns \
                or stale >= STALE_ROUNDS:  # fmt: skip
            break
        y = _master_prices(columns, len(launches), values, y)
        for key in counts:  # along the subgradient: more ΔV than the budget, a dearer ΔV
            mu[key] *= step[key] ** heading[key]
    return found
