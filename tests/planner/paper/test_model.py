"""The Eq. 22 model: dimensions, the disjoint-cycle gap, parameters re-valued without rebuild."""

import cvxpy as cp
import numpy as np
import pytest

from sdc_cvx.milp.solve import solve_milp
from sdc_cvx.milp.types import SolverOptions
from sdc_cvx.planner.paper.driver import read_path
from sdc_cvx.planner.paper.linearize import Coefficients
from sdc_cvx.planner.paper.model import ModelSize, PathModel


def coefficients(costs, durations=None, tmax=100.0):
    """Hand-made coefficients: fixed cost and duration per edge, no alpha freedom."""
    return Coefficients.fixed(costs, 0.0 if durations is None else durations, tmax)


def test_paper_dimensions_before_filtering():
    """Part V: N = 11 gives 154 binaries, 341 reals, 1070 constraints."""
    assert ModelSize.paper(11) == ModelSize(154, 341, 1070)


def test_dimensions_of_a_sparse_model():
    edges_from, edges_to = [0, 1, 2, 0], [1, 2, 0, 2]
    model = PathModel(3, edges_from, edges_to, n=3, tmax_days=100.0)
    size = model.size()
    m, n_debris = 4, 3
    assert size.binaries == m + 3 * n_debris  # s, x, y, z
    assert size.continuous == 3 * m + 2 * n_debris  # p, d, w, t, u


# Debris A=0, B=1, C=2, D=3.  C and D are the same orbit: C<->D costs 0 and takes 0 days.
EDGES = [
    (0, 1, 10.0), (2, 3, 0.0), (3, 2, 0.0), (1, 2, 50.0), (1, 3, 50.0), (0, 2, 60.0),
    (0, 3, 60.0), (2, 1, 70.0), (3, 1, 70.0), (2, 0, 80.0), (3, 0, 80.0), (1, 0, 90.0),
]  # fmt: skip


def cycle_instance():
    frm, to, cost = (np.array(col) for col in zip(*EDGES, strict=True))
    model = PathModel(4, frm, to, n=4, tmax_days=100.0)
    model.update(coefficients(cost))
    return model, frm, to, cost


def test_unamended_rows_admit_a_path_plus_a_cycle():
    """Without ordering rows, A->B plus the free cycle C<->D satisfies every other row."""
    model, frm, to, _ = cycle_instance()
    rows = [
        c for name, group in model.constraint_groups.items() if name != "ordering" for c in group
    ]
    relaxed = cp.Problem(model.problem.objective, rows)
    relaxed.solve(solver=cp.HIGHS)
    chosen = {(int(frm[e]), int(to[e])) for e in np.flatnonzero(model.s.value > 0.5)}
    assert relaxed.value == pytest.approx(10.0)
    assert chosen == {(0, 1), (2, 3), (3, 2)}  # a path and a disjoint cycle


def test_ordering_rows_forbid_the_cycle():
    model, frm, to, cost = cycle_instance()
    report = solve_milp(model.problem, SolverOptions())
    path, legs = read_path(model, 4)
    assert sorted(path) == [0, 1, 2, 3]
    # the cheapest real path: A->B->C->D or A->B->D->C (10 + 50 + 0)
    assert report.objective == pytest.approx(60.0)
    assert sum(cost[legs]) == pytest.approx(60.0)


def test_zero_length_legs_stay_legal():
    """T_min = 0: a path whose legs all take 0 days is accepted (docs/design.md §5.2)."""
    model, *_ = cycle_instance()
    solve_milp(model.problem, SolverOptions())
    assert np.allclose(model.t.value, 0.0, atol=1e-6)


def test_duration_rows_bind_and_parameters_are_re_valued():
    """Same Problem object, new durations: the too-slow edge is avoided after the update."""
    frm, to = np.array([0, 1, 0, 2]), np.array([1, 2, 2, 1])
    # paths of 3 debris: 0->1->2 (cost 2, slow) or 0->2->1 (cost 5, fast)
    model = PathModel(3, frm, to, n=3, tmax_days=100.0)
    problem = model.problem
    model.update(coefficients([1.0, 1.0, 2.0, 3.0], durations=[10.0, 10.0, 10.0, 10.0]))
    solve_milp(problem, SolverOptions())
    assert read_path(model, 3)[0] == [0, 1, 2]
    model.update(coefficients([1.0, 1.0, 2.0, 3.0], durations=[60.0, 60.0, 10.0, 10.0]))
    report = solve_milp(problem, SolverOptions())
    assert model.problem is problem
    assert read_path(model, 3)[0] == [0, 2, 1]
    assert report.objective == pytest.approx(5.0)
    # the dates follow the durations: 0 at the start, then 10, then 20
    assert model.t.value[[0, 2, 1]] == pytest.approx([0.0, 10.0, 20.0], abs=1e-6)


def test_infeasible_model_is_reported_as_such():
    frm, to = np.array([0, 1]), np.array([1, 2])
    model = PathModel(3, frm, to, n=3, tmax_days=100.0)
    model.update(coefficients([1.0, 1.0], durations=[60.0, 60.0]))
    report = solve_milp(model.problem, SolverOptions())
    assert report.status.value == "infeasible" and report.objective is None


def test_model_is_dpp():
    model, *_ = cycle_instance()
    assert model.problem.is_dcp(dpp=True)
