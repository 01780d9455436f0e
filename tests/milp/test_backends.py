"""Backend results read honestly: time limits, missing incumbents, option names, checks."""

import time
import warnings
from dataclasses import replace

import cvxpy as cp
import numpy as np
import pytest

from sdc_cvx.errors import MissionError
from sdc_cvx.milp.backends import (
    BACKENDS,
    available_backends,
    backend_kwargs,
    installed_backends,
)
from sdc_cvx.milp.solve import check_result, solve_milp
from sdc_cvx.milp.types import (
    DEFAULT_BACKEND,
    MILP_BACKENDS,
    SolverOptions,
    Status,
    backend_importable,
)
from tests.milp import unchecked_options

INSTALLED = installed_backends()
EASY_OPTIMUM = 2034.0  # of easy_knapsack(), found by every backend without limits


def hard_knapsack():
    """A 200-binary multi-constraint knapsack with a cardinality row: no backend finishes
    it in 1 ms, and none has an incumbent by then, even on a loaded machine (with 60
    binaries CBC sometimes had one)."""
    rng = np.random.default_rng(0)
    n = 200
    weights = rng.integers(1, 100, (80, n))
    x = cp.Variable(n, boolean=True)
    values = rng.integers(1, 100, n)
    problem = cp.Problem(
        cp.Maximize(values @ x), [weights @ x <= weights.sum(1) // 2, cp.sum(x) == n // 2]
    )
    return problem, x


def easy_knapsack():
    """x = 0 is feasible, so every backend has an incumbent at once; proving the optimum
    takes them 1-10 s here.  The objective has a constant (+5): bounds must include it."""
    rng = np.random.default_rng(1)
    n = 80
    weights = rng.integers(1, 100, (20, n))
    x = cp.Variable(n, boolean=True)
    values = rng.integers(1, 100, n)
    problem = cp.Problem(cp.Maximize(values @ x + 5), [weights @ x <= weights.sum(1) // 3])
    return problem, x


def infeasible_problem():
    x = cp.Variable(5, boolean=True)
    rows = [cp.sum(x) >= 2.5, x[0] + x[1] <= 0, cp.sum(x[2:]) <= 1.5]
    return cp.Problem(cp.Minimize(cp.sum(x)), rows)


BY_BACKEND = [
    pytest.param(name, marks=pytest.mark.requires_backend(name)) for name in MILP_BACKENDS
]
"""The backends as parameters, each skipped unless installed (``requires_backend``)."""


def skip_if_unlicensed(report):
    text = report.message.lower()
    if report.status == Status.ERROR and ("license" in text or "size limit" in text):
        pytest.skip(f"{report.backend} cannot run here: {report.message[:120]}")


# --------------------------------------------------------------------------- status per backend
@pytest.mark.parametrize("backend", BY_BACKEND)
def test_time_limit_without_incumbent_is_no_solution(backend):
    problem, x = hard_knapsack()
    report = solve_milp(problem, SolverOptions(backend=backend, time_limit_s=1e-3))
    skip_if_unlicensed(report)
    assert report.status == Status.NO_SOLUTION, report
    assert report.objective is None and report.mip_gap is None
    assert not report.status.has_solution
    assert x.value is None  # no all-zero or fractional point left behind


@pytest.mark.parametrize("backend", BY_BACKEND)
def test_time_limit_with_incumbent_keeps_it(backend):
    problem, x = easy_knapsack()
    start = time.perf_counter()
    report = solve_milp(problem, SolverOptions(backend=backend, time_limit_s=0.5))
    elapsed = time.perf_counter() - start
    skip_if_unlicensed(report)
    assert report.status in (Status.TIME_LIMIT, Status.OPTIMAL), report
    if report.status == Status.TIME_LIMIT:
        assert elapsed >= 0.45  # the limit reached the backend, in seconds
    assert report.objective == pytest.approx(problem.objective.value)
    assert report.objective <= EASY_OPTIMUM + 1e-6
    assert np.allclose(x.value, np.round(x.value), atol=1e-6)  # an integral incumbent
    if report.dual_bound is not None:  # maximisation: the bound is above, constant included
        assert report.dual_bound >= report.objective - 1e-6
    if backend == "HIGHS":
        assert report.nodes is not None and report.dual_bound is not None


@pytest.mark.parametrize("backend", BY_BACKEND)
def test_stop_at_the_relative_gap_is_optimal(backend):
    """SCIP says 'gaplimit' and GLPK 'feasible' (CVXPY: optimal_inaccurate) here."""
    problem, x = easy_knapsack()
    report = solve_milp(problem, SolverOptions(backend=backend, mip_gap=0.05, time_limit_s=60))
    skip_if_unlicensed(report)
    assert report.status == Status.OPTIMAL, report
    assert report.objective >= (1 - 0.05) * EASY_OPTIMUM
    if report.mip_gap is not None:
        assert 0 <= report.mip_gap <= 0.05 + 1e-9


@pytest.mark.parametrize("backend", BY_BACKEND)
def test_infeasible_is_reported(backend):
    problem = infeasible_problem()
    report = solve_milp(problem, SolverOptions(backend=backend))
    skip_if_unlicensed(report)
    assert report.status == Status.INFEASIBLE, report
    assert report.objective is None and report.dual_bound is None


def test_maximisation_bound_and_objective_include_the_constant():
    problem, x = easy_knapsack()
    report = solve_milp(problem, SolverOptions(mip_gap=0.05))
    assert report.status == Status.OPTIMAL
    assert report.objective == pytest.approx(float(problem.objective.value))
    assert report.objective <= report.dual_bound <= report.objective / (1 - 0.05)


# --------------------------------------------------------------------------- what CVXPY hides
def test_cvxpy_reports_highs_time_limit_without_incumbent_as_user_limit():
    """Why solve_milp reads HiGHS's primal_solution_status (docs/design.md §5)."""
    problem, x = hard_knapsack()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problem.solve(solver="HIGHS", time_limit=1e-3)
    assert problem.status == cp.USER_LIMIT and np.allclose(x.value, 0.0)


@pytest.mark.requires_backend("CBC")
def test_cvxpy_reports_cbc_time_limit_without_incumbent_as_optimal_inaccurate():
    problem, x = hard_knapsack()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problem.solve(solver="CBC", maximumSeconds=1e-3)
    assert problem.status == cp.OPTIMAL_INACCURATE  # yet there is no integer solution:
    assert not np.allclose(x.value, np.round(x.value), atol=1e-6)


@pytest.mark.requires_backend("SCIP")
def test_cvxpy_raises_on_scip_time_limit_without_incumbent():
    problem, _ = hard_knapsack()
    with pytest.raises(cp.error.SolverError), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problem.solve(solver="SCIP", scip_params={"limits/time": 1e-3})


# --------------------------------------------------------------------------- options
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
        ("GLPK_MI", {"tm_lim": 7000, "mip_gap": 1e-3}),
        ("GUROBI", {"TimeLimit": 7.0, "MIPGap": 1e-3, "Threads": 2, "Seed": 3}),
        (
            "CPLEX",
            {
                "cplex_params": {
                    "timelimit": 7.0,
                    "mip.tolerances.mipgap": 1e-3,
                    "threads": 2,
                    "randomseed": 3,
                }
            },
        ),  # fmt: skip
        ("XPRESS", {"timelimit": 7.0, "miprelstop": 1e-3, "threads": 2, "randomseed": 3}),
        (
            "MOSEK",
            {
                "mosek_params": {
                    "MSK_DPAR_OPTIMIZER_MAX_TIME": 7.0,
                    "MSK_DPAR_MIO_TOL_REL_GAP": 1e-3,
                    "MSK_IPAR_NUM_THREADS": 2,
                    "MSK_IPAR_MIO_SEED": 3,
                }
            },
        ),  # fmt: skip
        ("COPT", {"TimeLimit": 7.0, "RelGap": 1e-3, "Threads": 2}),
    ],
)
def test_options_reach_each_backend_under_its_own_names(backend, expected):
    options = SolverOptions(backend=backend.lower(), time_limit_s=7.0, mip_gap=1e-3, threads=2,
                            seed=3)  # fmt: skip
    kwargs = backend_kwargs(options)
    assert kwargs.pop("solver") == backend and kwargs.pop("verbose") is False
    assert kwargs == expected


@pytest.mark.requires_backend("SCIP")
def test_unsupported_options_are_reported_not_passed():
    problem, _ = easy_knapsack()
    report = solve_milp(problem, SolverOptions(backend="SCIP", threads=2, mip_gap=0.05))
    assert report.status == Status.OPTIMAL and report.ignored_options == ("threads",)
    assert BACKENDS["CBC"].kwargs(SolverOptions(backend="CBC", seed=1))[1] == ("seed",)
    assert BACKENDS["GLPK_MI"].kwargs(SolverOptions(backend="GLPK_MI", seed=1, threads=2))[1] == (
        "threads",
        "seed",
    )


def test_glpk_time_limit_is_in_milliseconds():
    assert backend_kwargs(SolverOptions(backend="GLPK_MI", time_limit_s=1e-4))["tm_lim"] == 1


def test_refused_option_is_an_error_not_a_traceback():
    problem, _ = hard_knapsack()
    report = solve_milp(problem, SolverOptions(seed=-5))
    assert report.status == Status.ERROR and "random_seed" in report.message


@pytest.mark.requires_backend("SCIP")
def test_scip_refuses_a_bad_seed_by_its_name():
    problem, _ = hard_knapsack()
    report = solve_milp(problem, SolverOptions(backend="SCIP", seed=-5))
    assert report.status == Status.ERROR and "invalid" in report.message


@pytest.mark.requires_backend("SCIPY")
def test_scipy_knows_our_option_names():
    """SciPy passes unknown names to HiGHS 'verbatim' with only a warning."""
    problem, _ = easy_knapsack()
    kwargs = backend_kwargs(SolverOptions(backend="SCIPY", time_limit_s=5.0, mip_gap=0.05))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        problem.solve(**kwargs)
    assert not [w for w in caught if "Unrecognized" in str(w.message)]


def test_invalid_options_rejected():
    with pytest.raises(ValueError, match="mip_gap"):
        SolverOptions(mip_gap=1.5)
    with pytest.raises(ValueError, match="time_limit_s"):
        SolverOptions(time_limit_s=0)


# --------------------------------------------------------------------------- registry
def test_registry_lists_every_milp_backend_cvxpy_knows():
    assert MILP_BACKENDS[0] == DEFAULT_BACKEND
    assert set(MILP_BACKENDS) == {"HIGHS", "SCIP", "CBC", "GLPK_MI", "SCIPY", "GUROBI", "CPLEX",
                                  "XPRESS", "MOSEK", "COPT"}  # fmt: skip
    assert set(MILP_BACKENDS) <= set(cp.settings.SOLVERS)
    assert tuple(BACKENDS) == MILP_BACKENDS  # the table holds every name, in that order


def test_a_backend_cvxpy_can_call_is_one_whose_module_is_found_without_cvxpy():
    """The CLI checks the chosen backend by its module alone (CVXPY not imported): every
    backend CVXPY lists as installed here must pass that check, and a name that is no
    backend must not."""
    installed = set(cp.installed_solvers()) & set(MILP_BACKENDS)
    assert installed, "no MILP backend installed"
    assert {name for name in installed if backend_importable(name)} == installed
    assert not backend_importable("NOT_A_BACKEND")


def test_available_backends():
    rows = available_backends()
    assert [row["name"] for row in rows] == list(MILP_BACKENDS)
    installed = set(cp.installed_solvers())
    for row in rows:
        assert row["installed"] == (row["name"] in installed)
        assert row["package"] == BACKENDS[row["name"]].package
        if row["installed"]:
            assert isinstance(row["version"], str)
    assert rows[0]["default"] and not any(row["default"] for row in rows[1:])
    assert available_backends(["highs"])[0]["name"] == "HIGHS"
    with pytest.raises(ValueError, match="unknown MILP backend"):
        available_backends(["NOPE"])


def test_unknown_and_uninstalled_backends_are_errors():
    problem, _ = easy_knapsack()
    with pytest.raises(MissionError, match="backend must be one of HIGHS, .*got 'NOPE'"):
        SolverOptions(backend="nope")  # refused when made (issue 48, item 16)
    report = solve_milp(problem, unchecked_options("NOPE"))  # the MILP layer's own check
    assert report.status == Status.ERROR and "unknown MILP backend 'NOPE'" in report.message
    missing = [name for name in MILP_BACKENDS if name not in INSTALLED]
    if missing:
        report = solve_milp(problem, SolverOptions(backend=missing[0]))
        assert report.status == Status.ERROR and "is not installed" in report.message


# --------------------------------------------------------------------------- result check
def test_check_result_accepts_a_solution_and_names_what_is_wrong():
    x = cp.Variable(3, boolean=True)
    y = cp.Variable()
    problem = cp.Problem(cp.Minimize(y), [y >= 300 * cp.sum(x) - 300, cp.sum(x) == 2])
    x.value, y.value = np.array([1.0, 1.0, 0.0]), 300.0
    assert check_result(problem) is None
    x.save_value(np.array([1.0, 0.7, 0.3]))  # as a backend's point is stored (no projection)
    assert "away from an integer" in check_result(problem)
    x.value = np.array([1.0, 1.0, 0.0])
    y.value = 300.0 - 1e-4  # relative to |300 sum(x) - 300| = 300: 3.3e-7, accepted
    assert check_result(problem) is None
    y.value = 300.0 - 1e-2  # 3.3e-5 relative
    assert "violated" in check_result(problem)
    y.value = None
    assert "no value" in check_result(problem)


@pytest.mark.requires_backend("SCIPY")
def test_failed_check_is_an_error_and_leaves_no_point(monkeypatch):
    problem, x = easy_knapsack()
    entry = BACKENDS["SCIPY"]

    def shifted(raw, context):
        raw.x += 0.25
        return entry.read(raw, context)

    monkeypatch.setitem(BACKENDS, "SCIPY", replace(entry, read=shifted))
    report = solve_milp(problem, SolverOptions(backend="SCIPY", mip_gap=0.05))
    assert report.status == Status.ERROR and "result check failed" in report.message
    assert report.objective is None and x.value is None


def test_an_unknown_fallback_backend_is_refused_when_the_options_are_made():
    with pytest.raises(MissionError, match="fallback must name MILP backends.*got NOPE"):
        SolverOptions(fallback=("NOPE",))
    assert SolverOptions(fallback="highs").fallback == ("HIGHS",)  # one name, not its letters
