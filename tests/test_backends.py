"""Backend results read honestly: time limits, missing incumbents, option names."""

import cvxpy as cp
import numpy as np
import pytest

from sdc_cvx.backends import SolverOptions, Status, backend_kwargs, solve_milp


def hard_knapsack():
    """A 60-binary multi-constraint knapsack HiGHS cannot finish in 0.1 ms."""
    rng = np.random.default_rng(0)
    n = 60
    weights = rng.integers(1, 100, (30, n))
    x = cp.Variable(n, boolean=True)
    values = rng.integers(1, 100, n)
    problem = cp.Problem(
        cp.Maximize(values @ x), [weights @ x <= weights.sum(1) // 2, cp.sum(x) == n // 2]
    )
    return problem, x


def test_time_limit_without_incumbent_is_no_solution():
    """CVXPY reports user_limit with all-zero values here; that must not pass as a solution."""
    problem, x = hard_knapsack()
    report = solve_milp(problem, SolverOptions(time_limit_s=1e-4))
    assert problem.status == cp.USER_LIMIT  # what CVXPY says
    assert report.status == Status.NO_SOLUTION and report.objective is None
    assert not report.status.has_solution


def test_time_limit_with_incumbent_keeps_it():
    problem, x = hard_knapsack()
    report = solve_milp(problem, SolverOptions(time_limit_s=0.5))
    assert report.status in (Status.TIME_LIMIT, Status.OPTIMAL)
    assert report.objective == pytest.approx(problem.value)
    assert np.allclose(x.value, np.round(x.value), atol=1e-6)  # an integral incumbent
    assert report.nodes is not None and report.dual_bound is not None


def test_refused_option_is_an_error_not_a_traceback():
    problem, _ = hard_knapsack()
    report = solve_milp(problem, SolverOptions(seed=-5))
    assert report.status == Status.ERROR and "random_seed" in report.message


@pytest.mark.parametrize(
    ("backend", "expected"),
    [
        ("HIGHS", {"time_limit": 7.0, "mip_rel_gap": 1e-3, "threads": 2, "random_seed": 3}),
        ("SCIPY", {"scipy_options": {"time_limit": 7.0, "mip_rel_gap": 1e-3, "disp": False}}),
        (
            "SCIP",
            {
                "scip_params": {
                    "limits/time": 7.0,
                    "limits/gap": 1e-3,
                    "randomization/randomseedshift": 3,
                }
            },
        ),  # fmt: skip
        ("CBC", {"maximumSeconds": 7.0, "allowableFractionGap": 1e-3, "numberThreads": 2}),
    ],
)
def test_options_reach_each_backend_under_its_own_names(backend, expected):
    options = SolverOptions(backend=backend.lower(), time_limit_s=7.0, mip_gap=1e-3, threads=2,
                            seed=3)  # fmt: skip
    kwargs = backend_kwargs(options)
    assert kwargs.pop("solver") == backend and kwargs.pop("verbose") is False
    assert kwargs == expected


def test_invalid_options_rejected():
    with pytest.raises(ValueError, match="mip_gap"):
        SolverOptions(mip_gap=1.5)
    with pytest.raises(ValueError, match="time_limit_s"):
        SolverOptions(time_limit_s=0)
