"""The MILP layer's vocabulary: statuses, options, reports and the backend table.

:data:`BACKENDS` is the one table of the MILP backends CVXPY can call: for each, its
Python package, our options (time limit, relative gap, threads, verbosity, seed) in the
backend's own names, and a reader that turns the backend's raw result into our terms
(the readers are in :mod:`sdc_cvx.milp.backends`, imported when first used).  The
scenario validation and the command line's ``solvers`` read it; this module does not
import CVXPY.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import StrEnum
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .backends import Native, RawContext

DEFAULT_BACKEND = "HIGHS"
METHODS = ("certified", "paper")


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
    method : {"certified", "paper"}
        ``"certified"`` (default): the mission's optimum bracketed by a proven lower
        bound and the best plan, refined until they are within ``gap``
        (:mod:`sdc_cvx.planner.certified`); ``time_limit_s`` then bounds the whole
        search, which returns its best plan and gap when it runs out.  ``"paper"``: the
        paper's sequential linearisation (Part IV-C), a local method with no bound;
        ``time_limit_s`` bounds each MILP.
    gap : float
        Relative gap at which a certified answer is ``optimal`` (default 0.1 %).
    presolve : bool, optional
        Let the backend presolve (None: its default).  The certified search turns it
        off for HiGHS: on its time-expanded relaxations HiGHS's presolve took 29 s
        where the solve alone took 0.9 s (``benchmarks/certify.py``).
    """

    backend: str = DEFAULT_BACKEND
    time_limit_s: float | None = None
    mip_gap: float | None = 1e-6
    threads: int | None = None
    verbose: bool = False
    seed: int | None = None
    fallback: tuple[str, ...] = ()
    method: str = "certified"
    gap: float = 1e-3
    presolve: bool | None = None

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"method must be one of {METHODS}, got {self.method!r}")
        if not (isinstance(self.gap, int | float) and 0 <= self.gap < 1):
            raise ValueError(f"gap must be a number in [0, 1), got {self.gap!r}")
        object.__setattr__(self, "backend", self.backend.upper())
        if isinstance(self.fallback, str):  # one backend, not its letters
            object.__setattr__(self, "fallback", (self.fallback,))
        object.__setattr__(self, "fallback", tuple(str(b).upper() for b in self.fallback))
        unknown = [b for b in self.fallback if b not in BACKENDS]
        if unknown:
            raise ValueError(f"fallback must name MILP backends, from {', '.join(BACKENDS)}; "
                             f"got {', '.join(unknown)}")  # fmt: skip
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
        for ours in ("time_limit_s", "mip_gap", "threads", "seed", "verbose", "presolve"):
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


def _milliseconds(seconds: float) -> int:
    return max(1, int(round(seconds * 1000)))


def _reader(name: str) -> Callable[[object, RawContext], Native]:
    """The reader ``name`` of :mod:`sdc_cvx.milp.backends` (which imports CVXPY), on first call."""

    def read(raw, ctx: RawContext) -> Native:
        from . import backends

        return getattr(backends, name)(raw, ctx)

    read.__name__ = read.__qualname__ = name
    return read


_VERIFIED = "verified here by solving (cvxpy 1.9.3)"


_VERIFIED_FREE = "verified by solving small models with the size-limited pip build (cvxpy 1.9.3)"


BACKENDS: dict[str, Backend] = {
    b.name: b
    for b in (
        Backend(
            "HIGHS", "highspy", "highspy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "threads": "threads",
             "seed": "random_seed", "presolve": "presolve"},
            _reader("_read_highs"),
            converters={"presolve": lambda on: "on" if on else "off"},
            stats="raw: model_status, info (HighsInfo: mip_dual_bound, mip_gap, "
            "mip_node_count, simplex_iteration_count, primal_solution_status), run_time; "
            "solver_stats.extra_stats is the HighsInfo, solve_time the run_time",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIP", "PySCIPOpt", "pyscipopt",
            {"time_limit_s": "limits/time", "mip_gap": "limits/gap",
             "seed": "randomization/randomseedshift"},
            _reader("_read_scip"), nest="scip_params",
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
            _reader("_read_cbc"), reports_time=False,
            stats="raw: status (CVXPY's), primal, value only; CVXPY drops the CyCbcModel "
            "(nodeCount, bestPossibleObjValue): no bound, gap, nodes; extra_stats and "
            "solve_time None. cylp has no seed setting",
            verified=_VERIFIED + " (numberThreads accepted; its effect not measured)",
        ),
        Backend(
            "GLPK_MI", "cvxopt", "cvxopt",
            {"time_limit_s": "tm_lim", "mip_gap": "mip_gap"},
            _reader("_read_glpk"), reports_time=False,
            converters={"time_limit_s": _milliseconds},
            stats="raw: status (CVXPY's), primal, value only: no bound, gap, nodes, time; "
            "a time limit is told apart from the gap stop by the elapsed time. "
            "GLPK is single-threaded and has no seed",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIPY", "scipy", "scipy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "verbose": "disp"},
            _reader("_read_scipy"), nest="scipy_options", reports_time=False,
            stats="raw: scipy.optimize.OptimizeResult (status, message, x, fun, "
            "mip_dual_bound, mip_gap, mip_node_count); solver_stats.extra_stats holds the "
            "three mip_* only with a solution. scipy.optimize.milp has no threads or seed",
            verified=_VERIFIED,
        ),
        Backend(
            "GUROBI", "gurobipy", "gurobipy",
            {"time_limit_s": "TimeLimit", "mip_gap": "MIPGap", "threads": "Threads",
             "seed": "Seed"},
            _reader("_read_gurobi"), commercial=True,
            stats="raw: dict with model (gurobipy Model: Status, SolCount, ObjBound, "
            "MIPGap, NodeCount, IterCount, Runtime); solver_stats.extra_stats is the Model",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "CPLEX", "cplex", "cplex",
            {"time_limit_s": "timelimit", "mip_gap": "mip.tolerances.mipgap",
             "threads": "threads", "seed": "randomseed"},
            _reader("_read_cplex"), nest="cplex_params", commercial=True,
            stats="raw: dict with model (cplex.Cplex: solution.get_status, "
            "solution.MIP.get_best_objective / get_mip_relative_gap, "
            "solution.progress.get_num_nodes_processed); solver_stats has solve_time only",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "XPRESS", "xpress", "xpress",
            {"time_limit_s": "timelimit", "mip_gap": "miprelstop", "threads": "threads",
             "seed": "randomseed"},
            _reader("_read_xpress"), commercial=True,
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
            _reader("_read_mosek"), nest="mosek_params", commercial=True,
            stats="raw: dict with task (mosek.Task: getsolsta/getprosta(itg), "
            "getdouinf mio_obj_bound / mio_obj_rel_gap, getintinf mio_num_solved_nodes); "
            "solver_stats.extra_stats has mio_intpnt_iter, mio_simplex_iter only",
            verified="option names accepted by a mosek 11.2 Task (a wrong name is refused); "
            "solving and the status reading not verified: needs a license",
        ),
        Backend(
            "COPT", "coptpy", "coptpy",
            {"time_limit_s": "TimeLimit", "mip_gap": "RelGap", "threads": "Threads"},
            _reader("_read_copt"), commercial=True,
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
