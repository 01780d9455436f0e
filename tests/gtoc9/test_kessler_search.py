"""GTOC9's Kessler Run searched for J (issue 47, items 1-3): the leg table, the mass chain,
the mission beam search against an exhaustive search, the scenario file, ``gtoc9-plan``.

Reference values come from GTOC9's constants page (typed here), from the validator's own
mass chain (:func:`sdc_cvx.gtoc9.campaign_file.launch_mass`, a backward loop over events)
and from brute force over the same grid of dates, never from the code under test.
"""

import itertools
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from sdc_cvx.errors import MissionError
from sdc_cvx.gtoc9 import Event, Gtoc9Rules
from sdc_cvx.gtoc9.campaign_file import launch_mass
from sdc_cvx.gtoc9.legs import Gtoc9Legs
from sdc_cvx.gtoc9.plan import PlannedMission, chain_mass
from sdc_cvx.gtoc9.scenario import read_kessler_scenario
from sdc_cvx.gtoc9.search import SearchSettings, plan_mission
from sdc_cvx.physics.leg_bounds import LegCosts
from tests.conftest import REPO, computed_once

pytestmark = pytest.mark.requires_shared_data("gtoc9/debris_data.txt")

EXAMPLE = REPO / "examples" / "gtoc9_kessler_run.toml"


@pytest.fixture(scope="module")
@computed_once
def legs():
    return Gtoc9Legs.build(direct=True)  # both structures: every test covers the direct leg


def test_the_mass_chain_is_the_validators_on_the_same_impulses():
    dvs = [120.0, 310.5, 42.25, 0.0, 250.0]
    zero = (0.0, 0.0, 0.0)
    events = [Event(0.0, (7e6, 0, 0), (0, 7.5e3, 0), zero, 0)]  # the launch at debris 0
    for k, dv in enumerate(dvs, start=1):  # a departure then an arrival, the leg's ΔV split
        events += [Event(10.0 * k - 5, (7e6, 0, 0), (0, 7.5e3, 0), (0.4 * dv, 0, 0), k - 1),
                   Event(10.0 * k, (7e6, 0, 0), (0, 7.5e3, 0), (0, 0.6 * dv, 0), k)]
    events.append(Event(10.0 * len(dvs) + 5, (7e6, 0, 0), (0, 7.5e3, 0), zero, len(dvs)))
    assert chain_mass(dvs) == pytest.approx(launch_mass(events), rel=1e-12)
    # by hand: one leg of 100 m/s between two debris
    grow = math.exp(100.0 / (340.0 * 9.80665))
    assert chain_mass([100.0]) == pytest.approx(2030.0 * grow + 30.0, rel=1e-12)


def test_a_leg_of_the_table_is_the_same_leg_priced_alone(legs):
    i, j = 121, 25  # a leg of a planned mission (days 60-76)
    alone = LegCosts.build(legs.table.origin.take([legs.edge(i, j)]),
                           legs.table.target.take([legs.edge(i, j)]), legs.table.a_low,
                           legs.table.a_high, mu=398600.4418e9,
                           eccentricity=tuple(v.take([legs.edge(i, j)])
                                              for v in legs.table.eccentricity))
    assert legs.ids[i] == str(i) and legs.ids[j] == str(j)
    # the edge of (i, j) runs from i to j
    assert legs.origin[legs.edge(i, j)] == i and legs.target[legs.edge(i, j)] == j
    dates = np.arange(0.0, 2900.0, 1.0)
    table = Gtoc9Legs(legs.ids, legs.origin, legs.target, legs.table, legs.start_mjd2000,
                      direct=False).cost(i, j, dates, dates + 20.0).cost
    single = alone.cost_at(np.zeros(len(dates), int), dates, dates + 20.0, rule="free",
                           j2=legs.j2).cost  # fmt: skip
    np.testing.assert_array_equal(table, single)
    assert np.isfinite(table).any()
    # the direct leg only ever lowers the cost, and is the cheaper one where it says so
    both = legs.cost(i, j, dates, dates + 20.0)
    assert np.all(both.cost <= np.where(np.isfinite(table), table, np.inf))
    direct = both.side == 0
    np.testing.assert_allclose(both.cost[direct],
                               legs.direct_cost(legs.edge(i, j), dates, dates + 20.0)[direct])


