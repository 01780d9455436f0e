"""Run statuses (sdc_cvx.solution.RunStatus): an enum that reads and writes as today's strings."""

import json

import pytest

from sdc_cvx.solution import RunStatus


@pytest.mark.parametrize(
    "status, text",
    [
        (RunStatus.CONVERGED, "converged"),
        (RunStatus.CONVERGED_UNCONFIRMED, "converged_unconfirmed"),
        (RunStatus.ITERATION_LIMIT, "iteration_limit"),
        (RunStatus.TIME_LIMIT, "time_limit"),
        (RunStatus.STALLED, "stalled"),
    ],
)
def test_a_status_is_its_string(status, text):
    assert status == text and str(status) == text and f"{status}" == text
    assert RunStatus(text) is status
    assert json.dumps({"status": status}) == json.dumps({"status": text})


def test_every_run_status_so_far_has_a_plan():
    assert all(status.is_solved for status in RunStatus)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("file.csv", None), r"catalog must be a Catalog, got str 'file.csv': read the file"),
        ((None, {"n": 3}), r"mission must be a Mission, got dict .*Mission\(\*\*\{'n': 3\}\)"),
    ],
)
def test_solve_names_an_argument_of_the_wrong_kind(args, message):
    from sdc_cvx import solve

    with pytest.raises(TypeError, match=message):
        solve(*args)
