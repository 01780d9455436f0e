"""Scenario files: loading, every key, one-line errors with dotted keys, overrides, round trip."""

import json
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from sdc_cvx import Catalog, Mission, SolverOptions
from sdc_cvx.inputs.catalog import CatalogError
from sdc_cvx.study.scenario import (
    CATALOG_FORMATS,
    Scenario,
    ScenarioError,
    Selection,
    apply_overrides,
    load,
)
from tests.conftest import EXAMPLES, PAPER_CSV, SHARED_DATA

FULL = """
[catalog]
path = "debris.csv"
format = "csv"
[mission]
n = 4
tmax_days = 300
deorbit_days = 1.5
operations_dv_mps = 2.0
min_transfer_days = 3.0
drift_altitude_km = [450, 1100.0]
preopt_days = 45.0
dv_max_mps = 800.0
drift_inclination = "free"
j2 = 1.086e-3
[solver]
backend = "scipy"
time_limit_s = 60.0
mip_gap = 1e-4
threads = 2
verbose = true
seed = 7
"""


def write(folder: Path, text: str, name: str = "scenario.toml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


def load_error(folder: Path, text: str) -> str:
    with pytest.raises(ScenarioError) as info:
        load(write(folder, text))
    message = str(info.value)
    assert "\n" not in message and "scenario.toml" in message
    return message


@pytest.fixture
def debris_csv(tmp_path):
    (tmp_path / "debris.csv").write_text(PAPER_CSV.read_text())
    return tmp_path / "debris.csv"


# ---------------------------------------------------------------------- loading
@pytest.mark.parametrize("name", ["paper.toml", "short_mission.toml", "n4.toml", "n6.toml"])
def test_every_example_loads_and_its_catalog_reads(name):
    scenario = load(EXAMPLES / name)
    assert scenario.source == (EXAMPLES / name).resolve()
    assert len(scenario.load_catalog()) == 11
    assert load(EXAMPLES / name) == scenario


def test_examples_say_what_their_names_say():
    assert load(EXAMPLES / "paper.toml") == Scenario()
    short = load(EXAMPLES / "short_mission.toml").mission
    assert (short.n, short.tmax_days) == (4, 250.0)
    assert load(EXAMPLES / "n4.toml").mission.n == 4
    n6 = load(EXAMPLES / "n6.toml")
    assert n6.mission.n == 6 and n6.catalog_path == PAPER_CSV.resolve()


def test_every_documented_key(tmp_path, debris_csv):
    scenario = load(write(tmp_path, FULL))
    assert scenario.catalog_path == debris_csv.resolve() and scenario.catalog_format == "csv"
    assert scenario.mission == Mission(
        n=4, tmax_days=300.0, deorbit_days=1.5, operations_dv_mps=2.0, min_transfer_days=3.0,
        drift_altitude_km=(450.0, 1100.0), preopt_days=45.0, dv_max_mps=800.0,
        drift_inclination="free", j2=1.086e-3,
    )  # fmt: skip
    assert scenario.solver == SolverOptions(backend="SCIPY", time_limit_s=60.0, mip_gap=1e-4,
                                            threads=2, verbose=True, seed=7)  # fmt: skip
    assert isinstance(scenario.mission.tmax_days, float)  # an integer is fine for a number
    assert scenario.load_catalog().ids == Catalog.paper_case().ids


def test_empty_file_is_the_paper_case(tmp_path):
    scenario = load(write(tmp_path, ""))
    assert scenario == Scenario() and scenario.catalog_path is None
    assert scenario.load_catalog().source == Catalog.paper_case().source


def test_catalog_path_is_relative_to_the_scenario_file(tmp_path, debris_csv, monkeypatch):
    sub = tmp_path / "sub"
    sub.mkdir()
    monkeypatch.chdir(sub)  # not where the scenario is
    scenario = load(write(tmp_path, '[catalog]\npath = "debris.csv"\n'))
    assert scenario.catalog_path == debris_csv.resolve() and scenario.catalog_format == "csv"


# ---------------------------------------------------------------------- errors
@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("[mission]\ntmax = 3\n", ["unknown key mission.tmax", "did you mean tmax_days",
                                   "allowed keys in [mission]: n, tmax_days"]),
        ("[solver]\nbackend = 'HIGHS'\nmipgap = 0.1\n", ["unknown key solver.mipgap", "mip_gap"]),
        ("[catalog]\nfile = 'x.csv'\n", ["unknown key catalog.file", "path, format"]),
        ("[mision]\nn = 3\n", ["unknown table [mision]", "catalog, mission, solver"]),
        ("n = 3\n", ["'n' outside a table", "mission.n"]),
        ("mission = 3\n", ["mission must be a table"]),
        ("[mission]\ntmax_days = '365'\n", ["mission.tmax_days must be a finite number",
                                            "'365' (string)"]),
        ("[mission]\nn = 4.0\n", ["mission.n must be an integer", "4.0 (float)"]),
        ("[mission]\nn = true\n", ["mission.n must be an integer", "true (boolean)"]),
        ("[mission]\ntmax_days = false\n", ["mission.tmax_days must be a finite number"]),
        ("[mission]\ntmax_days = inf\n", ["mission.tmax_days must be a finite number"]),
        ("[mission]\ndrift_altitude_km = [400]\n", ["mission.drift_altitude_km must be an "
                                                    "array of 2 numbers"]),
        ("[solver]\nthreads = 2.5\n", ["solver.threads must be an integer"]),
        ("[solver]\nverbose = 1\n", ["solver.verbose must be a boolean"]),
        ("[catalog]\npath = 5\n", ["catalog.path must be a string"]),
    ],
)  # fmt: skip
def test_unknown_names_and_wrong_types_name_the_dotted_key(tmp_path, text, expected):
    message = load_error(tmp_path, text)
    for part in expected:
        assert part in message


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("[mission]\ntmax_days = -1\n", "mission.tmax_days must be > 0, got -1.0"),
        ("[mission]\nn = 1\n", "mission.n must be >= 2"),
        ("[mission]\ndeorbit_days = -0.5\n", "mission.deorbit_days must be >= 0"),
        ("[mission]\ndrift_altitude_km = [1200, 400]\n",
         "mission.drift_altitude_km must satisfy 0 < low < high"),
        ("[mission]\ndrift_inclination = 'best'\n", "mission.drift_inclination must be one of"),
        ("[solver]\nmip_gap = 1.5\n", "solver.mip_gap must be in [0, 1)"),
        ("[solver]\ntime_limit_s = 0\n", "solver.time_limit_s must be > 0"),
        ("[solver]\nthreads = 0\n", "solver.threads must be a positive integer"),
        ("[solver]\nbackend = 'CLARABEL'\n", "solver.backend must be a MILP backend, one of HIGHS"),
    ],
)  # fmt: skip
def test_out_of_range_values_name_the_dotted_key(tmp_path, text, expected):
    assert expected in load_error(tmp_path, text)


