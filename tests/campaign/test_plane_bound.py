"""The plane-change value bound (campaign/plane_bound.py) and the campaigns it proves.

The least ΔV of turning an orbit's plane is re-derived here from the velocity vectors
(two circular velocities of the same speed whose planes differ by dI), not imported.
"""

from __future__ import annotations

import numpy as np
import pytest

from sdc_cvx import Mission
from sdc_cvx.campaign.plane_bound import least_plane_change_dv, plane_value_bound
from sdc_cvx.campaign.search import solve_campaign
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from sdc_cvx.solution import RunStatus
from tests.campaign.bruteforce import value_optimum

MU = 3.986e14  # m^3/s^2, as the package's (the paper's Table 1)


def test_the_least_plane_change_is_the_turn_at_the_slowest_apoapsis():
    """At the apoapsis of the Hohmann ellipse from 6778 to 7578 km (the slowest the
    vehicle flies), turning the velocity by dI about the radius costs |v2 - v1|; any
    other burn (faster, or changing the speed too) costs more."""
    low, high = 6.778e6, 7.578e6
    v_apo = np.sqrt(MU * 2 * low / (high * (low + high)))  # vis-viva at r = high
    for d_inc in np.radians([0.5, 7.9, 28.5]):
        v1 = v_apo * np.array([0.0, 1.0, 0.0])
        v2 = v_apo * np.array([0.0, np.cos(d_inc), np.sin(d_inc)])
        least = least_plane_change_dv(0.0, d_inc, low, high)
        assert least == pytest.approx(np.linalg.norm(v2 - v1))
        circular = np.sqrt(MU / high) * np.array([0.0, np.cos(d_inc), np.sin(d_inc)])
        assert least < np.linalg.norm(circular - v1)  # and raising the speed costs more


def test_debris_whose_plane_change_no_budget_pays_never_share_a_mission():
    """Three stages at 71 deg and one at 99.5 deg (28.5 deg apart: 3.6 km/s at the band's
    top), budgets of 1 km/s, two missions of two: the lone stage flies alone, so the
    campaign is worth at most (10 + 8) + 9, not the four most valuable, 28."""
    inc = np.radians([71.0, 71.1, 71.2, 99.5])
    a, band, values = np.full(4, 7.2e6), (400.0, 1200.0), np.array([10.0, 8.0, 1.0, 9.0])
    bound = plane_value_bound(inc, a, values, [2, 2], 1000.0, band)
    assert bound.groups == 2
    assert bound.value == pytest.approx(27.0) and bound.forced == (0, 1, 3)
    # budgets that pay the turn: one group, the four most valuable
    wide = plane_value_bound(inc, a, values, [2, 2], 4000.0, band)
    assert wide.groups == 1 and wide.value == pytest.approx(28.0)
    # a tie at the edge of a group's best: two sets reach the bound, none is forced
    tied = np.array([10.0, 8.0, 8.0, 9.0])
    assert plane_value_bound(inc, a, tied, [2, 2], 1000.0, band).forced is None
    assert plane_value_bound(inc, a, tied, [3, 2], 1000.0, band).forced == (0, 1, 2, 3)


def test_a_campaign_whose_debris_the_bound_forces_is_the_brute_forces():
    """Distinct values, one group: the most valuable debris are forced; their least-ΔV
    campaign fits the budgets, so no enumeration is needed, and it is the brute force's
    most valuable campaign at its least ΔV."""
    catalog = sso_catalog(7, seed=9, inclination_spread_deg=0.8)
    rng = np.random.default_rng(9)
    values = dict(zip(catalog.ids, rng.permutation(np.arange(1, 8)) * 1.5, strict=True))
    days, ranges, tmax, budgets = (0.0, 365.25), ((2, 3), (2, 2)), (300.0, 300.0), (600.0, 400.0)
    campaign = Campaign.of(days, Mission(), n=[list(r) for r in ranges], tmax_days=list(tmax),
                           objective="max-value", dv_budget_mps=list(budgets),
                           values=values)  # fmt: skip
    lines: list[str] = []
    sol = solve_campaign(catalog, campaign, workers=1, log=lines.append)
    assert any("the slowest speed flown" in line for line in lines)
    best = value_optimum(catalog, days, ranges, tmax, budgets, values)
    assert sol.status == RunStatus.OPTIMAL and sol.certified
    assert sol.value == pytest.approx(best.value) and sol.value_bound == pytest.approx(best.value)
    assert sol.lower_bound_mps <= best.dv_mps + 1e-6
    assert sol.total_dv_mps <= best.dv_mps * (1 + 1e-3) + 1e-6
    assert sol.total_dv_mps >= best.dv_mps - 2 * 0.05  # the brute force's grid error
    for mission, budget in zip(sol.missions, budgets, strict=True):
        assert mission.total_dv_mps <= budget + 1e-9
