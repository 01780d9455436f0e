"""Scenario statuses of a study (sdc_cvx.study.results): the strings of results.csv."""

import json

from sdc_cvx.solution import RunStatus
from sdc_cvx.study.results import (
    FAILURE_STATUSES,
    LOST,
    SOLVED_STATUSES,
    ScenarioStatus,
    is_solved,
)


def test_statuses_keep_the_strings_of_results_csv():
    assert SOLVED_STATUSES == (
        "optimal",
        "feasible",
        "converged",
        "converged_unconfirmed",
        "iteration_limit",
        "time_limit",
        "stalled",
        "within_gap",
        "over_capacity",
    )
    assert FAILURE_STATUSES == ("infeasible", "solver_failure", "error")
    assert LOST == "lost" and json.dumps({"status": LOST}) == '{"status": "lost"}'


def test_only_lost_is_run_again_on_resume():
    assert [s for s in ScenarioStatus if not s.is_terminal] == [ScenarioStatus.LOST]


def test_solved_means_a_run_status_with_a_plan():
    assert all(is_solved(s) for s in RunStatus)
    assert not any(is_solved(s) for s in ScenarioStatus)
    assert is_solved("converged") and not is_solved("infeasible")