def test_a_problem_of_several_keys_names_them_all(tmp_path):
    message = load_error(tmp_path, "[mission]\nn = 5\ndeorbit_days = 80\n")
    assert "mission.n" in message and "mission.deorbit_days" in message
    assert "mission.tmax_days" in message and "leaves no time" in message


def test_every_problem_is_reported_on_one_line(tmp_path):
    message = load_error(tmp_path, "[mission]\nn = 1\ntmax_days = -1\n[solver]\nmip_gap = 2\n")
    assert "mission.n" in message and "mission.tmax_days" in message
    assert "solver.mip_gap" in message


def test_missing_catalog_file_names_the_resolved_path(tmp_path):
    message = load_error(tmp_path, '[catalog]\npath = "data/nowhere.csv"\n')
    assert "catalog.path" in message and str(tmp_path / "data" / "nowhere.csv") in message


def test_catalog_formats(tmp_path):
    (tmp_path / "debris.tle").write_text("")
    (tmp_path / "debris.txt").write_text("")
    (tmp_path / "debris.dat").write_text("")
    scenario = load(write(tmp_path, '[catalog]\npath = "debris.tle"\n'))
    assert scenario.catalog_format == "tle"  # from the extension
    with pytest.raises(CatalogError, match="empty file: no TLE element sets"):
        scenario.load_catalog()  # read only when asked for
    assert load(write(tmp_path, '[catalog]\npath = "debris.txt"\n')).catalog_format == "tle"
    for fmt in ("omm", "gtoc9"):
        scenario = load(write(tmp_path, f'[catalog]\npath = "debris.txt"\nformat = "{fmt}"\n'))
        assert scenario.catalog_format == fmt
    message = load_error(tmp_path, '[catalog]\npath = "debris.dat"\n')
    assert "cannot tell the format" in message and ", ".join(CATALOG_FORMATS) in message
    message = load_error(tmp_path, '[catalog]\npath = "debris.tle"\nformat = "xls"\n')
    assert "catalog.format must be one of csv, tle, omm, gtoc9" in message
    message = load_error(tmp_path, '[catalog]\nformat = "tle"\n')
    assert "catalog.format = 'tle' needs catalog.path" in message


