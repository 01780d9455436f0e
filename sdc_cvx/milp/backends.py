"""MILP backends through CVXPY, with one normalised result (like linopy's status/termination).

:data:`BACKENDS` is the registry: for every backend CVXPY can call with MILP
support, its Python package, our options (time limit, relative gap, threads,
verbosity, seed) in the backend's own names, and a reader that turns the
backend's raw result into a :class:`SolveReport`.

:func:`solve_milp` runs one backend.  It drives CVXPY's documented three steps
(``get_problem_data``, ``SolvingChain.solve_via_data``, ``unpack_results``) instead of
``Problem.solve`` so that it sees the backend's own answer before CVXPY maps it,
because that mapping loses facts the driver needs (checked on cvxpy 1.9.3):

* HiGHS: a time limit without an incumbent is ``user_limit`` with all-zero values;
* CBC: a time limit without an incumbent is ``optimal_inaccurate`` with objective
  1e50 and a fractional point;
* SCIP, SciPy, GLPK_MI, CPLEX, Xpress: a time limit without an incumbent raises
  ``SolverError`` (``solver_error``), the same as a real failure;
* SCIP: a time limit *with* an incumbent gives ``problem.value`` NaN in the raw
  result (CVXPY re-evaluates the objective on unpacking; we do the same);
* SCIP ``gaplimit`` and GLPK ``feasible`` (stopped at the requested relative gap)
  come back as ``optimal_inaccurate``, like a time limit;
* Gurobi, COPT: a time limit without an incumbent becomes ``infeasible_inaccurate``.

A time limit *with* an incumbent is ``user_limit`` (HiGHS, Gurobi) or
``optimal_inaccurate`` (SCIP, CBC, SciPy, GLPK_MI, CPLEX, Xpress, COPT); all become
``Status.TIME_LIMIT`` here.

A solution is then checked (:func:`check_result`): integrality of boolean/integer
variables and every constraint's violation within 1e-6 (relative to max(1, |lhs|,
|rhs|) of the row, like SCIP's and CPLEX's feasibility tolerances); a failed check is
``Status.ERROR`` ("result check failed: ...").  Statistics a backend does not
report are ``None``, never 0.

:func:`solve_with_fallback` tries a chain of backends in order.
"""

from __future__ import annotations

import copy
import functools
import importlib.metadata
import importlib.util
import math
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum

import cvxpy as cp
import numpy as np
from cvxpy import settings as cvxpy_settings

DEFAULT_BACKEND = "HIGHS"
CHECK_TOLERANCE = 1e-6
"""Integrality and constraint-violation tolerance of :func:`check_result`."""

_LIMIT_FRACTION = 0.9
"""For backends whose raw result cannot tell a time limit from another stop (GLPK_MI,
XPRESS, MOSEK): the stop counts as the time limit when the backend ran at least this
fraction of it."""


