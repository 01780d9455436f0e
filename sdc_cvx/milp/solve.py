"""Solving a CVXPY MILP with one backend (:func:`solve_milp`) or a chain of them
(:func:`solve_with_fallback`), with the result checked (:func:`check_result`).

See :mod:`sdc_cvx.milp.readers` for how each backend's raw answer is read.
"""

from __future__ import annotations

import copy
import time
import warnings
from collections.abc import Sequence
from dataclasses import replace

import cvxpy as cp
import numpy as np
from cvxpy import settings as cvxpy_settings

from .backends import BACKENDS, _installed
from .output import backend_stdout
from .readers import RawContext
from .types import SolveReport, SolverOptions, Status

CHECK_TOLERANCE = 1e-6
"""Integrality and constraint-violation tolerance of :func:`check_result`."""


# --------------------------------------------------------------------------- checking
def check_result(problem: cp.Problem, tol: float = CHECK_TOLERANCE) -> str | None:
    """Why the values in ``problem`` are not a solution, or None if they are.

    Boolean and integer variables must be within ``tol`` of an integer (booleans also of
    [0, 1]); every constraint's ``violation()`` must be within ``tol`` relative to
    max(1, |lhs|, |rhs|) of its row (SCIP's and CPLEX's feasibility tolerances are
    relative: big-M rows in days reach a few hundred).
    """
    for var in problem.variables():
        value = var.value
        if value is None:
            return f"variable {var.name()} has no value"
        value = np.asarray(value, dtype=float)
        if not np.all(np.isfinite(value)):
            return f"variable {var.name()} is not finite"
        if var.attributes["boolean"] or var.attributes["integer"]:
            off = float(np.max(np.abs(value - np.round(value)), initial=0.0))
            if off > tol:
                return f"variable {var.name()} is {off:.3g} away from an integer"
            if var.attributes["boolean"] and (value.min() < -tol or value.max() > 1 + tol):
                return f"boolean variable {var.name()} outside [0, 1]"
    for k, con in enumerate(problem.constraints):
        violation = np.atleast_1d(np.asarray(con.violation(), dtype=float))
        scale = np.ones_like(violation)
        for arg in con.args:
            side = arg.value
            if side is not None:
                scale = np.maximum(scale, np.broadcast_to(np.abs(side), scale.shape))
        worst = float(np.max(violation / scale, initial=0.0))
        if not worst <= tol:
            label = type(con).__name__
            return f"constraint {k} ({label}, {con.size} rows) violated by {worst:.3g} (relative)"
    return None


# --------------------------------------------------------------------------- solving
def solve_milp(problem: cp.Problem, options: SolverOptions, *, warm_start=False) -> SolveReport:
    """Solve ``problem`` with the chosen backend and report the outcome honestly.

    Only when ``report.status.has_solution`` do the problem's variables hold the
    backend's point (checked with :func:`check_result`); otherwise they are None.

    Returns
    -------
    SolveReport
        Never raises for solver failures: they come back as ``Status.ERROR`` with the
        backend's message.
    """
    name = options.backend
    wall = time.perf_counter()
    backend = BACKENDS.get(name)

    def error(message, seconds=0.0, ignored=()):
        _clear(problem)
        return SolveReport(Status.ERROR, None, None, None, None, seconds,
                           max(time.perf_counter() - wall - seconds, 0.0), name, message,
                           ignored_options=ignored)  # fmt: skip

    if backend is None:
        return error(f"unknown MILP backend {name!r}; known: {', '.join(BACKENDS)}")
    if name not in _installed():
        return error(f"{name} is not installed (pip install {backend.package})")
    kwargs, ignored = backend.kwargs(options)
    kwargs.pop("solver")
    verbose = kwargs.pop("verbose")
    try:
        data, chain, inverse = problem.get_problem_data(name, solver_opts=copy.deepcopy(kwargs))
    except (cp.error.SolverError, cp.error.DCPError, ValueError) as err:
        return error(f"{type(err).__name__}: {err}", ignored=ignored)
    start = time.perf_counter()
    try:
        with warnings.catch_warnings(), backend_stdout(verbose):
            warnings.simplefilter("ignore")  # the status is read and reported below
            raw = chain.solve_via_data(problem, data, warm_start, verbose, copy.deepcopy(kwargs))
    except Exception as err:  # noqa: BLE001 - any backend failure (license, option, crash)
        return error(f"{type(err).__name__}: {err}", time.perf_counter() - start, ignored)
    elapsed = time.perf_counter() - start
    context = RawContext(
        sign=-1.0 if isinstance(problem.objective, cp.Maximize) else 1.0,
        offset=_offset(inverse),
        elapsed=elapsed,
        time_limit=options.time_limit_s,
    )
    try:
        native = backend.read(raw, context)
    except Exception as err:  # noqa: BLE001 - an unexpected raw result
        return error(f"cannot read the {name} result: {type(err).__name__}: {err}", elapsed,
                     ignored)  # fmt: skip
    status, message = native.status, native.message
    if status.has_solution:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                problem.unpack_results(raw, chain, inverse)
        except Exception as err:  # noqa: BLE001 - CVXPY's own reading disagrees
            status, message = Status.ERROR, f"{message}, but CVXPY returned no point: {err}"
        else:
            failure = check_result(problem) or _objective_mismatch(problem, native.objective)
            if failure:
                status, message = Status.ERROR, f"{message}; result check failed: {failure}"
    if not status.has_solution:
        _clear(problem)
    solve_seconds = native.seconds if native.seconds is not None else elapsed
    has = status.has_solution
    return SolveReport(
        status=status,
        objective=float(problem.objective.value) if has else None,
        dual_bound=None if status in (Status.INFEASIBLE, Status.UNBOUNDED) else native.bound,
        mip_gap=native.gap if has else None,
        nodes=native.nodes,
        solve_seconds=float(solve_seconds),
        overhead_seconds=max(time.perf_counter() - wall - solve_seconds, 0.0),
        backend=name,
        message=str(message),
        iterations=native.iterations,
        ignored_options=ignored,
    )


