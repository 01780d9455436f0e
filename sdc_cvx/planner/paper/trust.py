"""The trust intervals of the iterations: references, phases 1 and 2 (paper Part IV-C).

Each edge copy is linearised around a reference (drift radius, departure date) within
trust intervals (:class:`TrustState`).  After an accepted step the chosen copies'
references move to the solution; phase 1 keeps the intervals wide while the path changes,
phase 2 halves the chosen copies' intervals once it is stable, and a new path restores
them (:meth:`TrustSteps.move_references`).  A step whose true plan ends after T_max is
rejected and its copies narrowed (:meth:`TrustSteps.reject_late`).

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ...physics.plan import PlanEvaluation
from .linearize import TrustRegion


@dataclass
class TrustState:
    """The references and trust intervals of the edge copies (paper Part IV-C)."""

    region: TrustRegion
    alpha0: float  # the wide radius half-width restored on a new path [km]
    tau0: float  # the wide date half-width [days]
    windows: tuple[np.ndarray, np.ndarray]  # each copy's departure-date window [days]
    visited_paths: set[tuple[int, ...]] = field(default_factory=set)
    initial_retries: int = 0  # narrowings before any path was found
    last_solution: tuple | None = None  # the last MILP's path, copies, radii and true ΔV
    same_solution: int = 0  # iterations in a row before the last that gave its solution


class TrustSteps:
    """The driver's steps on the trust intervals.

    A part of :class:`~sdc_cvx.planner.paper.driver._Driver`: they move its
    :class:`TrustState` (``trust``) by its ``settings``.
    """

    def move_references(self, path, legs, a_legs, evaluation: PlanEvaluation, path_changed: bool):
        """Move the chosen edges' references to the solution; update the trust intervals.

        A chosen edge's reference becomes the solution's radius and its true departure
        date (kept inside its date window); other edges keep theirs.  A new path
        restores the wide intervals (phase 1); a stable path halves them (phase 2).
        """
        self.set_references(legs, a_legs, evaluation.departure_day)
        if path_changed:
            m = len(self.trust.region.a_ref)
            self.trust.region = replace(self.trust.region, alpha_km=np.full(m, self.trust.alpha0),
                                  tau_days=np.full(m, self.trust.tau0))  # fmt: skip
        else:
            self.narrow(legs, dates=True)

    def set_references(self, legs, a_drift, departure_day):
        """Linearise ``legs`` around these radii [m] and departure dates (within windows)."""
        a_ref, t_ref = self.trust.region.a_ref.copy(), self.trust.region.t_ref.copy()
        a_ref[legs] = a_drift
        t_ref[legs] = np.clip(
            departure_day, self.trust.windows[0][legs], self.trust.windows[1][legs]
        )
        self.trust.region = replace(self.trust.region, a_ref=a_ref, t_ref=t_ref)

    def narrow(self, edges, *, dates: bool):
        """Halve the radius (and date) intervals of ``edges``; other edges stay wide."""
        alpha, tau = self.trust.region.alpha_km.copy(), self.trust.region.tau_days.copy()
        alpha[edges] = np.maximum(alpha[edges] * self.settings.shrink, self.settings.min_alpha_km)
        if dates:
            tau[edges] = tau[edges] * self.settings.shrink
        self.trust.region = replace(self.trust.region, alpha_km=alpha, tau_days=tau)

    def reject_late(self, legs, evaluation: PlanEvaluation):
        """The linear durations under-estimated (date cross terms): narrow the chosen copies."""
        self.narrow(legs, dates=True)
        self.log.notes.append(
            f"iteration {len(self.log.history) - 1}: true plan ends on day "
            f"{evaluation.end_day:.1f}, after T_max: step rejected, intervals narrowed"
        )
        self.mark_rejected(
            f"true plan ends on day {evaluation.end_day:.1f}, after T_max = "
            f"{self.mission.tmax_days:g}; intervals narrowed"
        )

    def advance(self, path, legs, a_legs, evaluation: PlanEvaluation, changed: bool):
        """Move the references to the solution (phase 1 or 2, see :meth:`move_references`).

        A path seen before does not restore wide intervals (no ping-pong between paths).
        """
        revisited = changed and tuple(path) in self.trust.visited_paths
        self.trust.visited_paths.add(tuple(path))
        self.move_references(path, legs, a_legs, evaluation, changed and not revisited)