class Status(StrEnum):
    """Outcome of one MILP solve."""

    OPTIMAL = "optimal"  # proven optimal within the requested relative gap
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
        SCIPY, GUROBI, CPLEX, XPRESS, MOSEK, COPT (see :data:`BACKENDS`).
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
    fallback : tuple of str
        Backends tried in turn, with the same settings, when ``backend`` raises, fails
        or returns a result that fails the check (:func:`solve_with_fallback`).
    """

    backend: str = DEFAULT_BACKEND
    time_limit_s: float | None = None
    mip_gap: float | None = 1e-6
    threads: int | None = None
    verbose: bool = False
    seed: int | None = None
    fallback: tuple[str, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "backend", self.backend.upper())
        object.__setattr__(self, "fallback", tuple(str(b).upper() for b in self.fallback))
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
        Objective of the incumbent (linearised ΔV, m/s), evaluated by CVXPY at the
        returned point.
    dual_bound : float or None
        Best bound proven by the backend (objective's units, constant included).
    mip_gap : float or None
        Relative gap as the backend defines it (HiGHS, SciPy, Gurobi, CPLEX, COPT:
        |primal - bound| / |primal|; SCIP: over min(|primal|, |bound|)).
    nodes : int or None
        Branch-and-bound nodes.
    solve_seconds : float
        Time inside the backend [s]: its own clock where it reports one
        (``Backend.reports_time``), else the wall time of CVXPY's interface call.
    overhead_seconds : float
        CVXPY's part of the wall time (canonicalisation, data transfer) [s].
    backend : str
    message : str
        Backend status in its own words (and why a result was rejected).
    iterations : int or None
        Simplex (LP) iterations.
    fallbacks : tuple of str
        Backends that failed before this one in :func:`solve_with_fallback`, one
        message each ("SCIP failed: <reason>; used HIGHS").
    ignored_options : tuple of str
        Options set but not supported by the backend (not passed on).
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
    iterations: int | None = None
    fallbacks: tuple[str, ...] = ()
    ignored_options: tuple[str, ...] = ()


# --------------------------------------------------------------------------- raw results
@dataclass
class RawContext:
    """What a reader needs besides the raw result."""

    sign: float  # +1 for Minimize, -1 for Maximize (CVXPY minimises -f)
    offset: float  # constant CVXPY keeps out of the backend's objective
    elapsed: float  # wall time of the interface call [s]
    time_limit: float | None

    def user(self, native):
        """A backend objective value in the problem's terms (sign, constant)."""
        value = _finite(native)
        return None if value is None else self.sign * (value + self.offset)

    def at_time_limit(self) -> bool:
        return self.time_limit is not None and self.elapsed >= _LIMIT_FRACTION * self.time_limit


@dataclass
class Native:
    """A backend's outcome in our terms, read from its raw result."""

    status: Status
    message: str
    bound: float | None = None  # in the problem's terms (RawContext.user)
    gap: float | None = None
    nodes: int | None = None
    iterations: int | None = None
    seconds: float | None = None
    objective: float | None = None  # the backend's own objective, problem's terms


# --------------------------------------------------------------------------- registry
@dataclass(frozen=True)
class Backend:
    """One MILP backend CVXPY can call.

    Attributes
    ----------
    name : str
        CVXPY's solver name.
    package : str
        Python distribution that provides it (``pip install``).
    module : str
        Importable module of that distribution.
    options : dict
        Our option -> the backend's name for it (``SolverOptions`` field names as
        keys); an option absent here is not supported and is not passed on.
    nest : str or None
        Keyword under which CVXPY expects the backend's options as a dict
        (``scip_params``, ``scipy_options``, ...), None for top-level keywords.
    read : callable
        ``read(raw, RawContext) -> Native``: the raw result of
        ``SolvingChain.solve_via_data`` in our terms.
    stats : str
        Where the statistics are: in the raw result, and what CVXPY keeps of them
        in ``problem.solver_stats``.
    verified : str
        How the option names and the status reading were checked.
    trust_infeasible : bool
        Whether an INFEASIBLE answer is taken as the model's answer; when False,
        :func:`solve_with_fallback` asks the next backend.
    reports_time : bool
        Whether the backend reports its own solve time.
    commercial : bool
    converters : dict
        Our option -> function converting our value to the backend's (units).
    """

    name: str
    package: str
    module: str
    options: dict
    read: Callable[[object, RawContext], Native]
    stats: str
    verified: str
    nest: str | None = None
    trust_infeasible: bool = True
    reports_time: bool = True
    commercial: bool = False
    converters: dict = field(default_factory=dict)

    def kwargs(self, options: SolverOptions) -> tuple[dict, tuple[str, ...]]:
        """``Problem.solve`` keywords for ``options`` and the options the backend lacks."""
        settings, ignored = {}, []
        for ours in ("time_limit_s", "mip_gap", "threads", "seed", "verbose"):
            value = getattr(options, ours)
            if value is None or (ours == "verbose" and ours not in self.options):
                continue  # verbosity itself is CVXPY's ``verbose`` keyword
            theirs = self.options.get(ours)
            if theirs is None:
                ignored.append(ours)
                continue
            settings[theirs] = self.converters.get(ours, _same)(value)
        kwargs = {"solver": self.name, "verbose": options.verbose}
        if self.nest is None:
            kwargs.update(settings)
        elif settings:
            kwargs[self.nest] = settings
        return kwargs, tuple(ignored)


