"""The min-ΔV campaign search: column generation with a certified lower bound.

The search (``docs/design.md`` §10, run by :func:`~sdc_cvx.campaign.search.solve_campaign`),
in named steps (:class:`CampaignSearch`, one method each):

1. *Launches*: each launch's candidates with their RAANs at its launch day; each
   launch priced alone (no prices): a launch with no flyable mission makes the campaign
   infeasible, said with its day.
2. *Greedy* (the baseline): the best first mission, its debris removed, the best second
   and so on; its missions are columns too.  Where it leaves required debris over,
   exchanges with the last launch and more passes that weigh them (squeaky wheel) until
   the pool holds a campaign, whose launches are then shared out again a few at a time
   (:mod:`~sdc_cvx.campaign.regroup`).
3. *Column generation*: the master LP over the pool gives prices ``y`` on the debris and
   ``sigma_k`` on the launches; each launch is priced (in parallel: a process pool, or
   a Dask cluster); its columns join the pool.  Whatever the prices, the Lagrangian
   bound ``L(y) = sum_k B_k(y) - sum_i y_i`` is a lower bound of every campaign, where
   ``B_k(y)`` is the launch's proven lower bound of ``min over its missions of (ΔV +
   sum of the prices of their debris)`` (it equals the LP value plus the sum of the
   launches' most negative reduced costs); the best is kept.  Where debris must go, the
   master's prices stay in a box around those of the best bound
   (:mod:`~sdc_cvx.campaign.price_box`: its LP is degenerate and its own duals prove
   nothing).  The integer master over the pool is the plan.  The loop ends when no
   launch has a column of negative reduced cost (the LP is solved), or plan and bound
   meet.
   *Dive*: where the gap left is too wide to close (:data:`CLOSING_SHARE` of the plan
   or more), a campaign built on the LP one mission at a time
   (:mod:`~sdc_cvx.campaign.dive`), the plan if cheaper.
4. *Closing*: if a gap is left, every mission whose reduced cost could be below
   ``plan - L(y)`` is enumerated (a campaign cheaper than the plan can only be made of
   such missions); the integer master over the pool is then the optimum, and the same
   master priced at the paths' certified lower bounds is the bound.

References
----------
.. [1] G. B. Dantzig and P. Wolfe, "Decomposition principle for linear programs",
   Operations Research 8(1), 101-111, 1960.
.. [2] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005 (the Lagrangian bound, and reduced-cost enumeration of columns).
.. [3] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import MissionInfeasible, SolverFailure
from ..inputs.campaign import Campaign
from ..inputs.catalog import Catalog
from ..milp.types import SolverOptions
from ..planner.nodes import MissionNodes
from .dive import dive
from .greedy import greedy_campaign, repair
from .launch_bounds import shown_bound, sizes_bound
from .master import solve_ip, solve_lp
from .price_box import PriceCentre, uniform_centre
from .pricing import Column, Launch, Pricing, best_of_counts, infeasible_launch
from .regroup import regroup
from .result import GreedyCampaign

PATH_TOL_MPS = 0.01
"""Absolute tolerance of each mission's schedule [m/s] (the single mission's)."""
MAX_ROUNDS = 200
"""Column generation rounds at most."""
ROUND_SHARE = 0.25
"""Share of the time left that one round of the column generation may take: its
pricings that would take longer stop at their share of it (a round whose prices make
the pricing hard, as the first rounds after a dear campaign mended from greedy, would
otherwise take all the time)."""
ROUND_FLOOR_S = 10.0
"""Least time a pricing of a round has [s], whatever its share."""
FEWEST_WEIGHT = 4.0
"""Shares of the time of the launches alone that a launch's fewest debris has (the other
counts of its range one each): its plan is the first campaign's."""
MASTER_SHARE = 0.02
"""Share of the time left that a round's integer master may take (with a time limit):
with a few thousand columns its MILP can take minutes (GTOC9-all: over 4 minutes at a
quarter of the time left), and the closing step solves it to the end anyway."""
MASTER_FLOOR_S = 5.0
"""Least time of a round's integer master [s]."""
CLOSING_SHARE = 0.25
"""The closing step runs where the gap left is at most this share of the plan [-]: wider,
it would enumerate about every mission of every launch (GTOC9-all, 43 % after its LP was
solved: 2 GB a worker and past its time limit, the time limit not reached between steps)."""
LP_SHARE = 0.01
"""Where the gap left is too wide to close, the column generation stops once its LP is
within this share of that gap above the bound [-]: its last rounds raise the bound by
metres per second against a gap of kilometres per second (GTOC9-all: rounds 10-15, 2
minutes each, 5473.76 -> 5483.23 m/s against a gap of 4087 m/s), time the dive needs."""
EVERY_MISSION_MPS = 1e6
"""A ΔV no mission reaches [m/s] (a leg costs at most a few km/s): a window this wide
around a launch's best mission enumerates every mission that flies from it."""


