"""The campaign's master: one mission per launch, each debris removed at most once.

Over a pool of columns (flyable missions, :class:`~sdc_cvx.campaign.pricing.Column`),
declared in CVXPY::

    min  sum_c cost_c lambda_c
    s.t. sum_{c of launch k} lambda_c            = 1   for every launch k   (dual sigma_k)
         sum_{c removing debris i} lambda_c     <= 1   for every debris i   (dual y_i >= 0)
         sum_{c removing debris i} lambda_c      = 1   for i in must_remove (dual y_i free)
         lambda_c in {0, 1}

Its LP relaxation (lambda >= 0) gives the prices of the pricing problems: a column's
reduced cost is ``cost_c + sum_{i in c} y_i - sigma_k``.  While the pool is too small
for the LP to be feasible, an artificial column per row (cost :data:`ARTIFICIAL_MPS`)
keeps it feasible; it leaves once real columns can replace it.  Its integer program
over the pool is a campaign that flies (an upper bound of the campaign).  The pool
changes every round, so the problem is declared anew each time (a few hundred columns:
milliseconds), unlike the single mission's relaxation whose Parameters are reused.

References
----------
.. [1] G. B. Dantzig and P. Wolfe, "Decomposition principle for linear programs",
   Operations Research 8(1), 101-111, 1960.
.. [2] G. Desaulniers, J. Desrosiers and M. M. Solomon (eds.), *Column Generation*,
   Springer, 2005.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import cvxpy as cp
import numpy as np
import scipy.sparse as sp

from ..errors import SolverFailure
from ..milp.solve import chain_of, solve_with_fallback
from ..milp.types import SolverOptions

ARTIFICIAL_MPS = 1e5
"""Cost of an artificial column [m/s]: above any campaign of real missions."""
LP_BACKEND = "HIGHS"
"""The master LP's backend, whatever the MILP backend: its duals are the prices (HiGHS
is a dependency of sdc_cvx and returns them)."""


@dataclass(frozen=True)
class MasterLP:
    """The LP relaxation's optimum and prices.

    Attributes
    ----------
    value : float
        LP optimum [m/s] (artificial columns included, at their cost).
    sigma : ndarray
        Dual of each launch's row [m/s], shape (K,).
    prices : ndarray
        Dual ``y_i`` of each debris' row [m/s], shape (N,) (0 for a debris on no row).
    weights : ndarray
        LP value of each column.
    artificial : float
        Total weight of the artificial columns (0 when real columns cover every row).
    """

    value: float
    sigma: np.ndarray
    prices: np.ndarray
    weights: np.ndarray
    artificial: float


@dataclass(frozen=True)
class MasterPlan:
    """The integer master's optimum over the pool.

    Attributes
    ----------
    value : float
        Sum of the chosen columns' costs [m/s].
    chosen : tuple of int
        Index into the pool of the column chosen for each launch, in launch order.
    backend : str
    """

    value: float
    chosen: tuple[int, ...]
    backend: str


def _rows(columns, n_launches: int, n_debris: int):
    """Launch and debris incidence matrices of the pool (launch x column, debris x column)."""
    m = len(columns)
    launch = sp.csr_matrix((np.ones(m), ([c.launch for c in columns], np.arange(m))),
                           shape=(n_launches, m))  # fmt: skip
    rows = [i for c in columns for i in c.debris]
    cols = [k for k, c in enumerate(columns) for _ in c.debris]
    debris = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n_debris, m))
    return launch, debris


def solve_lp(columns, n_launches: int, n_debris: int, must_remove=(), *,
             costs=None) -> MasterLP:  # fmt: skip
    """The master's LP relaxation over ``columns``, with artificial columns (see above).

    Parameters
    ----------
    columns : sequence of Column
    n_launches, n_debris : int
    must_remove : sequence of int
        Catalog rows removed exactly once.
    costs : array_like, optional
        Cost of each column (default their ΔV [m/s]; a max-value campaign's master
        minimises minus their value).

    Returns
    -------
    MasterLP

    Raises
    ------
    SolverFailure
        The LP backend failed, or its duals do not price its own optimum (a wrong sign
        convention would be caught here rather than mislead the pricing).
    """
    launch, debris = _rows(columns, n_launches, n_debris)
    costs = np.array([c.dv_mps for c in columns]) if costs is None else np.asarray(costs)
    must = np.zeros(n_debris, dtype=bool)
    must[list(must_remove)] = True
    packed = np.flatnonzero((np.asarray(debris.sum(axis=1)).ravel() > 0) & ~must)
    required = np.flatnonzero(must)
    weights = cp.Variable(len(columns), nonneg=True)
    idle = cp.Variable(n_launches, nonneg=True)  # artificial: a launch without a mission
    missing = cp.Variable(len(required), nonneg=True)  # artificial: must_remove uncovered
    rows = {
        "launch": launch @ weights + idle == 1,
        "packed": debris[packed, :] @ weights <= 1,
        "required": debris[required, :] @ weights + missing == 1,
    }
    constraints = [rows["launch"]] + [rows[name] for name, size in
                                      (("packed", len(packed)), ("required", len(required)))
                                      if size]  # fmt: skip
    objective = costs @ weights + ARTIFICIAL_MPS * (cp.sum(idle) + cp.sum(missing))
    problem = cp.Problem(cp.Minimize(objective), constraints)
    report = solve_with_fallback(problem, chain_of(SolverOptions(backend=LP_BACKEND)))
    if report.status.value != "optimal":
        raise SolverFailure(f"the campaign master LP failed: {report.message}")
    sigma = -np.asarray(rows["launch"].dual_value, dtype=float).ravel()
    prices = np.zeros(n_debris)
    for name, members in (("packed", packed), ("required", required)):
        if len(members):
            prices[members] = np.asarray(rows[name].dual_value, dtype=float).ravel()
    value = float(problem.value)
    dual_value = float(sigma.sum() - prices[np.r_[packed, required]].sum())
    if abs(dual_value - value) > 1e-6 * max(1.0, abs(value)):
        raise SolverFailure(
            f"the campaign master LP's duals give {dual_value:.6f} m/s for an optimum of "
            f"{value:.6f} m/s: prices not usable"
        )
    artificial = float(np.sum(idle.value)) + float(np.sum(missing.value)) if len(required) \
        else float(np.sum(idle.value))  # fmt: skip
    # a packing row's multiplier must be >= 0 for the Lagrangian bound to hold; a solver's
    # -1e-12 is rounding: any y >= 0 is a valid multiplier, so clip (the prices stay exact)
    prices[packed] = np.maximum(prices[packed], 0.0)
    return MasterLP(value, sigma, prices, np.asarray(weights.value, dtype=float), artificial)


def solve_ip(columns, n_launches: int, n_debris: int, must_remove=(), *,
             solver: SolverOptions, costs=None, at_least=None) -> MasterPlan | None:  # fmt: skip
    """The integer master over ``columns``: the cheapest campaign they make, or None.

    Parameters
    ----------
    columns : sequence of Column
    n_launches, n_debris : int
    must_remove : sequence of int
    solver : SolverOptions
        MILP backend (its fallback chain is used); solved to optimality (gap 0).
    costs : array_like, optional
        Cost of each column [m/s] (default their ΔV; their lower bounds give a bound of
        every campaign made of these paths).
    at_least : (array_like, float), optional
        ``(weights, minimum)``: only campaigns whose columns' weights sum to at least
        ``minimum`` (a max-value campaign's value, held while its ΔV is minimised).

    Returns
    -------
    MasterPlan or None
        None when no campaign can be made of the pool.

    Raises
    ------
    SolverFailure
        The backend failed.
    """
    if not columns:
        return None
    launch, debris = _rows(columns, n_launches, n_debris)
    if np.any(np.asarray(launch.sum(axis=1)).ravel() == 0):
        return None  # a launch without any column
    costs = np.array([c.dv_mps for c in columns]) if costs is None else np.asarray(costs)
    pick = cp.Variable(len(columns), boolean=True)
    must = np.zeros(n_debris, dtype=bool)
    must[list(must_remove)] = True
    constraints = [launch @ pick == 1]
    on_row = np.flatnonzero(np.asarray(debris.sum(axis=1)).ravel() > 1)
    free = on_row[~must[on_row]]
    if len(free):
        constraints.append(debris[free, :] @ pick <= 1)
    if must.any():
        constraints.append(debris[np.flatnonzero(must), :] @ pick == 1)
    if at_least is not None:
        constraints.append(np.asarray(at_least[0], dtype=float) @ pick >= at_least[1])
    problem = cp.Problem(cp.Minimize(costs @ pick), constraints)
    exact = replace(solver, mip_gap=0.0, time_limit_s=None)
    report = solve_with_fallback(problem, chain_of(exact))
    if report.status.value == "infeasible":
        return None
    if report.status.value != "optimal":
        raise SolverFailure(f"the campaign master MILP failed: {report.message}")
    chosen = np.flatnonzero(pick.value > 0.5)
    chosen = tuple(int(c) for c in sorted(chosen, key=lambda c: columns[c].launch))
    return MasterPlan(float(costs[list(chosen)].sum()), chosen, report.backend)
