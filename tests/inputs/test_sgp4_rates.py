"""RAAN rates fitted to SGP4 (issue 26, item 4): the fit against SGP4 measured another way,
the planner's legs with the fitted rates, the catalog methods and scenario option that carry
them, the command line."""

import dataclasses

import numpy as np
import pandas as pd
import pytest
from sgp4.api import Satrec

from sdc_cvx import solve
from sdc_cvx.errors import CatalogError, ScenarioError
from sdc_cvx.flight.ephemeris import DebrisEphemeris
from sdc_cvx.flight.plan import FlightPlan
from sdc_cvx.inputs.catalog import Catalog
from sdc_cvx.inputs.formats import read_tle
from sdc_cvx.inputs.mission import Mission
from sdc_cvx.inputs.selection import select
from sdc_cvx.network.edges import node_orbits
from sdc_cvx.physics.orbits import J2, MU_EARTH, R_EARTH
from sdc_cvx.study.scenario import Scenario, load
from tests.conftest import computed_once, shared_file
from tests.flight.test_ephemeris import tle_lines
from tests.test_cli import cli_process

SSO_TLE = "sso_rocket_bodies_2020/sso_rb.tle"
DAY_S = 86400.0
JD_1949_12_31 = 2433281.5
"""Julian date of 1949-12-31 00:00 UTC."""


@pytest.fixture(scope="module")
@computed_once
def rocket_bodies():
    return read_tle(shared_file(SSO_TLE))


def node_deg(r, v):
    """Osculating RAAN [deg] of TEME states, unwrapped: the node of h = r x v."""
    h = np.cross(r, v)
    return np.degrees(np.unwrap(np.arctan2(h[:, 0], -h[:, 1])))


def j2_rate_deg_per_day(a_m, e, inc_rad):
    """First-order J2 RAAN rate (Eq. 7), written here: -3/2 J2 n (R/a)^2 cos i / (1-e^2)^2."""
    n = np.sqrt(MU_EARTH / np.asarray(a_m) ** 3)
    rate = -1.5 * J2 * n * (R_EARTH / a_m) ** 2 * np.cos(inc_rad) / (1.0 - np.square(e)) ** 2
    return np.degrees(rate) * DAY_S


@pytest.mark.requires_shared_data(SSO_TLE)
def test_fitted_rates_are_the_drift_of_sgp4s_osculating_node(rocket_bodies):
    """The file's own lines (Satrec.twoline2rv), the osculating node every 7.3 minutes over
    100 days, a least-squares quadratic through it (drag curves the node): its mean slope
    over the window is the fitted rate (measured 4e-8 deg/day apart), its value at the start
    the fitted RAAN (4e-6 deg); the fit is 0.0026-0.0034 deg/day below the J2 formula."""
    days = 100.0
    fitted = rocket_bodies.with_sgp4_rates(days)
    assert fitted.raan_rates == "sgp4" and rocket_bodies.raan_rates == "j2"
    lines = tle_lines(shared_file(SSO_TLE))
    t = np.arange(0.0, days, 7.3 / 1440.0)
    jd = (rocket_bodies.start - pd.Timestamp("1949-12-31T00:00:00Z")).value / (DAY_S * 1e9)
    for k, ident in enumerate(rocket_bodies.ids):
        satrec = Satrec.twoline2rv(*lines[ident])
        errors, r, v = satrec.sgp4_array(np.full(t.shape, JD_1949_12_31 + jd), t)
        assert not errors.any()
        curve, slope, at_start = np.polyfit(t, node_deg(r, v), 2)
        row = fitted.frame.iloc[k]
        assert row["raan_rate_deg_per_day"] == pytest.approx(slope + curve * days, abs=1e-6)
        assert (row["raan_deg"] - at_start + 180.0) % 360.0 - 180.0 == pytest.approx(0, abs=1e-4)
    shift = fitted.frame["raan_rate_deg_per_day"] - j2_rate_deg_per_day(
        rocket_bodies.a_m, rocket_bodies.e, rocket_bodies.inc_rad
    )
    assert shift.between(-0.0040, -0.0020).all(), shift.describe()


