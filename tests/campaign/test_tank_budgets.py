"""Max-value campaigns whose missions must fit their vehicle's tank (issue 27: "each mission
within its ΔV budget — or its propellant capacity when a vehicle is given").

The reference is the campaign brute force (``tests/campaign/bruteforce.py``: every path's
best schedule on a grid, its physics re-derived from the paper) with each path's
propellant computed here by the rocket equation, kits left at each debris, written again
from the textbook: ``m_before = m_after exp(ΔV / (g0 Isp))``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from sdc_cvx import Mission, Vehicle
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.inputs.vehicle import dv_ceiling_mps
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import GRID, advanced, campaigns_of
from tests.planner.bruteforce import Enumeration

G0 = 9.80665
DRY, KIT, ISP = 500.0, 150.0, 300.0


def propellant_kg(leg_dv):
    """Propellant of a plan flown from its first debris (kit left there too), ending dry."""
    mass = DRY
    for dv in reversed(leg_dv):  # the last debris' kit, then the leg to it, and so on
        mass = (mass + KIT) * math.exp(dv / (G0 * ISP))
    mass += KIT  # the first debris' kit, left at t = 0
    return mass - DRY - (len(leg_dv) + 1) * KIT


def tank_options(catalog, launch_days, ranges, tmaxes, tank_kg, rule):
    """Per launch, every debris set with a path whose best schedule fits the tank (its
    cheapest such path), and how near any path's propellant comes to the tank [kg]."""
    options, margin = [], np.inf
    for day, (low, high), tmax in zip(launch_days, ranges, tmaxes, strict=True):
        sets = {}
        for n in range(low, high + 1):
            middle, zoom = GRID[n]
            enum = Enumeration(advanced(catalog, day), n, tmax, middle_count=middle,
                               zoom_count=zoom, walk=8)  # fmt: skip
            for plan in enum.plans[rule]:
                if not np.isfinite(plan.dv):
                    continue
                need = propellant_kg(plan.leg_dv)
                margin = min(margin, abs(need - tank_kg))
                key = frozenset(enum.ids(plan))
                if need <= tank_kg and plan.dv < sets.get(key, np.inf):
                    sets[key] = plan.dv
        options.append(sorted(sets.items(), key=lambda kv: kv[1]))
    return options, margin


def test_the_tank_ceiling_is_the_rocket_equation_with_only_the_last_kit_aboard():
    vehicle = Vehicle(dry_mass_kg=DRY, propellant_kg=60.0, isp_s=ISP, kit_mass_kg=KIT)
    ceiling = dv_ceiling_mps(vehicle)
    assert ceiling == pytest.approx(G0 * ISP * math.log((DRY + KIT + 60.0) / (DRY + KIT)))
    # all of it burned on the last leg needs the whole tank; on the first leg, more
    assert propellant_kg([0.0, ceiling]) == pytest.approx(60.0)
    assert propellant_kg([ceiling, 0.0]) > 60.0


def test_a_campaign_without_budgets_takes_its_tanks_ceilings():
    vehicle = Vehicle(dry_mass_kg=DRY, propellant_kg=60.0, isp_s=ISP, kit_mass_kg=KIT)
    campaign = Campaign.of([0.0, 200.0], Mission(vehicle=vehicle), n=[[2, 3]],
                           objective="max-value")  # fmt: skip
    assert campaign.tank_limited and campaign.budgets_from_tank
    assert campaign.dv_budget_mps == pytest.approx((dv_ceiling_mps(vehicle),) * 2)
    assert campaign.to_dict()["dv_budget_from"] == "tank"
    given = Campaign.of([0.0], Mission(vehicle=vehicle), n=[[2, 3]], objective="max-value",
                        dv_budget_mps=100.0)  # fmt: skip
    assert given.tank_limited and not given.budgets_from_tank
    assert given.dv_budget_mps == (100.0,)
    with pytest.raises(Exception, match="dry_mass_kg, propellant_kg and isp_s"):
        Campaign.of([0.0], Mission(), n=[[2, 3]], objective="max-value")


