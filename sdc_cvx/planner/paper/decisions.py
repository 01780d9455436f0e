"""The decision rules of the sequential linearisation (paper Part IV-C), as one pure function.

After each iteration the driver (:mod:`sdc_cvx.planner.paper.driver`) sums up what the
MILP and the true model said in an :class:`Outcome`, keeps where the run is in a
:class:`Phase`, and asks :func:`decide` what to do next; ``_Driver.run`` dispatches on
the :class:`Action`.  :func:`decide` needs no MILP and no physics: each rule has its
own unit test (``tests/planner/paper/test_decisions.py``).

The rules, in the order they are tried:

1. No path from the MILP: stop on the held plan if a time limit struck
   (:attr:`Action.FINISH_TIME_LIMIT`), else iterate again (the driver has narrowed
   the intervals).
2. The MILP kept the held plan's path but its step made the true ΔV worse: go back
   to the held plan, narrower.
3. A step whose true plan ends after T_max (or has a transfer shorter than T_min) is
   rejected, unless it is the first path, a confirming MILP, or the path has stalled
   (a stalled plan that ends a little late is made to fit by the re-optimisation).
4. Confirming a re-optimised point: the same path converges; another path leaves the
   confirmation and the iterations resume from it.
5. Same path, and the true ΔV stopped moving (or the intervals are at their
   narrowest): try the other side/inclination assumptions while rounds remain, else
   re-optimise in the true model (Part IV-D) and confirm with one more MILP, unless
   the confirmations are used up.
6. Otherwise move the references to the solution (phase 1 while the path changes,
   phase 2 halves the intervals while it is stable).

Equation, table and part numbers are those of Cerf's paper [1]_; the design rationale
is in ``docs/design.md`` §6.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum


class Action(Enum):
    """What the driver does after an iteration."""

    FINISH_TIME_LIMIT = "finish: a MILP hit its time limit without a solution"
    ITERATE = "iterate again (no path this time)"
    RETURN_TO_HELD = "reject the step: back to the held plan, narrower"
    REJECT_LATE = "reject the step: its true plan is late; narrow the chosen copies"
    FINISH_CONVERGED = "finish: the confirming MILP kept the re-optimised path"
    LEAVE_CONFIRMATION = "the confirming MILP chose another path: resume from it"
    TRY_FLIP = "try other side/inclination assumptions (else re-optimise)"
    REOPTIMIZE_AND_CONFIRM = "re-optimise in the true model, confirm with one more MILP"
    REOPTIMIZE_AND_FINISH = "re-optimise in the true model and finish (confirmations used up)"
    MOVE = "move the references to the solution"


@dataclass(frozen=True)
class Outcome:
    """One iteration as the rules see it.

    Attributes
    ----------
    solved : bool
        The MILP gave a path (False: infeasible linearisation or no solution).
    stopped : bool
        A MILP reached its time limit without a solution while a plan is held.
    worse_than_held : bool
        Same path as the held plan, but a higher true ΔV than it.
    changed : bool
        The path differs from the last one (always True for the first path).
    first : bool
        No path before this one (or the assumptions were just flipped).
    late : bool
        The true plan ends after T_max or has a transfer shorter than T_min.
    stalled : bool
        Same path, and the true ΔV moved by at most ``dv_tol_mps``.
    narrowest : bool
        The chosen copies' radius intervals are at ``min_alpha_km``.
    """

    solved: bool = True
    stopped: bool = False
    worse_than_held: bool = False
    changed: bool = False
    first: bool = False
    late: bool = False
    stalled: bool = False
    narrowest: bool = False


@dataclass(frozen=True)
class Phase:
    """Where the run is: confirming a re-optimised point or not, and the rounds used."""

    confirming: bool = False
    flips: int = 0
    confirmations: int = 0


def decide(phase: Phase, outcome: Outcome, settings) -> Action:
    """The next action (see the module docstring for the rules).

    ``settings`` is a :class:`~sdc_cvx.planner.paper.settings.SequentialSettings` (only
    ``max_assumption_rounds`` and ``max_confirmations`` are read).
    """
    if not outcome.solved:
        return Action.FINISH_TIME_LIMIT if outcome.stopped else Action.ITERATE
    if outcome.worse_than_held:
        return Action.RETURN_TO_HELD
    if outcome.late and not outcome.first and not phase.confirming and not outcome.stalled:
        return Action.REJECT_LATE
    if phase.confirming:
        return Action.LEAVE_CONFIRMATION if outcome.changed else Action.FINISH_CONVERGED
    if not outcome.changed and (outcome.stalled or outcome.narrowest):
        if phase.flips < settings.max_assumption_rounds:
            return Action.TRY_FLIP
        if phase.confirmations == settings.max_confirmations:
            return Action.REOPTIMIZE_AND_FINISH
        return Action.REOPTIMIZE_AND_CONFIRM
    return Action.MOVE