def test_csv_format_is_forced_whatever_the_extension(tmp_path, debris_csv):
    (tmp_path / "debris.dat").write_text(debris_csv.read_text())
    scenario = load(write(tmp_path, '[catalog]\npath = "debris.dat"\nformat = "CSV"\n'))
    assert scenario.catalog_format == "csv" and len(scenario.load_catalog()) == 11


def test_bad_toml_syntax_gives_the_line(tmp_path):
    message = load_error(tmp_path, "[mission]\nn = 5\ntmax_days = \n")
    assert "invalid TOML" in message and "line 3" in message


def test_missing_or_unreadable_scenario_file(tmp_path):
    with pytest.raises(ScenarioError, match="nowhere.toml: file not found"):
        load(tmp_path / "nowhere.toml")
    (tmp_path / "binary.toml").write_bytes(b"\xff\xfe[mission]")
    with pytest.raises(ScenarioError, match="not a UTF-8 text file"):
        load(tmp_path / "binary.toml")


def test_bad_catalog_content_is_a_catalog_error(tmp_path):
    (tmp_path / "bad.csv").write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,2.5,98,10\n")
    scenario = load(write(tmp_path, '[catalog]\npath = "bad.csv"\n'))
    with pytest.raises(CatalogError, match="row 1"):
        scenario.load_catalog()


# ---------------------------------------------------------------------- overrides
def test_overrides_by_field_name_and_dotted_key():
    dotted = {"solver.time_limit_s": 10, "mission.preopt_days": 40}
    scenario = Scenario().with_overrides(n=4, tmax_days=300, backend="scipy", **dotted)
    mission = scenario.mission
    assert (mission.n, mission.tmax_days, mission.preopt_days) == (4, 300.0, 40.0)
    assert scenario.solver.backend == "SCIPY" and scenario.solver.time_limit_s == 10.0
    assert scenario.mission.deorbit_days == 0.0  # untouched


def test_none_means_not_given(tmp_path):
    scenario = load(EXAMPLES / "short_mission.toml")
    assert scenario.with_overrides(n=None, backend=None, catalog_path=None) == scenario


def test_overrides_are_validated_like_a_file():
    with pytest.raises(ScenarioError, match=r"^overrides: mission\.n must be >= 2"):
        Scenario().with_overrides(n=1)
    with pytest.raises(ScenarioError, match=r"mission\.n must be an integer, got true \(boolean\)"):
        Scenario().with_overrides(n=True)
    with pytest.raises(ScenarioError, match="unknown override 'tmax'"):
        Scenario().with_overrides(tmax=3)
    # a sweep's misspelt key (found as a new user): the nearest one is offered
    with pytest.raises(ScenarioError, match=r"'mission\.tmax_day' \(did you mean "
                                            r"mission\.tmax_days\?\)"):
        Scenario().with_overrides(**{"mission.tmax_day": 100.0})
    with pytest.raises(ScenarioError, match=r"^command line: solver\.mip_gap"):
        apply_overrides(Scenario(), {"mip_gap": 3.0}, origin="command line")


