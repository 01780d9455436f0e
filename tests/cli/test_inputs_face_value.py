"""Inputs no longer taken at face value (issue 48, items 5-10), through real processes
and the API.

- 5: one element set with a wrong epoch (2056 among sets of 2020) is not the default start:
  the start is taken from the bulk and the outlier is named.
- 6: a CSV whose angles are radians is refused, naming the file and the columns.
- 7: an injection orbit's a_km in metres exits 2 naming the scenario key.
- 8: RAAN rates fitted to SGP4 need dated element sets: a catalog without epochs or start
  (the paper's Table 5) is refused, saying what is needed.
- 9: the phase angles (arglat_deg, argp_deg, mean_anomaly_deg) take the RAAN's range.
- 10: values the MILP cannot take (1e300) and values that mean nothing (all 0, or 0 for
  every candidate) are refused before the MILP, as an empty values file is.
"""

import warnings

import pandas as pd
import pytest

from sdc_cvx.errors import CatalogError, CatalogWarning
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.catalog import Catalog
from sdc_cvx.inputs.formats import read_catalog
from sdc_cvx.inputs.mission import Mission, MissionError
from sdc_cvx.inputs.values import read_values
from tests.test_cli import cli_process

# five SSO rocket bodies of 2020 (sso_rb.tle); the second's epoch year typed 56 for 20
OUTLIER_TLE = """\
0 THOR AGENA D R/B
1   733U 64002A   20145.30230088 +.00000007 +00000-0 +20152-4 0  9992
2   733 099.0143 035.9085 0032950 303.3378 056.4651 14.32394256935785
0 THOR AGENA D R/B
1   815U 64031C   56147.19804992 -.00000013  00000-0  17013-4 0  9994
2   815  99.8646 150.6351 0012488  52.4516 307.7793 14.27329406905632
0 DELTA 1 R/B
1  1433U 65051B   20146.31086254 +.00000082 +00000-0 +29247-4 0  9998
2  1433 098.4231 232.8240 0041657 274.5531 085.0909 14.56747764872077
0 DELTA 1 R/B
1  1983U 66008B   20145.90470930 +.00000083 +00000-0 +25604-4 0  9997
2  1983 097.9274 093.5364 0070785 241.8374 117.5665 14.61706703869523
0 THOR BURNER 2 R/B
1  2741U 67010B   20146.62751708 +.00000004 +00000-0 +20605-4 0  9998
2  2741 099.0131 016.4909 0052730 226.6315 133.0467 14.27945097769273
"""
# day 146.62751708 of 2020, the latest of the four good epochs
LATEST_GOOD = pd.Timestamp("2020-01-01T00:00:00Z") + pd.Timedelta(days=145.62751708)


# ---------------------------------------------------------------------- item 5
def test_a_wrong_epoch_is_not_the_default_start_and_is_named(tmp_path):
    path = tmp_path / "outlier.tle"
    path.write_text(OUTLIER_TLE)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        catalog = read_catalog(path, on_invalid="set aside")
    assert abs(catalog.start - LATEST_GOOD) < pd.Timedelta(seconds=1)
    assert sorted(catalog.ids) == ["1433", "1983", "2741", "733"]
    assert list(catalog.invalid["id"]) == ["815"]
    said = [str(w.message) for w in caught if issubclass(w.category, CatalogWarning)]
    assert any("catalog number 815" in text and "2056" in text for text in said), said


def test_the_catalog_command_keeps_the_four_good_sets(tmp_path):
    path = tmp_path / "outlier.tle"
    path.write_text(OUTLIER_TLE)
    done = cli_process("catalog", str(path))
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert "4 debris from" in done.stderr and "RAANs at 2020-05-25" in done.stderr
    assert "catalog number 815" in done.stderr and "2056-05-26" in done.stderr
    for good in ("733", "1433", "1983", "2741"):
        assert f"catalog number {good})" not in done.stderr, done.stderr


# ---------------------------------------------------------------------- item 6
RADIANS = "id,a_km,e,inc_deg,raan_deg\n1,7078,0.001,1.71,0.5\n2,7178,0.001,1.72,2.1\n" \
          "3,7128,0.001,1.70,4.0\n4,7100,0.001,1.71,5.9\n"  # fmt: skip
