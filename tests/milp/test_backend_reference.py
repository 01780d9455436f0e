"""Every MILP backend against brute force on small instances of OUR model (Eq. 22).

Each instance is a PathModel with hand-made coefficients (a fixed cost and a fixed
duration per edge, as in tests/test_model.py).  Its optimum is computed here
independently by enumerating every ordered path of n distinct debris: the cost is the
sum of the edge costs; dates follow durations (the first debris at day 0, each leg
departs T_deorb after the previous arrival); the path is feasible iff the chained
legs plus n T_deorb fit T_max.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, replace

import numpy as np
import pytest

from sdc_cvx.milp.backends import BACKENDS, installed_backends
from sdc_cvx.milp.solve import solve_milp, solve_with_fallback
from sdc_cvx.milp.types import SolverOptions, Status
from sdc_cvx.planner.paper.linearize import Coefficients
from sdc_cvx.planner.paper.model import PathModel
from tests.milp import unchecked_options

REL = 1e-6


def coefficients(costs, durations, tmax):
    """Hand-made coefficients: fixed cost and duration per edge, no alpha freedom."""
    return Coefficients.fixed(costs, durations, tmax)


@dataclass(frozen=True)
class Instance:
    name: str
    n_debris: int
    n: int
    frm: np.ndarray
    to: np.ndarray
    cost: np.ndarray
    duration: np.ndarray
    tmax: float
    deorbit: float

    def edge(self):
        return {(int(i), int(j)): k for k, (i, j) in enumerate(zip(self.frm, self.to, strict=True))}

    def paths(self):
        """Every ordered path of n distinct debris over existing edges: (path, cost, days)."""
        edge = self.edge()
        for path in itertools.permutations(range(self.n_debris), self.n):
            legs = [edge.get(pair) for pair in itertools.pairwise(path)]
            if None in legs:
                continue
            days = float(self.duration[legs].sum()) + self.n * self.deorbit
            yield path, float(self.cost[legs].sum()), days

    def enumerate(self):
        """Brute-force optimum: (cost, path), or (None, None) if no path fits T_max."""
        feasible = [(c, p) for p, c, days in self.paths() if days <= self.tmax + 1e-9]
        return min(feasible) if feasible else (None, None)

    def unconstrained(self):
        return min(c for _, c, _ in self.paths())

    def model(self):
        model = PathModel(self.n_debris, self.frm, self.to, n=self.n, tmax_days=self.tmax,
                          deorbit_days=self.deorbit)  # fmt: skip
        model.update(coefficients(self.cost, self.duration, self.tmax))
        return model


def make_instance(name, n_debris, n, *, seed, density=1.0, deorbit=0.0, tmax="binding"):
    """Random costs (m/s, not integers: few ties) and durations (days) on random edges.

    ``tmax``: "binding" puts T_max halfway between the shortest path and the cheapest
    path's duration (the cheapest path is then too slow); "loose" above every path;
    "infeasible" below the shortest path; a number is used as is.
    """
    rng = np.random.default_rng(seed)
    pairs = [(i, j) for i in range(n_debris) for j in range(n_debris) if i != j]
    keep = [pair for pair in pairs if rng.random() < density]
    frm, to = (np.array(col) for col in zip(*keep, strict=True))
    cost = np.round(rng.uniform(5.0, 150.0, len(keep)), 3)
    duration = np.round(rng.uniform(2.0, 60.0, len(keep)), 3)
    probe = Instance(name, n_debris, n, frm, to, cost, duration, 1e9, deorbit)
    paths = list(probe.paths())
    cheapest = min(paths, key=lambda row: row[1])
    shortest = min(days for _, _, days in paths)
    longest = max(days for _, _, days in paths)
    if tmax == "binding":
        tmax = round((shortest + cheapest[2]) / 2, 3)
    elif tmax == "loose":
        tmax = round(longest + 10.0, 3)
    elif tmax == "infeasible":
        tmax = round(shortest - 1.0, 3)
    return replace(probe, tmax=float(tmax))


INSTANCES = [
    make_instance("N4-n3-binding", 4, 3, seed=1),
    make_instance("N5-n4-deorbit-binding", 5, 4, seed=2, deorbit=5.0),
    make_instance("N6-n4-loose", 6, 4, seed=3, tmax="loose"),
    make_instance("N6-n5-deorbit-sparse-binding", 6, 5, seed=4, density=0.7, deorbit=3.0),
    make_instance("N7-n5-sparse-binding", 7, 5, seed=5, density=0.6),
    make_instance("N7-n3-deorbit-binding", 7, 3, seed=6, deorbit=10.0),
    make_instance("N5-n4-infeasible", 5, 4, seed=7, deorbit=2.0, tmax="infeasible"),
]
BY_NAME = {instance.name: instance for instance in INSTANCES}


def test_instances_exercise_the_model():
    """Durations bind somewhere (the cheapest path is too slow), T_deorb is used, sizes vary."""
    binding = [i for i in INSTANCES if i.enumerate()[0] not in (None, i.unconstrained())]
    assert len(binding) >= 4
    assert any(i.deorbit > 0 for i in binding) and any(i.deorbit == 0 for i in binding)
    assert BY_NAME["N6-n4-loose"].enumerate()[0] == BY_NAME["N6-n4-loose"].unconstrained()
    assert BY_NAME["N5-n4-infeasible"].enumerate() == (None, None)
    assert {i.n_debris for i in INSTANCES} == {4, 5, 6, 7}
    assert {i.n for i in INSTANCES} == {3, 4, 5}


def read_plan(instance: Instance, model: PathModel):
    """The backend's path, its legs (edge indices) and the dates it chose."""
    chosen = np.flatnonzero(np.asarray(model.s.value) > 0.5)
    successor = {int(instance.frm[e]): (int(instance.to[e]), int(e)) for e in chosen}
    assert len(successor) == len(chosen) == instance.n - 1, "one leg out of each debris"
    targets = {to for to, _ in successor.values()}
    starts = set(successor) - targets
    assert len(starts) == 1, f"not a single path: {successor}"
    path, legs = [starts.pop()], []
    while path[-1] in successor:
        nxt, leg = successor[path[-1]]
        path.append(nxt)
        legs.append(leg)
    assert len(path) == len(set(path)) == instance.n, f"not a simple path of n: {path}"
    return path, legs, np.asarray(model.t.value, dtype=float)


