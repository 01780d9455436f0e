"""MILP backends through CVXPY, with one normalised result (like linopy's status/termination).

:func:`solve_milp` maps our options (time limit, relative gap, threads, verbosity,
seed) to each backend's own names, runs ``problem.solve`` and reads the outcome
into a :class:`SolveReport`.  A time limit reached without an incumbent is *not* a
solution: CVXPY reports it as ``user_limit`` with all-zero variables, so the
backend's own solution status is read (DESIGN §5).  Statistics a backend does not
report are ``None``, never 0.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass
from enum import StrEnum

import cvxpy as cp
from cvxpy import settings as cvxpy_settings

DEFAULT_BACKEND = "HIGHS"


class Status(StrEnum):
    """Outcome of one MILP solve."""

    OPTIMAL = "optimal"
    TIME_LIMIT = "time_limit"  # stopped by a limit, with an incumbent solution
    NO_SOLUTION = "no_solution"  # stopped by a limit before finding any solution
    INFEASIBLE = "infeasible"
    UNBOUNDED = "unbounded"
    ERROR = "error"

    @property
    def has_solution(self) -> bool:
        return self in (Status.OPTIMAL, Status.TIME_LIMIT)


@dataclass(frozen=True)
class SolverOptions:
    """Backend and its settings.

    Parameters
    ----------
    backend : str
        A CVXPY solver name with MILP support: HIGHS (default), SCIP, CBC, GLPK_MI,
        SCIPY, GUROBI, CPLEX, XPRESS, MOSEK, COPT.
    time_limit_s : float, optional
        Wall-clock limit per MILP solve [s].
    mip_gap : float, optional
        Relative MIP gap at which the backend may stop.
    threads : int, optional
        Threads the backend may use.
    verbose : bool
        Show the backend's log.
    seed : int, optional
        Random seed, where the backend has one.
    """

    backend: str = DEFAULT_BACKEND
    time_limit_s: float | None = None
    mip_gap: float | None = 1e-6
    threads: int | None = None
    verbose: bool = False
    seed: int | None = None

    def __post_init__(self):
        object.__setattr__(self, "backend", self.backend.upper())
        if self.time_limit_s is not None and not self.time_limit_s > 0:
            raise ValueError(f"time_limit_s must be > 0, got {self.time_limit_s!r}")
        if self.mip_gap is not None and not 0 <= self.mip_gap < 1:
            raise ValueError(f"mip_gap must be in [0, 1), got {self.mip_gap!r}")
        if self.threads is not None and not (isinstance(self.threads, int) and self.threads >= 1):
            raise ValueError(f"threads must be a positive integer, got {self.threads!r}")


@dataclass(frozen=True)
class SolveReport:
    """Normalised outcome of a MILP solve.

    Attributes
    ----------
    status : Status
    objective : float or None
        Objective of the incumbent (linearised ΔV, m/s).
    dual_bound : float or None
        Best bound proven by the backend.
    mip_gap : float or None
        Relative gap reported by the backend.
    nodes : int or None
        Branch-and-bound nodes.
    solve_seconds : float
        Time inside the backend [s].
    overhead_seconds : float
        CVXPY's part of the wall time (canonicalisation, data transfer) [s].
    backend : str
    message : str
        Backend status in its own words.
    """

    status: Status
    objective: float | None
    dual_bound: float | None
    mip_gap: float | None
    nodes: int | None
    solve_seconds: float
    overhead_seconds: float
    backend: str
    message: str


def backend_kwargs(options: SolverOptions) -> dict:
    """Keyword arguments of ``Problem.solve`` for the options, in the backend's own names."""
    o, name = options, options.backend
    kwargs = {"solver": name, "verbose": o.verbose}
    if name == "HIGHS":
        settings = {"time_limit": o.time_limit_s, "mip_rel_gap": o.mip_gap,
                    "threads": o.threads, "random_seed": o.seed}  # fmt: skip
    elif name == "SCIPY":
        settings = {
            "scipy_options": _drop_none(
                {"time_limit": o.time_limit_s, "mip_rel_gap": o.mip_gap, "disp": o.verbose}
            )
        }
    elif name == "SCIP":
        settings = {
            "scip_params": _drop_none(
                {
                    "limits/time": o.time_limit_s,
                    "limits/gap": o.mip_gap,
                    "randomization/randomseedshift": o.seed,
                }
            )
        }
    elif name == "CBC":
        settings = {"maximumSeconds": o.time_limit_s, "allowableFractionGap": o.mip_gap,
                    "numberThreads": o.threads}  # fmt: skip
    elif name == "GUROBI":
        settings = {"TimeLimit": o.time_limit_s, "MIPGap": o.mip_gap, "Threads": o.threads,
                    "Seed": o.seed}  # fmt: skip
    else:
        settings = {}
    kwargs.update(_drop_none(settings))
    return kwargs