@pytest.mark.slow
def test_the_most_valuable_campaign_within_the_tanks_is_the_brute_forces():
    """Heavy kits (150 kg on a 500 kg vehicle): the tank's ΔV ceiling (only the last kit
    aboard) would fly a mission of three, but no such mission's best schedule fits the
    tank with its kits aboard; the most debris removed is four, not five, and the value
    bound says five is not ruled out (another schedule might fit): ``feasible``."""
    catalog = sso_catalog(8, seed=11, inclination_spread_deg=0.8)
    days, ranges, tmaxes, rule = (0.0, 200.0), ((2, 3), (2, 2)), (250.0, 150.0), "free"
    tank = 115.0
    values = {k: 1.0 for k in catalog.ids}
    options, margin = tank_options(catalog, days, ranges, tmaxes, tank, rule)
    assert margin > 0.05  # no path within the grid's error of the tank
    best = max(campaigns_of(options, values), key=lambda c: (c[0], -c[1]))
    assert best[0] == 4.0
    vehicle = Vehicle(dry_mass_kg=DRY, propellant_kg=tank, isp_s=ISP, kit_mass_kg=KIT)
    campaign = Campaign.of(days, Mission(drift_inclination=rule, vehicle=vehicle),
                           n=[list(r) for r in ranges], tmax_days=list(tmaxes),
                           objective="max-value", values=values)  # fmt: skip
    sol = solve_campaign(catalog, campaign, workers=1)
    assert sol.value == pytest.approx(best[0])
    assert sol.value_bound is None or sol.value_bound >= best[0] - 1e-9
    assert sol.total_dv_mps <= best[1] * (1 + 1e-3) + 1e-6
    for mission in sol.missions:  # each one flies on its tank, by the rocket equation here
        assert propellant_kg([leg.dv_mps for leg in mission.legs]) <= tank * (1 + 1e-9)
        assert mission.vehicle["fits"] is True
    relaxed, _ = tank_options(catalog, days, ranges, tmaxes, np.inf, rule)
    ceiling = dv_ceiling_mps(vehicle)
    unbound = max(w for w, dv, chosen in campaigns_of(
        [[(k, dv) for k, dv in o if dv <= ceiling] for o in relaxed], values))  # fmt: skip
    assert unbound == 5.0  # the tank binds: the ΔV ceiling alone would remove five
    assert sol.status == RunStatus.FEASIBLE and sol.value_bound == pytest.approx(unbound)
    assert any("more propellant than their tank holds" in note for note in sol.notes)


def test_a_least_dv_campaign_over_its_tank_is_over_capacity_and_names_the_missions():
    """``objective = "min-dv"`` searches without the tank: where a mission of its answer
    needs more propellant than the tank holds (the rocket equation here), the campaign is
    ``over_capacity``, never certified, and says which missions; missions.csv has each
    mission's propellant and fit."""
    catalog = sso_catalog(7, seed=5, inclination_spread_deg=0.8)
    free = Vehicle(dry_mass_kg=DRY, propellant_kg=1e4, isp_s=ISP, kit_mass_kg=KIT)
    campaign = Campaign.of([0.0, 200.0], Mission(vehicle=free), n=[2, 2],
                           tmax_days=[250.0, 150.0])  # fmt: skip
    roomy = solve_campaign(catalog, campaign, workers=1)
    assert roomy.certified and roomy.status != RunStatus.OVER_CAPACITY
    needs = [propellant_kg([leg.dv_mps for leg in m.legs]) for m in roomy.missions]
    assert abs(needs[0] - needs[1]) > 1.0
    tank = 0.5 * (needs[0] + needs[1])  # one mission fits, the other does not
    small = Vehicle(dry_mass_kg=DRY, propellant_kg=tank, isp_s=ISP, kit_mass_kg=KIT)
    sol = solve_campaign(catalog, Campaign.of([0.0, 200.0], Mission(vehicle=small), n=[2, 2],
                                              tmax_days=[250.0, 150.0]), workers=1)  # fmt: skip
    assert sol.status == RunStatus.OVER_CAPACITY and not sol.certified
    over = int(np.argmax(needs))
    assert f"mission {over + 1} needs {needs[over]:.1f} kg of {tank:.1f} kg" in sol.notes[-1]
    assert f"mission {2 - over} needs" not in sol.notes[-1]
    frame = sol.missions_frame()
    assert frame["fits"].tolist() == [need <= tank for need in needs]
    assert frame["propellant_needed_kg"].to_numpy() == pytest.approx(needs, rel=1e-6)
    assert f"over the tank: mission {over + 1}" in sol.summary()