def _offset(inverse) -> float:
    """The objective constant CVXPY keeps out of the backend (its last inverse data)."""
    try:
        value = inverse[-1][cvxpy_settings.OFFSET]  # SolverInverseData delegates to a dict
    except (IndexError, KeyError, TypeError):
        return 0.0
    return 0.0 if value is None else float(np.asarray(value).item())


def _objective_mismatch(problem: cp.Problem, native: float | None) -> str | None:
    if native is None:
        return None
    ours = float(problem.objective.value)
    if abs(ours - native) <= CHECK_TOLERANCE * max(1.0, abs(ours)):
        return None
    return f"backend objective {native:.9g} differs from the returned point's {ours:.9g}"


def _clear(problem: cp.Problem) -> None:
    for var in problem.variables():
        var.value = None


# --------------------------------------------------------------------------- fallback
def fallback_reason(report: SolveReport, *, retry_no_solution: bool = False) -> str | None:
    """Why the next backend of a chain should be tried after ``report``, or None.

    ERROR (a raise, a refused option, a failed result check, not installed) and
    UNBOUNDED (the sequential models are bounded, so this is a backend failure, e.g.
    CVXPY's reading of CBC's "unset") always fall back.  INFEASIBLE does only when the
    backend's registry entry has ``trust_infeasible=False``: an infeasible
    linearisation is an answer the driver acts on (it narrows the intervals), and
    asking every backend would multiply the time of those iterations.  NO_SOLUTION (a
    time limit without incumbent) falls back only with ``retry_no_solution``.
    """
    if report.status in (Status.ERROR, Status.UNBOUNDED):
        return f"{report.status.value}: {report.message}"
    backend = BACKENDS.get(report.backend)
    if report.status == Status.INFEASIBLE and backend is not None and not backend.trust_infeasible:
        return f"infeasible, which {report.backend} is not trusted to prove"
    if report.status == Status.NO_SOLUTION and retry_no_solution:
        return f"no solution within the time limit: {report.message}"
    return None


def chain_of(options: SolverOptions) -> list[SolverOptions]:
    """``options`` followed by one copy per backend of its ``fallback`` list."""
    return [options] + [replace(options, backend=name, fallback=()) for name in options.fallback]


def solve_with_fallback(
    problem: cp.Problem,
    chain: Sequence[SolverOptions],
    *,
    warm_start=False,
    retry_no_solution=False,
) -> SolveReport:
    """Solve with the first backend of ``chain`` that does not fail (:func:`fallback_reason`).

    Returns
    -------
    SolveReport
        The report of the backend used, whose ``fallbacks`` lists one message per
        backend that failed before it ("SCIP failed: <reason>; used HIGHS").  When every
        backend fails, the last report (with the earlier failures in ``fallbacks``).
    """
    if not chain:
        raise ValueError("the backend chain is empty")
    failures: list[tuple[str, str]] = []
    report = None
    for k, options in enumerate(chain):
        try:
            report = solve_milp(problem, options, warm_start=warm_start)
        except Exception as err:  # noqa: BLE001 - a backend that raises is a failure too
            _clear(problem)
            report = SolveReport(Status.ERROR, None, None, None, None, 0.0, 0.0,
                                 options.backend, f"{type(err).__name__}: {err}")  # fmt: skip
        reason = fallback_reason(report, retry_no_solution=retry_no_solution)
        if reason is None or k == len(chain) - 1:
            break
        failures.append((options.backend, reason))
    used_next = [name for name, _ in failures[1:]] + [report.backend]
    messages = [
        f"{name} failed: {reason}; used {nxt}"
        for (name, reason), nxt in zip(failures, used_next[: len(failures)], strict=True)
    ]
    return replace(report, fallbacks=tuple(messages))