def assert_feasible_plan(instance: Instance, model: PathModel, objective: float):
    path, legs, dates = read_plan(instance, model)
    assert float(instance.cost[legs].sum()) == pytest.approx(objective, rel=REL)
    days = float(instance.duration[legs].sum()) + instance.n * instance.deorbit
    assert days <= instance.tmax * (1 + REL)
    # dates follow durations: day 0 at the first debris, then T_deorb + duration per leg
    expected = np.concatenate(
        [[0.0], np.cumsum(instance.duration[legs] + instance.deorbit)]
    )  # fmt: skip
    assert dates[path] == pytest.approx(expected, abs=1e-6 * max(1.0, instance.tmax))


def skip_unless_usable(name):
    if name not in installed_backends():
        pytest.skip(f"{name} is not installed (pip install {BACKENDS[name].package})")


def skip_if_unlicensed(report):
    text = report.message.lower()
    if report.status == Status.ERROR and ("license" in text or "size limit" in text):
        pytest.skip(f"{report.backend} cannot run here: {report.message[:120]}")


@pytest.mark.slow
@pytest.mark.parametrize("backend", list(BACKENDS))
@pytest.mark.parametrize("instance", INSTANCES, ids=lambda i: i.name)
def test_backend_matches_enumeration(backend, instance):
    skip_unless_usable(backend)
    best, best_path = instance.enumerate()
    model = instance.model()
    report = solve_milp(model.problem, SolverOptions(backend=backend, time_limit_s=60.0))
    skip_if_unlicensed(report)
    if best is None:
        assert report.status == Status.INFEASIBLE, report
        assert report.objective is None
        return
    assert report.status == Status.OPTIMAL, report
    assert report.objective == pytest.approx(best, rel=REL)
    assert_feasible_plan(instance, model, report.objective)
    if report.dual_bound is not None:
        assert report.dual_bound <= best * (1 + REL) + 1e-9