def csv_catalog(**kwargs):
    """Three near-circular debris at 700-900 km, with or without epochs."""
    rows = pd.DataFrame(
        {
            "id": ["a", "b", "c"],
            "a_km": [7078.0, 7178.0, 7278.0],
            "e": [0.001, 0.0, 0.002],
            "inc_deg": [98.2, 98.6, 99.0],
            "raan_deg": [10.0, 200.0, 350.0],
            "arglat_deg": [0.0, 90.0, 180.0],
        }
    )
    return Catalog.from_frame(rows, **kwargs)  # fmt: skip


def test_the_catalog_keeps_its_rates_through_its_methods():
    catalog = csv_catalog(start="2021-03-01")
    fitted = catalog.with_sgp4_rates(200.0)
    rate = fitted.frame["raan_rate_deg_per_day"].to_numpy()
    assert fitted.subset(["a", "c"]).raan_rates == "sgp4"
    assert fitted.with_orbit("injection", 7000.0, 0.0, 98.0, 5.0).raan_rates == "sgp4"
    assert select(fitted, altitude_km=(600, 850))[0].raan_rates == "sgp4"
    later = fitted.advanced(150.0)  # a campaign's launch: the fitted rates carry the RAANs
    assert later.raan_rates == "sgp4" and later.start == fitted.start + pd.Timedelta(days=150)
    expected = (fitted.frame["raan_deg"] + 150.0 * rate) % 360.0
    np.testing.assert_allclose(later.frame["raan_deg"], expected, atol=1e-9)
    with pytest.raises(ValueError, match="fitted to SGP4 already"):
        fitted.with_sgp4_rates(200.0)
    with pytest.raises(ValueError, match="raan_rates must be one of j2, sgp4"):
        dataclasses.replace(catalog, raan_rates="sgp5")


def test_the_planner_takes_the_fitted_rates_and_the_vehicle_keeps_j2():
    catalog = csv_catalog(start="2021-03-01")
    fitted = catalog.with_sgp4_rates(365.25)
    mission = Mission(n=2, tmax_days=365.25)
    j2 = node_orbits(catalog, mission)
    sgp4 = node_orbits(fitted, mission)
    np.testing.assert_allclose(np.degrees(sgp4.rate) * DAY_S, fitted.frame["raan_rate_deg_per_day"])
    np.testing.assert_allclose(
        np.degrees(j2.rate) * DAY_S, j2_rate_deg_per_day(catalog.a_m, catalog.e, catalog.inc_rad)
    )
    assert np.all(np.abs(np.degrees(sgp4.rate - j2.rate) * DAY_S) > 1e-3)
    # the injection orbit is the vehicle's: its J2 rate
    with_injection = node_orbits(fitted.with_orbit("injection", 7000.0, 0.0, 98.0, 5.0), mission)
    assert np.degrees(with_injection.rate[-1]) * DAY_S == pytest.approx(
        j2_rate_deg_per_day(7000e3, 0.0, np.radians(98.0)), rel=1e-12
    )


def test_a_row_whose_epoch_is_the_start_keeps_its_raan_and_flies_the_same():
    """Fitted at its own epoch, the mean node is the element set's (measured 4e-8 deg
    apart): the debris the flight replay builds from the fitted catalog are those read."""
    catalog = csv_catalog(start="2021-03-01")
    fitted = catalog.with_sgp4_rates(100.0)
    np.testing.assert_allclose(fitted.frame["raan_deg"], catalog.frame["raan_deg"], atol=1e-6)
    r1, _ = DebrisEphemeris.from_catalog(catalog).state(2, [0.0, 50 * DAY_S])
    r2, _ = DebrisEphemeris.from_catalog(fitted).state(2, [0.0, 50 * DAY_S])
    np.testing.assert_allclose(r1, r2, rtol=0, atol=1.0)  # [m]


def test_a_catalog_without_dates_gets_no_sgp4_rates():
    """Issue 48, item 8: the paper case (no epochs, no start) was fitted from an invented
    epoch and silently answered another plan; it is refused, saying what is needed (also
    tests/cli/test_inputs_face_value.py)."""
    for catalog in (Catalog.paper_case(), csv_catalog()):
        with pytest.raises(CatalogError, match="has no epochs and no start: give a TLE"):
            catalog.with_sgp4_rates(365.25)


