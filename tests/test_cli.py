"""Command line: run, edges, catalog, solvers; success and failure paths, files written."""

import importlib.metadata
import json
import os
import signal
import stat
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

import cvxpy as cp
import pandas as pd
import pytest
from click.testing import CliRunner

from sdc_cvx import Catalog, Mission, preoptimize
from sdc_cvx.cli import main
from sdc_cvx.inputs.formats import read_gtoc9
from sdc_cvx.study.scenario import Selection, load
from tests.conftest import EXAMPLES, PAPER_CSV, REPO, SHARED_DATA, as_terminal_job

GTOC9 = SHARED_DATA / "gtoc9" / "debris_data.txt"


@pytest.mark.slow
def test_run_paper_case_writes_the_run_folder(tmp_path):
    result = CliRunner().invoke(main, ["run", "--out", str(tmp_path / "out"), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "5 -> 8 -> 2 -> 6 -> 10" in result.output and ", optimal (gap" in result.output
    data = json.loads((tmp_path / "out" / "solution.json").read_text())
    assert data["path"] == ["5", "8", "2", "6", "10"] and data["total_dv_mps"] <= 500.7
    # certified by default: a proven bound within 0.1 % of the plan, below Table 8's 500.7
    assert data["method"] == "certified" and data["certified"] and data["status"] == "optimal"
    assert data["total_dv_mps"] - data["lower_bound_mps"] <= 1e-3 * data["total_dv_mps"]
    # the status says how the relaxations were solved: here by labels, no MILP at all
    assert data["model_size"]["milp_solves"] == 0
    assert "status    optimal: certified search, every relaxation solved by labels" in result.output
    assert data["start"] is None  # Table 5 has no epochs
    legs = pd.read_csv(tmp_path / "out" / "legs.csv")
    assert len(legs) == 4 and abs(legs["dv_mps"].sum() - data["total_dv_mps"]) < 1e-6
    # the relaxation rounds, or the search's bound and plan at each change when it needed none
    steps = len(data["iterations"]) or len(data["search_trace"])
    assert steps > 0 and len(pd.read_csv(tmp_path / "out" / "iterations.csv")) == steps
    for figure in ("orbits", "raan", "cost", "iterations"):  # paper Figs. 17-19, Table 7
        png = (tmp_path / "out" / f"{figure}.png").read_bytes()
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 20_000
    assert not list((tmp_path / "out").glob(".*.tmp"))  # no temp files left behind


@pytest.mark.slow
def test_run_shows_progress_per_iteration_when_forced(tmp_path):
    result = CliRunner().invoke(main, ["run", "--out", str(tmp_path), "--n", "3", "--progress"])
    assert result.exit_code == 0, result.output
    steps = [line for line in result.stderr.splitlines() if line.startswith("  ")]
    assert any(line.startswith("  cost tables done") for line in steps)
    assert any(line.startswith("  plan ") and "m/s" in line for line in steps)
    assert not any(line in result.stdout for line in steps)
    log = (tmp_path / "run.log").read_text()
    assert all(line in log for line in steps)


@pytest.mark.slow
def test_run_shows_no_progress_when_stderr_is_not_a_terminal(tmp_path):
    result = CliRunner().invoke(main, ["run", "--out", str(tmp_path), "--n", "3"])
    assert result.exit_code == 0, result.output
    assert "it  0" not in result.output and "Choosing 3 of 11 debris" in result.stderr
    assert "path      " in result.stdout


def test_run_infeasible_mission_exit_code_and_reason(tmp_path):
    result = CliRunner().invoke(main, ["run", "--tmax-days", "20", "--preopt-days", "5",
                                       "--out", str(tmp_path)])  # fmt: skip
    assert result.exit_code == 3
    assert "infeasible mission: proven" in result.output and "Relax one of" in result.output
    assert not (tmp_path / "solution.json").exists()


def test_run_bad_catalog_names_the_file_row_and_field(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7100,2.5,98,20\n")
    result = CliRunner().invoke(main, ["run", "--catalog", str(bad)])
    assert result.exit_code == 2
    assert "bad.csv" in result.output and "row 2" in result.output and "'e'" in result.output


def test_run_bad_mission_parameter(tmp_path):
    result = CliRunner().invoke(main, ["run", "--n", "1", "--out", str(tmp_path)])
    assert result.exit_code == 2 and "n must be >= 2" in result.output


def test_edges_prints_csv():
    result = CliRunner().invoke(main, ["edges"])
    assert result.exit_code == 0
    lines = result.stdout.strip().splitlines()
    kept = preoptimize(Catalog.paper_case(), Mission()).counts()["kept"]
    assert lines[0].startswith("from_id,to_id") and len(lines) == 1 + kept


# ---------------------------------------------------------------------- scenario files
def run_in(folder: Path, *args):
    """``run`` invoked from ``folder`` (where a run folder would be created)."""
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(folder)
        return CliRunner().invoke(main, ["run", *map(str, args)])


def assert_nothing_written(folder: Path, inputs=("scenario.toml",)):
    assert sorted(p.name for p in folder.iterdir()) == sorted(inputs)


def assert_one_line_error(result, *parts):
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    for part in parts:
        assert part in lines[0]


@pytest.mark.parametrize(
    ("text", "parts"),
    [
        ("[mission]\nn = 5\ntmax_days = = 3\n", ["scenario.toml", "invalid TOML", "line 3"]),
        ("[mission]\ntmax = 3\n", ["scenario.toml", "unknown key mission.tmax", "tmax_days"]),
        ("[mission]\nn = true\n", ["mission.n must be an integer", "true (boolean)"]),
        ("[solver]\nmip_gap = 2.0\n", ["solver.mip_gap must be in [0, 1)"]),
        ('[catalog]\npath = "gone.csv"\n', ["catalog.path: file not found", "gone.csv"]),
        ('[catalog]\npath = "scenario.toml"\nformat = "xls"\n', ["catalog.format must be one of"]),
    ],
)
def test_run_invalid_scenario_exits_2_and_writes_nothing(tmp_path, text, parts):
    (tmp_path / "scenario.toml").write_text(text)
    result = run_in(tmp_path, "scenario.toml")
    assert_one_line_error(result, *parts)
    assert_nothing_written(tmp_path)
    result = run_in(tmp_path, "scenario.toml", "--out", tmp_path / "out")
    assert result.exit_code == 2 and not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("args", "parts"),
    [
        (["--n", "1"], ["command line: mission.n must be >= 2"]),
        (["--n", "12"], ["mission.n", "exceeds the 11 candidate debris"]),
        (["--mip-gap", "-1"], ["solver.mip_gap"]),
        (["--backend", "CLARABEL"], ["solver.backend must be a MILP backend"]),
        (["--catalog", "gone.csv"], ["catalog.path: file not found", "gone.csv"]),
        (["--catalog", "scenario.toml", "--format", "xls"], ["catalog.format must be one of"]),
        (["missing.toml"], ["missing.toml: file not found"]),
        (["--start", "2020-06-01"], ["command line: catalog.start needs catalog.path"]),
        (["--catalog", "scenario.toml", "--format", "csv", "--start", "soon"],
         ["catalog.start must be a date and time", "'soon'"]),
        (["--altitude-km", "900", "600"],
         ["command line: selection.altitude_km must be [low, high] with low <= high"]),
        (["--max-eccentricity", "-1"], ["selection.max_eccentricity must be >= 0"]),
    ],
)  # fmt: skip
def test_run_invalid_flags_exit_2_and_write_nothing(tmp_path, args, parts):
    (tmp_path / "scenario.toml").write_text("")
    result = run_in(tmp_path, *args)
    assert_one_line_error(result, *parts)
    assert_nothing_written(tmp_path)


def test_run_backend_not_installed_exits_2(tmp_path):
    missing = next((b for b in ("GUROBI", "CPLEX", "XPRESS", "COPT")
                    if b not in cp.installed_solvers()), None)  # fmt: skip
    if missing is None:
        pytest.skip("every commercial backend is installed")
    result = run_in(tmp_path, "--backend", missing.lower())
    assert_one_line_error(result, f"'{missing}' is not installed", "HIGHS")
    assert_nothing_written(tmp_path, ())


def test_run_bad_catalog_from_scenario_writes_nothing(tmp_path):
    (tmp_path / "bad.csv").write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,2.5,98,10\n")
    (tmp_path / "scenario.toml").write_text('[catalog]\npath = "bad.csv"\n')
    result = run_in(tmp_path, "scenario.toml")
    assert result.exit_code == 2 and "bad.csv" in result.stderr and "'e'" in result.stderr
    assert_nothing_written(tmp_path, ("scenario.toml", "bad.csv"))


def test_run_infeasible_scenario_exits_3_and_writes_nothing(tmp_path):
    (tmp_path / "scenario.toml").write_text("[mission]\ntmax_days = 20.0\npreopt_days = 5.0\n")
    result = run_in(tmp_path, "scenario.toml")
    assert result.exit_code == 3
    assert result.stderr.splitlines()[-1].startswith("error: infeasible mission: ")
    assert_nothing_written(tmp_path)


@pytest.mark.slow
def test_run_scenario_with_flag_override(tmp_path):
    (tmp_path / "scenario.toml").write_text(
        "[mission]\nn = 5\npreopt_days = 61.0\n[solver]\ntime_limit_s = 60.0\n"
    )
    out = tmp_path / "out"
    result = run_in(tmp_path, "scenario.toml", "--n", "4", "--out", out, "--quiet", "--svg")
    assert result.exit_code == 0, result.output
    used = load(out / "scenario.toml")
    assert used.mission.n == 4 and used.solver.time_limit_s == 60.0 and used.catalog_path is None
    assert "\nn = 4\n" in (out / "scenario.toml").read_text()
    data = json.loads((out / "solution.json").read_text())
    assert len(data["path"]) == 4 and data["mission"]["n"] == 4
    assert not list(out.glob(".*.tmp"))


@pytest.mark.slow
def test_run_json_prints_only_the_solution_on_stdout(tmp_path):
    result = CliRunner().invoke(main, ["run", "--n", "3", "--json", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)  # nothing else on stdout
    assert len(data["path"]) == 3
    assert data == json.loads((tmp_path / "solution.json").read_text())
    assert "total dV" in result.stderr


@pytest.mark.slow
def test_run_example_scenario_writes_it_to_the_run_folder(tmp_path):
    example = EXAMPLES / "n4.toml"  # the paper case with n = 4: certified in seconds
    result = CliRunner().invoke(main, ["run", str(example), "--out", str(tmp_path), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "5 -> 8 -> 10 -> 6" in result.stdout and ", optimal (gap" in result.stdout
    assert load(tmp_path / "scenario.toml") == load(example)


# ---------------------------------------------------------------------- catalog
def test_catalog_prints_the_paper_table():
    result = CliRunner().invoke(main, ["catalog"])
    assert result.exit_code == 0, result.output
    lines = result.stdout.strip().splitlines()
    assert len(lines) == 12
    for title in ("id", "altitude [km]", "inclination [deg]", "RAAN [deg]", "J2 rate [deg/day]"):
        assert title in lines[0]
    assert lines[1].split()[:5] == ["1", "652.4", "98.0000", "221.1000", "0.986206"]
    assert "11 debris from paper Table 5" in result.stderr


def test_catalog_of_a_file(tmp_path):
    (tmp_path / "debris.csv").write_text(
        "id,a_km,e,inc_deg,raan_deg\nA,7000,0.001,98,10\nB,7100,0.002,97,20\n"
    )
    result = CliRunner().invoke(main, ["catalog", str(tmp_path / "debris.csv")])
    assert result.exit_code == 0, result.output
    assert [line.split()[0] for line in result.stdout.splitlines()[1:]] == ["A", "B"]


def test_catalog_bad_file_exits_2(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7100,2.5,98,20\n1,x,0,98,1\n")
    result = CliRunner().invoke(main, ["catalog", str(bad)])
    assert result.exit_code == 2 and result.stdout == ""
    assert result.stderr.startswith("error: ") and "bad.csv" in result.stderr
    assert "row 2" in result.stderr and "duplicate id" in result.stderr  # every problem
    result = CliRunner().invoke(main, ["catalog", str(tmp_path / "gone.csv")])
    assert_one_line_error(result, "file not found", "gone.csv")
    result = CliRunner().invoke(main, ["catalog", str(bad), "--format", "gtoc9"])
    assert result.exit_code == 2 and "looks like a 'csv' catalog, not 'gtoc9'" in result.stderr


# ---------------------------------------------------------------------- solvers
def test_solvers_lists_highs_with_its_version():
    result = CliRunner().invoke(main, ["solvers"])
    assert result.exit_code == 0, result.output
    rows = {line.split()[0]: line.split() for line in result.stdout.splitlines()[1:-1]}
    assert set(rows) == {"HIGHS", "SCIP", "CBC", "GLPK_MI", "SCIPY", "GUROBI", "CPLEX",
                         "XPRESS", "MOSEK", "COPT"}  # fmt: skip
    assert rows["HIGHS"] == ["HIGHS", "*", "yes", "highspy", importlib.metadata.version("highspy")]
    assert "default" in result.stdout.splitlines()[-1]


# ---------------------------------------------------------------------- edges
def test_edges_with_a_scenario_and_override(tmp_path):
    (tmp_path / "scenario.toml").write_text("[mission]\npreopt_days = 30.0\ndv_max_mps = 900.0\n")
    result = CliRunner().invoke(main, ["edges", str(tmp_path / "scenario.toml")])
    assert result.exit_code == 0, result.output
    kept = preoptimize(Catalog.paper_case(), Mission(preopt_days=30.0, dv_max_mps=900.0))
    assert len(result.stdout.strip().splitlines()) == 1 + kept.counts()["kept"]
    args = ["edges", str(tmp_path / "scenario.toml"), "--dv-max", "300"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    fewer = preoptimize(Catalog.paper_case(), Mission(preopt_days=30.0, dv_max_mps=300.0))
    assert len(result.stdout.strip().splitlines()) == 1 + fewer.counts()["kept"]
    result = CliRunner().invoke(main, ["edges", str(tmp_path / "scenario.toml"), "--dv-max", "-1"])
    assert_one_line_error(result, "mission.dv_max_mps must be > 0")


@pytest.mark.slow
def test_sweep_command_writes_one_row_per_scenario(tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(
        '[base.mission]\nn = 3\n[grid]\n"mission.tmax_days" = [300.0, 365.25]\n'
        '[[cases]]\n"mission.tmax_days" = 5.0\n'
    )
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["sweep", str(study), "--out", str(out), "--workers", "1"])
    assert result.exit_code == 0, result.output
    assert "2 of 3 scenarios solved" in result.output
    results = pd.read_csv(out / "results.csv")
    assert sorted(results["status"]) == ["infeasible", "optimal", "optimal"]
    solved = results[results["status"] == "optimal"]
    assert (solved["gap_rel"] <= 1e-3).all() and solved["certified"].all()


@pytest.mark.slow
def test_a_sweep_where_nothing_is_solved_is_not_a_success(tmp_path):
    """Every scenario infeasible: exit 3 and the statuses counted (not exit 0); its float
    parameters without noise in results.csv (0.1 + 0.2, not 0.30000000000000004)."""
    study = tmp_path / "study.toml"
    study.write_text('[base.mission]\nn = 3\n[grid]\n"mission.tmax_days" = [5.0, 5.5]\n'
                     '"mission.deorbit_days" = [0.30000000000000004]\n')  # fmt: skip
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", "sweep", str(study), "--out",
                           str(out), "--workers", "1"], capture_output=True, text=True,
                          timeout=600,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 3, done.stderr
    assert "no scenario was solved (2 infeasible)" in done.stderr
    text = (out / "results.csv").read_text()
    assert "0.30000000000000004" not in text and ",0.3," in text


def test_sweep_command_rejects_a_bad_study_before_solving(tmp_path):
    study = tmp_path / "study.toml"
    study.write_text('[grid]\n"mission.tmax" = [300.0]\n')
    result = CliRunner().invoke(main, ["sweep", str(study), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2 and "mission.tmax" in result.output
    assert not (tmp_path / "out" / "results.csv").exists()


@pytest.mark.slow
def test_run_falls_back_from_an_unavailable_backend(tmp_path):
    result = CliRunner().invoke(
        main,
        [
            "run",
            "--method",
            "paper",  # the certified search solves its relaxations by labels here
            "--backend",
            "MOSEK",
            "--fallback",
            "HIGHS",
            "--n",
            "3",
            "--quiet",
            "--out",
            str(tmp_path),
        ],
    )
    assert result.exit_code == 0, result.output
    data = json.loads((tmp_path / "solution.json").read_text())
    assert data["backend"] == "HIGHS"
    assert any("MOSEK failed" in note and "used HIGHS" in note for note in data["notes"])


# ---------------------------------------------------------------------- start and selection
@pytest.mark.slow
def test_run_selection_is_written_to_the_run_folder_and_reproduces_the_run(tmp_path):
    (tmp_path / "scenario.toml").write_text('[mission]\nn = 3\n[selection]\nexclude_ids = ["7"]\n')
    out = tmp_path / "out"
    result = run_in(tmp_path, "scenario.toml", "--altitude-km", "670", "880", "--out", out)
    assert result.exit_code == 0, result.output
    assert "kept 8 of 11 candidates (dropped: 1 excluded, 2 altitude)" in result.stderr
    used = load(out / "scenario.toml")  # the file's filter and the flag's
    assert used.selection == Selection(altitude_km=(670.0, 880.0), exclude_ids=("7",))
    kept, _ = used.selection.apply(Catalog.paper_case())
    first = json.loads((out / "solution.json").read_text())
    assert set(first["path"]) <= set(kept.ids) == {"2", "3", "4", "5", "6", "8", "9", "10"}
    result = run_in(tmp_path, out / "scenario.toml", "--out", tmp_path / "again")
    assert result.exit_code == 0, result.output
    assert "kept 8 of 11 candidates (dropped: 1 excluded, 2 altitude)" in result.stderr
    again = json.loads((tmp_path / "again" / "solution.json").read_text())
    assert again["path"] == first["path"] and again["total_dv_mps"] == first["total_dv_mps"]


@pytest.mark.slow
def test_run_flag_overrides_the_scenario_selection(tmp_path):
    (tmp_path / "scenario.toml").write_text("[selection]\naltitude_km = [600, 900]\n")
    result = run_in(tmp_path, "scenario.toml", "--altitude-km", "670", "880", "--ids", "[2-8]",
                    "--n", "3", "--out", tmp_path / "out", "--quiet")  # fmt: skip
    assert result.exit_code == 0, result.output
    used = load(tmp_path / "out" / "scenario.toml")
    assert used.selection == Selection(altitude_km=(670.0, 880.0), ids=("[2-8]",))
    path = json.loads((tmp_path / "out" / "solution.json").read_text())["path"]
    assert set(path) <= set("2345678")


def epoch_catalog(folder: Path) -> Path:
    """Table 5 with epochs: every row at 2020-05-24 but the first, at 2020-05-25 (the latest)."""
    header, *rows = PAPER_CSV.read_text().splitlines()
    epochs = ["2020-05-25"] + ["2020-05-24"] * (len(rows) - 1)
    lines = [f"{header},epoch"] + [f"{row},{day}" for row, day in zip(rows, epochs, strict=True)]
    (folder / "epochs.csv").write_text("\n".join(lines) + "\n")
    return folder / "epochs.csv"


@pytest.mark.slow
@pytest.mark.parametrize(
    ("file_start", "flags", "expected"),
    [
        (None, [], "2020-05-25T00:00:00+00:00"),  # the latest epoch
        ("2020-06-01T06:00:00Z", [], "2020-06-01T06:00:00+00:00"),
        ("2020-06-01T06:00:00Z", ["--start", "2020-07-01"], "2020-07-01T00:00:00+00:00"),
    ],
)
def test_run_records_the_start_and_the_flag_overrides_it(tmp_path, file_start, flags, expected):
    epoch_catalog(tmp_path)
    start = "" if file_start is None else f"start = {file_start}\n"
    (tmp_path / "scenario.toml").write_text(f'[catalog]\npath = "epochs.csv"\n{start}')
    out = tmp_path / "out"
    result = run_in(tmp_path, "scenario.toml", "--n", "3", "--out", out, "--quiet", *flags)
    assert result.exit_code == 0, result.output
    assert json.loads((out / "solution.json").read_text())["start"] == expected
    assert f"start     {expected} (the catalog's RAANs are at this date)" in result.stdout
    # the day 0 taken is kept, also where the scenario left it to the latest epoch
    assert load(out / "scenario.toml").catalog_start == datetime.fromisoformat(expected)


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_catalog_start_moves_the_raans_of_the_gtoc9_file():
    args = ["catalog", str(GTOC9), "--format", "gtoc9", "--ids", "0"]
    result = CliRunner().invoke(main, [*args, "--start", "2059-06-01"])  # the epochs: 2060
    assert result.exit_code == 0, result.output
    assert "RAANs at 2059-06-01T00:00:00+00:00" in result.stderr
    raan = read_gtoc9(GTOC9, start=datetime(2059, 6, 1, tzinfo=UTC)).frame["raan_deg"][0]
    latest = read_gtoc9(GTOC9).frame["raan_deg"][0]
    assert abs(raan - latest) > 1.0
    row = result.stdout.splitlines()[1].split()
    assert row[0] == "0" and row[3] == f"{raan:.4f}"


@pytest.mark.requires_shared_data("gtoc9/debris_data.txt")
def test_catalog_start_decades_from_the_epochs_exits_2():
    """Issue 20: a --start 60 years before the GTOC9 epochs (2060) is refused."""
    args = ["catalog", str(GTOC9), "--format", "gtoc9", "--start", "2000-01-01"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, result.output
    assert "argument 'start': 2000-01-01T00:00:00+00:00 is 21,919 days (60.0 years)" in (
        result.stderr
    )
    assert "Traceback" not in result.output


def test_progress_heartbeat_names_the_phase_while_silent(capsys):
    """A long silent phase (seeding, a MILP) still gets a line every few seconds."""
    from sdc_cvx.cli import RunProgress

    with RunProgress(show=True, heartbeat_s=0.1) as steps:
        steps.set_phase("seeding: re-optimising cheap paths")
        time.sleep(0.6)
    beats = [line for line in capsys.readouterr().err.splitlines() if " s: seeding" in line]
    assert len(beats) >= 2
    assert any(" s: seeding" in line for line in steps.log_text().splitlines())


@pytest.mark.slow
def test_run_progress_and_run_log_say_which_steps_were_rejected(options_by_the_paper):
    # the paper's driver is the one that rejects steps
    result, out, _ = options_by_the_paper
    rejected = [line for line in result.stderr.splitlines() if "step rejected:" in line]
    assert rejected and all("held plan worse" in line for line in rejected)
    log = (out / "run.log").read_text()
    assert log.count("step rejected:") == len(rejected)
    assert "Choosing 5 of 11 debris from paper Table 5" in log and "total dV  2985.8" in log
    assert "status    converged: path from the seeding" in result.stdout


def cli_process(*args: str, cwd=None, timeout: float = 300) -> subprocess.CompletedProcess:
    """``python -m sdc_cvx ARGS`` in a real process, on this checkout (PYTHONPATH)."""
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    return subprocess.run([sys.executable, "-m", "sdc_cvx", *args], cwd=cwd or REPO, env=env,
                          capture_output=True, text=True, timeout=timeout)  # fmt: skip


@pytest.mark.slow
def test_run_json_prints_json_only_through_a_real_process(tmp_path):
    result = cli_process("run", "--n", "3", "--json", "--out", str(tmp_path / "out"))
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)  # no backend banner or progress line around it
    assert data["path"] and data["total_dv_mps"] > 0
    assert data == json.loads((tmp_path / "out" / "solution.json").read_text())


@pytest.mark.slow
def test_ctrl_c_during_run_keeps_the_best_plan_with_its_gap(tmp_path):
    import signal

    out, live = tmp_path / "out", tmp_path / "out.log"
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    run = subprocess.Popen([sys.executable, "-m", "sdc_cvx", "run", "--n", "6", "--quiet",
                            "--out", str(out)], cwd=REPO, env=env, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True,
                           preexec_fn=as_terminal_job)  # fmt: skip
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and run.poll() is None:
        if live.exists() and " plan " in live.read_text():  # a plan is held
            break
        time.sleep(0.05)
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=300)
    assert run.returncode == 0, stderr
    data = json.loads((out / "solution.json").read_text())
    assert data["status"] in ("feasible", "optimal") and data["lower_bound_mps"] is not None
    if data["status"] == "feasible":  # stopped before the search ended: said so, with its gap
        assert "interrupted: the best plan so far" in data["notes"]
        assert "feasible, gap " in stdout and "interrupted" in stdout
    assert not live.exists() and not list(tmp_path.glob(".*partial"))


@pytest.mark.slow
def test_a_full_disk_is_exit_4_and_leaves_nothing_beside_the_folder(tmp_path, monkeypatch):
    import errno

    from sdc_cvx.report import run_folder

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    csv = tmp_path / "d.csv"
    csv.write_text("id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7050,0.001,98,40\n")
    monkeypatch.setattr(run_folder, "_swap_in", full)
    out = tmp_path / "work" / "out"
    result = CliRunner().invoke(main, ["run", "--catalog", str(csv), "--n", "2", "--quiet",
                                       "--out", str(out)])  # fmt: skip
    assert result.exit_code == 4, result.output
    assert "cannot write the run folder" in result.stderr and "No space left" in result.stderr
    assert "invalid input" not in result.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.csv"]  # no out, out.log, stage


def test_the_heartbeat_reaches_the_live_log_when_stderr_is_quiet(tmp_path, capsys):
    """run.log gets the heartbeat too, not only a terminal (issue 20, item 9)."""
    from sdc_cvx.cli import RunProgress
    from sdc_cvx.report.run_folder import open_live_log

    stream = open_live_log(tmp_path / "out")
    with RunProgress(show=False, heartbeat_s=0.1, live_log=tmp_path / "out.log",
                     stream=stream) as steps:  # fmt: skip
        steps.search_step("  cost tables: 40% done (92352 of 230880 edges, 10 s)")
        time.sleep(0.6)
    steps.discard_live_log()
    beats = [line for line in steps.log_text().splitlines() if " s: certified search" in line]
    assert beats and all("cost tables: 40% done" in line for line in beats)
    assert capsys.readouterr().err == ""  # quiet: nothing on the terminal


def test_a_live_log_that_cannot_be_written_does_not_stop_the_run(tmp_path):
    from sdc_cvx.cli import RunProgress

    class Full:
        closed = False

        def write(self, text):
            raise OSError(28, "No space left on device")

        def close(self):
            pass

    with RunProgress(show=False, live_log=tmp_path / "x.log", stream=Full()) as steps:
        steps.say("first")
        steps.say("second")
    assert "No space left on device" in steps.log_failed
    assert [line.split(" ", 1)[1] for line in steps.lines] == ["first", "second"]


@pytest.mark.parametrize("command", [["run", "--n", "2"],
                                     ["campaign", str(EXAMPLES / "campaign_gtoc9.toml")]])
def test_a_named_pipe_beside_out_is_refused_not_read(tmp_path, command):
    """``r.log`` a named pipe: reading it to see whose it is blocked for ever (issue 28,
    2.3); it is refused at once, and left as it was."""
    pipe = tmp_path / "r.log"
    os.mkfifo(pipe)
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", *command, "--quiet", "--out", "r"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "r.log exists and is not a regular file" in done.stderr
    assert stat.S_ISFIFO(pipe.stat().st_mode) and not (tmp_path / "r").exists()


def interrupted_script(script: str, folder) -> subprocess.CompletedProcess:
    """``script`` (which sends itself a Ctrl-C) in a real process, as a terminal's job."""
    return subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          cwd=folder, timeout=300, preexec_fn=as_terminal_job,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip


SIGINT_DURING_EDGES = """
import os, signal, sys, time
import sdc_cvx.network.edges as edges
real = edges.preoptimize
def interrupted(*args, **kwargs):  # Ctrl-C arrives while the edge table is built
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(5)
    return real(*args, **kwargs)
edges.preoptimize = interrupted
from sdc_cvx.cli import main
main(["run", "--n", "3", "--out", "r", "--quiet"])
"""


@pytest.mark.slow
def test_ctrl_c_while_the_edge_table_is_built_keeps_the_answer(tmp_path):
    """The search is over and its answer known: a Ctrl-C then (issue 28, 1.3) writes the
    run folder without edges.csv, exit 0, instead of 'Aborted!' and nothing."""
    done = interrupted_script(SIGINT_DURING_EDGES, tmp_path)
    assert done.returncode == 0, done.stderr
    data = json.loads((tmp_path / "r" / "solution.json").read_text())
    assert data["status"] == "optimal"
    assert not (tmp_path / "r" / "edges.csv").exists()
    assert "without edges.csv" in (tmp_path / "r" / "run.log").read_text()
    assert not (tmp_path / "r.log").exists()


SIGINT_DURING_WRITING = """
import os, signal, sys, time
import sdc_cvx.report.run_folder as folder
real = folder.write_run
def interrupted(*args, **kwargs):  # Ctrl-C arrives while the run folder is written
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(0.5)
    return real(*args, **kwargs)
folder.write_run = interrupted
from sdc_cvx.cli import main
main(["run", "--n", "3", "--out", "r"])
"""


@pytest.mark.slow
def test_ctrl_c_while_the_run_folder_is_written_keeps_the_answer(tmp_path):
    """Issue 28, 1.3: a Ctrl-C while the figures are written lost the optimal answer
    ('interrupted while writing: nothing written', exit 130); the folder is finished."""
    done = interrupted_script(SIGINT_DURING_WRITING, tmp_path)
    assert done.returncode == 0, done.stderr
    assert "interrupted: finishing the run folder first" in done.stderr
    assert json.loads((tmp_path / "r" / "solution.json").read_text())["status"] == "optimal"
    assert (tmp_path / "r" / "orbits.png").is_file() and not (tmp_path / "r.log").exists()


@pytest.mark.parametrize("command", [["campaign", str(EXAMPLES / "campaign_gtoc9.toml")],
                                     ["sweep", str(EXAMPLES / "study_tmax_n.toml")]])
def test_a_bad_scheduler_address_is_refused_before_any_work(tmp_path, command):
    """Issue 28, 2.3: a traceback from distributed (campaign), 'cannot write the sweep
    folder' and a half-made folder (sweep); now one line, exit 2, nothing written."""
    pytest.importorskip("distributed")
    done = subprocess.run([sys.executable, "-m", "sdc_cvx", *command, "--scheduler",
                           "not an address", "--out", "out"], capture_output=True, text=True,
                          cwd=tmp_path, timeout=120,
                          env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    assert done.returncode == 2, done.stderr
    assert "--scheduler: cannot use the Dask scheduler 'not an address'" in done.stderr
    assert "Traceback" not in done.stderr and list(tmp_path.iterdir()) == []


@pytest.mark.slow
def test_ctrl_c_while_the_cost_tables_are_built_stops_at_once(tmp_path):
    """Issue 28, 2.2: the first Ctrl-C during the cost tables took 91 s to act (the search
    asked only between its later steps); the tables now ask at every chunk."""
    from sdc_cvx.inputs.synthetic import sso_catalog

    csv = tmp_path / "d.csv"
    sso_catalog(400, seed=2).frame[["id", "a_km", "e", "inc_deg", "raan_deg"]].to_csv(
        csv, index=False)  # fmt: skip
    run = subprocess.Popen([sys.executable, "-m", "sdc_cvx", "run", "--catalog", str(csv),
                            "--n", "3", "--out", "r"], cwd=tmp_path, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True, preexec_fn=as_terminal_job,
                           env={"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin"})  # fmt: skip
    live = tmp_path / "r.log"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and run.poll() is None:
        if live.exists() and "leg costs of every pair" in live.read_text():
            break
        time.sleep(0.02)
    time.sleep(0.5)  # inside the tables (about 160,000 edges: several seconds)
    if run.poll() is not None:  # the whole run beat the signal: nothing to check
        pytest.skip("the run ended before the Ctrl-C")
    asked = time.monotonic()
    run.send_signal(signal.SIGINT)
    stdout, stderr = run.communicate(timeout=300)
    assert run.returncode == 130, stderr  # (it once went on to the end: exit 0, 20 s later)
    assert time.monotonic() - asked < 10.0
    assert "interrupted before any plan: nothing written" in stderr
    assert not (tmp_path / "r").exists()


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs Linux's /proc")
def test_a_folder_whose_file_system_refuses_writes_is_refused_before_solving(tmp_path):
    """Issue 28, 2.4: as root, /sys and /proc pass the permission check (os.access) but
    refuse every new file: a campaign solved for 48 s before it said so."""
    result = cli_process("campaign", str(EXAMPLES / "campaign_small.toml"), "--out",
                         "/proc/sdc_cvx_out", cwd=tmp_path, timeout=60)  # fmt: skip
    assert result.returncode == 2, result.stderr
    assert "error: --out: cannot write the campaign folder /proc/sdc_cvx_out" in result.stderr
    assert "Campaign of" not in result.stderr and not result.stdout