def test_the_eccentricity_only_adds_to_a_legs_cost(legs):
    circular = Gtoc9Legs.build(eccentricity=False, direct=True)
    assert legs.direct and circular.direct
    rng = np.random.default_rng(5)
    i = rng.integers(0, 123, 20000)
    j = (i + rng.integers(1, 123, 20000)) % 123
    t = rng.uniform(0.0, 2900.0, 20000)
    d = rng.uniform(1.0, 25.0, 20000)
    priced, paper = legs.cost(i, j, t, t + d).cost, circular.cost(i, j, t, t + d).cost
    finite = np.isfinite(paper)
    assert finite.sum() > 100
    assert np.all(priced[finite] >= paper[finite] - 1e-9)
    assert np.all(np.isinf(priced[~finite]))


def _gtoc9_rows():
    """GTOC9's debris file as (id, epoch, a, e, i, RAAN, argp, M) rows."""
    path = REPO.parent / "shared" / "data" / "gtoc9" / "debris_data.txt"
    return np.loadtxt(path)


def _hohmann_with_plane_change(r1, r2, theta, mu=398600.4418e9):
    """Eq. 11-13 of the paper, written again: the plane change at the higher radius."""
    low, high = min(r1, r2), max(r1, r2)
    at = 0.5 * (low + high)
    v_low, v_high = math.sqrt(mu / low), math.sqrt(mu / high)
    v_peri = math.sqrt(mu * (2 / low - 1 / at))
    v_apo = math.sqrt(mu * (2 / high - 1 / at))
    return (v_peri - v_low) + math.sqrt(v_high**2 + v_apo**2
                                        - 2 * v_high * v_apo * math.cos(theta))


def test_the_direct_leg_is_a_hohmann_transfer_with_the_plane_angle_and_its_phasing():
    legs = Gtoc9Legs.build(eccentricity=False, direct=True)
    rows = _gtoc9_rows()
    mu, r_eq, j2 = 398600.4418e9, 6378137.0, 1.08262668e-3

    def raan(k, day):  # GTOC9's equations page: the secular J2 rate from the epoch
        _, epoch, a, e, inc, node, _, _ = rows[k]
        n = math.sqrt(mu / a**3)
        rate = -1.5 * j2 * (r_eq / (a * (1 - e * e))) ** 2 * n * math.cos(inc)
        return node + rate * (23467.0 + day - epoch) * 86400.0

    checked = 0
    for i, j, t_d, t_a in ((121, 25, 60.0, 70.0), (7, 85, 480.0, 490.0), (3, 14, 1000.0, 1003.0),
                           (40, 87, 1800.0, 1812.5)):
        a_i, a_j, inc_i, inc_j = rows[i][2], rows[j][2], rows[i][4], rows[j][4]
        angles = []
        for day in (t_d, t_a):
            gap = raan(j, day) - raan(i, day)
            angles.append(math.acos(math.cos(inc_i) * math.cos(inc_j)
                                    + math.sin(inc_i) * math.sin(inc_j) * math.cos(gap)))
        n_j = math.sqrt(mu / a_j**3)
        phasing = math.sqrt(mu / a_j) * math.pi / (1.5 * n_j * (t_a - t_d) * 86400.0)
        expected = _hohmann_with_plane_change(a_i, a_j, min(angles)) + phasing
        got = float(legs.direct_cost(legs.edge(i, j), t_d, t_a))
        assert got == pytest.approx(expected, rel=1e-6), (i, j)
        checked += 1
    assert checked == 4


def test_a_legs_box_bound_is_never_above_a_leg_in_its_box(legs):
    rng = np.random.default_rng(11)
    count = 40000
    i = rng.integers(0, 123, count)
    j = (i + rng.integers(1, 123, count)) % 123
    t1 = rng.uniform(0.0, 2900.0, count)
    t3 = t1 + rng.uniform(1.0, 25.0, count)
    bound = legs.bound(i, j, t1, t1 + 2.0, t3, t3 + 2.0)
    for u, w in ((0.0, 0.0), (2.0, 2.0), (0.7, 1.3), (2.0, 0.0)):
        leg = legs.cost(i, j, t1 + u, t3 + w).cost
        finite = np.isfinite(leg)
        assert finite.any()
        assert np.all(bound[finite] <= leg[finite] + 1e-9)