# --------------------------------------------------------------------------- fallback
def test_fallback_skips_unknown_and_uninstalled_backends():
    instance = BY_NAME["N5-n4-deorbit-binding"]
    best, _ = instance.enumerate()
    model = instance.model()
    missing = [name for name in BACKENDS if name not in installed_backends()]
    chain = [unchecked_options("NO_SUCH_SOLVER")]  # refused by SolverOptions
    chain += [SolverOptions(backend=missing[0])] if missing else []
    chain += [SolverOptions(backend="HIGHS")]
    report = solve_with_fallback(model.problem, chain)
    assert report.status == Status.OPTIMAL and report.backend == "HIGHS"
    assert report.objective == pytest.approx(best, rel=REL)
    assert len(report.fallbacks) == len(chain) - 1
    assert report.fallbacks[0].startswith("NO_SUCH_SOLVER failed: error: unknown MILP backend")
    assert report.fallbacks[-1].endswith("; used HIGHS")
    if missing:
        assert f"{missing[0]} failed: error: {missing[0]} is not installed" in report.fallbacks[1]
    assert_feasible_plan(instance, model, report.objective)


def corrupting(read):
    """A SciPy reader that also moves every entry of the raw point by 0.3 (off integrality)."""

    def read_and_corrupt(raw, context):
        raw.x += 0.3
        return read(raw, context)

    return read_and_corrupt


def test_fallback_after_a_failed_result_check(monkeypatch):
    skip_unless_usable("SCIPY")
    instance = BY_NAME["N6-n5-deorbit-sparse-binding"]
    best, _ = instance.enumerate()
    model = instance.model()
    scipy_entry = BACKENDS["SCIPY"]
    monkeypatch.setitem(BACKENDS, "SCIPY", replace(scipy_entry, read=corrupting(scipy_entry.read)))
    alone = solve_milp(model.problem, SolverOptions(backend="SCIPY"))
    assert alone.status == Status.ERROR and "result check failed" in alone.message
    assert alone.objective is None and model.s.value is None  # no half-trusted point left
    chain = [SolverOptions(backend="SCIPY"), SolverOptions(backend="HIGHS")]
    report = solve_with_fallback(model.problem, chain)
    assert report.backend == "HIGHS" and report.status == Status.OPTIMAL
    assert report.objective == pytest.approx(best, rel=REL)
    (message,) = report.fallbacks
    assert message.startswith("SCIPY failed: error:") and "result check failed" in message
    assert message.endswith("; used HIGHS")


def test_fallback_after_a_backend_that_raises(crash_backend):
    instance = BY_NAME["N7-n3-deorbit-binding"]
    best, _ = instance.enumerate()
    model = instance.model()
    crash_backend("SCIP")
    report = solve_with_fallback(model.problem, [SolverOptions(backend="SCIP"), SolverOptions()])
    assert report.backend == "HIGHS" and report.objective == pytest.approx(best, rel=REL)
    assert report.fallbacks == ("SCIP failed: error: RuntimeError: simulated crash; used HIGHS",)


def test_infeasible_is_an_answer_not_a_failure():
    skip_unless_usable("SCIP")
    model = BY_NAME["N5-n4-infeasible"].model()
    chain = [SolverOptions(backend="SCIP"), SolverOptions(backend="HIGHS")]
    report = solve_with_fallback(model.problem, chain)
    assert report.backend == "SCIP" and report.status == Status.INFEASIBLE
    assert report.fallbacks == ()


def test_untrusted_infeasible_asks_the_next_backend(monkeypatch):
    skip_unless_usable("GLPK_MI")
    monkeypatch.setitem(BACKENDS, "GLPK_MI", replace(BACKENDS["GLPK_MI"], trust_infeasible=False))
    model = BY_NAME["N5-n4-infeasible"].model()
    chain = [SolverOptions(backend="GLPK_MI"), SolverOptions(backend="HIGHS")]
    report = solve_with_fallback(model.problem, chain)
    assert report.backend == "HIGHS" and report.status == Status.INFEASIBLE
    assert report.fallbacks == (
        "GLPK_MI failed: infeasible, which GLPK_MI is not trusted to prove; used HIGHS",
    )


def test_all_failing_returns_the_last_error():
    model = BY_NAME["N4-n3-binding"].model()
    chain = [unchecked_options("NOPE1"), unchecked_options("NOPE2")]
    report = solve_with_fallback(model.problem, chain)
    assert report.status == Status.ERROR and report.backend == "NOPE2"
    assert report.fallbacks == (
        f"NOPE1 failed: error: unknown MILP backend 'NOPE1'; known: {', '.join(BACKENDS)}; "
        "used NOPE2",
    )
