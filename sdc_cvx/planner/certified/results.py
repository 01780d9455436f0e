"""What the certified search takes and returns: the mission as nodes, each certified path,
and the result with its bracket (:func:`~sdc_cvx.planner.certified.search.certify`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...physics.leg_bounds import IMPULSIVE
from ..fixed_path import PathSchedule


@dataclass(frozen=True)
class CertifiedNodes:
    """The mission as the certified search needs it (positions into the catalog).

    Attributes
    ----------
    legs : int
        Transfers on a path.
    ops_days, cost_mps : ndarray
        Operations time [days] and cost [m/s] at each node.
    first : int or None
    must_visit, excluded : tuple of int
    tmax_days, tmin_days : float
    rule : str
    j2 : float
    model : TransferModel
        The leg physics (:mod:`~sdc_cvx.physics.models`), impulsive by default.
    eccentricity : Eccentricities or None
        The nodes' mean eccentricity vectors where the legs price them
        (:mod:`~sdc_cvx.physics.eccentricity`).
    """

    legs: int
    ops_days: np.ndarray
    cost_mps: np.ndarray
    first: int | None
    must_visit: tuple[int, ...]
    excluded: tuple[int, ...]
    tmax_days: float
    tmin_days: float
    rule: str
    j2: float
    model: object = field(default=IMPULSIVE)
    eccentricity: object = None

    def edge_eccentricity(self, origin, target) -> tuple | None:
        """The ``(origin, target)`` eccentricity vectors of edges between node positions,
        as :meth:`~sdc_cvx.physics.leg_bounds.LegCosts.build` takes them (None: circular
        legs)."""
        if self.eccentricity is None:
            return None
        return tuple(self.eccentricity.take(np.asarray(k)) for k in (origin, target))

    def least_cost(self) -> float:
        """A bound no plan is below [m/s], known before any search: its L + 1 node costs
        at their least (every transfer costs >= 0)."""
        usable = np.ones(len(self.cost_mps), dtype=bool)
        usable[list(self.excluded)] = False
        return float(np.sort(self.cost_mps[usable])[: self.legs + 1].sum())


@dataclass(frozen=True)
class CertifiedPath:
    """One path the search certified: its best schedule and its bracket.

    Attributes
    ----------
    path : tuple of int
        Node positions.
    schedule : PathSchedule
        Best schedule found (transfers only).
    upper_mps, lower_mps : float
        Total ΔV of that schedule with the node costs, and no schedule of the path costs
        less [m/s].
    """

    path: tuple[int, ...]
    schedule: PathSchedule
    upper_mps: float
    lower_mps: float


@dataclass(frozen=True)
class CertifiedResult:
    """Best plan found and what is proven about the optimum.

    Attributes
    ----------
    path : tuple of int
        Node positions (empty when no plan was found).
    schedule : PathSchedule or None
    upper_mps : float
        Total ΔV of the plan (transfers and operations) [m/s]; ``inf`` without a plan.
    lower_mps : float
        No plan costs less [m/s] (``inf``: proven infeasible).
    status : {"optimal", "feasible", "infeasible", "no_plan"}
        ``optimal``: within the requested gap; ``feasible``: a limit stopped the search;
        ``infeasible``: proven that no plan exists; ``no_plan``: stopped before any plan.
    log : list of dict
    paths : tuple of CertifiedPath
        Every path certified on the way that flies, cheapest first (the columns of a
        campaign's master, :mod:`sdc_cvx.campaign`).
    complete : bool
        False when a limit (time, iterations, a failed MILP) ended the search rather
        than its own criterion (an enumeration is then not known to be whole).
    trace : tuple of (float, float, float)
        ``(seconds, bound, plan)`` each time the bound or the plan changed, seconds from
        the start of :func:`certify` (the setup included).
    """

    path: tuple[int, ...]
    schedule: PathSchedule | None
    upper_mps: float
    lower_mps: float
    status: str
    log: list
    milp_solves: int
    cells: int
    seconds: float
    notes: tuple[str, ...] = ()
    edges: int = 0
    paths_certified: int = 0
    paths: tuple[CertifiedPath, ...] = ()
    complete: bool = True
    trace: tuple = ()

    @property
    def gap_mps(self) -> float:
        return self.upper_mps - self.lower_mps

    @property
    def gap_rel(self) -> float:
        if not np.isfinite(self.upper_mps) or self.upper_mps == 0:
            return np.inf if not np.isfinite(self.upper_mps) else 0.0
        return max(self.gap_mps, 0.0) / self.upper_mps


def allowed_gap(upper: float, gap_rel: float, gap_abs: float) -> float:
    """The gap a certificate may leave below a plan of ``upper`` m/s [m/s]."""
    return max(gap_rel * abs(upper), gap_abs)


def within_gap(upper: float, lower: float, gap_rel: float, gap_abs: float) -> bool:
    """The plan ``upper`` is certified by the bound ``lower`` (both m/s) within the gap."""
    allowed = allowed_gap(upper, gap_rel, gap_abs) * (1 + 1e-9)
    return bool(np.isfinite(upper) and upper - lower <= allowed)