def test_catalog_override_is_relative_to_the_current_directory(tmp_path, debris_csv, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scenario = load(EXAMPLES / "n4.toml").with_overrides(catalog_path="debris.csv")
    assert scenario.catalog_path == debris_csv.resolve() and scenario.mission.n == 4
    with pytest.raises(ScenarioError, match="catalog.path: file not found"):
        scenario.with_overrides(catalog="other.csv")
    (tmp_path / "debris.tle").write_text("")
    assert scenario.with_overrides(catalog="debris.tle").catalog_format == "tle"  # chosen again


# ---------------------------------------------------------------------- writing
@pytest.mark.parametrize("name", ["paper.toml", "short_mission.toml", "n4.toml", "n6.toml"])
def test_to_toml_round_trips(tmp_path, name):
    scenario = load(EXAMPLES / name)
    again = load(write(tmp_path, scenario.to_toml()))
    assert again == scenario


def test_to_toml_fills_every_default_and_round_trips(tmp_path, debris_csv):
    scenario = load(write(tmp_path, FULL, "full.toml")).with_overrides(seed=3)
    text = scenario.to_toml()
    for key in ("n", "tmax_days", "deorbit_days", "operations_dv_mps", "min_transfer_days",
                "drift_altitude_km", "preopt_days", "dv_max_mps", "drift_inclination", "j2",
                "backend", "time_limit_s", "mip_gap", "threads", "verbose", "seed"):  # fmt: skip
        assert f"\n{key} = " in text
    assert f'path = "{debris_csv.resolve()}"' in text  # absolute
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    assert load(write(elsewhere, text)) == scenario



def test_to_toml_keeps_the_day_zero_a_run_took(tmp_path, debris_csv):
    """Found as a user: a run folder's scenario.toml said ``start`` was "not set (the
    latest epoch)", so running it again after the TLE file was refreshed gave another
    day 0; the start the run took is now written (one the scenario set stays as set)."""
    import dataclasses
    from datetime import datetime

    scenario = load(write(tmp_path, FULL, "full.toml"))
    assert scenario.catalog_start is None
    taken = datetime(2020, 5, 26, 8, 51, 28, 399680, tzinfo=UTC)
    again = load(write(tmp_path, scenario.to_toml(start=taken), "again.toml"))
    assert again.catalog_start == taken
    assert dataclasses.replace(again, catalog_start=None) == scenario
    chosen = scenario.with_overrides(catalog_start="2020-01-01T00:00:00Z")
    assert load(write(tmp_path, chosen.to_toml(start=taken), "set.toml")) == chosen


def test_to_toml_of_the_defaults(tmp_path):
    text = Scenario().to_toml()
    assert "\npath" not in text and "Table 5" in text and "n = 5" in text
    solver = text.split("[solver]")[1]
    assert "# not set" in solver and "time_limit_s" in solver  # said,
    assert "time_limit_s =" not in solver  # not written
    assert load(write(tmp_path, text)) == Scenario()


def test_to_dict():
    data = Scenario().with_overrides(time_limit_s=5).to_dict()
    assert data["catalog"] == {"path": None, "format": "csv"}
    assert data["mission"]["drift_altitude_km"] == [400.0, 1200.0]
    assert data["solver"]["time_limit_s"] == 5.0 and data["solver"]["seed"] is None


# ---------------------------------------------------------------------- start and selection
GTOC9 = SHARED_DATA / "gtoc9" / "debris_data.txt"
START_AND_SELECTION = """
[catalog]
path = "debris.csv"
start = 2020-06-01T12:00:00Z
[selection]
altitude_km = [700, 850.0]
inclination_deg = [98.0, 98.8]
max_eccentricity = 0.0002
ids = ["1*", "[3-9]"]
names = ["*"]
exclude_ids = ["8"]
"""


def test_start_and_selection_keys_are_read(tmp_path, debris_csv):
    scenario = load(write(tmp_path, START_AND_SELECTION))
    assert scenario.catalog_start == datetime(2020, 6, 1, 12, tzinfo=UTC)
    assert scenario.selection == Selection(
        altitude_km=(700.0, 850.0), inclination_deg=(98.0, 98.8), max_eccentricity=0.0002,
        ids=("1*", "[3-9]"), names=("*",), exclude_ids=("8",),
    )  # fmt: skip
    # Table 5 has no epochs: the RAANs are taken as they are, at the start given
    catalog = scenario.load_catalog()
    assert catalog.start == pd.Timestamp("2020-06-01T12:00:00Z")
    assert list(catalog.frame["raan_deg"]) == list(Catalog.paper_case().frame["raan_deg"])


@pytest.mark.parametrize(
    ("value", "hour"),
    [("2020-06-01T14:00:00+02:00", 12), ("'2020-06-01T12:00:00Z'", 12),
     ("'2020-06-01 12:00'", 12), ("2020-06-01T12:00:00", 12), ("2020-06-01", 0)],
)  # fmt: skip
def test_start_forms_give_a_utc_date(tmp_path, debris_csv, value, hour):
    """Offsets are converted, naive dates and times are UTC, a date is its midnight."""
    scenario = load(write(tmp_path, f'[catalog]\npath = "debris.csv"\nstart = {value}\n'))
    assert scenario.catalog_start == datetime(2020, 6, 1, hour, tzinfo=UTC)
    assert scenario.catalog_start.tzinfo == UTC


def test_start_and_selection_round_trip_through_to_toml(tmp_path, debris_csv):
    scenario = load(write(tmp_path, START_AND_SELECTION, "given.toml"))
    text = scenario.to_toml()
    assert "\nstart = 2020-06-01" in text and "\n[selection]\naltitude_km = [700.0, 850.0]" in text
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    again = load(write(elsewhere, text))
    assert again == scenario and again.selection == scenario.selection
    assert again.catalog_start == scenario.catalog_start
    defaults = Scenario().to_toml()  # nothing set: said in comments, read back as unset
    assert "# not set (no filter; max_eccentricity 0.05): altitude_km" in defaults
    assert load(write(tmp_path, defaults)).selection == Selection()


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_start_moves_the_raans_of_a_catalog_with_epochs(tmp_path):
    text = f'[catalog]\npath = "{GTOC9}"\nformat = "gtoc9"\n'
    latest = load(write(tmp_path, text)).load_catalog()
    scenario = load(write(tmp_path, text + "start = 2059-06-01T00:00:00Z\n"))  # epochs 2060
    catalog = scenario.load_catalog()
    assert catalog.start == pd.Timestamp("2059-06-01T00:00:00Z") != latest.start
    assert not np.allclose(catalog.frame["raan_deg"], latest.frame["raan_deg"])
    assert load(write(tmp_path, scenario.to_toml())).load_catalog().start == catalog.start


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_a_start_decades_from_the_epochs_is_refused(tmp_path):
    """GTOC9's epochs are in 2060: a start in 2000 would move each RAAN with J2 alone for
    60 years (issue 20); refused, naming the argument and the nearest epoch."""
    text = f'[catalog]\npath = "{GTOC9}"\nformat = "gtoc9"\nstart = 2000-01-01T00:00:00Z\n'
    with pytest.raises(CatalogError) as caught:
        load(write(tmp_path, text)).load_catalog()
    assert "argument 'start': 2000-01-01T00:00:00+00:00 is 21," in str(caught.value)
    assert "(60.0 years) from the nearest epoch of the catalog (2060-" in str(caught.value)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("[selection]\naltitude_km = [900, 600]\n",
         "selection.altitude_km must be [low, high] with low <= high, got [900.0, 600.0]"),
        ("[selection]\ninclination_deg = [99, 97]\n", "selection.inclination_deg must be [low"),
        ("[selection]\naltitude_km = [600]\n", "selection.altitude_km must be an array of 2"),
        ("[selection]\naltitude_km = ['600', 900]\n", "selection.altitude_km must be an array"),
        ("[selection]\nmax_eccentricity = -0.1\n", "selection.max_eccentricity must be >= 0"),
        ("[selection]\nmax_eccentricity = '0.1'\n", "selection.max_eccentricity must be a number"),
        ("[selection]\nmax_eccentricity = nan\n", "selection.max_eccentricity must be a number"),
        ("[selection]\nids = '43*'\n", "selection.ids must be an array of strings"),
        ("[selection]\nexclude_ids = ['  ']\n", "selection.exclude_ids must not hold an empty"),
        ("[selection]\naltitude = [600, 900]\n",
         "unknown key selection.altitude (did you mean altitude_km?)"),
        ("[selecton]\nids = ['1']\n", "unknown table [selecton] (did you mean selection?)"),
        ("ids = ['1']\n", "'ids' outside a table (did you mean selection.ids?)"),
        ('[catalog]\npath = "debris.csv"\nstart = "yesterday"\n',
         "catalog.start must be a date and time, a TOML datetime or an ISO-8601 string"),
        ('[catalog]\npath = "debris.csv"\nstart = 12:00:00\n', "catalog.start must be a date"),
        ('[catalog]\npath = "debris.csv"\nstart = 2020\n', "got 2020 (integer)"),
        ("[catalog]\nstart = 2020-06-01T00:00:00Z\n", "catalog.start needs catalog.path"),
    ],
)  # fmt: skip
def test_bad_start_or_selection_names_the_dotted_key(tmp_path, debris_csv, text, expected):
    assert expected in load_error(tmp_path, text)