"""Sun-synchronous orbits (98 deg = 1.71 rad) with their angles in radians."""
GEO_TLE = """\
1 90001U 20001A   20145.30230088 +.00000000 +00000-0 +00000-0 0  9999
2 90001   0.0500   1.0000 0001000   0.0000   0.0000  1.00273791    10
1 90002U 20001A   20145.30230088 +.00000000 +00000-0 +00000-0 0  9990
2 90002   0.0500   2.5000 0001000   0.0000  10.0000  1.00273791    18
1 90003U 20001A   20145.30230088 +.00000000 +00000-0 +00000-0 0  9991
2 90003   0.0500   4.0000 0001000   0.0000  20.0000  1.00273791    17
"""
"""Three geostationary element sets whose angles are all small: degrees, as TLEs are."""


@pytest.mark.parametrize("on_invalid", ["raise", "set aside"])
def test_angles_in_radians_are_refused_naming_the_file_and_columns(tmp_path, on_invalid):
    """Not equatorial rows (inclination 0 either way), nor two rows only, nor a format
    whose angles are degrees by definition (TLE): read as given."""
    (tmp_path / "geo.tle").write_text(GEO_TLE)
    assert len(read_catalog(tmp_path / "geo.tle", on_invalid=on_invalid)) == 3
    path = tmp_path / "degrees.csv"
    path.write_text("id,a_km,e,inc_deg,raan_deg\n1,7078,0,0,0.5\n2,7178,0,0,2.1\n"
                    "3,7128,0,0,4.0\n")  # fmt: skip
    assert len(Catalog.from_csv(path, on_invalid=on_invalid)) == 3
    path.write_text("id,a_km,e,inc_deg,raan_deg\n1,7078,0,1.5,0.5\n2,7178,0,1.7,2.1\n")
    assert len(Catalog.from_csv(path, on_invalid=on_invalid)) == 2
    path = tmp_path / "radians.csv"
    path.write_text(RADIANS)
    with pytest.raises(CatalogError, match=r"radians\.csv, columns 'inc_deg' and 'raan_deg'"):
        Catalog.from_csv(path, on_invalid=on_invalid)


def test_run_on_angles_in_radians_exits_2(tmp_path):
    path = tmp_path / "radians.csv"
    path.write_text(RADIANS)
    done = cli_process("run", "--catalog", str(path), "--n", "2", "--quiet",
                       "--out", str(tmp_path / "out"))  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr and not (tmp_path / "out").exists()
    assert "radians.csv, columns 'inc_deg' and 'raan_deg'" in done.stderr
    assert "radians? (degrees are expected" in done.stderr



# ---------------------------------------------------------------------- item 7
def test_an_injection_a_km_in_metres_is_refused_naming_the_key(tmp_path):
    with pytest.raises(MissionError, match=r"injection a_km must be at most 100,000 km"):
        Mission(n=3, injection=(7_178_000.0, 0.0, 98.0, 10.0))
    Mission(n=3, injection=(42_164.0, 0.0, 0.1, 10.0))  # GEO: an Earth orbit
    scenario = tmp_path / "injection.toml"
    scenario.write_text("[mission]\nn = 3\ninjection = [7178000.0, 0.0, 98.0, 10.0]\n")
    done = cli_process("run", str(scenario), "--quiet", "--out", str(tmp_path / "out"))
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr and not (tmp_path / "out").exists()
    assert "injection.toml: mission.injection: injection a_km" in done.stderr
    assert "got 7178000.0: metres?" in done.stderr


# ---------------------------------------------------------------------- item 8
def test_sgp4_rates_on_a_catalog_without_dates_exit_2_saying_what_is_needed(tmp_path):
    done = cli_process("run", "--raan-rates", "sgp4", "--n", "3", "--quiet",
                       "--out", str(tmp_path / "out"))  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr and not (tmp_path / "out").exists()
    assert "paper Table 5: raan_rates = \"sgp4\"" in done.stderr
    assert "no epochs and no start: give a TLE or OMM file, a CSV with an 'epoch' column" \
        in done.stderr  # fmt: skip


