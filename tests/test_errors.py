"""The exception families (sdc_cvx.errors) and the CLI exit codes that map from them."""

import pytest

from sdc_cvx import errors
from sdc_cvx.cli import EXIT_CODES, INFEASIBLE, INPUT_ERROR, SOLVER_FAILED, exit_code


@pytest.mark.parametrize(
    "cls, family, builtin, code",
    [
        (errors.CatalogError, errors.InputError, ValueError, INPUT_ERROR),
        (errors.MissionError, errors.InputError, ValueError, INPUT_ERROR),
        (errors.ScenarioError, errors.InputError, ValueError, INPUT_ERROR),
        (errors.MissionInfeasible, errors.PlanningError, RuntimeError, INFEASIBLE),
        (errors.SolverFailure, errors.PlanningError, RuntimeError, SOLVER_FAILED),
        (errors.SweepError, errors.SdcError, RuntimeError, INPUT_ERROR),
    ],
)
def test_each_error_has_a_family_and_an_exit_code(cls, family, builtin, code):
    assert issubclass(cls, family) and issubclass(cls, errors.SdcError)
    assert issubclass(cls, builtin)  # except clauses written for the old bases still work
    assert exit_code(cls("x")) == code
    assert code in EXIT_CODES.values()


def test_the_old_homes_re_export_the_same_classes():
    from sdc_cvx.inputs.catalog import CatalogError
    from sdc_cvx.inputs.mission import MissionError
    from sdc_cvx.planner.paper.driver import MissionInfeasible, SolverFailure
    from sdc_cvx.study.runner import SweepError
    from sdc_cvx.study.scenario import ScenarioError

    assert (CatalogError, MissionError, ScenarioError) == (
        errors.CatalogError,
        errors.MissionError,
        errors.ScenarioError,
    )
    assert (MissionInfeasible, SolverFailure, SweepError) == (
        errors.MissionInfeasible,
        errors.SolverFailure,
        errors.SweepError,
    )


def test_problems_are_kept():
    err = errors.CatalogError.collect("f.csv", [f"p{k}" for k in range(25)])
    assert len(err.problems) == 25 and str(err).endswith("... and 5 more")
    assert errors.ScenarioError.collect("s.toml", ["a", "b"]).problems == ("a", "b")