def test_selection_applies_every_filter_and_reports_unmatched_patterns():
    kept, report = Selection(altitude_km=(700, 850), exclude_ids=("8",)).apply(Catalog.paper_case())
    assert kept.ids == ("3", "4", "5", "6", "7", "9")
    assert set(report["id"]) == {"1", "2", "8", "10", "11"}
    kept, _ = Selection(max_eccentricity=0.0001, ids=("1*",)).apply(Catalog.paper_case())
    assert kept.ids == ("1", "10")  # 11: e = 0.0003
    with pytest.raises(ValueError, match="'Z' match no debris"):
        Selection(ids=("Z",)).apply(Catalog.paper_case())


def test_start_and_selection_overrides(tmp_path, debris_csv):
    scenario = Scenario().with_overrides(catalog=debris_csv, start="2020-06-01", ids=["2", "3"])
    assert scenario.catalog_start == datetime(2020, 6, 1, tzinfo=UTC)
    assert scenario.selection == Selection(ids=("2", "3"))
    changed = scenario.with_overrides(**{"selection.altitude_km": [600, 700]}, ids=None)
    assert changed.selection == Selection(altitude_km=(600.0, 700.0), ids=("2", "3"))
    with pytest.raises(ScenarioError, match=r"^overrides: selection\.altitude_km must be"):
        scenario.with_overrides(altitude_km=(700, 600))