def _same(value):
    return value


def _finite(value):
    try:
        value = float(value)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) and abs(value) < 1e20 else None


def _int(value):
    try:
        return None if value is None or value < 0 else int(value)
    except (TypeError, ValueError):
        return None


def _try(function, default=None):
    """``function()``, or ``default`` when the backend refuses (no such attribute yet)."""
    try:
        return function()
    except Exception:  # noqa: BLE001 - backends raise their own types for "unavailable"
        return default


def _limit_status(has_incumbent: bool) -> Status:
    return Status.TIME_LIMIT if has_incumbent else Status.NO_SOLUTION


_INF_OR_UNB = "infeasible or unbounded"


# -- HiGHS ------------------------------------------------------------------------------
_HIGHS_LIMITS = {"kTimeLimit", "kIterationLimit", "kSolutionLimit", "kInterrupt",
                 "kObjectiveBound", "kObjectiveTarget", "kMemoryLimit"}  # fmt: skip


def _read_highs(raw, ctx: RawContext) -> Native:
    code, info = raw["model_status"], raw["info"]
    feasible = getattr(info, "primal_solution_status", 0) == 2  # kSolutionStatusFeasible
    if code == "kOptimal":
        status = Status.OPTIMAL
    elif code in _HIGHS_LIMITS:
        status = _limit_status(feasible)
    elif code == "kInfeasible":
        status = Status.INFEASIBLE
    elif code == "kUnboundedOrInfeasible":
        status, code = Status.INFEASIBLE, f"{code} ({_INF_OR_UNB})"
    elif code == "kUnbounded":
        status = Status.UNBOUNDED
    else:
        status = Status.ERROR
    return Native(
        status, code,
        bound=ctx.user(info.mip_dual_bound),
        gap=_finite(info.mip_gap) if feasible else None,
        nodes=_int(info.mip_node_count),
        iterations=_int(info.simplex_iteration_count),
        seconds=_finite(raw["run_time"]),
        objective=ctx.user(info.objective_function_value) if feasible else None,
    )  # fmt: skip


# -- SCIP -------------------------------------------------------------------------------
_SCIP_LIMITS = {"timelimit", "nodelimit", "totalnodelimit", "stallnodelimit", "sollimit",
                "bestsollimit", "memlimit", "restartlimit", "userinterrupt"}  # fmt: skip


def _read_scip(raw, ctx: RawContext) -> Native:
    model, code = raw["model"], raw["scip_status"]
    has = max(model.getNSols(), model.getNCountedSols()) > 0
    if code == "optimal":
        status = Status.OPTIMAL
    elif code == "gaplimit":  # stopped at limits/gap: optimal within the requested gap
        status = Status.OPTIMAL if has else Status.ERROR
    elif code in _SCIP_LIMITS:
        status = _limit_status(has)
    elif code == "infeasible":
        status = Status.INFEASIBLE
    elif code == "inforunbd":
        status, code = Status.INFEASIBLE, f"{code} ({_INF_OR_UNB})"
    elif code == "unbounded":
        status = Status.UNBOUNDED
    else:
        status = Status.ERROR
    return Native(
        status, code,
        bound=ctx.user(model.getDualbound()),
        gap=_finite(model.getGap()) if has else None,
        nodes=_int(model.getNTotalNodes()),
        iterations=_int(model.getNLPIterations()),
        seconds=_finite(model.getSolvingTime()),
        objective=ctx.user(model.getPrimalbound()) if has else None,
    )  # fmt: skip


