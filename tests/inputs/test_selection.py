"""Candidate selection: ranges, patterns, the orbits the drift model does not cover."""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import pytest
from click.testing import CliRunner

from sdc_cvx.cli import main
from sdc_cvx.inputs.catalog import Catalog
from sdc_cvx.inputs.formats import read_tle
from sdc_cvx.inputs.selection import select, summary
from tests.conftest import shared_file

R_T_KM = 6378.137


def catalog_of(rows) -> Catalog:
    """Catalog of (id, name, altitude km, e, inc deg) rows, all RAANs 0, one epoch."""
    frame = pd.DataFrame(
        [
            {"id": ident, "name": name, "a_km": R_T_KM + alt, "e": e, "inc_deg": inc,
             "raan_deg": 0.0, "epoch": "2020-05-24T00:00:00Z"}
            for ident, name, alt, e, inc in rows
        ]
    )  # fmt: skip
    return Catalog.from_frame(frame, source="test catalog")


@pytest.fixture
def mixed():
    return catalog_of(
        [
            ("733", "THOR AGENA D R/B", 780.0, 0.003, 99.0),
            ("815", "THOR AGENA D R/B", 950.2, 0.001, 99.9),
            ("1433", "DELTA 1 R/B", 880.0, 0.080, 98.4),  # eccentric (perigee 299 km)
            ("2000", "POLAR SAT", 800.0, 0.001, 90.3),  # near-polar: RAAN rate ~ 0
            ("34427", "COSMOS 2251 DEB", 790.0, 0.003, 74.0),  # prograde: fine
            ("34428", "COSMOS 2251 DEB", 600.0, 0.002, 89.6),  # polar and at the bound
        ]
    )


def test_default_drops_eccentric_and_near_polar_orbits(mixed):
    kept, report = select(mixed)
    assert kept.ids == ("733", "815", "34427")
    assert report["id"].tolist() == ["1433", "2000", "34428"]
    assert report["checks"].tolist() == ["eccentricity", "near-polar", "near-polar"]
    assert report["reason"][0] == (
        "eccentricity 0.0800 > 0.05 (the cost model treats orbits as circular of radius a)"
    )
    assert report["reason"][1].startswith("inclination 90.30 deg within 0.5 deg of 90 (J2 RAAN ")
    assert "drift transfers cannot close RAAN gaps" in report["reason"][1]
    polar_rate = mixed.frame["raan_rate_deg_per_day"][3]
    assert abs(polar_rate) < 0.04 and f"{polar_rate:.4f} deg/day" in report["reason"][1]
    assert kept.start == mixed.start and kept.source == mixed.source
    assert summary(kept, report) == "kept 3 of 6 candidates (dropped: 1 eccentricity, 2 near-polar)"
    kept, report = select(mixed, eccentricity_max=math.inf, polar_margin_deg=0.0)
    assert len(kept) == 6 and report.empty
    assert summary(kept, report) == "kept 6 of 6 candidates (none dropped)"


def test_ranges_and_every_reason(mixed):
    kept, report = select(mixed, altitude_km=(600, 900), inclination_deg=(96, 100))
    assert kept.ids == ("733",)
    reasons = dict(zip(report["id"], report["reason"], strict=True))
    assert reasons["815"] == "altitude 950.2 km outside [600, 900]"
    assert reasons["34427"] == "inclination 74.00 deg outside [96, 100]"
    assert reasons["34428"].startswith("inclination 89.60 deg outside [96, 100]; inclination 89.60")
    assert report.set_index("id")["checks"]["34428"] == "inclination,near-polar"  # bounds inclusive
    assert summary(kept, report) == (
        "kept 1 of 6 candidates (dropped: 1 altitude, 3 inclination, 1 eccentricity, 2 near-polar;"
        " 5 debris in all, one failing several checks counts in each)"
    )  # 7 per check for 5 debris: the counts overlap, and the line says so
    assert list(report.columns) == ["id", "name", "altitude_km", "inc_deg", "e", "checks", "reason"]


def test_id_and_name_patterns(mixed):
    kept, report = select(mixed, ids=["7*", "34*"], exclude_ids="34428")
    assert kept.ids == ("733", "34427")
    assert report.set_index("id")["reason"]["815"] == "id 815 matches none of '7*', '34*'"
    assert report.set_index("id")["checks"]["34428"] == "excluded,near-polar"
    kept, _ = select(mixed, names="cosmos 2251*")  # names: case-insensitive
    assert kept.ids == ("34427",)
    kept, _ = select(mixed, ids="?33")
    assert kept.ids == ("733",)


