"""Messages a new user met that misled (issue 28, 3.3), each kept right by a test."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from sdc_cvx import Catalog, Mission
from sdc_cvx.cli import main
from sdc_cvx.errors import MissionError
from sdc_cvx.study.scenario import Scenario


def test_a_scenario_saved_with_a_byte_order_mark_reads(tmp_path):
    """Some editors start a UTF-8 file with a BOM; TOML read it as 'Invalid statement'."""
    path = tmp_path / "s.toml"
    path.write_bytes(b"\xef\xbb\xbf[mission]\nn = 3\n")
    assert Scenario.load(path).mission.n == 3


def test_a_negative_n_is_not_answered_with_advice_about_must_include():
    with pytest.raises(MissionError) as refused:
        Mission(n=-3)
    assert "n must be >= 2" in str(refused.value)
    assert "must_include" not in str(refused.value)


def test_a_blank_id_is_shown_quoted_not_invisible():
    with pytest.raises(MissionError, match=r"not in the catalog: '', ' 7'"):
        Mission(n=3, must_include=("", " 7")).check_candidates(Catalog.paper_case())


def test_the_live_log_does_not_say_a_campaign_log_becomes_run_log(tmp_path):
    from sdc_cvx.report.run_folder import LIVE_LOG_SIGNATURE

    assert "run.log" not in LIVE_LOG_SIGNATURE


def test_overlapping_drop_reasons_say_they_overlap(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7050,0.2,60,40\n"
                    "3,7100,0.001,98,70\n4,7100,0.001,98,90\n")  # fmt: skip
    result = CliRunner().invoke(main, ["catalog", str(path), "--inclination-deg", "90", "100",
                                       "--max-eccentricity", "0.01"])  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "kept 3 of 4 candidates (dropped: 1 inclination, 1 eccentricity" in result.stderr
    assert "; 1 debris in all, one failing several checks counts in each" in result.stderr


def test_edges_takes_the_candidate_filters_and_sets_aside_what_is_not_an_orbit(tmp_path):
    """``edges`` read strictly, with none of the filters ``run`` has."""
    path = tmp_path / "d.csv"
    path.write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7050,0.001,98,40\n"
                    "3,7100,0.001,98,70\n4,6500,0.001,98,90\n5,7300,0.001,98,20\n")  # fmt: skip
    result = CliRunner().invoke(main, ["edges", "--catalog", str(path), "--all",
                                       "--altitude-km", "600", "800"])  # fmt: skip
    assert result.exit_code == 0, result.output
    ids = {line.split(",")[0] for line in result.stdout.splitlines()[1:]}
    assert ids == {"1", "2", "3"}  # 4 and 5 are outside 600-800 km
    assert "kept 3 of 5 candidates (dropped: 2 altitude)" in result.stderr


@pytest.mark.slow
def test_the_papers_method_with_low_thrust_says_what_t0_bounds_and_what_would_help():
    """At 3e-5 m/s^2 the spirals and plane changes of the paper case outlast the year (the
    certified method proves it); the paper's method says that T0 bounds the coast only and
    that more thrust shortens the rest (issue 29)."""
    from sdc_cvx import SolverOptions, solve
    from sdc_cvx.errors import MissionInfeasible

    mission = Mission(transfer="low-thrust", vehicle={"accel_mps2": 3e-5})
    with pytest.raises(MissionInfeasible, match="T0 bounds each leg's coast.*more thrust"):
        solve(Catalog.paper_case(), mission, solver=SolverOptions(method="paper"))


def test_a_header_of_hundreds_of_columns_is_not_listed_whole(tmp_path):
    """A wide CSV without the orbit columns (a spreadsheet export, 400 columns): the
    message names what is missing and a few of the columns found, on short lines (it was
    one line of thousands of characters), through a real subprocess."""
    import subprocess
    import sys

    path = tmp_path / "wide.csv"
    names = [f"col{k}" for k in range(400)]
    path.write_text("id," + ",".join(names) + "\n1," + ",".join("0" * 400) + "\n")
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(path),
                           "--out", str(tmp_path / "out")], capture_output=True, text=True,
                          timeout=120)  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "missing required column(s) 'a_km'" in done.stderr
    assert "'col0'" in done.stderr and "and 389 more" in done.stderr
    assert max(len(line) for line in done.stderr.splitlines()) < 400


def test_hundreds_of_unknown_ids_are_not_listed_whole():
    with pytest.raises(ValueError) as caught:
        Catalog.paper_case().subset([f"X{k}" for k in range(360)])
    message = str(caught.value)
    assert "'X0'" in message and "and 348 more" in message and len(message) < 500


def test_accel_on_the_command_line_replaces_the_scenarios_thrust(tmp_path):
    """Found as a user: `run examples/low_thrust.toml --accel 1e-3` was refused ("give
    thrust_n or accel_mps2, not both") although flags override the scenario."""
    from sdc_cvx.study.scenario import apply_overrides
    from tests.conftest import EXAMPLES

    base = Scenario.load(EXAMPLES / "low_thrust.toml")
    assert base.mission.vehicle.thrust_n is not None
    changed = apply_overrides(base, {"vehicle.accel_mps2": 1e-3}, origin="command line")
    assert changed.mission.vehicle.accel_mps2 == 1e-3 and changed.mission.vehicle.thrust_n is None
    assert changed.mission.vehicle.dry_mass_kg == base.mission.vehicle.dry_mass_kg


def test_a_sweep_may_vary_the_vehicle(tmp_path):
    """Found as a user: a grid on vehicle.thrust_n was refused as "not a dotted key"."""
    from sdc_cvx.study.study import load_study
    from tests.conftest import EXAMPLES

    path = tmp_path / "study.toml"
    path.write_text(f'base = "{(EXAMPLES / "low_thrust.toml").as_posix()}"\n[grid]\n'
                    '"vehicle.thrust_n" = [0.05, 0.2]\n')  # fmt: skip
    study = load_study(path)
    assert [s.scenario.mission.vehicle.thrust_n for s in study.scenarios] == [0.05, 0.2]


def test_options_a_run_ignores_are_said_through_a_real_process(tmp_path):
    """Found as a user: --accel without --transfer low-thrust, and --force-model without
    --fly, were silently ignored."""
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "run", "--n", "3", "--accel", "1e-4",
                           "--force-model", "j2-j4", "--quiet", "--out", str(tmp_path / "r")],
                          capture_output=True, text=True, timeout=300)  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert "warning: --accel is a low-thrust vehicle's" in done.stderr
    assert "warning: --force-model is --fly's" in done.stderr


