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
.. [3] R. E. Marsten, W. W. Hogan and J. W. Blankenship, "The BOXSTEP method for
   large-scale optimization", Operations Research 23(3), 389-405, 1975.
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
    boxed : float
        Total weight of the box's columns (0: the box does not bind, the value is the
        LP's).
    """

    value: float
    sigma: np.ndarray
    prices: np.ndarray
    weights: np.ndarray
    artificial: float
    boxed: float = 0.0


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
             costs=None, box=None) -> MasterLP:  # fmt: skip
    """The master's LP relaxation over ``columns``, with artificial columns (see above).

    With ``box = (centre, width)`` its prices stay within ``width`` of ``centre`` (the
    boxstep method [3]_): each debris' row gets a column that covers it short at cost
    ``width - centre_i`` (so ``y_i >= centre_i - width``) and one that covers it twice
    over at cost ``centre_i + width`` (so ``y_i <= centre_i + width``); a packing row
    already has ``y_i >= 0``.  Its value is then the most the pool's missions can prove
    at prices in the box, not the LP's.

    Parameters
    ----------
    columns : sequence of Column
    n_launches, n_debris : int
    must_remove : sequence of int
        Catalog rows removed exactly once.
    costs : array_like, optional
        Cost of each column (default their ΔV [m/s]; a max-value campaign's master
        minimises minus their value).
    box : (ndarray, float), optional
        Centre of the prices, shape (N,), and the box's half-width [m/s].

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
    packed_rows = debris[packed, :] @ weights
    required_rows = debris[required, :] @ weights + missing
    objective = costs @ weights + ARTIFICIAL_MPS * (cp.sum(idle) + cp.sum(missing))
    box_columns = []
    if box is not None:
        centre, width = np.asarray(box[0], dtype=float), float(box[1])
        over_packed = cp.Variable(len(packed), nonneg=True)  # y_i <= centre_i + width
        over = cp.Variable(len(required), nonneg=True)
        under = cp.Variable(len(required), nonneg=True)  # y_i >= centre_i - width
        packed_rows = packed_rows - over_packed
        required_rows = required_rows - over + under
        objective = objective + (width + centre[packed]) @ over_packed + (
            (width + centre[required]) @ over + (width - centre[required]) @ under)
        box_columns = [over_packed, over, under]
    rows = {
        "launch": launch @ weights + idle == 1,
        "packed": packed_rows <= 1,
        "required": required_rows == 1,
    }
    constraints = [rows["launch"]] + [rows[name] for name, size in
                                      (("packed", len(packed)), ("required", len(required)))
                                      if size]  # fmt: skip
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
    boxed = float(sum(np.sum(v.value) for v in box_columns if v.size))
    return MasterLP(value, sigma, prices, np.asarray(weights.value, dtype=float), artificial,
                    boxed)  # fmt: skip


def solve_ip(columns, n_launches: int, n_debris: int, must_remove=(), *,
             solver: SolverOptions, costs=None, at_least=None,
             time_limit_s: float | None = None) -> MasterPlan | None:  # fmt: skip
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
    time_limit_s : float, optional
        Stop the MILP there with its best campaign [s] (then a campaign the pool makes,
        not necessarily its cheapest; default: solved to the end).

    Returns
    -------
    MasterPlan or None
        None when no campaign can be made of the pool (or none was found within
        ``time_limit_s``).

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
    exact = replace(solver, mip_gap=0.0, time_limit_s=time_limit_s)
    report = solve_with_fallback(problem, chain_of(exact))
    if report.status.value in ("infeasible", "no_solution"):
        return None
    if report.status.value not in ("optimal", "time_limit"):
        raise SolverFailure(f"the campaign master MILP failed: {report.message}")
    chosen = np.flatnonzero(pick.value > 0.5)
    chosen = tuple(int(c) for c in sorted(chosen, key=lambda c: columns[c].launch))
    return MasterPlan(float(costs[list(chosen)].sum()), chosen, report.backend)
