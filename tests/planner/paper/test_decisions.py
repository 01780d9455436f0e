"""The driver's decision rules, one test each, without a MILP (sdc_cvx.planner.paper.decisions)."""

import pytest

from sdc_cvx.planner.paper.decisions import Action, Outcome, Phase, decide
from sdc_cvx.planner.paper.settings import SequentialSettings

SETTINGS = SequentialSettings()


def test_no_path_iterates_again():
    assert decide(Phase(), Outcome(solved=False), SETTINGS) is Action.ITERATE


def test_time_limit_without_a_solution_finishes_on_the_held_plan():
    outcome = Outcome(solved=False, stopped=True)
    assert decide(Phase(), outcome, SETTINGS) is Action.FINISH_TIME_LIMIT


def test_a_step_that_makes_the_held_plan_worse_returns_to_it():
    outcome = Outcome(worse_than_held=True, late=True, stalled=True)
    assert decide(Phase(confirming=True), outcome, SETTINGS) is Action.RETURN_TO_HELD


def test_a_late_step_is_rejected():
    assert decide(Phase(), Outcome(changed=True, late=True), SETTINGS) is Action.REJECT_LATE


@pytest.mark.parametrize(
    "phase, outcome",
    [
        (Phase(), Outcome(changed=True, first=True, late=True)),  # the first path
        (Phase(), Outcome(late=True, stalled=True)),  # the re-optimisation makes it fit
    ],
)
def test_a_late_first_or_stalled_path_is_not_rejected(phase, outcome):
    assert decide(phase, outcome, SETTINGS) is not Action.REJECT_LATE


def test_a_late_confirming_step_is_judged_by_its_path():
    phase = Phase(confirming=True)
    assert decide(phase, Outcome(late=True), SETTINGS) is Action.FINISH_CONVERGED
    assert decide(phase, Outcome(late=True, changed=True), SETTINGS) is Action.LEAVE_CONFIRMATION


def test_the_confirming_milp_keeping_the_path_converges():
    assert decide(Phase(confirming=True), Outcome(), SETTINGS) is Action.FINISH_CONVERGED


def test_the_confirming_milp_choosing_another_path_resumes_from_it():
    outcome = Outcome(changed=True)
    assert decide(Phase(confirming=True), outcome, SETTINGS) is Action.LEAVE_CONFIRMATION


@pytest.mark.parametrize("outcome", [Outcome(stalled=True), Outcome(narrowest=True)])
def test_a_stable_path_first_tries_other_assumptions(outcome):
    assert decide(Phase(), outcome, SETTINGS) is Action.TRY_FLIP


def test_without_assumption_rounds_left_a_stable_path_is_reoptimised_and_confirmed():
    phase = Phase(flips=SETTINGS.max_assumption_rounds)
    assert decide(phase, Outcome(stalled=True), SETTINGS) is Action.REOPTIMIZE_AND_CONFIRM


def test_with_the_confirmations_used_up_the_reoptimised_path_is_the_answer():
    phase = Phase(flips=SETTINGS.max_assumption_rounds, confirmations=SETTINGS.max_confirmations)
    assert decide(phase, Outcome(stalled=True), SETTINGS) is Action.REOPTIMIZE_AND_FINISH


@pytest.mark.parametrize(
    "outcome",
    [
        Outcome(changed=True),  # phase 1: a new path
        Outcome(),  # phase 2: same path, the true ΔV still moving, intervals not narrowest
        Outcome(changed=True, stalled=False, narrowest=True),  # a new path is never stable
    ],
)
def test_otherwise_the_references_move(outcome):
    assert decide(Phase(), outcome, SETTINGS) is Action.MOVE


def test_decide_is_pure():
    phase, outcome = Phase(flips=1), Outcome(stalled=True)
    assert decide(phase, outcome, SETTINGS) is decide(phase, outcome, SETTINGS)
    assert phase == Phase(flips=1) and outcome == Outcome(stalled=True)
