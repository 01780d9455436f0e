"""The driver's work in the true model: evaluation, re-optimisation, the final schedule.

A path chosen by the MILP is evaluated with the true cost and duration (Eq. 10-13,
:func:`~sdc_cvx.physics.plan.evaluate_plan`).  Once the path is stable, each leg's side and
drift inclination are checked against the cheapest alternative at its date and time (the
assumptions of Part IV-C, :meth:`TrueModelSteps.flip_assumptions`), and the fixed path is
re-optimised in the true model (Part IV-D, :func:`~sdc_cvx.planner.paper.reoptimize.reoptimize`).
The answer's path then flies on its schedule optimised globally
(:meth:`TrueModelSteps.global_schedule`, :func:`~sdc_cvx.planner.fixed_path.solve_path`).

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

import numpy as np

from ...physics.leg_bounds import LegCosts
from ...physics.orbits import SECONDS_PER_DAY
from ...physics.plan import PlanEvaluation, evaluate_plan
from ..fixed_path import PathProblem, schedule_plan, solve_path
from .linearize import TrustRegion
from .reoptimize import reoptimize

SCHEDULE_TOL_MPS = 0.01
"""Certificate of the final path's schedule [m/s] (:meth:`TrueModelSteps.global_schedule`)."""



class TrueModelSteps:
    """The driver's steps in the true model.

    A part of :class:`~sdc_cvx.planner.paper.driver._Driver`: they read its
    mission, nodes and orbits, and set the sides and drift inclinations of its edge
    copies (``geometry``).
    """

    def evaluate(self, path, legs, a_legs) -> PlanEvaluation:
        return evaluate_plan(
            self.orbits, path, a_legs, self.geometry.inc_drift[legs],
            deorbit_days=self.nodes.deorbit_days, j2=self.mission.j2, model=self.geometry.model,
        )  # fmt: skip

    def true_optimum(self, path, legs, a_start, **options):
        """:func:`~sdc_cvx.planner.paper.reoptimize.reoptimize` of ``path`` from the copies'
        choices."""
        g = self.geometry
        return reoptimize(
            self.orbits, path, g.side[legs], g.inc_drift[legs], a_start,
            tmax_days=self.mission.tmax_days, deorbit_days=self.nodes.deorbit_days,
            a_low=g.a_low, a_high=g.a_high, j2=self.mission.j2,
            inclination=self.mission.drift_inclination,
            min_days=self.mission.shortest_leg_days, model=g.model, **options,
        )  # fmt: skip

    def adopt(self, legs, final):
        """The copies ``legs`` take the sides and drift inclinations of a re-optimised plan."""
        side, inc = self.geometry.side.copy(), self.geometry.inc_drift.copy()
        side[legs], inc[legs] = final.side, final.inc_drift
        self.geometry = self.geometry._replace(side=side, inc_drift=inc)

    def reoptimize(self, path, legs, a_legs):
        start = time.perf_counter()
        final = self.true_optimum(path, legs, a_legs)
        self.adopt(legs, final)  # the confirming MILP linearises around this plan
        self.log.timings["reoptimize_s"] = self.log.timings.get("reoptimize_s", 0.0) + (
            time.perf_counter() - start
        )
        self.log.notes.append(f"re-optimisation: {final.message}; {final.improved_by_mps:+.2f} m/s")
        ends_in_time = self.bound_by(path, legs, final.a_drift, final.evaluation)
        cost = self.total(path, final.evaluation)
        if ends_in_time and (
            self.held.best is None
            or cost < self.total(self.held.best[0], self.held.best[2].evaluation)
        ):
            self.held.best = (path, legs, final)
        return final

    def global_schedule(self, path, final):
        """The final path's schedule, optimised globally (:func:`solve_path`).

        The re-optimisation (Part IV-D) is local: on the same path it can stop tens of
        m/s above the best schedule.  The path's certified schedule replaces it when it
        is cheaper; either way a note says what is known of the schedule (not of the path,
        which only the certified method can prove).

        Returns
        -------
        PlanEvaluation, tuple
            The plan, and the legs' ``(a_drift, inc_drift, side)``.
        """
        start = time.perf_counter()
        g, mission, ops = self.geometry, self.mission, self.nodes.deorbit_days
        legs_table = LegCosts.build(self.orbits.take(path[:-1]), self.orbits.take(path[1:]),
                                    g.a_low, g.a_high, model=g.model)  # fmt: skip
        problem = PathProblem(legs_table, tuple(range(len(path) - 1)),
                              tuple(float(ops[k]) for k in path), mission.tmax_days,
                              mission.shortest_leg_days, mission.drift_inclination,
                              mission.j2)  # fmt: skip
        local = float(final.evaluation.dv_mps.sum())
        # no finer than the model's box bounds resolve a path (low thrust: a few mm/s a leg)
        tol = max(SCHEDULE_TOL_MPS, 2.0 * len(path) * g.model.bound_tol_mps)
        schedule = solve_path(problem, tol_mps=tol)
        self.log.timings["global_schedule_s"] = time.perf_counter() - start
        if not schedule.feasible or schedule.upper_mps >= local - tol:
            if schedule.lower_mps >= local - tol:
                self.log.notes.append(
                    f"the path's schedule is its optimum within "
                    f"{tol:.2g} m/s (the path itself is not proven)"
                )
            return final.evaluation, (final.a_drift, final.inc_drift, final.side)
        plan, notes = schedule_plan(self.orbits, path, schedule, deorbit_days=ops,
                                    tmax_days=mission.tmax_days, j2=mission.j2,
                                    model=g.model)  # fmt: skip
        self.log.notes += notes + [
            f"the path's schedule optimised globally: {local:.2f} -> "
            f"{schedule.upper_mps:.2f} m/s of transfers (the local re-optimisation stopped "
            f"above it; the path itself is not proven)"
        ]  # fmt: skip
        return plan, (schedule.a_drift, schedule.inc_drift, schedule.side)

    def flip_assumptions(self, path, legs, a_legs, evaluation) -> bool:
        """Resume with another side/inclination for legs where one is clearly cheaper."""
        origins, targets = self.orbits.take(path[:-1]), self.orbits.take(path[1:])
        # each leg may take its own time plus all of the mission's slack
        slack = max(self.mission.tmax_days - evaluation.end_day, 0.0)
        allotted = (evaluation.duration_days + slack) * SECONDS_PER_DAY
        best = self.geometry.model.cheapest_transfer(
            origins, targets, evaluation.departure_day * SECONDS_PER_DAY, allotted,
            self.geometry.a_low, self.geometry.a_high,
            inclination=self.mission.drift_inclination, j2=self.mission.j2,
        )  # fmt: skip
        better = best.dv < evaluation.dv_mps - 0.5
        differs = (best.side != self.geometry.side[legs]) | ~np.isclose(
            best.inc_drift, self.geometry.inc_drift[legs]
        )
        flip = np.flatnonzero(better & differs)
        if flip.size == 0:
            return False
        side, inc = self.geometry.side.copy(), self.geometry.inc_drift.copy()
        a_ref = self.trust.region.a_ref.copy()
        ids = self.catalog.ids
        for leg in flip:
            edge = legs[leg]
            side[edge], inc[edge], a_ref[edge] = (
                best.side[leg],
                best.inc_drift[leg],
                best.a_drift[leg],
            )
            self.log.notes.append(
                f"leg {ids[path[leg]]}->{ids[path[leg + 1]]}: resumed with "
                f"side {int(best.side[leg]):+d}, drift inclination "
                f"{np.rad2deg(best.inc_drift[leg]):.2f} deg ({best.dv[leg]:.1f} m/s "
                f"instead of {evaluation.dv_mps[leg]:.1f})"
            )
        self.geometry = self.geometry._replace(side=side, inc_drift=inc)
        m = len(a_ref)
        self.trust.region = TrustRegion(a_ref, self.trust.region.t_ref,
                                        np.full(m, self.trust.alpha0),
                                        np.full(m, self.trust.tau0))  # fmt: skip
        return True