def test_an_element_set_sgp4_cannot_fly_over_the_window_is_named():
    """220 km with a large drag term: decays in 2.5 days (SGP4 error 6)."""
    row = {"id": "99001", "a_km": 6600.0, "e": 0.001, "inc_deg": 98.0, "raan_deg": 10.0,
           "epoch": "2020-05-24T00:00:00Z", "argp_deg": 0.0, "mean_anomaly_deg": 0.0,
           "bstar": 0.01}  # fmt: skip
    catalog = Catalog.from_frame(pd.DataFrame([row]))
    catalog.with_sgp4_rates(1.0)
    with pytest.raises(CatalogError, match=r"debris 99001: SGP4 cannot propagate") as caught:
        catalog.with_sgp4_rates(30.0)
    assert "error 6 (" in str(caught.value) and 'raan_rates = "j2"' in str(caught.value)
    # one debris, one problem: the advice that follows is not counted as another
    assert str(caught.value).startswith("1 problem in ") and len(caught.value.problems) == 1
    with pytest.raises(ValueError, match="longer than two orbital periods"):
        catalog.with_sgp4_rates(0.05)


# ---------------------------------------------------------------------- the plan
def wrapped_duration(gap_deg, relative_deg_per_day):
    """Eq. 10: the gap taken modulo 360 deg in the direction of the relative rate."""
    gap = np.mod(gap_deg, 360.0)
    if relative_deg_per_day < 0:
        gap -= 360.0
    return gap / relative_deg_per_day


@pytest.mark.requires_shared_data(SSO_TLE)
def test_a_plan_with_sgp4_rates_closes_its_raan_gaps_with_them(tmp_path):
    """Each leg's duration is Eq. 10 with the debris' fitted rates (the J2 ones would be
    days off); the run folder's fly re-reads the same fitted debris."""
    text = (f'[catalog]\npath = "{shared_file(SSO_TLE)}"\nraan_rates = "sgp4"\n'
            "[mission]\nn = 3\ntmax_days = 200.0\n")  # fmt: skip
    (tmp_path / "s.toml").write_text(text)
    scenario = load(tmp_path / "s.toml")
    catalog, _ = scenario.select_candidates()
    assert catalog.raan_rates == "sgp4"
    solution = solve(catalog, scenario.mission, solver=scenario.solver)
    frame = catalog.frame.set_index("id")
    j2 = pd.Series(j2_rate_deg_per_day(catalog.a_m, catalog.e, catalog.inc_rad), frame.index)
    off = []
    for leg in solution.legs:
        drift = j2_rate_deg_per_day(leg.drift_a_km * 1e3, 0.0, np.radians(leg.drift_inc_deg))
        for rates, kept in ((frame["raan_rate_deg_per_day"], True), (j2, False)):
            at = leg.departure_day
            origin = frame.at[leg.from_id, "raan_deg"] + rates[leg.from_id] * at
            target = frame.at[leg.to_id, "raan_deg"] + rates[leg.to_id] * at
            days = wrapped_duration(target - origin, drift - rates[leg.to_id])
            if kept:
                assert days == pytest.approx(leg.duration_days, abs=0.01)
            else:
                off.append(abs(days - leg.duration_days))
    assert max(off) > 0.5  # the J2 rates would not have closed the gaps on these dates
    solution.save(tmp_path / "run", formats=(), scenario_toml=scenario.to_toml())
    plan = FlightPlan.from_run_folder(tmp_path / "run")
    assert plan.catalog.raan_rates == "sgp4" and plan.catalog.ids == solution.path
    flown = plan.catalog.frame.set_index("id")
    for column in ("raan_deg", "raan_rate_deg_per_day"):
        np.testing.assert_allclose(flown[column], frame.loc[list(solution.path), column],
                                   rtol=0, atol=1e-9)  # fmt: skip


