"""The plans in hand: the seeding before the first MILP, and the plans that bound the answer.

Before the first MILP a few cheap paths are re-optimised in the true model and the best
is held (:meth:`IncumbentSteps.seed`).  Every plan that meets T_max and T_min in the true
model then bounds the answer: edges on no path that could beat it leave the MILP
(:mod:`~sdc_cvx.network.dominance`), each MILP starts from it, and a step that makes it
worse goes back to it.  The answer is the cheapest re-optimised plan (Part IV-D) that
ends by T_max.

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ...errors import SolverFailure
from ...network.dominance import cheapest_paths
from ...physics.orbits import SECONDS_PER_DAY
from ...physics.plan import PlanEvaluation
from ...solution import RunStatus
from .settings import frozen_gaps

SEED_BISECTION_STEPS = 12  # a seed plan is an estimate: the driver re-optimises its answer


@dataclass
class Incumbents:
    """The plans in hand: they bound the answer and prune the MILP."""

    upper: tuple = (np.inf, None)  # cheapest plan that ends by T_max: (ΔV, (path, legs, a))
    best: tuple | None = None  # cheapest re-optimised plan that ends by T_max: (path, legs, final)
    stopped: bool = False  # a MILP reached its time limit without a solution


class IncumbentSteps:
    """The driver's steps on the plans it holds.

    A part of :class:`~sdc_cvx.planner.paper.driver._Driver`: they keep its
    :class:`Incumbents` (``held``) and read its problem (``kept``, ``geometry``,
    ``floor``) and trust state.
    """

    def seed(self):
        """Hold the cheapest re-optimised plan among paths that are cheap leg by leg.

        Skipped when the RAAN gaps are frozen (the paper's case: same answer and
        iterations with or without, three times slower with).  Two rankings,
        ``seed_paths`` paths each: by the pre-optimised edge costs (Part
        IV-B, at the references), and with leg k costed as the cheapest transfer leaving
        on the day it would leave if every leg took an equal share of the mission,
        within that share (the same pre-optimisation at the leg's own date).  On GTOC9
        the second ranks first the path that sequential linearisation alone reached
        only by chance (815th by the first); on small catalogs either may be the one.
        """
        count = self.settings.seed_paths
        if count <= 0 or frozen_gaps(self.catalog, self.mission):
            return  # frozen gaps: the day-0 costs hold all year and the MILP finds the plan
        start = time.perf_counter()
        kept, g, legs_count = self.kept, self.geometry, self.nodes.legs
        first_ops, ops = self.depart_range[0], float(self.mission.deorbit_days)
        share = (self.mission.tmax_days - first_ops - legs_count * ops) / legs_count
        if share <= 0:
            return
        leg_costs = np.stack([
            g.model.cheapest_transfer(g.origin, g.target,
                                      (first_ops + k * (share + ops)) * SECONDS_PER_DAY,
                                      share * SECONDS_PER_DAY, g.a_low, g.a_high,
                                      inclination=self.mission.drift_inclination,
                                      j2=self.mission.j2).dv
            for k in range(legs_count)
        ])  # fmt: skip
        candidates = {}  # path -> edges, in order of ranking
        for cost in (kept["dv_mps"].to_numpy(dtype=float), leg_costs):
            ranked = cheapest_paths(
                kept["i"], kept["j"], cost, legs_count, first=self.nodes.first,
                must_visit=self.nodes.must_visit, width=max(200, count),
            )  # fmt: skip
            distinct = {}  # the ranking lists date-window copies of a route: count routes
            for _, path, legs in ranked:
                distinct.setdefault(path, legs)
                if len(distinct) == count:
                    break
            for path, legs in distinct.items():
                candidates.setdefault(path, legs)
        a_ref = kept["drift_a_km"].to_numpy(dtype=float) * 1e3
        # a quick estimate of every candidate, then the full re-optimisation of the best
        fits = []
        for path, legs in candidates.items():
            path, legs = list(path), list(legs)
            final = self.true_optimum(path, legs, a_ref[legs], polish=False,
                                      bisection_steps=SEED_BISECTION_STEPS)  # fmt: skip
            if self.bound_by(path, legs, final.a_drift, final.evaluation):
                fits.append((self.total(path, final.evaluation), path, legs))
        held = None
        if fits:
            _, path, legs = min(fits, key=lambda fit: fit[0])
            final = self.true_optimum(path, legs, a_ref[legs])
            if self.bound_by(path, legs, final.a_drift, final.evaluation):
                held = (self.copies_holding(legs, final.evaluation.departure_day), final)
        self.log.timings["seed_s"] = time.perf_counter() - start
        if held is not None:
            # the held plan's copies take its sides, inclinations, radii and dates: the
            # first MILP is linearised around it and can start from it
            legs, final = held
            self.adopt(legs, final)
            self.set_references(legs, final.a_drift, final.evaluation.departure_day)
            shown = "->".join(self.id_path(self.held.upper[1][0]))
            self.log.notes.append(
                f"held before the first MILP: {shown} at {self.held.upper[0]:.1f} m/s (cheapest of "
                f"{len(candidates)} paths re-optimised); {int((~self.undominated()).sum())} of "
                f"{len(kept)} edge copies dominated"
            )

    def worse_than_held(self, path, evaluation) -> bool:
        """The MILP kept the held plan's path but its step made the true ΔV worse.

        (A step that only ends late is rejected in :meth:`run`, around the same point.)
        """
        cost, plan = self.held.upper
        if plan is None or list(plan[0]) != list(path):
            return False
        return self.total(path, evaluation) > cost + self.settings.dv_tol_mps

    def return_to_held(self):
        """Reject the step: linearise the held plan's copies around it, narrower."""
        path, legs, a_drift = self.held.upper[1]
        self.set_references(legs, a_drift, self.evaluate(path, legs, a_drift).departure_day)
        self.narrow(legs, dates=True)
        self.log.notes.append(
            f"iteration {len(self.log.history) - 1}: the step made the held plan worse in the true "
            "model: rejected, intervals narrowed around the held plan"
        )
        self.mark_rejected("made the held plan worse in the true model; back to the held plan")

    def undominated(self) -> np.ndarray:
        """Edges on some path that may cost less than the cheapest plan in hand."""
        cost = self.held.upper[0]
        return self.floor <= cost + 1e-9 * abs(cost) + 1e-6

    def bound_by(self, path, legs, a_drift, evaluation: PlanEvaluation):
        """Keep the cheapest plan seen that meets T_max and T_min in the true model.

        The plan is held in the copies whose date windows contain its departures
        (:meth:`copies_holding`), so that the MILP restricted to them admits it.
        """
        ends_in_time = self.fits(evaluation)
        cost = self.total(path, evaluation)
        if ends_in_time and cost < self.held.upper[0]:
            legs = self.copies_holding(legs, evaluation.departure_day)
            self.held.upper = (cost, (path, legs, np.asarray(a_drift, dtype=float)))
        return ends_in_time

    def copies_holding(self, legs, departure_day) -> list[int]:
        """For each leg, the copy of its edge whose date window holds its departure [days].

        A copy is taken only with the leg's own drift side and inclination (the plan
        flew those); a leg with no such copy keeps its own.
        """
        g, (lo, hi) = self.geometry, self.trust.windows
        edge = self.kept["i"].to_numpy() * len(self.catalog) + self.kept["j"].to_numpy()
        out = []
        for copy, day in zip(legs, departure_day, strict=True):
            holds = (edge == edge[copy]) & (lo <= day + 1e-9) & (day <= hi + 1e-9)
            holds &= (g.side == g.side[copy]) & np.isclose(g.inc_drift, g.inc_drift[copy])
            out.append(int(copy) if holds[copy] or not holds.any() else int(np.argmax(holds)))
        return out

    def fits(self, evaluation: PlanEvaluation) -> bool:
        """The plan ends by T_max and no transfer is shorter than T_min (true model)."""
        return evaluation.end_day <= self.mission.tmax_days + 1e-6 and bool(
            np.all(evaluation.duration_days >= self.mission.shortest_leg_days - 1e-6)
        )

    def total(self, path, evaluation) -> float:
        """Total ΔV of a plan: its transfers plus the operations at its debris [m/s]."""
        return float(evaluation.dv_mps.sum() + self.nodes.cost_mps[path].sum())

    def answer(self, status: RunStatus):
        """The best re-optimised plan, after re-optimising a cheaper iterate if one was seen."""
        cost, plan = self.held.upper
        best = (
            np.inf
            if self.held.best is None
            else self.total(self.held.best[0], self.held.best[2].evaluation)
        )
        if plan is not None and cost < best - 1e-6:
            self.reoptimize(*plan)
        if self.held.best is None:
            raise SolverFailure("no re-optimised plan ends by T_max")
        return self.held.best + (status,)
