"""An impulsive leg flown by optimised, closed-loop guidance (issue 46, item 1).

1. **Plan** the leg as a rendezvous in mean elements
   (:func:`~sdc_cvx.flight.rendezvous.plan_leg`): from the vehicle's measured mean state
   when it leaves debris i (:func:`~sdc_cvx.flight.mean_track.measure`) to debris j's
   track (:class:`~sdc_cvx.flight.mean_track.DebrisTrack`), four impulses with free
   epochs and vectors, seeded by the paper's leg (the plan's drift orbit, moved to close
   the RAAN gap in the leg's window if the window moved), the rendezvous within the
   window the mission leaves it.
2. **Fly it in closed loop**: each impulse is applied (its RTN components on the
   vehicle's state as flown), the vehicle's mean state measured by propagating its next
   orbit, and the impulses still to come re-planned from there with one more impulse at
   that epoch, which corrects the one just flown (:data:`CORRECTIONS` times at most; the
   two-body impulse of the model is some 30 m off in mean ``a`` per 50 m/s).  On a coast
   longer than :data:`TRIM_MIN_DAYS` the same re-plan is made at :data:`TRIM_FRACTIONS` of
   the coast left, its impulse flown as a ``trim`` (millimetres to centimetres per second:
   the force model's rates over weeks are not the model's).
3. **Target the arrival** in the force model itself
   (:func:`~sdc_cvx.flight.targeting.shoot`): an ``approach`` impulse three quarters of
   an orbit before the rendezvous, the plan's impulses left and the rendezvous epoch
   chosen so that the vehicle reaches the debris' position, then the ``arrive`` impulse
   matches its velocity: the rendezvous within metres and 0 m/s.

Kinds of impulse in ``maneuvers.csv``: ``depart`` (the first, leaving the debris),
``burn`` (the plan's others), ``trim``, ``approach``, ``arrive``.

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., Microcosm
   Press, 2013, §6.6 (phasing), §7.6 (targeting), §9.6 (secular J2 effects).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.mean_elements import RAAN, TWO_PI, rtn_vectors
from ..physics.orbits import SECONDS_PER_DAY
from ..physics.transfer import drift_a_for_duration
from .mean_track import DebrisTrack, measure
from .propagation import ForceModel
from .rendezvous import LegPlan, LegProblem, paper_seeds, plan_leg, replan
from .result import Maneuver
from .targeting import APPROACH_ORBITS, shoot
from .track import Track

CORRECTIONS = 2
"""Re-plans at an impulse's epoch that correct it (the second leaves millimetres per second)."""
SMALLEST_MPS = 1e-3
"""Corrections and trims below this [m/s] are not flown."""
TRIM_MIN_DAYS = 1.0
"""Coasts longer than this [days] are trimmed on the way."""
TRIM_FRACTIONS = (0.5, 0.2, 0.05)
"""Where a long coast is trimmed: at these fractions of what is left of it."""
MERGE_S = 60.0
"""Impulses of a plan closer than this [s] are flown as one."""


class GuidanceError(RuntimeError):
    """No rendezvous of the mean-element model was found for a leg (its note says why)."""


@dataclass(frozen=True)
class LegWindow:
    """When a leg may fly: the vehicle ready at ``t_ready``, the rendezvous by ``latest``,
    the plan's arrival ``t_plan`` [s after day 0]."""

    t_ready: float
    latest: float
    t_plan: float


def _round_us(t: float) -> float:
    """An epoch [s] on the microsecond (as the files write them)."""
    return round(float(t) * 1e6) / 1e6


