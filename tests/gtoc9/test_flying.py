"""GTOC9 legs flown by :mod:`sdc_cvx.gtoc9.flying`, checked by the project's validator and
by the tests' own GTOC9 (:mod:`tests.gtoc9.gtoc9_reference`: its ephemeris and ODE written
from GTOC9's equations page, SciPy's ``solve_ivp`` DOP853 at rtol 1e-12).

The mission: debris 0, 104 and 67, whose RAANs are within 0.25 deg of each other from
MJD2000 23947 to 23977 (inclinations within 0.25 deg, radii 28 and 26 km apart; found by
scanning GTOC9's debris every 5 days for pairs closer than 0.3 deg in RAAN and
inclination, 10 to 100 km apart in radius): launch at 0 on 23940, 7 days there, 15 days
to 104, 5 days there, 18 days to 67, 5 days there.
"""

import math
from pathlib import Path

import numpy as np
import pytest

from sdc_cvx.errors import MissionError
from sdc_cvx.gtoc9 import DebrisTable, check_mission, write_mission_file
from sdc_cvx.gtoc9.flying import GOAL_M, GOAL_MPS, fly_leg, fly_mission, paper_drift_leg
from tests.gtoc9 import gtoc9_reference as ref

pytestmark = pytest.mark.requires_shared_data("gtoc9/debris_data.txt")

IDS = [0, 104, 67]
ARRIVALS = [23940.0, 23962.0, 23985.0]
DEPARTURES = [23947.0, 23967.0, 23990.0]


@pytest.fixture(scope="module")
def table():
    return DebrisTable.read(ref.DEBRIS_FILE)


@pytest.fixture(scope="module")
def rows():
    return ref.debris_rows()


@pytest.fixture(scope="module")
def mission(table):
    """The mission flown, through a ``map`` that records its jobs (the pool's hook)."""
    jobs = []

    def recording_map(function, items):
        items = list(items)
        jobs.extend(items)
        return map(function, items)

    flown = fly_mission(IDS, DEPARTURES, ARRIVALS, debris=table, map=recording_map)
    return flown, jobs


def _hohmann_with_plane_change(r1, r2, di):
    """Two tangential impulses between circular orbits, the plane change combined with
    the one at the higher radius (Cerf 2013 Eq. 11-13), written here."""
    lo, hi = min(r1, r2), max(r1, r2)
    at = 0.5 * (lo + hi)
    v_lo, v_hi = math.sqrt(ref.MU / lo), math.sqrt(ref.MU / hi)
    v_peri, v_apo = math.sqrt(ref.MU * (2 / lo - 1 / at)), math.sqrt(ref.MU * (2 / hi - 1 / at))
    return (v_peri - v_lo) + math.sqrt(v_apo**2 + v_hi**2 - 2 * v_apo * v_hi * math.cos(di))


def _paper_estimate(rows, leg):
    """The drift leg's cost from the debris file's a and i and the leg's drift orbit."""
    a_i, inc_i = rows[leg.from_id][1], rows[leg.from_id][3]
    a_j, inc_j = rows[leg.to_id][1], rows[leg.to_id][3]
    a_d, inc_d = leg.paper.a_drift, leg.paper.inc_drift
    return (_hohmann_with_plane_change(a_i, a_d, abs(inc_d - inc_i))
            + _hohmann_with_plane_change(a_d, a_j, abs(inc_j - inc_d)))  # fmt: skip


def _raan(row, mjd2000):
    t0, a, e, inc, raan0 = row[:5]
    p = a * (1 - e**2)
    return raan0 - 1.5 * ref.J2 * (ref.RE / p) ** 2 * math.sqrt(ref.MU / a**3) * math.cos(inc) * (
        mjd2000 - t0) * 86400.0  # fmt: skip


@pytest.mark.slow
def test_the_mission_passes_the_validator(mission, table, tmp_path: Path):
    flown, jobs = mission
    path = write_mission_file(tmp_path / "mission_01.txt", flown.events)
    report = check_mission(path, table)
    assert report.violations == []
    assert report.debris == IDS
    assert report.dv_mps == pytest.approx(flown.dv_total_mps, rel=1e-12)
    assert report.m0_kg == pytest.approx(flown.m0_kg, rel=1e-12)
    assert report.cost_meur == pytest.approx(flown.cost_meur, rel=1e-12)
    assert [job[1:5] for job in jobs] == [(0, 23947.0, 104, 23962.0), (104, 23967.0, 67, 23985.0)]


@pytest.mark.slow
def test_the_events_are_in_the_competitions_order(mission):
    events = mission[0].events
    assert (events[0].epoch, events[0].ident, events[0].dv) == (23940.0, 0, (0.0, 0.0, 0.0))
    assert (events[-1].epoch, events[-1].ident, events[-1].dv) == (23990.0, 67, (0.0, 0.0, 0.0))
    idents = [e.ident for e in events]
    # arrival 0, departure 0, DSMs, arrival 104, departure 104, DSMs, arrival 67, departure 67
    debris_events = [(e.ident, e.epoch) for e in events if e.ident != -1]
    assert debris_events == [(0, 23940.0), (0, 23947.0), (104, 23962.0), (104, 23967.0),
                             (67, 23985.0), (67, 23990.0)]  # fmt: skip
    assert idents.count(-1) >= 2
    assert all(b.epoch <= a.epoch for b, a in zip(events, events[1:], strict=False))