def _brute_force_pair(legs, available, launches, grid):
    """The cheapest one-leg mission over every ordered pair, launch and grid date."""
    best = math.inf
    for a, b in itertools.permutations(np.flatnonzero(available), 2):
        for t0 in launches:
            for leave, arrive in grid:
                cost = float(legs.cost(a, b, t0 + leave, t0 + arrive).cost)
                best = min(best, cost)
    return best


def test_a_two_debris_mission_is_the_exhaustive_searchs_cheapest(legs):
    available = np.zeros(123, bool)
    available[[3, 14, 28, 30, 100, 90]] = True
    settings = SearchSettings(beam=500, day_price_mps=0.0, waits_days=(0.0, 3.0),
                              launch_window_days=20.0, launch_step_days=10.0, max_debris=3)
    found = plan_mission(legs, available, 1200.0, 2952.0, settings=settings)
    grid = [(5.0 + w, float(d)) for w in (0.0, 3.0) for d in range(int(5 + w) + 1, 31)]
    expected = _brute_force_pair(legs, available, [1200.0, 1210.0, 1220.0], grid)
    assert math.isfinite(expected)
    assert found[0].dv == pytest.approx(expected, abs=1e-9)


def test_every_planned_mission_keeps_gtoc9s_rules(legs):
    rules = Gtoc9Rules()
    settings = SearchSettings(beam=60, max_debris=8)
    missions = plan_mission(legs, np.ones(123, bool), 100.0, 2952.0, settings=settings)
    assert len(missions) == settings.max_debris - 1
    for m in missions:
        assert len(set(m.debris)) == len(m.debris)
        assert m.launch >= 100.0 and m.end <= 2952.0
        assert m.fits(rules)
        for k in range(1, len(m.debris)):
            assert m.departures[k - 1] - m.arrivals[k - 1] >= rules.stay_days - 1e-9
            assert m.arrivals[k] - m.arrivals[k - 1] <= rules.dt_r_days + 1e-9
            assert m.arrivals[k] > m.departures[k - 1]
            again = float(legs.cost(m.debris[k - 1], m.debris[k], m.departures[k - 1],
                                    m.arrivals[k]).cost)  # fmt: skip
            assert m.leg_dv[k - 1] == pytest.approx(again, abs=1e-9)
        assert m.end - m.arrivals[-1] == pytest.approx(rules.stay_days)


def test_the_scenario_holds_gtoc9s_constants():
    scenario = read_kessler_scenario(EXAMPLE)
    r = scenario.rules
    # GTOC9's problem and constants pages
    assert (r.start_mjd2000, r.end_mjd2000) == (23467.0, 26419.0)
    assert (r.stay_days, r.dt_r_days, r.dt_m_days) == (5.0, 30.0, 30.0)
    assert (r.min_perigee_m, r.eps_r_m, r.eps_v_mps) == (6600e3, 100.0, 1.0)
    assert (r.m_dry_kg, r.m_de_kg, r.max_propellant_kg) == (2000.0, 30.0, 5000.0)
    assert (r.isp_s, r.g0_mps2) == (340.0, 9.80665)
    assert (r.launch_cost_meur, r.alpha_meur_per_kg2) == (55.0, 2.0e-6)
    assert scenario.debris_path.resolve().name == "debris_data.txt"
    assert r == Gtoc9Rules()  # every key written in the example is GTOC9's default


def test_a_scenario_with_errors_names_each_one(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[campaign]\nobjective = "min-dv"\nremove_all = false\n'
                   '[rules]\nstay_days = "five"\nwarp = 9\n[search]\nbeam = 0\n[extra]\n')
    with pytest.raises(MissionError) as err:
        read_kessler_scenario(bad)
    text = str(err.value)
    for expected in ("[campaign] objective: expected 'gtoc9-cost'", "[campaign] remove_all",
                     "[rules] stay_days: expected float", "[rules] warp: unknown key",
                     "[search] beam must be > 0", "unknown table [extra]"):
        assert expected in text
    assert str(bad) in text