def test_max_eccentricity_may_be_infinite(tmp_path):
    """``inf`` keeps every eccentricity, as :func:`sdc_cvx.inputs.selection.select` allows."""
    scenario = load(write(tmp_path, "[selection]\nmax_eccentricity = inf\n"))
    assert scenario.selection.max_eccentricity == float("inf")
    assert "\nmax_eccentricity = inf\n" in scenario.to_toml()
    assert load(write(tmp_path, scenario.to_toml())) == scenario


def test_to_dict_has_start_and_selection_only_when_set(debris_csv):
    data = Scenario().to_dict()
    assert "start" not in data["catalog"] and "selection" not in data  # a sweep's sha unchanged
    data = Scenario().with_overrides(catalog=debris_csv, start="2020-06-01T12:00:00+02:00",
                                     max_eccentricity=0.0, exclude_ids=["8"]).to_dict()  # fmt: skip
    assert data["catalog"]["start"] == "2020-06-01T10:00:00+00:00"
    assert data["selection"] == {"max_eccentricity": 0.0, "exclude_ids": ["8"]}
    json.dumps(data)  # JSON-ready


def test_selection_types_and_catalog_strict_round_trip(tmp_path, debris_csv):
    text = (f'[catalog]\npath = "{debris_csv}"\nstrict = true\n'
            '[selection]\ntypes = ["rocket-body", "debris"]\nnames = ["SL-8 R/B*"]\n')  # fmt: skip
    scenario = load(write(tmp_path, text))
    assert scenario.catalog_strict is True
    assert scenario.selection.types == ("rocket-body", "debris")
    again = load(write(tmp_path, scenario.to_toml(), "again.toml"))
    assert again == scenario and again.catalog_strict
    assert "strict" not in Scenario().to_dict()["catalog"]  # unset: the sweep's sha as before


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ('[selection]\ntypes = ["rocket"]\n', "selection.types must hold rocket-body, debris, "
         "payload, got ['rocket']"),
        ("[catalog]\nstrict = 1\n", "catalog.strict must be a boolean"),
        ("[catalog]\nstrict = true\n", "catalog.strict needs catalog.path"),
    ],
)  # fmt: skip
def test_bad_types_and_strict_name_the_key(tmp_path, text, expected):
    with pytest.raises(ScenarioError) as caught:
        load(write(tmp_path, text))
    assert expected in str(caught.value)


def test_a_scenario_whose_catalog_moved_loads_with_the_catalog_where_it_is(tmp_path,
                                                                           monkeypatch):
    """A run folder's scenario.toml names its catalog by an absolute path: once the
    project moved, neither ``run SCENARIO --catalog FILE`` nor ``fly --catalog`` could
    load it (the file's own path was checked first).  ``catalog_path`` replaces it
    before the check, relative to the current folder."""
    scenario = tmp_path / "scenario.toml"
    scenario.write_text('[catalog]\npath = "/nowhere/debris.csv"\n\n[mission]\nn = 3\n',
                        encoding="utf-8")  # fmt: skip
    with pytest.raises(ScenarioError, match="file not found"):
        Scenario.load(scenario)
    (tmp_path / "here.csv").write_text(PAPER_CSV.read_text())
    monkeypatch.chdir(tmp_path)
    moved = Scenario.load(scenario, catalog_path="here.csv")
    assert moved.catalog_path == tmp_path / "here.csv" and moved.mission.n == 3
    assert len(moved.load_catalog()) == len(Catalog.from_csv(PAPER_CSV))
