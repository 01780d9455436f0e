"""Each MILP backend's raw result read in our terms (like linopy's status/termination).

The backend table :data:`~sdc_cvx.milp.backends.BACKENDS` names, for every backend CVXPY
can call with MILP support, a reader defined here that turns the backend's raw result
into our terms (:class:`Native`); :mod:`sdc_cvx.milp.solve` makes the
:class:`~sdc_cvx.milp.types.SolveReport`.

:func:`~sdc_cvx.milp.solve.solve_milp` runs one backend.  It drives CVXPY's documented three steps
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

A solution is then checked (:func:`~sdc_cvx.milp.solve.check_result`): integrality of
boolean/integer variables and every constraint's violation within 1e-6 (relative to max(1, |lhs|,
|rhs|) of the row, like SCIP's and CPLEX's feasibility tolerances); a failed check is
``Status.ERROR`` ("result check failed: ...").  Statistics a backend does not
report are ``None``, never 0.

:func:`~sdc_cvx.milp.solve.solve_with_fallback` tries a chain of backends in order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cvxpy as cp
from cvxpy import settings as cvxpy_settings

from .types import Status

_LIMIT_FRACTION = 0.9
"""For backends whose raw result cannot tell a time limit from another stop (GLPK_MI,
XPRESS, MOSEK): the stop counts as the time limit when the backend ran at least this
fraction of it."""


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


def read_highs(raw, ctx: RawContext) -> Native:
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


def read_scip(raw, ctx: RawContext) -> Native:
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
def read_cbc(raw, ctx: RawContext) -> Native:
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
def read_glpk(raw, ctx: RawContext) -> Native:
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
def read_scipy(raw, ctx: RawContext) -> Native:
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


def read_gurobi(raw, ctx: RawContext) -> Native:
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


def read_cplex(raw, ctx: RawContext) -> Native:
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
def read_xpress(raw, ctx: RawContext) -> Native:
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
def read_mosek(raw, ctx: RawContext) -> Native:
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


def read_copt(raw, ctx: RawContext) -> Native:
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