def test_gtoc9_plan_rejects_a_bad_scenario_through_a_real_process(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[rules]\ndt_r_from = "sometime"\n')
    run = subprocess.run([sys.executable, "-m", "sdc_cvx", "gtoc9-plan", str(bad), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2
    assert "dt_r_from" in run.stderr and str(bad) in run.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_gtoc9_plan_writes_its_campaign_through_a_real_process(tmp_path):
    scenario = tmp_path / "kessler.toml"
    debris = REPO.parent / "shared" / "data" / "gtoc9" / "debris_data.txt"
    scenario.write_text(f'[catalog]\npath = "{debris}"\n[search]\nbeam = 20\nrounds = 1\n'
                        'launch_window_days = 10.0\n')
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "sdc_cvx", "gtoc9-plan", str(scenario),
                          "--out", str(out), "--quiet"], capture_output=True, text=True,
                         timeout=600)  # fmt: skip
    assert run.returncode in (0, 3), run.stderr
    plan = json.loads((out / "plan.json").read_text())
    assert plan["status"] == ("complete" if run.returncode == 0 else "incomplete")
    removed = [k for m in plan["missions"] for k in m["debris"]]
    assert len(removed) == len(set(removed)) == plan["removed"]
    rules = Gtoc9Rules()
    total = 0.0
    for before, after in itertools.pairwise(plan["missions"]):
        assert after["arrivals_mjd2000"][0] >= before["departures_mjd2000"][-1] + 30.0 - 1e-9
    for m in plan["missions"]:
        assert m["m0_kg"] == pytest.approx(chain_mass(m["leg_dv_mps"]), abs=1e-5)
        total += 55.0 + 2.0e-6 * (m["m0_kg"] - 2000.0) ** 2
        planned = PlannedMission(tuple(m["debris"]), (0.0,), (5.0,), tuple(m["leg_dv_mps"]))
        assert planned.fits(rules)
    assert plan["J_meur"] == pytest.approx(total, abs=1e-4)
    assert plan["lower_bound_meur"] <= plan["J_meur"]
    assert f"{plan['J_meur']:.2f} MEUR" in run.stdout


@pytest.mark.parametrize("command", ["campaign", "run"])
def test_the_campaign_commands_point_a_kessler_run_to_gtoc9_plan(command, tmp_path):
    run = subprocess.run([sys.executable, "-m", "sdc_cvx", command, str(EXAMPLE), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, timeout=120)
    assert run.returncode == 2
    assert f"gtoc9-plan {EXAMPLE}" in run.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_planned_mission_flown_by_gtoc9_plan_passes_the_check(legs, tmp_path):
    from sdc_cvx.cli.gtoc9_plan import _fly
    from sdc_cvx.gtoc9 import DebrisTable, check_folder, find_debris_file
    from sdc_cvx.gtoc9.plan import PlannedCampaign

    # tests/gtoc9/test_flying.py's mission (planes within 0.25 deg), planned by the table
    start = legs.start_mjd2000
    arrivals, departures = (23940.0, 23962.0, 23985.0), (23947.0, 23967.0, 23990.0)
    first = legs.cost(0, 104, departures[0] - start, arrivals[1] - start)
    second = legs.cost(104, 67, departures[1] - start, arrivals[2] - start)
    mission = PlannedMission((0, 104, 67), tuple(t - start for t in arrivals),
                             tuple(t - start for t in departures),
                             (float(first.cost), float(second.cost)),
                             (float(first.a_drift), float(second.a_drift)),
                             (float(first.inc_drift), float(second.inc_drift)))
    said = []
    _fly(PlannedCampaign((mission,)), start, tmp_path, Gtoc9Rules(), 2, said.append)
    report = check_folder(tmp_path, DebrisTable.read(find_debris_file()))
    assert not report.all_violations, report.all_violations
    assert [tuple(m.debris) for m in report.missions] == [(0, 104, 67)]
    assert any("mission 1 flown" in line for line in said)
    summary = json.loads((tmp_path / "campaign.json").read_text())
    assert len(summary["missions"]) == 1
