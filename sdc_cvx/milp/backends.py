"""The MILP backends CVXPY can call: the one table, and which of them are usable here.

:data:`BACKENDS` is the one table of the MILP backends CVXPY can call: for each, its
Python package, our options (time limit, relative gap, threads, verbosity, seed) in the
backend's own names, and the reader that turns the backend's raw result into our terms
(:mod:`sdc_cvx.milp.readers`).  Its names are :data:`~sdc_cvx.milp.types.MILP_BACKENDS`,
which the scenario validation reads without importing CVXPY.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import cvxpy as cp

from .readers import (
    Native,
    RawContext,
    read_cbc,
    read_copt,
    read_cplex,
    read_glpk,
    read_gurobi,
    read_highs,
    read_mosek,
    read_scip,
    read_scipy,
    read_xpress,
)
from .types import BACKEND_MODULES, DEFAULT_BACKEND, MILP_BACKENDS, SolverOptions, package_version


@dataclass(frozen=True)
class Backend:
    """One MILP backend CVXPY can call.

    Attributes
    ----------
    name : str
        CVXPY's solver name.
    package : str
        Python distribution that provides it (``pip install``).
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
    options: dict
    read: Callable[[object, RawContext], Native]
    stats: str
    verified: str
    nest: str | None = None
    trust_infeasible: bool = True
    reports_time: bool = True
    commercial: bool = False
    converters: dict = field(default_factory=dict)

    @property
    def module(self) -> str:
        """Importable module of the distribution (:data:`~sdc_cvx.milp.types.BACKEND_MODULES`)."""
        return BACKEND_MODULES[self.name]

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


_VERIFIED = "verified here by solving (cvxpy 1.9.3)"


_VERIFIED_FREE = "verified by solving small models with the size-limited pip build (cvxpy 1.9.3)"


BACKENDS: dict[str, Backend] = {
    b.name: b
    for b in (
        Backend(
            "HIGHS", "highspy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "threads": "threads",
             "seed": "random_seed", "presolve": "presolve"},
            read_highs,
            converters={"presolve": lambda on: "on" if on else "off"},
            stats="raw: model_status, info (HighsInfo: mip_dual_bound, mip_gap, "
            "mip_node_count, simplex_iteration_count, primal_solution_status), run_time; "
            "solver_stats.extra_stats is the HighsInfo, solve_time the run_time",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIP", "PySCIPOpt",
            {"time_limit_s": "limits/time", "mip_gap": "limits/gap",
             "seed": "randomization/randomseedshift"},
            read_scip, nest="scip_params",
            stats="raw: a dict with scip_status and model (pyscipopt Model: getDualbound, "
            "getGap, getNTotalNodes, getNLPIterations, getSolvingTime, getNSols); "
            "solver_stats.extra_stats is that dict (extra_stats['model']). No threads: "
            "CVXPY calls the sequential optimize(), parallel/* only acts in concurrent mode",
            verified=_VERIFIED,
        ),
        Backend(
            "CBC", "cylp",
            {"time_limit_s": "maximumSeconds", "mip_gap": "allowableFractionGap",
             "threads": "numberThreads"},
            read_cbc, reports_time=False,
            stats="raw: status (CVXPY's), primal, value only; CVXPY drops the CyCbcModel "
            "(nodeCount, bestPossibleObjValue): no bound, gap, nodes; extra_stats and "
            "solve_time None. cylp has no seed setting",
            verified=_VERIFIED + " (numberThreads accepted; its effect not measured)",
        ),
        Backend(
            "GLPK_MI", "cvxopt",
            {"time_limit_s": "tm_lim", "mip_gap": "mip_gap"},
            read_glpk, reports_time=False,
            converters={"time_limit_s": _milliseconds},
            stats="raw: status (CVXPY's), primal, value only: no bound, gap, nodes, time; "
            "a time limit is told apart from the gap stop by the elapsed time. "
            "GLPK is single-threaded and has no seed",
            verified=_VERIFIED,
        ),
        Backend(
            "SCIPY", "scipy",
            {"time_limit_s": "time_limit", "mip_gap": "mip_rel_gap", "verbose": "disp"},
            read_scipy, nest="scipy_options", reports_time=False,
            stats="raw: scipy.optimize.OptimizeResult (status, message, x, fun, "
            "mip_dual_bound, mip_gap, mip_node_count); solver_stats.extra_stats holds the "
            "three mip_* only with a solution. scipy.optimize.milp has no threads or seed",
            verified=_VERIFIED,
        ),
        Backend(
            "GUROBI", "gurobipy",
            {"time_limit_s": "TimeLimit", "mip_gap": "MIPGap", "threads": "Threads",
             "seed": "Seed"},
            read_gurobi, commercial=True,
            stats="raw: dict with model (gurobipy Model: Status, SolCount, ObjBound, "
            "MIPGap, NodeCount, IterCount, Runtime); solver_stats.extra_stats is the Model",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "CPLEX", "cplex",
            {"time_limit_s": "timelimit", "mip_gap": "mip.tolerances.mipgap",
             "threads": "threads", "seed": "randomseed"},
            read_cplex, nest="cplex_params", commercial=True,
            stats="raw: dict with model (cplex.Cplex: solution.get_status, "
            "solution.MIP.get_best_objective / get_mip_relative_gap, "
            "solution.progress.get_num_nodes_processed); solver_stats has solve_time only",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "XPRESS", "xpress",
            {"time_limit_s": "timelimit", "mip_gap": "miprelstop", "threads": "threads",
             "seed": "randomseed"},
            read_xpress, commercial=True,
            stats="raw: CVXPY's status, primal, getObjVal, solve_time; the problem object "
            "is deleted: no bound, gap, nodes. CVXPY silently drops control names Xpress "
            "does not know",
            verified=_VERIFIED_FREE,
        ),
        Backend(
            "MOSEK", "mosek",
            {"time_limit_s": "MSK_DPAR_OPTIMIZER_MAX_TIME",
             "mip_gap": "MSK_DPAR_MIO_TOL_REL_GAP", "threads": "MSK_IPAR_NUM_THREADS",
             "seed": "MSK_IPAR_MIO_SEED"},
            read_mosek, nest="mosek_params", commercial=True,
            stats="raw: dict with task (mosek.Task: getsolsta/getprosta(itg), "
            "getdouinf mio_obj_bound / mio_obj_rel_gap, getintinf mio_num_solved_nodes); "
            "solver_stats.extra_stats has mio_intpnt_iter, mio_simplex_iter only",
            verified="option names accepted by a mosek 11.2 Task (a wrong name is refused); "
            "solving and the status reading not verified: needs a license",
        ),
        Backend(
            "COPT", "coptpy",
            {"time_limit_s": "TimeLimit", "mip_gap": "RelGap", "threads": "Threads"},
            read_copt, commercial=True,
            stats="raw: dict with model (coptpy Model: status, hasmipsol, bestbnd, bestgap, "
            "nodecnt, simplexiter, solvingtime); solver_stats.extra_stats is the Model. "
            "COPT has no seed parameter",
            verified=_VERIFIED_FREE,
        ),
    )
}  # fmt: skip
"""The MILP backends CVXPY can call, the default (HiGHS) first."""


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