# -- CBC --------------------------------------------------------------------------------
def _read_cbc(raw, ctx: RawContext) -> Native:
    # CVXPY keeps only its own status, the point and CBC's objective: the CyCbcModel
    # (nodeCount, bestPossibleObjValue) is dropped, so no bound, gap or nodes.
    code = raw["status"]
    value = raw.get("value")
    incumbent = _finite(value) is not None and abs(float(value)) < 1e50
    if code == cp.OPTIMAL:
        status = Status.OPTIMAL
    elif code == cp.OPTIMAL_INACCURATE:  # "stopped on time/nodes/solutions"
        status = _limit_status(incumbent)
        if not incumbent:
            code = f"{code} with objective {value!r}: no integer solution"
    elif code == cp.INFEASIBLE:
        status = Status.INFEASIBLE
    elif code == cp.UNBOUNDED:  # also CVXPY's reading of CBC's "unset"
        status, code = Status.UNBOUNDED, f"{code} (CBC 'linear relaxation unbounded' or 'unset')"
    else:
        status = Status.ERROR
    return Native(status, str(code), objective=ctx.user(value) if incumbent else None)


# -- GLPK_MI ----------------------------------------------------------------------------
def _read_glpk(raw, ctx: RawContext) -> Native:
    # CVXPY keeps its mapping of cvxopt's status only: 'optimal' -> optimal,
    # 'feasible' -> optimal_inaccurate (stopped by tm_lim *or* at mip_gap),
    # 'undefined' (no integer solution at tm_lim) -> solver_error.  The elapsed time
    # tells the time limit apart.
    code = raw["status"]
    if code == cp.OPTIMAL:
        status = Status.OPTIMAL
    elif code == cp.OPTIMAL_INACCURATE:
        if ctx.at_time_limit():
            status, code = Status.TIME_LIMIT, "feasible (time limit)"
        else:
            status, code = Status.OPTIMAL, "feasible (relative gap reached)"
    elif code == cvxpy_settings.SOLVER_ERROR and ctx.at_time_limit():
        status, code = Status.NO_SOLUTION, "undefined (time limit, no integer solution)"
    elif code == cp.INFEASIBLE:
        status = Status.INFEASIBLE
    elif code == cp.UNBOUNDED:
        status = Status.UNBOUNDED
    else:
        status = Status.ERROR
    return Native(status, str(code))


# -- SciPy ------------------------------------------------------------------------------
def _read_scipy(raw, ctx: RawContext) -> Native:
    code, has = int(raw.status), raw.x is not None
    status = {0: Status.OPTIMAL, 1: _limit_status(has), 2: Status.INFEASIBLE,
              3: Status.UNBOUNDED}.get(code, Status.ERROR)  # fmt: skip
    return Native(
        status, str(raw.message),
        bound=ctx.user(raw.get("mip_dual_bound")),
        gap=_finite(raw.get("mip_gap")) if has else None,
        nodes=_int(raw.get("mip_node_count")),
        objective=ctx.user(raw.get("fun")) if has else None,
    )  # fmt: skip


# -- Gurobi -----------------------------------------------------------------------------
_GUROBI_CODES = {2: "OPTIMAL", 3: "INFEASIBLE", 4: "INF_OR_UNBD", 5: "UNBOUNDED", 6: "CUTOFF",
                 7: "ITERATION_LIMIT", 8: "NODE_LIMIT", 9: "TIME_LIMIT", 10: "SOLUTION_LIMIT",
                 11: "INTERRUPTED", 12: "NUMERIC", 13: "SUBOPTIMAL", 14: "INPROGRESS",
                 15: "USER_OBJ_LIMIT", 16: "WORK_LIMIT", 17: "MEM_LIMIT"}  # fmt: skip