def test_a_position_on_the_orbit_that_is_not_a_number_is_named(tmp_path):
    """Found as a user: `arglat_deg = abc` was read as blank, then `fly` said the catalog
    gave no arglat_deg; blank stays allowed (optional per row)."""
    from sdc_cvx.errors import CatalogError

    path = tmp_path / "debris.csv"
    path.write_text("id,a_km,e,inc_deg,raan_deg,arglat_deg\n1,7178,0.001,98.6,10,abc\n"
                    "2,7180,0.001,98.6,12,\n3,7190,0.001,98.6,14,45\n")  # fmt: skip
    with pytest.raises(CatalogError, match="row 1.*field 'arglat_deg': expected a number"):
        Catalog.from_csv(path)


# the first two element sets of the SSO rocket bodies (2020), as that file has them
TWO_TLES = """\
0 THOR AGENA D R/B
1   733U 64002A   20145.30230088 +.00000007 +00000-0 +20152-4 0  9992
2   733 099.0143 035.9085 0032950 303.3378 056.4651 14.32394256935785
0 THOR AGENA D R/B
1   815U 64031C   20147.19804992 -.00000013  00000-0  17013-4 0  9995
2   815  99.8646 150.6351 0012488  52.4516 307.7793 14.27329406905632
"""


def test_a_tle_file_is_read_from_python_by_the_reader_readme_names(tmp_path):
    """Found as a new user: README showed ``Catalog.from_csv`` only, and the reader of TLE,
    OMM and GTOC9 files was not at the top level.  ``sdc_cvx.read_catalog`` is, and
    ``solve`` given a path names it."""
    import sdc_cvx

    path = tmp_path / "two.tle"
    path.write_text(TWO_TLES, encoding="utf-8")
    catalog = sdc_cvx.read_catalog(path)
    assert list(catalog.frame["id"]) == ["733", "815"]
    assert catalog.frame["inc_deg"].tolist() == pytest.approx([99.0143, 99.8646])
    with pytest.raises(TypeError, match=r"sdc_cvx\.read_catalog\("):
        sdc_cvx.solve(str(path), Mission(n=2))
