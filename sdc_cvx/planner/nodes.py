"""The mission's nodes and a plan's legs: what both planning methods share.

:class:`MissionNodes` is what the mission options make of the catalog's debris (the
injection orbit as an extra node, the operations time and cost at each node, the nodes
fixed, required or excluded); :func:`make_legs` writes a plan evaluated in the true model
as :class:`~sdc_cvx.solution.Leg` rows.  The certified search
(:mod:`sdc_cvx.planner.certified`, through :mod:`sdc_cvx.planner.api`), the paper's method
(:mod:`sdc_cvx.planner.paper`) and the campaigns (:mod:`sdc_cvx.campaign`) use them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..inputs.catalog import Catalog
from ..inputs.mission import Mission
from ..physics.orbits import R_EARTH, perigee_lowering_dv
from ..physics.plan import PlanEvaluation
from ..solution import Leg

INJECTION_ID = "injection"
"""The injection orbit's id among the nodes (:attr:`MissionNodes.catalog`)."""


@dataclass(frozen=True)
class MissionNodes:
    """What the mission options (issue 8) make of the catalog's debris, per node.

    Attributes
    ----------
    catalog : Catalog
        The candidates, plus the injection orbit as a last row when there is one.
    legs : int
        Transfers on the path: n - 1, or n with an injection orbit.
    deorbit_days, cost_mps : ndarray
        Operations time T_deorb [days] and cost C_k [m/s] at each node (0 at the
        injection orbit).
    first : int or None
        Node fixed at the head of the path (the injection orbit or ``mission.first``).
    must_visit, excluded : tuple of int
        Nodes that must be / must not be on the path.
    """

    catalog: Catalog
    legs: int
    deorbit_days: np.ndarray
    cost_mps: np.ndarray
    first: int | None
    must_visit: tuple[int, ...]
    excluded: tuple[int, ...]

    @classmethod
    def of(cls, catalog: Catalog, mission: Mission) -> MissionNodes:
        """The nodes of ``mission`` over ``catalog`` (ids checked by ``check_candidates``)."""
        index = {k: n for n, k in enumerate(catalog.ids)}
        first = index[mission.first] if mission.first is not None else None
        if mission.injection is not None:
            catalog = catalog.with_orbit(INJECTION_ID, *mission.injection)
            first = len(catalog) - 1
        debris = np.arange(len(catalog)) != (first if mission.injection is not None else -1)
        cost = np.full(len(catalog), float(mission.operations_dv_mps))
        if mission.deorbit_by == "vehicle":
            # lower the debris' perigee, release it, raise the vehicle's perigee back
            lower = perigee_lowering_dv(catalog.a_m, R_EARTH + 1e3 * mission.deorbit_perigee_km)
            cost += 2.0 * lower
        return cls(
            catalog=catalog,
            legs=mission.n - 1 + (mission.injection is not None),
            deorbit_days=np.where(debris, float(mission.deorbit_days), 0.0),
            cost_mps=np.where(debris, cost, 0.0),
            first=first,
            must_visit=tuple(index[k] for k in mission.must_include),
            excluded=tuple(index[k] for k in mission.exclude),
        )

    def operations(self, path, mission: Mission) -> dict:
        """``Solution.operations`` of a path: who deorbits, where it starts, the cost at
        each debris [m/s] (the injection orbit has none) and their total."""
        ids = self.catalog.ids
        return {
            "scenario": mission.deorbit_by,
            "start": INJECTION_ID if mission.injection is not None else "first debris",
            "per_debris_mps": {ids[k]: float(self.cost_mps[k]) for k in path
                               if k != self.first or mission.injection is None},
            "total_mps": float(self.cost_mps[list(path)].sum()),
        }  # fmt: skip


def make_legs(ids, path, a_drift, inc_drift, side, plan: PlanEvaluation) -> tuple[Leg, ...]:
    """Legs of a plan evaluated with the true model, in people's units."""
    return tuple(
        Leg(
            from_id=ids[path[k]],
            to_id=ids[path[k + 1]],
            departure_day=float(plan.departure_day[k]),
            duration_days=float(plan.duration_days[k]),
            drift_a_km=float(a_drift[k] / 1e3),
            drift_alt_km=float((a_drift[k] - R_EARTH) / 1e3),
            drift_inc_deg=float(np.rad2deg(inc_drift[k])),
            side=int(side[k]),
            dv_mps=float(plan.dv_mps[k]),
        )
        for k in range(len(path) - 1)
    )