def _read_gurobi(raw, ctx: RawContext) -> Native:
    model = raw["model"]
    code = int(model.Status)
    has = _try(lambda: model.SolCount, 0) > 0
    if code == 2:
        status = Status.OPTIMAL
    elif code in (7, 8, 9, 10, 11, 13, 15, 16, 17):
        status = _limit_status(has)
    elif code in (3, 4):
        status = Status.INFEASIBLE
    elif code == 5:
        status = Status.UNBOUNDED
    else:
        status = Status.ERROR
    name = _GUROBI_CODES.get(code, str(code))
    return Native(
        status, name if code != 4 else f"{name} ({_INF_OR_UNB})",
        bound=ctx.user(_try(lambda: model.ObjBound)),
        gap=_finite(_try(lambda: model.MIPGap)) if has else None,
        nodes=_int(_try(lambda: model.NodeCount)),
        iterations=_int(_try(lambda: model.IterCount)),
        seconds=_finite(_try(lambda: model.Runtime)),
        objective=ctx.user(_try(lambda: model.ObjVal)) if has else None,
    )  # fmt: skip


# -- CPLEX ------------------------------------------------------------------------------
_CPLEX_OPTIMAL = {1, 101, 102}  # optimal, MIP_optimal, optimal_tolerance (within mipgap)
_CPLEX_INFEASIBLE = {3, 103}
_CPLEX_INF_OR_UNB = {4, 119}
_CPLEX_UNBOUNDED = {2, 118}
_CPLEX_LIMITS = {104, 105, 106, 107, 108, 111, 112, 113, 114, 127, 128, 131, 132}
# MIP_sol_lim, node limit (feasible / infeasible), time limit (feasible / infeasible),
# memory limit, abort, MIP_feasible, populate limit, deterministic time limit


def _read_cplex(raw, ctx: RawContext) -> Native:
    model = raw["model"]
    solution = model.solution
    code = int(solution.get_status())
    text = f"{_try(solution.get_status_string, '')} ({code})"
    has = bool(_try(solution.is_primal_feasible, False))
    if code in _CPLEX_OPTIMAL:
        status = Status.OPTIMAL
    elif code in _CPLEX_INFEASIBLE:
        status = Status.INFEASIBLE
    elif code in _CPLEX_INF_OR_UNB:
        status, text = Status.INFEASIBLE, f"{text} ({_INF_OR_UNB})"
    elif code in _CPLEX_UNBOUNDED:
        status = Status.UNBOUNDED
    elif code in _CPLEX_LIMITS:
        status = _limit_status(has)
    else:
        status = Status.ERROR
    mip = solution.MIP
    return Native(
        status, text,
        bound=ctx.user(_try(mip.get_best_objective)),
        gap=_finite(_try(mip.get_mip_relative_gap)) if has else None,
        nodes=_int(_try(solution.progress.get_num_nodes_processed)),
        iterations=_int(_try(solution.progress.get_num_iterations)),
        seconds=_finite(raw.get(cvxpy_settings.SOLVE_TIME)),
        objective=ctx.user(_try(solution.get_objective_value)) if has else None,
    )  # fmt: skip


# -- Xpress -----------------------------------------------------------------------------
def _read_xpress(raw, ctx: RawContext) -> Native:
    # CVXPY deletes the problem object and keeps its mapping of SolStatus only:
    # OPTIMAL, FEASIBLE -> optimal_inaccurate, NOTFOUND -> solver_error, ...
    code = raw[cvxpy_settings.STATUS]
    if code == cp.OPTIMAL:
        status, text = Status.OPTIMAL, "OPTIMAL"
    elif code == cp.OPTIMAL_INACCURATE:
        status, text = Status.TIME_LIMIT, "FEASIBLE (stopped by a limit)"
    elif code == cvxpy_settings.SOLVER_ERROR and ctx.at_time_limit():
        status, text = Status.NO_SOLUTION, "NOTFOUND (time limit, no integer solution)"
    elif code == cp.INFEASIBLE:
        status, text = Status.INFEASIBLE, "INFEASIBLE"
    elif code == cp.UNBOUNDED:
        status, text = Status.UNBOUNDED, "UNBOUNDED"
    else:
        status, text = Status.ERROR, str(code)
    seconds = _finite(raw.get(cvxpy_settings.SOLVE_TIME))
    has = status.has_solution
    return Native(status, text, seconds=seconds,
                  objective=ctx.user(raw.get("getObjVal")) if has else None)  # fmt: skip