def test_bad_arguments(mixed):
    with pytest.raises(ValueError, match=r"ids pattern\(s\) '99\*' match no debris"):
        select(mixed, ids=["7*", "99*"])
    with pytest.raises(ValueError, match="altitude_km must be finite with low <= high"):
        select(mixed, altitude_km=(900, 600))
    with pytest.raises(ValueError, match="altitude_km must be two numbers"):
        select(mixed, altitude_km=(900,))
    with pytest.raises(ValueError, match="eccentricity_max must be >= 0"):
        select(mixed, eccentricity_max=-0.1)
    no_names = Catalog.from_frame(mixed.frame[["id", "a_km", "e", "inc_deg", "raan_deg"]])
    with pytest.raises(ValueError, match="has no names"):
        select(no_names, names="*")


def test_everything_dropped_gives_an_empty_catalog(mixed):
    kept, report = select(mixed, altitude_km=(2000, 3000))
    assert len(kept) == 0 and len(report) == 6
    assert summary(kept, report).startswith("kept 0 of 6 candidates (dropped: 6 altitude")


# ---------------------------------------------------------------------- real data
def pykep_tle() -> Path:
    return shared_file("pykep_tle/tle.txt")  # skips the test when the file is absent


def test_pykep_selection_says_why_objects_go():
    path = pykep_tle()
    lines = path.read_text().splitlines()
    eccentric = sum(float("0." + line[26:33]) > 0.05 for line in lines if line.startswith("2 "))
    catalog = read_tle(path)
    kept, report = select(catalog)
    # GTO/Molniya-like debris of the set, and 6 near-circular orbits above LEO (GPS, GEO)
    assert report["checks"].str.contains("eccentricity").sum() == eccentric == 12
    apogee = report["altitude_km"] + (report["altitude_km"] + R_T_KM) * report["e"]
    assert len(report) == 18 and report["checks"].str.contains("above-leo").sum() == 14
    assert (report[report["checks"] == "above-leo"]["altitude_km"] > 2000).all()
    assert (report["checks"].str.contains("above-leo") == (apogee > 2000)).all()
    assert "COSMOS 2251 DEB" in set(kept.frame["name"])  # prograde fragments at 74 deg stay
    kept, report = select(catalog, altitude_km=(600, 900), inclination_deg=(96, 100.5))
    assert len(kept) + len(report) == len(catalog) == 499
    assert kept.frame["altitude_km"].between(600, 900).all()
    cosmos = report[report["name"] == "COSMOS 2251 DEB"]
    assert cosmos["reason"].str.contains(r"inclination 7\d\.\d\d deg outside \[96, 100.5\]").all()
    assert summary(kept, report) == (
        f"kept {len(kept)} of 499 candidates (dropped: "
        f"{report['checks'].str.contains('altitude').sum()} altitude, "
        f"{report['checks'].str.contains('inclination').sum()} inclination, 12 eccentricity, "
        f"{report['checks'].str.contains('above-leo').sum()} above-leo"
        + (f"; {len(report)} debris in all, one failing several checks counts in each)"
           if report["checks"].str.count(",").sum() else ")")
    )


def test_cli_catalog_reports_the_dropped_objects():
    path = pykep_tle()
    args = ["catalog", str(path), "--altitude-km", "600", "900", "--ids", "34*", "--exclude-ids",
            "3442?", "--max-eccentricity", "0.01"]  # fmt: skip
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    first = result.stderr.splitlines()[0]
    assert first.startswith("kept ") and " of 499 candidates (dropped: " in first
    excluded = sum(ident.startswith("3442") and len(ident) == 5 for ident in read_tle(path).ids)
    assert f"{excluded} excluded" in first and "altitude" in first and "eccentricity" in first
    assert "dropped 34434: altitude 991.7 km outside [600, 900]" in result.stderr
    shown = [line.split()[0] for line in result.stdout.strip().splitlines()[1:]]
    assert shown and all(ident.startswith("34") and ident[:4] != "3442" for ident in shown)
    result = CliRunner().invoke(main, ["catalog", str(path), "--altitude-km", "10", "20"])
    assert result.exit_code == 2 and "error: no candidate left in" in result.stderr
    result = CliRunner().invoke(main, ["catalog", "--ids", "Z*"])  # the paper's table
    assert result.exit_code == 2
    assert "error: candidate selection: ids pattern(s) 'Z*' match no debris" in result.stderr


def test_cli_catalog_of_the_paper_table_is_unchanged_by_the_default_checks():
    result = CliRunner().invoke(main, ["catalog"])
    assert result.exit_code == 0 and "kept" not in result.stderr
    result = CliRunner().invoke(main, ["catalog", "--inclination-deg", "98", "98.5"])
    assert "kept 6 of 11 candidates (dropped: 5 inclination)" in result.stderr
