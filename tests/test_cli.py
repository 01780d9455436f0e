"""Command line: run and edges, success and failure paths, files written."""

import json

import pandas as pd
from click.testing import CliRunner

from sdc_cvx import Catalog, Mission, preoptimize
from sdc_cvx.cli import main


def test_run_paper_case_writes_the_run_folder(tmp_path):
    result = CliRunner().invoke(main, ["run", "--out", str(tmp_path / "out"), "--quiet"])
    assert result.exit_code == 0, result.output
    assert "5 -> 8 -> 2 -> 6 -> 10" in result.output
    data = json.loads((tmp_path / "out" / "solution.json").read_text())
    assert data["path"] == ["5", "8", "2", "6", "10"] and data["total_dv_mps"] <= 500.7
    legs = pd.read_csv(tmp_path / "out" / "legs.csv")
    assert len(legs) == 4 and abs(legs["dv_mps"].sum() - data["total_dv_mps"]) < 1e-6
    assert len(pd.read_csv(tmp_path / "out" / "iterations.csv")) == len(data["iterations"])
    assert not list((tmp_path / "out").glob(".*.tmp"))  # no temp files left behind


def test_run_shows_progress_per_iteration(tmp_path):
    result = CliRunner().invoke(main, ["run", "--out", str(tmp_path), "--n", "3"])
    assert result.exit_code == 0, result.output
    assert "it  0" in result.output


def test_run_infeasible_mission_exit_code_and_reason(tmp_path):
    result = CliRunner().invoke(main, ["run", "--tmax-days", "20", "--preopt-days", "5",
                                       "--out", str(tmp_path)])  # fmt: skip
    assert result.exit_code == 3
    assert "infeasible mission" in result.output and "Relax one of" in result.output
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