# -- MOSEK ------------------------------------------------------------------------------
def _read_mosek(raw, ctx: RawContext) -> Native:
    import mosek

    task = raw["task"]
    integer = mosek.soltype.itg
    solsta = _try(lambda: task.getsolsta(integer))
    prosta = _try(lambda: task.getprosta(integer))
    nsol = _try(lambda: task.getintinf(mosek.iinfitem.mio_num_int_solutions), 0)
    seconds = _finite(_try(lambda: task.getdouinf(mosek.dinfitem.optimizer_time)))
    text = f"solsta {solsta}, prosta {prosta}"
    if solsta == mosek.solsta.integer_optimal:
        status = Status.OPTIMAL
    elif prosta == mosek.prosta.prim_infeas:
        status = Status.INFEASIBLE
    elif prosta == mosek.prosta.dual_infeas:
        status = Status.UNBOUNDED
    elif solsta == mosek.solsta.prim_feas:
        status = Status.TIME_LIMIT
    elif (
        nsol == 0
        and ctx.time_limit is not None
        and (seconds or ctx.elapsed) >= (_LIMIT_FRACTION * ctx.time_limit)
    ):
        status = Status.NO_SOLUTION
    else:
        status = Status.ERROR
    has = status.has_solution

    def dou(item):
        return _try(lambda: task.getdouinf(getattr(mosek.dinfitem, item)))

    return Native(
        status, text,
        bound=ctx.user(dou("mio_obj_bound")),
        gap=_finite(dou("mio_obj_rel_gap")) if has else None,
        nodes=_int(_try(lambda: task.getintinf(mosek.iinfitem.mio_num_solved_nodes))),
        iterations=_int(_try(lambda: task.getlintinf(mosek.liinfitem.mio_simplex_iter))),
        seconds=seconds,
        objective=ctx.user(dou("mio_obj_int")) if has else None,
    )  # fmt: skip


# -- COPT -------------------------------------------------------------------------------
_COPT_CODES = {0: "UNSTARTED", 1: "OPTIMAL", 2: "INFEASIBLE", 3: "UNBOUNDED", 4: "INF_OR_UNB",
               5: "NUMERICAL", 6: "NODELIMIT", 7: "IMPRECISE", 8: "TIMEOUT", 9: "UNFINISHED",
               10: "INTERRUPTED", 11: "ITERLIMIT"}  # fmt: skip


def _read_copt(raw, ctx: RawContext) -> Native:
    model = raw["model"]
    code = int(model.status)
    has = bool(_try(lambda: model.hasmipsol, False))
    if code == 1:
        status = Status.OPTIMAL
    elif code in (6, 8, 10, 11):
        status = _limit_status(has)
    elif code in (2, 4):
        status = Status.INFEASIBLE
    elif code == 3:
        status = Status.UNBOUNDED
    else:
        status = Status.ERROR
    text = _COPT_CODES.get(code, str(code)) + (f" ({_INF_OR_UNB})" if code == 4 else "")
    return Native(
        status, text,
        bound=ctx.user(_try(lambda: model.bestbnd)),
        gap=_finite(_try(lambda: model.bestgap)) if has else None,
        nodes=_int(_try(lambda: model.nodecnt)),
        iterations=_int(_try(lambda: model.simplexiter)),
        seconds=_finite(_try(lambda: model.solvingtime)),
        objective=ctx.user(_try(lambda: model.objval)) if has else None,
    )  # fmt: skip