@pytest.mark.slow
def test_sgp4_rates_of_a_csv_dated_by_its_start_say_where_the_sets_come_from(tmp_path):
    path = tmp_path / "dated.csv"
    path.write_text("id,a_km,e,inc_deg,raan_deg\n1,7078,0.001,98.2,10\n2,7178,0,98.6,20\n"
                    "3,7278,0.002,99.0,30\n")  # fmt: skip
    with pytest.raises(CatalogError, match="no epochs and no start"):
        Catalog.from_csv(path).with_sgp4_rates(100.0)
    assert Catalog.from_csv(path, start="2021-03-01").with_sgp4_rates(100.0).raan_rates == "sgp4"
    done = cli_process("run", "--catalog", str(path), "--start", "2021-03-01", "--raan-rates",
                       "sgp4", "--n", "2", "--tmax-days", "100", "--out",
                       str(tmp_path / "out"))  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "the element sets are the catalog's elements dated at its start" in done.stderr


# ---------------------------------------------------------------------- item 9
@pytest.mark.parametrize("column", ["arglat_deg", "argp_deg", "mean_anomaly_deg"])
def test_a_phase_angle_of_1e12_is_refused_as_a_raan_is(tmp_path, column):
    path = tmp_path / "phase.csv"
    path.write_text(f"id,a_km,e,inc_deg,raan_deg,{column}\n1,7078,0.001,98,10,-36000\n"
                    "2,7178,0.001,98,20,1e12\n")  # fmt: skip
    with pytest.raises(CatalogError) as caught:
        Catalog.from_csv(path)
    assert caught.value.problems == (
        f"{path}, row 2 (line 3), field '{column}': expected an angle in [-36000, 36000] deg "
        "(wrapped), got '1e12'",
    )
    if column == "arglat_deg":
        done = cli_process("catalog", str(path))
        assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
        assert "row 2 (line 3), field 'arglat_deg': expected an angle" in done.stderr


# ---------------------------------------------------------------------- item 10
VALUE_SCENARIO = ('[catalog]\nvalues = "values.csv"\n[mission]\ntmax_days = 365.25\n'
                  '[campaign]\nobjective = "max-value"\nlaunch_days = [0.0, 365.25]\n'
                  "n = [[2, 3], [2, 2]]\ndv_budget_mps = 150.0\n")  # fmt: skip
"""A max-value campaign of the paper's Table 5 (debris ids 1-11)."""


@pytest.mark.parametrize(("values", "said"), [
    ("id,value\n5,1e300\n8,7\n", "values.csv, line 2, field value: expected a number of at "
                                  "most 1e+09, got '1e300': divide every value"),
    ("id,value\n5,0\n8,0.0\n", "values.csv, field value: every one of the 2 rows is 0: "
                                "such values mean nothing"),
])  # fmt: skip
@pytest.mark.slow
def test_values_the_milp_cannot_take_or_that_mean_nothing_exit_2(tmp_path, values, said):
    (tmp_path / "values.csv").write_text(values)
    (tmp_path / "s.toml").write_text(VALUE_SCENARIO)
    with pytest.raises(CatalogError, match="field value: e"):
        read_values(tmp_path / "values.csv")
    done = cli_process("campaign", str(tmp_path / "s.toml"), "--workers", "1",
                       "--out", str(tmp_path / "out"))  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "Traceback" not in done.stderr and not (tmp_path / "out").exists()
    assert "s.toml: catalog.values:" in done.stderr and said in done.stderr


def test_campaign_values_the_milp_cannot_take_or_that_mean_nothing_are_refused():
    def campaign(values):
        return Campaign.of([0.0, 365.25], Mission(n=2), objective="max-value",
                           dv_budget_mps=150.0, values=values)  # fmt: skip

    with pytest.raises(MissionError, match=r"values must be at most 1e\+09"):
        campaign({"5": 1e300, "8": 7.0})
    with pytest.raises(MissionError, match="values are all 0 .2 debris.: such values mean"):
        campaign({"5": 0.0, "8": 0})
    worthless = campaign({"5": 0.0, "999": 3.0})  # worth something, but not a candidate
    with pytest.raises(MissionError, match=r"the 1 candidate\(s\) the values name \(5\) "
                                           "are all worth 0"):  # fmt: skip
        worthless.check_candidates([str(k) for k in range(1, 12)])
    campaign({"5": 1e9, "8": 0.0}).check_candidates([str(k) for k in range(1, 12)])