# ---------------------------------------------------------------------- scenario and CLI
def test_the_scenario_option_round_trips_and_says_what_is_allowed(tmp_path):
    scenario = Scenario().with_overrides(raan_rates="sgp4")
    assert scenario.catalog_raan_rates == "sgp4" and Scenario().catalog_raan_rates == "j2"
    assert 'raan_rates = "sgp4"' in scenario.to_toml()  # the paper case too: no path
    (tmp_path / "a.toml").write_text(scenario.to_toml())
    assert load(tmp_path / "a.toml") == scenario
    assert "raan_rates" not in Scenario().to_dict()["catalog"]  # a sweep's sha as before
    (tmp_path / "b.toml").write_text(Scenario().to_toml())
    assert load(tmp_path / "b.toml").catalog_raan_rates == "j2"
    with pytest.raises(ScenarioError, match=r"catalog\.raan_rates must be one of j2, sgp4"):
        Scenario().with_overrides(raan_rates="sgp5")
    campaign = tmp_path / "c.toml"
    campaign.write_text('[catalog]\nraan_rates = "sgp4"\n[campaign]\nlaunch_days = [0, 300]\n'
                        "tmax_days = 200.0\n")  # fmt: skip
    assert load(campaign).rate_window_days() == 500.0
    assert scenario.rate_window_days() == scenario.mission.tmax_days


def test_a_bad_value_exits_2_naming_the_key_and_the_values(tmp_path):
    result = cli_process("run", "--raan-rates", "sgp5", "--out", str(tmp_path / "x"))
    assert result.returncode == 2
    assert "--raan-rates" in result.stderr and "'j2', 'sgp4'" in result.stderr
    (tmp_path / "s.toml").write_text('[catalog]\nraan_rates = "fitted"\n')
    result = cli_process("run", str(tmp_path / "s.toml"), "--out", str(tmp_path / "y"))
    assert result.returncode == 2, result.stderr
    assert "catalog.raan_rates must be one of j2, sgp4" in result.stderr
    assert not (tmp_path / "x").exists() and not (tmp_path / "y").exists()


@pytest.mark.slow
@pytest.mark.requires_shared_data(SSO_TLE)
def test_run_with_sgp4_rates_through_a_real_process(tmp_path):
    out = tmp_path / "run"
    result = cli_process("run", "--catalog", str(shared_file(SSO_TLE)), "--raan-rates", "sgp4",
                         "--n", "3", "--tmax-days", "200", "--out", str(out))  # fmt: skip
    assert result.returncode == 0, result.stderr
    assert "RAAN rates fitted to SGP4 over 200 days for 81 debris" in result.stderr
    assert load(out / "scenario.toml").catalog_raan_rates == "sgp4"
    assert 'raan_rates = "sgp4"' in (out / "scenario.toml").read_text()


@pytest.mark.slow
@pytest.mark.requires_shared_data(SSO_TLE)
def test_a_campaign_fits_over_its_window_and_fly_reads_each_mission_back(tmp_path):
    """Rates fitted from day 0 to the last launch plus T_max (150 + 120 days), carried to
    each launch by themselves; fly's reading of each mission folder gets the same debris."""
    from sdc_cvx.flight.plan import run_folder_plans

    text = (
        f'[catalog]\npath = "{shared_file(SSO_TLE)}"\nraan_rates = "sgp4"\n'
        "[mission]\nn = 2\ntmax_days = 120.0\n[campaign]\nlaunch_days = [0.0, 150.0]\n"
    )
    (tmp_path / "c.toml").write_text(text)
    result = cli_process("campaign", str(tmp_path / "c.toml"), "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    assert "RAAN rates fitted to SGP4 over 270 days for 81 debris" in result.stderr
    fitted = read_tle(shared_file(SSO_TLE)).with_sgp4_rates(270.0)
    plans = run_folder_plans(tmp_path / "out")
    for (_, plan), day in zip(plans, (0.0, 150.0), strict=True):
        expected = fitted.advanced(day).frame.set_index("id").loc[list(plan.catalog.ids)]
        flown = plan.catalog.frame.set_index("id")
        assert plan.catalog.raan_rates == "sgp4" and plan.start == fitted.start + pd.Timedelta(
            days=day
        )
        for column in ("raan_deg", "raan_rate_deg_per_day"):
            np.testing.assert_allclose(flown[column], expected[column], rtol=0, atol=1e-9)