def _milliseconds(seconds: float) -> int:
    return max(1, int(round(seconds * 1000)))


_VERIFIED = "verified here by solving (cvxpy 1.9.3)"
_VERIFIED_FREE = "verified by solving small models with the size-limited pip build (cvxpy 1.9.3)"

BACKENDS: dict[str, Backend] = {
    b.name: b
    for b in (
        Backend(
            "HIGHS", "highspy", "highspy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "threads": "threads",
             "seed": "random_seed"},
            _read_highs,
            stats="raw: model_status, info (HighsInfo: mip_dual_bound, mip_gap, "
            "mip_node_count, simplex_iteration_count, primal_solution_status), run_time; "
            "solver_stats.extra_stats is the HighsInfo, solve_time the run_time",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIP", "PySCIPOpt", "pyscipopt",
            {"time_limit_s": "limits/time", "mip_gap": "limits/gap",
             "seed": "randomization/randomseedshift"},
            _read_scip, nest="scip_params",
            stats="raw: a dict with scip_status and model (pyscipopt Model: getDualbound, "
            "getGap, getNTotalNodes, getNLPIterations, getSolvingTime, getNSols); "
            "solver_stats.extra_stats is that dict (extra_stats['model']). No threads: "
            "CVXPY calls the sequential optimize(), parallel/* only acts in concurrent mode",
            verified=_VERIFIED,
        ),
        Backend(
            "CBC", "cylp", "cylp",
            {"time_limit_s": "maximumSeconds", "mip_gap": "allowableFractionGap",
             "threads": "numberThreads"},
            _read_cbc, reports_time=False,
            stats="raw: status (CVXPY's), primal, value only; CVXPY drops the CyCbcModel "
            "(nodeCount, bestPossibleObjValue): no bound, gap, nodes; extra_stats and "
            "solve_time None. cylp has no seed setting",
            verified=_VERIFIED + " (numberThreads accepted; its effect not measured)",
        ),
        Backend(
            "GLPK_MI", "cvxopt", "cvxopt",
            {"time_limit_s": "tm_lim", "mip_gap": "mip_gap"},
            _read_glpk, reports_time=False,
            converters={"time_limit_s": _milliseconds},
            stats="raw: status (CVXPY's), primal, value only: no bound, gap, nodes, time; "
            "a time limit is told apart from the gap stop by the elapsed time. "
            "GLPK is single-threaded and has no seed",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIPY", "scipy", "scipy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "verbose": "disp"},
            _read_scipy, nest="scipy_options", reports_time=False,
            stats="raw: scipy.optimize.OptimizeResult (status, message, x, fun, "
            "mip_dual_bound, mip_gap, mip_node_count); solver_stats.extra_stats holds the "
            "three mip_* only with a solution. scipy.optimize.milp has no threads or seed",
            verified=_VERIFIED,
        ),
        Backend(
            "GUROBI", "gurobipy", "gurobipy",
            {"time_limit_s": "TimeLimit", "mip_gap": "MIPGap", "threads": "Threads",
             "seed": "Seed"},
            _read_gurobi, commercial=True,
            stats="raw: dict with model (gurobipy Model: Status, SolCount, ObjBound, "
            "MIPGap, NodeCount, IterCount, Runtime); solver_stats.extra_stats is the Model",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "CPLEX", "cplex", "cplex",
            {"time_limit_s": "timelimit", "mip_gap": "mip.tolerances.mipgap",
             "threads": "threads", "seed": "randomseed"},
            _read_cplex, nest="cplex_params", commercial=True,
            stats="raw: dict with model (cplex.Cplex: solution.get_status, "
            "solution.MIP.get_best_objective / get_mip_relative_gap, "
            "solution.progress.get_num_nodes_processed); solver_stats has solve_time only",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "XPRESS", "xpress", "xpress",
            {"time_limit_s": "timelimit", "mip_gap": "miprelstop", "threads": "threads",
             "seed": "randomseed"},
            _read_xpress, commercial=True,
            stats="raw: CVXPY's status, primal, getObjVal, solve_time; the problem object "
            "is deleted: no bound, gap, nodes. CVXPY silently drops control names Xpress "
            "does not know",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "MOSEK", "mosek", "mosek",
            {"time_limit_s": "MSK_DPAR_OPTIMIZER_MAX_TIME",
             "mip_gap": "MSK_DPAR_MIO_TOL_REL_GAP", "threads": "MSK_IPAR_NUM_THREADS",
             "seed": "MSK_IPAR_MIO_SEED"},
            _read_mosek, nest="mosek_params", commercial=True,
            stats="raw: dict with task (mosek.Task: getsolsta/getprosta(itg), "
            "getdouinf mio_obj_bound / mio_obj_rel_gap, getintinf mio_num_solved_nodes); "
            "solver_stats.extra_stats has mio_intpnt_iter, mio_simplex_iter only",
            verified="option names accepted by a mosek 11.2 Task (a wrong name is refused); "
            "solving and the status reading not verified: needs a license",
        ),
        Backend(
            "COPT", "coptpy", "coptpy",
            {"time_limit_s": "TimeLimit", "mip_gap": "RelGap", "threads": "Threads"},
            _read_copt, commercial=True,
            stats="raw: dict with model (coptpy Model: status, hasmipsol, bestbnd, bestgap, "
            "nodecnt, simplexiter, solvingtime); solver_stats.extra_stats is the Model. "
            "COPT has no seed parameter",
            verified=_VERIFIED_FREE,
        ),
    )
}  # fmt: skip
"""The MILP backends CVXPY can call, the default (HiGHS) first."""