@pytest.mark.slow
def test_the_mission_holds_in_the_tests_own_gtoc9(mission, rows):
    """Each arc flown by solve_ivp on the equations page's ODE, each rendezvous against
    the equations page's ephemeris: within 100 m and 1 m/s; perigee >= 6600 km."""
    events = mission[0].events
    for event in events:
        if event.ident == -1:
            continue
        r_d, v_d = ref.debris_state(rows[event.ident], event.epoch)
        arriving = any(e.ident == event.ident and e.epoch > event.epoch for e in events)
        v = np.array(event.v) + (np.array(event.dv) if arriving else 0.0)
        assert np.linalg.norm(np.array(event.r) - r_d) < 100.0
        assert np.linalg.norm(v - v_d) < 1.0
    stays = {(0, 23940.0), (104, 23962.0), (67, 23985.0)}
    for before, after in zip(events, events[1:], strict=False):
        if (before.ident, before.epoch) in stays:
            continue  # co-orbiting: no arc
        r1, v1, steps = ref.fly(np.array(before.r), np.array(before.v) + np.array(before.dv),
                                (after.epoch - before.epoch) * 86400.0)  # fmt: skip
        assert np.linalg.norm(r1 - np.array(after.r)) < 100.0
        assert np.linalg.norm(v1 - np.array(after.v)) < 1.0
        assert ref.osculating_perigee(steps).min() >= 6600e3


@pytest.mark.slow
def test_each_leg_meets_half_the_tolerances(mission):
    for leg in mission[0].legs:
        assert leg.miss_m <= GOAL_M and leg.miss_mps <= GOAL_MPS and leg.converged
        assert leg.notes == ()
        assert leg.epochs[0] == leg.t_depart and leg.epochs[-1] == leg.t_arrive
        assert leg.min_perigee_m >= 6600e3


@pytest.mark.slow
def test_the_flown_dv_is_within_30_percent_of_the_papers_drift_leg(mission, rows):
    for leg in mission[0].legs:
        estimate = _paper_estimate(rows, leg)
        assert leg.paper.dv_mps == pytest.approx(estimate, rel=1e-9)
        assert leg.dv_total_mps <= 1.3 * estimate
        assert leg.dv_total_mps >= 0.8 * estimate  # the leg is the drift leg's, not another


def test_the_drift_orbit_closes_the_raan_gap_in_the_legs_time(table, rows):
    """Eq. 10 checked from the debris file: the drift orbit's RAAN rate, over the leg less
    its two Hohmann half-orbits, closes the gap up to whole turns at the target's rate."""
    for i, t_dep, j, t_arr in ((0, 23947.0, 104, 23962.0), (104, 23967.0, 67, 23985.0)):
        drift = paper_drift_leg(table, i, t_dep, j, t_arr)
        a_i, a_j, a_d = rows[i][1], rows[j][1], drift.a_drift
        halves = sum(math.pi * math.sqrt((0.5 * (x + a_d)) ** 3 / ref.MU) for x in (a_i, a_j))
        coast = (t_arr - t_dep) * 86400.0 - halves
        n_d = math.sqrt(ref.MU / a_d**3)
        rate_d = -1.5 * ref.J2 * (ref.RE / a_d) ** 2 * n_d * math.cos(drift.inc_drift)
        t0, a, e, inc = rows[j][:4]
        rate_j = -1.5 * ref.J2 * (ref.RE / (a * (1 - e**2))) ** 2 * math.sqrt(ref.MU / a**3) * (
            math.cos(inc))  # fmt: skip
        gap = _raan(rows[j], t_dep) - _raan(rows[i], t_dep)
        closed = gap - (rate_d - rate_j) * coast
        assert abs(math.remainder(closed, 2 * math.pi)) < 1e-6
        assert drift.dv_mps == pytest.approx(
            _hohmann_with_plane_change(a_i, a_d, abs(drift.inc_drift - rows[i][3]))
            + _hohmann_with_plane_change(a_d, a_j, abs(rows[j][3] - drift.inc_drift)), rel=1e-9)


def test_a_given_drift_orbit_is_priced_not_moved(table, rows):
    drift = paper_drift_leg(table, 0, 23947.0, 104, 23962.0, a_drift=7.1e6, inc_drift=1.71)
    assert (drift.a_drift, drift.inc_drift) == (7.1e6, 1.71)
    expected = (_hohmann_with_plane_change(rows[0][1], 7.1e6, abs(1.71 - rows[0][3]))
                + _hohmann_with_plane_change(7.1e6, rows[104][1], abs(rows[104][3] - 1.71)))
    assert drift.dv_mps == pytest.approx(expected, rel=1e-9)


def test_malformed_requests_are_refused(table):
    with pytest.raises(MissionError, match="not after the departure"):
        fly_leg(table, 0, 23947.0, 104, 23947.0)
    with pytest.raises(MissionError, match="as many of each"):
        fly_mission([0, 104], [23947.0], [23940.0, 23962.0], debris=table)
    with pytest.raises(MissionError, match="1 seeds for 2 legs"):
        fly_mission(IDS, DEPARTURES, ARRIVALS, seeds=[None], debris=table)