class LegGuidance:
    """Fly one impulsive leg from ``track`` to debris ``target`` (module docstring).

    Parameters
    ----------
    track : Track
        The vehicle, at the debris it leaves, at ``window.t_ready``.
    leg : int
        The leg's number (1-based), for the manoeuvres.
    planned
        The plan's leg (:class:`~sdc_cvx.flight.plan.PlannedLeg`): drift orbit and side.
    target : int
        The target debris' row in ``ephemeris``.
    window : LegWindow
    ephemeris
        The debris (``state(position, seconds)``, ``a_m``).
    force : ForceModel
    pole, basis
        The leg's pole and its equatorial frame (rows x, y, z).
    rates : tuple of float
        Rate factors of the vehicle's orbits in ``force`` (RAAN, perigee, latitude).
    """

    def __init__(self, track: Track, leg: int, planned, target: int, window: LegWindow,
                 ephemeris, force: ForceModel, pole, basis, rates):  # fmt: skip
        self.track, self.leg, self.planned, self.window = track, leg, planned, window
        self.force, self.pole, self.basis, self.rates = force, pole, basis, rates
        self.consts = {"j2": force.j2, "mu": force.mu, "r_eq": force.r_eq}
        near = float(np.clip(window.t_plan, window.t_ready, window.latest))
        self.debris = DebrisTrack(ephemeris, target, window.t_ready,
                                  window.latest + SECONDS_PER_DAY, near, force, pole,
                                  basis)  # fmt: skip
        self.maneuvers: list[Maneuver] = []
        self.first: LegPlan | None = None

    # -- the model -------------------------------------------------------------------
    def _problem(self) -> LegProblem:
        start = measure(self.track.r, self.track.v, self.track.t, self.force, self.pole,
                        self.basis)  # fmt: skip
        return LegProblem(start, self.track.t, self.debris.at, self.window.t_ready,
                          self.window.latest, self.rates, True, self.consts)  # fmt: skip

    def _seed(self, problem: LegProblem):
        """The paper's leg: the plan's drift orbit, its radius moved to close the RAAN gap
        at the window's arrival if the window is not the plan's."""
        a_d = self.planned.drift_a_km * 1e3
        i_d = np.radians(self.planned.drift_inc_deg)
        t_arrive = float(np.clip(self.window.t_plan, self.window.t_ready, self.window.latest))
        half = np.pi * np.sqrt(a_d**3 / self.force.mu)
        duration = t_arrive - self.window.t_ready - 2.0 * half
        planned_s = self.planned.duration_days * SECONDS_PER_DAY
        if abs(duration + 2.0 * half - planned_s) > SECONDS_PER_DAY and duration > 0:
            goal = self.debris.at(np.array([self.window.t_ready]))[0]
            rate_target = (self.debris.lines[-1, RAAN] - self.debris.lines[0, RAAN]) / (
                self.debris.times[-1] - self.debris.times[0])  # fmt: skip
            gap = goal[RAAN] - problem.start[RAAN]
            moved = drift_a_for_duration(gap, rate_target, float(self.planned.side or 1), i_d,
                                         duration, j2=self.force.j2, mu=self.force.mu)  # fmt: skip
            if np.isfinite(moved) and abs(float(moved) - a_d) < 300e3:
                a_d = float(moved)
        return paper_seeds(problem, a_d, i_d, t_arrive - half)

    # -- flying ----------------------------------------------------------------------
    def fly(self) -> list[Maneuver]:
        """Plan, fly and target the leg; the manoeuvres flown.  Raises GuidanceError."""
        problem = self._problem()
        plan = plan_leg(problem, self._seed(problem))
        if plan is None:
            raise GuidanceError("no rendezvous of the mean-element model converged from the "
                                "plan's leg")  # fmt: skip
        self.first = plan
        plan = _merged(plan)
        kind = "depart"
        while True:
            plan, approach = self._coast_trimmed(plan)
            if approach:
                self._approach(plan, kind)
                return self.maneuvers
            plan = self._impulse(plan, kind)
            kind = "burn"

    def _period(self) -> float:
        a = 1.0 / (2.0 / np.linalg.norm(self.track.r) - self.track.v @ self.track.v / self.force.mu)
        return float(TWO_PI * np.sqrt(a**3 / self.force.mu))

    def _next_stop(self, plan: LegPlan) -> tuple[float, bool]:
        """The epoch [s] of the plan's next impulse, or of the approach (then True) when
        no impulse comes before it."""
        t_approach = plan.epochs[-1] - APPROACH_ORBITS * self._period()
        before = plan.epochs[:-1][plan.epochs[:-1] <= t_approach]
        if len(before):
            return _round_us(max(before[0], self.track.t)), False
        return _round_us(max(t_approach, self.track.t)), True

    def _coast_trimmed(self, plan: LegPlan) -> tuple[LegPlan, bool]:
        """Coast to the plan's next stop (:meth:`_next_stop`), trimmed on the way when the
        coast is long; the plan as last re-planned and whether the stop is the approach.
        Each trim's re-plan may move the next impulse: the stop follows it."""
        start = self.track.t
        t_stop, _ = self._next_stop(plan)
        if t_stop - start > TRIM_MIN_DAYS * SECONDS_PER_DAY:
            for fraction in TRIM_FRACTIONS:
                t_trim = _round_us(t_stop - fraction * (t_stop - start))
                if t_trim <= self.track.t + 0.5 * SECONDS_PER_DAY:
                    continue
                self._coast(t_trim)
                plan = self._correct(plan, "trim", new=True)
                t_stop, _ = self._next_stop(plan)
        t_stop, approach = self._next_stop(plan)
        self._coast(t_stop)
        return plan, approach

    def _coast(self, t: float) -> None:
        self.track.coast(t, self.force, self.pole)

    def _rtn_to_frame(self, dv_rtn) -> np.ndarray:
        radial, transverse, normal = rtn_vectors(self.track.r, self.track.v)
        return dv_rtn[0] * radial + dv_rtn[1] * transverse + dv_rtn[2] * normal

    def _impulse(self, plan: LegPlan, kind: str) -> LegPlan:
        """Fly the plan's next impulse (now), then correct it (module docstring)."""
        dv = self._rtn_to_frame(plan.dv_rtn[0])
        self.maneuvers.append(self.track.impulse(self.leg, kind, self.track.v + dv))
        return self._correct(plan.remaining(self.track.t + 1e-6), kind, new=False)

    def _correct(self, plan: LegPlan, kind: str, *, new: bool) -> LegPlan:
        """Re-plan from the vehicle's measured state with an impulse now; fly that impulse
        (a new ``kind`` manoeuvre, or added to the one just flown) when it matters."""
        for _ in range(CORRECTIONS if not new else 1):
            problem = self._problem()
            again = replan(problem, plan, extra_now=True)
            if not again.converged:
                return plan  # the plan as it was: the next re-plan or the targeting mends it
            extra = again.dv_rtn[0]
            plan = again.remaining(self.track.t + 1e-6)
            if np.linalg.norm(extra) < SMALLEST_MPS:
                return plan
            dv = self._rtn_to_frame(extra)
            if new:
                self.maneuvers.append(self.track.impulse(self.leg, kind, self.track.v + dv))
                new = False
                continue
            last = self.maneuvers.pop()
            self.track.v = self.track.v - last.dv_gcrf  # undo, then the sum at once
            self.maneuvers.append(self.track.impulse(self.leg, last.kind,
                                                     self.track.v + last.dv_gcrf + dv))
        return plan

    def _approach(self, plan: LegPlan, kind: str) -> None:
        """Shoot and fly the approach, the impulses left and the arrival."""
        between = plan.epochs[:-1] > self.track.t
        shot = shoot(self.track.r, self.track.v, self.track.t, plan.epochs[:-1][between],
                     plan.dv_rtn[:-1][between], plan.epochs[-1], self.debris.state,
                     self.force, self.pole, self.window.latest)  # fmt: skip
        if np.linalg.norm(shot.dv_approach) > 0.0:
            self.maneuvers.append(self.track.impulse(self.leg, "approach",
                                                     self.track.v + shot.dv_approach))
        for epoch, dv in zip(plan.epochs[:-1][between], shot.dv_between, strict=True):
            self._coast(float(epoch))
            self.maneuvers.append(self.track.impulse(self.leg, kind, self.track.v + dv))
            kind = "burn"
        self._coast(_round_us(shot.t_arrive))
        r_d, v_d = self.debris.state(self.track.t)
        self.maneuvers.append(self.track.impulse(self.leg, "arrive", v_d))
        self.miss_m = float(np.linalg.norm(self.track.r - r_d))


def _merged(plan: LegPlan) -> LegPlan:
    """The plan with impulses closer than :data:`MERGE_S` flown as one (their sum, at the
    later epoch: a plan that meets the target with two impulses at once)."""
    epochs, dvs = [plan.epochs[0]], [plan.dv_rtn[0]]
    for epoch, dv in zip(plan.epochs[1:], plan.dv_rtn[1:], strict=True):
        if epoch - epochs[-1] < MERGE_S:  # the first stays where it is: the departure
            epochs[-1] = epochs[-1] if len(epochs) == 1 else epoch
            dvs[-1] = dvs[-1] + dv
        else:
            epochs.append(epoch)
            dvs.append(dv)
    epochs = np.array([_round_us(t) for t in epochs])
    return LegPlan(epochs, np.array(dvs), float(np.linalg.norm(dvs, axis=1).sum()),
                   plan.branch, plan.residual_km, plan.converged)  # fmt: skip