MILP_BACKENDS = tuple(BACKENDS)


def package_version(module: str, package: str | None = None) -> str | None:
    """Version of an installed distribution (without importing it), or None."""
    try:
        if importlib.util.find_spec(module) is None:
            return None
        return importlib.metadata.version(package or module)
    except (ImportError, ValueError, importlib.metadata.PackageNotFoundError):
        return None


def available_backends(names: Sequence[str] | None = None) -> list[dict]:
    """The registry's backends (or ``names``) and whether CVXPY can call them here.

    Returns
    -------
    list of dict
        ``name``, ``installed`` (CVXPY lists it: the package imports; a commercial
        backend may still lack a license), ``version`` (of the package, or None),
        ``package``, ``commercial``, ``default``, ``options`` (our option -> its name).
    """
    installed = _installed()
    rows = []
    for name in MILP_BACKENDS if names is None else [n.upper() for n in names]:
        backend = BACKENDS.get(name)
        if backend is None:
            raise ValueError(f"unknown MILP backend {name!r}; known: {', '.join(BACKENDS)}")
        rows.append(
            {
                "name": name,
                "installed": name in installed,
                "version": package_version(backend.module, backend.package),
                "package": backend.package,
                "commercial": backend.commercial,
                "default": name == DEFAULT_BACKEND,
                "options": dict(backend.options),
            }
        )
    return rows


def installed_backends() -> list[str]:
    """Names of the registry's backends CVXPY can call here, in registry order."""
    return [name for name in MILP_BACKENDS if name in _installed()]


@functools.cache
def _installed() -> frozenset[str]:
    """CVXPY's installed solvers (1 ms a call; fixed once CVXPY is imported)."""
    return frozenset(cp.installed_solvers())


def backend_kwargs(options: SolverOptions) -> dict:
    """Keyword arguments of ``Problem.solve`` for the options, in the backend's own names.

    Options the backend does not support are left out (see :meth:`Backend.kwargs`).
    """
    backend = BACKENDS.get(options.backend)
    if backend is None:
        return {"solver": options.backend, "verbose": options.verbose}
    return backend.kwargs(options)[0]


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
        with warnings.catch_warnings():
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
