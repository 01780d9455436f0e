"""The mission's nodes and a plan's legs: what both planning methods share.

:class:`MissionNodes` is what the mission options make of the catalog's debris (the
injection orbit as an extra node, the operations time and cost at each node, the nodes
fixed, required or excluded); :func:`make_legs` writes a plan evaluated in the true model
as :class:`~sdc_cvx.solution.Leg` rows.  The certified search
(:mod:`sdc_cvx.planner.certified`, through :mod:`sdc_cvx.planner.api`), the paper's method
(:mod:`sdc_cvx.planner.paper`) and the campaigns (:mod:`sdc_cvx.campaign`) use them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..inputs.catalog import Catalog
from ..inputs.mission import Mission
from ..inputs.vehicle import G0, propellant_budget
from ..physics.orbits import R_EARTH, SECONDS_PER_DAY, perigee_lowering_dv
from ..physics.plan import PlanEvaluation
from ..solution import Leg, RunStatus

LONG_BURN = 0.01
"""Burn time of an impulsive leg, as a fraction of its duration, above which a note says
the impulsive model may not hold (the paper, Part IV-D)."""
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


def make_legs(ids, path, a_drift, inc_drift, side, plan: PlanEvaluation, *, orbits=None,
              mission: Mission | None = None, laps=None) -> tuple[Leg, ...]:  # fmt: skip
    """Legs of a plan evaluated with the true model, in people's units.

    With ``orbits`` (the nodes' :class:`~sdc_cvx.physics.transfer.NodeOrbits`) and the
    ``mission``, each leg carries the phases its transfer model reports (none for the
    impulsive leg, whose burns take no time) and its extra laps.
    """
    phases = [{} for _ in range(len(path) - 1)]
    days = {}
    if mission is not None and orbits is not None:
        p = np.asarray(path)
        days = mission.transfer_model().phase_days(
            orbits.a[p[:-1]], orbits.inc[p[:-1]], orbits.a[p[1:]], orbits.inc[p[1:]],
            np.asarray(a_drift), plan.duration_days)  # fmt: skip
    if days:
        laps = np.zeros(len(path) - 1, dtype=int) if laps is None or not len(laps) else laps
        phases = [{name: float(v[k]) for name, v in days.items()} | {"laps": int(laps[k])}
                  for k in range(len(path) - 1)]  # fmt: skip
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
            phases=phases[k],
            eccentricity_dv_mps=(None if plan.eccentricity_dv_mps is None
                                 else float(plan.eccentricity_dv_mps[k])),
        )
        for k in range(len(path) - 1)
    )


def with_vehicle(legs: tuple[Leg, ...], nodes: MissionNodes, path, mission: Mission,
                 status: RunStatus) -> tuple[tuple[Leg, ...], dict | None, RunStatus, list]:
    """The legs with their propellant and masses, the ``vehicle`` block of the solution,
    its status and notes.

    Without a vehicle: no change.  With a dry mass and an Isp: the propellant budget
    (:func:`~sdc_cvx.inputs.vehicle.propellant_budget`, the operations' ΔV at each debris
    included); a plan that needs more than the tank holds gets the status
    ``over_capacity`` and a note: it is never reported as flyable.  An impulsive plan
    with the vehicle's thrust or acceleration gets each leg's burn time (``burn_s``) and a
    note on any leg whose burns last more than :data:`LONG_BURN` of it.
    """
    vehicle = mission.vehicle
    if vehicle is None:
        return legs, None, status, []
    block = vehicle.to_dict()
    model = mission.transfer_model().describe()
    if "accel_mps2" in model:
        block["accel_mps2_flown"] = model["accel_mps2"]
    budget = None
    if vehicle.can_budget():
        budget = propellant_budget(vehicle, [leg.dv_mps for leg in legs],
                                   nodes.cost_mps[[int(k) for k in path]],
                                   kit_at_start=mission.injection is None)  # fmt: skip
    burns = _burn_seconds(legs, vehicle, mission, budget)
    masses = [{} for _ in legs]
    notes = []
    if budget is not None:
        for k, leg_masses in enumerate(masses):
            leg_masses |= {"propellant_kg": budget.propellant_kg[k],
                           "mass_before_kg": budget.mass_before_kg[k],
                           "mass_after_kg": budget.mass_after_kg[k]}  # fmt: skip
    if burns is not None:
        # the paper's condition for impulses (Part IV-D): burns short against the coast
        block["long_burns"] = []
        for k, leg in enumerate(legs):
            masses[k]["burn_s"] = burns[k]
            if burns[k] > LONG_BURN * leg.duration_days * SECONDS_PER_DAY:
                block["long_burns"].append(k)
                notes.append(
                    f"leg {leg.from_id} -> {leg.to_id}: its burns last {burns[k] / 3600:.1f} h, "
                    f"more than {100 * LONG_BURN:g} % of its {leg.duration_days:.1f} days: the "
                    "impulsive model may not hold (transfer = 'low-thrust' models such a "
                    "vehicle)")  # fmt: skip
    legs = tuple(replace(leg, masses=masses[k]) for k, leg in enumerate(legs))
    if budget is None:
        return legs, block, status, notes
    block |= {"propellant_needed_kg": budget.needed_kg, "operations_propellant_kg":
              budget.operations_kg, "wet_mass_kg": budget.wet_mass_kg,
              "capacity_kg": budget.capacity_kg, "margin_kg": budget.margin_kg,
              "fits": budget.fits}  # fmt: skip
    if not budget.fits:
        status = RunStatus.OVER_CAPACITY
        notes.append(
            f"not flyable with this vehicle: the plan needs {budget.needed_kg:.1f} kg of "
            f"propellant, the tank holds {budget.capacity_kg:.1f} kg (the least-ΔV plan; a plan "
            "of more ΔV spent later, on a lighter vehicle, might need less and is not searched)"
        )
    return legs, block, status, notes


def _burn_seconds(legs, vehicle, mission: Mission, budget) -> list[float] | None:
    """Each impulsive leg's burn time [s]: its ΔV over the vehicle's acceleration when it
    gives one, else its propellant at the exhaust speed over the thrust; None for a
    low-thrust plan (its phases are its burns) or without either."""
    if mission.transfer != "impulsive":
        return None
    if vehicle.accel_mps2 is not None:
        return [leg.dv_mps / float(vehicle.accel_mps2) for leg in legs]
    if vehicle.thrust_n is not None and budget is not None:
        exhaust = G0 * float(vehicle.isp_s)
        return [float(p) * exhaust / float(vehicle.thrust_n) for p in budget.propellant_kg]
    return None