@dataclass
class _Pool:
    """The columns found so far, one per (launch, path): the best schedule and the
    highest lower bound known of each."""

    columns: list[Column] = field(default_factory=list)
    index: dict = field(default_factory=dict)

    def add(self, columns) -> int:
        """Add ``columns``; the number that were new paths or cheaper schedules."""
        new = 0
        for column in columns:
            k = self.index.get(column.key)
            if k is None:
                self.index[column.key] = len(self.columns)
                self.columns.append(column)
                new += 1
                continue
            old = self.columns[k]
            new += column.dv_mps < old.dv_mps - 1e-9
            best = column if column.dv_mps < old.dv_mps else old
            lower = max(old.lower_mps, column.lower_mps)
            self.columns[k] = Column(best.launch, best.nodes, best.debris, best.dv_mps,
                                     min(lower, best.dv_mps), best.schedule)  # fmt: skip
        return new

    def __len__(self):
        return len(self.columns)


class CampaignSearch:
    """The search's state: launches, pool, best plan and bound, history; one method per
    step (see the module docstring)."""

    def __init__(self, catalog: Catalog, campaign: Campaign, solver: SolverOptions,
                 gap_rel: float, deadline: float, say, run, stop=None) -> None:  # fmt: skip
        self.catalog, self.campaign, self.solver = catalog, campaign, solver
        self.gap_rel, self.deadline, self.say, self.run = gap_rel, deadline, say, run
        self.stop = stop or (lambda: False)
        self.launches = Launch.all_of(campaign, catalog)
        # a launch with a range of n is priced once per count (its variants)
        self.variants = [replace(launch, mission=launch.mission.replace(n=count))
                         for k, launch in enumerate(self.launches)
                         for count in range(campaign.fewest(k), launch.mission.n + 1)]  # fmt: skip
        index = {k: n for n, k in enumerate(catalog.ids)}
        self.must = tuple(index[k] for k in campaign.required(catalog))
        self.pool = _Pool()
        self.upper, self.plan, self.lower = np.inf, None, -np.inf
        self.lagrangian = -np.inf  # the best Lagrangian bound L(y), that of the closing's prices
        self.history: list[dict] = []
        self.clock = time.perf_counter()
        self.pricings = 0
        self.notes: list[str] = []
        self.tol = PATH_TOL_MPS
        self.backends: set[str] = set()
        self.at_once = 1  # pricings that run at once (solve_campaign sets it)
        self.regroups = True  # a mended first campaign is shared out again (not in regroup's)
        self.centre = PriceCentre()  # the master's prices' box (launches_alone sets it)

    # ------------------------------------------------------------------ helpers
    def remaining(self) -> float | None:
        if not np.isfinite(self.deadline):
            return None
        return self.deadline - time.perf_counter()

    def out_of_time(self) -> bool:
        """True once the time limit has passed or the caller asked to stop."""
        left = self.remaining()
        return self.stop() or (left is not None and left <= 0)

    def limit_reached(self) -> str:
        """What stopped the search: the caller (Ctrl-C) or the time limit."""
        return "interrupted" if self.stop() else "time limit reached"

    def allowed(self) -> float:
        return max(self.gap_rel * abs(self.upper), PATH_TOL_MPS * len(self.launches))

    def within(self) -> bool:
        return bool(np.isfinite(self.upper) and self.upper - self.lower <= self.allowed() * (
            1 + 1e-9))  # fmt: skip

    def record(self, step: str, lp_value=None) -> None:
        lower = shown_bound(self.lower)
        self.history.append(dict(step=step, seconds=time.perf_counter() - self.clock,
                                 lower_mps=lower, upper_mps=self.upper,
                                 lp_mps=lp_value, columns=len(self.pool),
                                 pricings=self.pricings))  # fmt: skip
        plan = f"{self.upper:.2f} m/s" if np.isfinite(self.upper) else "none yet"
        if lower is None or lower <= 0:
            bound = "no useful bound yet" if lower is not None else "no bound yet"
        else:
            bound = f"bound {lower:.2f} m/s, gap {self.upper - lower:.2f} m/s"
        self.say(f"  {step}: plan {plan}, {bound}, {len(self.pool)} columns, "
                 f"{self.pricings} pricings")  # fmt: skip

    def price_all(self, tasks, *, share: bool | list = False, round_share: float | None = None,
                  ) -> list[Pricing]:  # fmt: skip
        """Run the pricing ``tasks`` (launch, keyword arguments) where they run, each with
        the schedules the pool knows of its launch's paths, none past the deadline.  A task
        that waits for a worker has that much less time; with ``share`` (the launches
        alone: without each launch's plan there is no campaign; True, or a weight per
        task) its share of the time left (the first wave given all of it took 121 s of a
        60 s limit: 27 counts of a range on 2 workers); with ``round_share``, its share
        of that part of the time left from when it starts (a round of the column
        generation: its pricings stopped there still bring their columns and a proven
        bound)."""
        left = self.remaining()
        waves = -(-len(tasks) // max(self.at_once, 1))
        least = np.zeros(len(tasks))
        if share is not False and left is not None:
            weights = np.ones(len(tasks)) * np.asarray(share, dtype=float)
            least = np.minimum(left * min(self.at_once, len(tasks)) * weights / weights.sum(),
                               left)  # fmt: skip
        if round_share is not None and left is not None:
            # each pricing its share from when it starts, not from the round's start (the
            # last wave of 50 pricings on 2 workers had waited past it and proved nothing)
            least[:] = min(max(ROUND_FLOOR_S, round_share * left / waves), left / waves)
        at = None if left is None else time.time() + left
        known: dict[int, dict] = {}
        for column in self.pool.columns:
            known.setdefault(column.launch, {})[column.nodes] = column.schedule
        out = self.run([(launch, dict(kwargs, solver=self.solver,
                                      time_limit_s=least[k] if least[k] else left,
                                      sent_at=time.time(), least_s=least[k], deadline_at=at,
                                      known=known.get(launch.index),
                                      path_tol_rel=self.gap_rel / 2))
                        for k, (launch, kwargs) in enumerate(tasks)])  # fmt: skip
        self.pricings += len(out)
        return out

    def unpriced(self, **options) -> dict:
        """Options of a pricing without prices (a launch alone, greedy): the mission's own
        gap, halved (its plan is a column and greedy's value, not a bound)."""
        return {"tol_mps": PATH_TOL_MPS, "gap_rel": self.gap_rel / 2, **options}

    def variant(self, k: int, count: int) -> Launch:
        """Launch ``k`` flying ``count`` debris."""
        return next(v for v in self.variants if v.index == k and v.mission.n == count)

    def per_launch(self, results: list[Pricing]) -> np.ndarray:
        """Each launch's least lower bound over its variants' ``results`` [m/s]."""
        bounds = np.full(len(self.launches), np.inf)
        for result in results:
            bounds[result.launch] = min(bounds[result.launch], result.lower_mps)
        return bounds

    def integer_gap(self, lp) -> bool:
        """Whether the gap left is the master's integer gap: too wide to close, and the
        LP ``lp`` (not boxed) within :data:`LP_SHARE` of it above the best bound (more
        rounds would raise the bound by no more than that; the dive may lower the plan)."""
        return bool(self.too_wide_to_close() and lp.boxed <= 1e-9 and lp.artificial <= 1e-6
                    and lp.value - self.lagrangian <= LP_SHARE * (
                        self.upper - self.lagrangian))  # fmt: skip

    def too_wide_to_close(self) -> bool:
        """A plan whose gap to the best Lagrangian bound is over :data:`CLOSING_SHARE`
        of it: the closing step would enumerate about every mission (the dive runs)."""
        return self.plan is not None and (
            self.upper - self.lagrangian > CLOSING_SHARE * self.upper)

    def master_plan(self, time_limit_s: float | None = None) -> None:
        """The integer master over the pool: the plan, if it improves (within
        ``time_limit_s``: the best campaign its MILP found by then)."""
        plan = solve_ip(self.pool.columns, len(self.launches), len(self.catalog), self.must,
                        solver=self.solver, time_limit_s=time_limit_s)  # fmt: skip
        if plan is not None:
            self.backends.add(plan.backend)
            if plan.value < self.upper - 1e-9:
                self.upper, self.plan = plan.value, [self.pool.columns[c] for c in plan.chosen]

    # ------------------------------------------------------------------ steps
    def solve(self) -> GreedyCampaign:
        """Steps 1 to 4 (the module docstring); the plan is ``self.plan``, or None."""
        alone = self.launches_alone()
        greedy = self.greedy(alone)
        if self.plan is None and greedy.dv_mps is None and self.out_of_time():
            raise SolverFailure(f"{self.limit_reached()} before any campaign was found")
        estimate = self.upper if np.isfinite(self.upper) else sum(p.upper_mps for p in alone)
        self.tol = max(PATH_TOL_MPS, self.gap_rel * estimate / (4 * len(self.launches)))
        self.record("launches alone and greedy")
        last = None
        if not self.within():
            last = self.generate_columns()
        if self.too_wide_to_close() and not self.out_of_time():
            dive(self)  # a better plan: the closing's window may then be narrow enough
        if not self.within() and not self.out_of_time() and (
                last is not None or self.plan is None):  # without a plan: no prices needed
            self.close(*(last or (None, None)))
        return greedy

    def launches_alone(self) -> list[Pricing]:
        """Step 1: each launch priced alone; infeasible launches end the campaign."""
        self.say(f"campaign: {len(self.launches)} launches, {len(self.catalog)} candidates; "
                 "each launch alone")  # fmt: skip
        # the fewest debris of every launch first, with more time: a plan for each soonest
        order = sorted(self.variants, key=lambda v: (v.mission.n, v.index))
        weights = [FEWEST_WEIGHT if v.mission.n == self.campaign.fewest(v.index) else 1.0
                   for v in order]  # fmt: skip
        results = self.price_all([(launch, self.unpriced()) for launch in order],
                                 share=weights)  # fmt: skip
        self.alone_bounds = self.per_launch(results)
        alone = [best_of_counts([r for r in results if r.launch == k])
                 for k in range(len(self.launches))]  # fmt: skip
        for launch, result in zip(self.launches, alone, strict=True):
            if result.status == "infeasible":
                raise MissionInfeasible(infeasible_launch(launch, self.campaign))
        unplanned = [launch.label() for launch, result in zip(self.launches, alone, strict=True)
                     if result.status == "no_plan"]  # fmt: skip
        if unplanned:  # a campaign needs a mission from every launch
            spent = time.perf_counter() - self.clock
            raise SolverFailure(
                f"{' and '.join(unplanned)}: " + ("interrupted before any plan" if self.stop()
                else f"the time limit stopped the search before any plan ({spent:.0f} s "
                "spent on the launches alone, each its share), so there is no campaign to "
                "return; allow more time"))  # fmt: skip
        for launch, result in zip(self.launches, alone, strict=True):
            self.pool.add(result.columns)
            best = result.columns[0] if result.columns else None
            self.say(f"  {launch.label()} alone: {result.upper_mps:.2f} m/s "
                     f"({self.path_text(best)}; {result.seconds:.1f} s)")  # fmt: skip
        # the Lagrangian bound at zero prices: every launch flies one mission, none
        # cheaper than the least its launch alone can fly; and with debris that must go
        # (remove_all: every one), the missions' sizes add up to at least their number
        self.lagrangian = float(np.sum(self.alone_bounds))
        sizes: dict[int, dict[int, float]] = {}
        for variant, result in zip(order, results, strict=True):
            sizes.setdefault(variant.index, {})[variant.mission.n] = result.lower_mps
        self.lower = max(self.lower, self.lagrangian, sizes_bound(sizes, len(self.must)))
        self.centre = uniform_centre(sizes, np.asarray(self.must, dtype=int),
                                     len(self.catalog))  # fmt: skip
        return alone

    def greedy(self, alone: list[Pricing]) -> GreedyCampaign:
        """Step 2: one mission at a time, the cheapest of the debris left; where it leaves
        required debris over and the pool holds no campaign, more passes that weigh them."""
        greedy = greedy_campaign(self, alone)
        self.master_plan()
        if self.plan is None and greedy.left_over:
            repair(self, alone, greedy)
            if self.plan is not None and self.regroups:  # mended, dear: shared out again
                regroup(self)
        return greedy

    def generate_columns(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Step 3: column generation until the LP is solved, the gap met or time out.

        Returns the prices of the best bound and the launches' bounds under them (step 4
        closes from that bound: its window is plan - L(prices)).
        """
        centre = self.centre
        last = None
        if centre.value > self.lagrangian:  # the uniform prize: a bound before any round
            self.lagrangian, last = centre.value, (centre.prices, centre.bounds)
        for round_ in range(1, MAX_ROUNDS + 1):
            if self.out_of_time():
                self.notes.append(f"{self.limit_reached()} during column generation")
                break
            width = centre.width
            lp = solve_lp(self.pool.columns, len(self.launches), len(self.catalog), self.must,
                          box=centre.box())  # fmt: skip
            tasks = [(launch, dict(prices=lp.prices, tol_mps=self.tol,
                                   stop_above_mps=lp.sigma[launch.index] - self.tol,
                                   seeds=self.seeds(launch, lp.prices)))
                     for launch in self.variants]  # fmt: skip
            results = self.price_all(tasks, round_share=ROUND_SHARE)
            bounds = self.per_launch(results)
            lagrangian = float(bounds.sum() - lp.prices.sum())
            if np.isfinite(lagrangian) and lagrangian > self.lagrangian:
                # the closing step needs the prices of the bound it closes from
                self.lagrangian, last = lagrangian, (lp.prices, bounds)
                self.lower = max(self.lower, lagrangian)
            moved = centre.update(lp.prices, bounds, lagrangian, lp.value)
            new = sum(self.pool.add(r.columns) for r in results)
            left = self.remaining()  # a round's plan is a heuristic: its share of the time
            self.master_plan(None if left is None else max(MASTER_FLOOR_S, MASTER_SHARE * left))
            box = f" in a box of ±{width:.1f} m/s" if lp.boxed > 1e-9 else ""
            self.record(f"round {round_} (LP {lp.value:.2f} m/s{box}, bound there "
                        f"{shown_bound(lagrangian) or 0:.2f} m/s{', the new centre' * moved}, "
                        f"{new} new columns)", lp.value)  # fmt: skip
            # solved: the pricing proves the LP's value (at the LP's own prices, every
            # launch's bound reaches its dual); the box LP's value is less where it binds
            slack = self.tol * len(self.launches) + 1e-9
            solved, master = lagrangian >= lp.value - slack, lp
            if solved and lp.boxed > 1e-9:
                master = solve_lp(self.pool.columns, len(self.launches), len(self.catalog),
                                  self.must)  # fmt: skip
                solved = lagrangian >= master.value - slack
            if solved and master.artificial > 1e-6:
                # the LP needs an artificial column at its optimum: no campaign is likely,
                # but a big-M cost proves it only where no price reaches it, so the closing
                # step proves it (every mission that flies, then the exact master)
                self.say("  the master LP needs its artificial columns: enumerating every "
                         "mission that flies to prove whether any campaign does")  # fmt: skip
                break
            stalled = new == 0 and (lp.boxed <= 1e-9 or not moved)  # moved: a new box
            if not solved and self.integer_gap(master):
                self.notes.append(
                    f"column generation stopped: its LP, {master.value:.2f} m/s, is within "
                    f"{master.value - self.lagrangian:.2f} m/s of the bound, and the gap left is "
                    "the master's integer gap: the time goes to the dive")  # fmt: skip
                self.say(f"  {self.notes[-1]}")
                break
            if self.within() or solved or self.out_of_time() or stalled:
                if self.out_of_time() and not self.within():
                    self.notes.append(f"{self.limit_reached()} during column generation")
                elif stalled and not solved and not self.within():
                    self.notes.append("column generation stalled: no new column")
                break
        else:
            self.notes.append(f"round limit ({MAX_ROUNDS}) of the column generation reached")
        return last

    def close(self, prices: np.ndarray | None, bounds: np.ndarray | None) -> None:
        """Step 4: every mission that could be on a cheaper campaign, then the exact master.

        Without a plan (the LP is fractional and the pool holds no campaign), every
        mission that flies is enumerated, without prices: the master over them then has
        a campaign, or proves that none exists.
        """
        if self.plan is None:
            prices, bounds = np.zeros(len(self.catalog)), np.asarray(self.alone_bounds)
            window = EVERY_MISSION_MPS
            self.say("  no campaign in the pool: every mission that flies, launch by launch")
        else:
            window = self.upper - self.lagrangian  # L(prices): the argument's own bound
            if self.too_wide_to_close():
                self.notes.append(
                    f"the closing step was not run: the gap left, {window:.2f} m/s "
                    f"({window / self.upper:.0%} of the plan), is too wide to close by "
                    "enumerating every mission within it of its launch's best"
                )  # fmt: skip
                self.say(f"  {self.notes[-1]}")
                return
            self.say(f"  closing the gap: every mission within {window:.2f} m/s of its "
                     "launch's best reduced cost")  # fmt: skip
        ceilings = np.asarray(bounds) + window + self.tol
        tasks = [(launch, dict(prices=prices, tol_mps=self.tol,
                               ceiling_mps=ceilings[launch.index]))
                 for launch in self.variants]  # fmt: skip
        results = self.price_all(tasks)
        new = sum(self.pool.add(r.columns) for r in results)
        self.master_plan()
        if all(r.complete for r in results):
            # a path the enumeration left out costs at least its launch's ceiling under the
            # prices: a floor of its own where its schedule's bound is weaker (one cut off
            # early under large prices bounds it by 0)
            enumerated = {c.key for r in results for c in r.columns}
            costs = [c.lower_mps if c.key in enumerated else max(
                c.lower_mps, ceilings[c.launch] - float(np.sum(prices[list(c.debris)])))
                for c in self.pool.columns]  # fmt: skip
            lower = solve_ip(self.pool.columns, len(self.launches), len(self.catalog), self.must,
                             solver=self.solver, costs=costs)  # fmt: skip
            if lower is None:
                raise MissionInfeasible(
                    "proven: no campaign removes each debris at most once with these "
                    f"missions ({self.missions_text()}): every mission that flies from each "
                    "launch was enumerated, and no choice of one per launch shares no debris"
                    f"{' and removes every must_remove debris' if self.must else ''}. Relax one "
                    "of: fewer debris per mission (n), must_remove, a longer mission "
                    "(tmax_days), more candidates"
                )
            self.lower = max(self.lower, min(lower.value, self.upper))
        else:
            self.notes.append(f"{self.limit_reached()} while closing the gap")
        self.record(f"closing ({new} new columns)")

    # ------------------------------------------------------------------ words
    def seeds(self, launch: Launch, prices) -> list[tuple[int, ...]]:
        """The pool's cheapest paths of ``launch`` under the prices (incumbents to start)."""
        mine = [c for c in self.pool.columns
                if c.launch == launch.index and len(c.debris) == launch.mission.n]  # fmt: skip
        mine.sort(key=lambda c: c.dv_mps + float(np.sum(prices[list(c.debris)])))
        return [c.nodes for c in mine[:3]]

    def path_text(self, column: Column | None) -> str:
        if column is None:
            return "no plan"
        ids = MissionNodes.of(self.launches[column.launch].catalog,
                              self.launches[column.launch].mission).catalog.ids  # fmt: skip
        return " -> ".join(ids[k] for k in column.nodes)

    def missions_text(self) -> str:
        counts = self.campaign.counts_text().split(", ")
        return ", ".join(f"n = {n} from day {d:g}" for d, n in zip(
            self.campaign.launch_days, counts, strict=True))  # fmt: skip
