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


def test_an_option_the_method_does_not_use_is_said():
    from sdc_cvx import Mission, SolverOptions
    from sdc_cvx.planner.api import ignored_options

    assert ignored_options(Mission(), SolverOptions()) == []
    assert ignored_options(Mission(), SolverOptions(method="paper")) == []
    (certified,) = ignored_options(Mission(dv_max_mps=500.0), SolverOptions())
    assert certified.startswith("mission.dv_max_mps = 500 is ignored")
    (paper,) = ignored_options(Mission(), SolverOptions(method="paper", gap=0.5))
    assert paper.startswith("solver.gap = 0.5 is ignored")


@pytest.mark.slow
def test_solve_warns_and_notes_an_ignored_option():
    from sdc_cvx import Catalog, Mission, solve
    from sdc_cvx.errors import IgnoredOptionWarning

    catalog = Catalog.paper_case().subset(["1", "2", "3"])
    with pytest.warns(IgnoredOptionWarning, match="dv_max_mps = 500 is ignored"):
        solution = solve(catalog, Mission(n=2, dv_max_mps=500.0))
    assert any("dv_max_mps = 500 is ignored" in note for note in solution.notes)


def test_a_wide_requested_gap_is_not_called_optimal():
    """--gap 0.5 printed "optimal (8.11 %)" (issue 20, item 8): optimal is 0.1 % at most."""
    from dataclasses import replace

    from sdc_cvx import Catalog, Mission, SolverOptions, solve
    from sdc_cvx.solution import OPTIMAL_GAP_MPS, OPTIMAL_GAP_REL

    catalog = Catalog.paper_case().subset(["1", "2", "3", "4", "5"])
    solution = solve(catalog, Mission(n=3), solver=SolverOptions(gap=0.5))
    tight = solution.gap_mps <= max(OPTIMAL_GAP_REL * solution.total_dv_mps, OPTIMAL_GAP_MPS)
    assert solution.status == (RunStatus.OPTIMAL if tight else RunStatus.WITHIN_GAP)
    assert solution.certified and solution.gap_requested == 0.5
    assert solution.to_dict()["gap_requested"] == 0.5
    wide = replace(solution, status=RunStatus.WITHIN_GAP,
                   lower_bound_mps=0.9189 * solution.total_dv_mps)  # fmt: skip
    assert wide.quality().startswith("within 8.11 % of the optimum (requested 50 %): gap ")
    assert "optimal" not in wide.summary().splitlines()[1]


@pytest.mark.parametrize("method", ["certified", "paper"])
def test_the_frames_of_a_solution_are_the_tables_of_its_run_folder(tmp_path, method):
    """Found as a user: ``iterations_frame()`` of a certified solve was empty while
    ``iterations.csv`` had its bound's rows, and ``legs_frame()`` lacked two columns of
    ``legs.csv``; README shows the frames as what the run folder holds."""
    from sdc_cvx import Mission, SolverOptions, read_catalog, solve
    from sdc_cvx.report.run_folder import CSV_FLOAT_FORMAT
    from tests.conftest import PAPER_CSV

    answer = solve(read_catalog(PAPER_CSV), Mission(n=3), solver=SolverOptions(method=method))
    answer.save(tmp_path / "run")
    legs, history = answer.legs_frame(), answer.iterations_frame()
    assert len(legs) == 2 and legs["cumulative_dv_mps"].iloc[-1] == answer.total_dv_mps
    assert len(history) > 0 and "step" in history
    for frame, name in ((legs, "legs.csv"), (history, "iterations.csv")):
        text = frame.to_csv(index=False, float_format=CSV_FLOAT_FORMAT)
        assert (tmp_path / "run" / name).read_text(encoding="utf-8") == text, name
