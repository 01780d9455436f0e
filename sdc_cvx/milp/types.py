"""The MILP layer's vocabulary: statuses, options, reports and the backends' names.

:data:`MILP_BACKENDS` names the MILP backends CVXPY can call; their table,
:data:`~sdc_cvx.milp.backends.BACKENDS`, holds the readers of their answers and so
imports CVXPY.  The scenario validation and the options' own checks read the names
here: this module does not import CVXPY.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import math
import numbers
from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum

from ..errors import MissionError

DEFAULT_BACKEND = "HIGHS"
BACKEND_MODULES = {"HIGHS": "highspy", "SCIP": "pyscipopt", "CBC": "cylp", "GLPK_MI": "cvxopt",
                   "SCIPY": "scipy", "GUROBI": "gurobipy", "CPLEX": "cplex", "XPRESS": "xpress",
                   "MOSEK": "mosek", "COPT": "coptpy"}  # fmt: skip
"""Each MILP backend CVXPY can call and the Python module CVXPY imports to call it."""
MILP_BACKENDS = tuple(BACKEND_MODULES)
"""The MILP backends CVXPY can call, the default first: the keys of
:data:`~sdc_cvx.milp.backends.BACKENDS`."""
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
        SCIPY, GUROBI, CPLEX, XPRESS, MOSEK, COPT (:data:`MILP_BACKENDS`).
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

    Raises
    ------
    MissionError
        An option out of its range or of the wrong type, or a backend name that is none
        of :data:`MILP_BACKENDS` (a known backend not installed here is accepted: a
        solve that needs a MILP then fails with :class:`~sdc_cvx.errors.SolverFailure`).
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
        if isinstance(self.fallback, str):  # one backend, not its letters
            object.__setattr__(self, "fallback", (self.fallback,))
        names = [self.backend, *self.fallback] if _is_sequence(self.fallback) else [self.backend]
        if all(isinstance(name, str) for name in names):
            object.__setattr__(self, "backend", self.backend.upper())
            if _is_sequence(self.fallback):
                object.__setattr__(self, "fallback", tuple(b.upper() for b in self.fallback))
        problems = list(self._problems())
        if problems:
            raise MissionError("invalid solver options: " + "; ".join(problems))

    def _problems(self):
        """Each rule the options break, in words (one :class:`MissionError` for all, as
        :func:`~sdc_cvx.solve_campaign` raises for its own options)."""
        known = ", ".join(MILP_BACKENDS)
        if not isinstance(self.backend, str):
            yield f"backend must be the name of a MILP backend ({known}), got {self.backend!r}"
        elif self.backend not in MILP_BACKENDS:
            yield f"backend must be one of {known}, got {self.backend!r}"
        if not _is_sequence(self.fallback):
            yield f"fallback must be a backend name or a sequence of them, got {self.fallback!r}"
        else:
            unknown = [b for b in self.fallback if not isinstance(b, str) or b not in MILP_BACKENDS]
            if unknown:
                yield (f"fallback must name MILP backends, from {known}; got "
                       f"{', '.join(map(str, unknown))}")  # fmt: skip
        if self.method not in METHODS:
            yield f"method must be one of {', '.join(METHODS)}, got {self.method!r}"
        if not (_is_real(self.gap) and 0 <= self.gap < 1):
            yield f"gap must be a number in [0, 1) (0.001 = 0.1 %), got {self.gap!r}"
        limit = self.time_limit_s  # inf, as before: no limit
        if limit is not None and not (_is_real(limit) or limit == math.inf) or not (
                limit is None or limit > 0):  # fmt: skip
            yield f"time_limit_s must be > 0 [s] (a number, or None), got {self.time_limit_s!r}"
        if self.mip_gap is not None and not (_is_real(self.mip_gap) and 0 <= self.mip_gap < 1):
            yield f"mip_gap must be in [0, 1) (a number, or None), got {self.mip_gap!r}"
        if self.threads is not None and not (_is_integer(self.threads) and self.threads >= 1):
            yield f"threads must be a positive integer (or None), got {self.threads!r}"
        if self.seed is not None and not _is_integer(self.seed):
            yield f"seed must be an integer (or None), got {self.seed!r}"
        for name in ("verbose", "presolve"):  # None: the default (off; the backend's)
            if (value := getattr(self, name)) is not None and not isinstance(value, bool):
                yield f"{name} must be True or False, got {value!r}"


def _is_real(value) -> bool:
    """A finite real number, not a bool."""
    return (isinstance(value, numbers.Real) and not isinstance(value, bool)
            and math.isfinite(value))  # fmt: skip


def _is_integer(value) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _is_sequence(value) -> bool:
    return isinstance(value, Sequence) and not isinstance(value, str)


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


def package_version(module: str, package: str | None = None) -> str | None:
    """Version of an installed distribution (without importing it), or None."""
    try:
        if importlib.util.find_spec(module) is None:
            return None
        return importlib.metadata.version(package or module)
    except (ImportError, ValueError, importlib.metadata.PackageNotFoundError):
        return None


def backend_importable(name: str) -> bool:
    """Whether the module CVXPY calls backend ``name`` through can be found here.

    Asked without importing it or CVXPY (a millisecond, where importing CVXPY to ask
    :func:`~sdc_cvx.milp.backends.installed_backends` takes 1-2 s).  CVXPY may still
    refuse a module it finds too old; a solve then reports the backend not installed
    and moves on along the fallback chain.
    """
    module = BACKEND_MODULES.get(name)
    try:
        return module is not None and importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        return False