def _drop_none(mapping: dict) -> dict:
    return {k: v for k, v in mapping.items() if v is not None and v != {}}


def solve_milp(problem: cp.Problem, options: SolverOptions, *, warm_start=False) -> SolveReport:
    """Solve ``problem`` with the chosen backend and report the outcome honestly.

    Returns
    -------
    SolveReport
        Never raises for solver failures: they come back as ``Status.ERROR`` with the
        backend's message.
    """
    wall = time.perf_counter()
    try:
        with warnings.catch_warnings():
            # CVXPY warns on inaccurate/limited results; the status is read and reported below
            warnings.filterwarnings("ignore", message="Solution may be inaccurate")
            problem.solve(warm_start=warm_start, **backend_kwargs(options))
        message = problem.status
    except (cp.error.SolverError, ValueError) as err:  # ValueError: an option the backend refuses
        return SolveReport(Status.ERROR, None, None, None, None, 0.0,
                           time.perf_counter() - wall, options.backend, str(err))  # fmt: skip
    wall = time.perf_counter() - wall
    stats = problem.solver_stats
    solve_seconds = float(stats.solve_time or 0.0)
    info = stats.extra_stats if options.backend == "HIGHS" else None
    status = _status(problem.status, info, limited=options.time_limit_s is not None)
    if status.has_solution and any(v.value is None for v in problem.variables()):
        status, message = Status.ERROR, f"{problem.status} but no variable values"
    if status == Status.INFEASIBLE and problem.status == cvxpy_settings.INFEASIBLE_OR_UNBOUNDED:
        message = "infeasible or unbounded (the model's variables are bounded: infeasible)"
    has = status.has_solution
    return SolveReport(
        status=status,
        objective=float(problem.value) if has else None,
        dual_bound=_info(info, "mip_dual_bound"),
        mip_gap=_info(info, "mip_gap") if has else None,
        nodes=_int_or_none(_info(info, "mip_node_count")),
        solve_seconds=solve_seconds,
        overhead_seconds=max(wall - solve_seconds, 0.0),
        backend=options.backend,
        message=str(message),
    )


def _status(cvxpy_status: str, highs_info, *, limited: bool) -> Status:
    if cvxpy_status == cp.OPTIMAL:
        return Status.OPTIMAL
    if cvxpy_status == cp.OPTIMAL_INACCURATE:
        # SCIP, CBC and SciPy report a time limit with an incumbent this way
        return Status.TIME_LIMIT if limited else Status.OPTIMAL
    if cvxpy_status == cp.USER_LIMIT:
        feasible = highs_info is not None and getattr(highs_info, "primal_solution_status", 0) == 2
        return Status.TIME_LIMIT if feasible else Status.NO_SOLUTION
    if cvxpy_status in (
        cp.INFEASIBLE,
        cp.INFEASIBLE_INACCURATE,
        cvxpy_settings.INFEASIBLE_OR_UNBOUNDED,
    ):
        return Status.INFEASIBLE
    if cvxpy_status in (cp.UNBOUNDED, cp.UNBOUNDED_INACCURATE):
        return Status.UNBOUNDED
    return Status.ERROR


def _info(info, name):
    value = getattr(info, name, None) if info is not None else None
    return None if value is None else float(value)


def _int_or_none(value):
    return None if value is None else int(value)
