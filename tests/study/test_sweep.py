"""Trade-study sweeps: study files, local pool and Dask, resume after a kill, failures, figure."""

import contextlib
import io
import os
import shutil
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pandas as pd
import pytest
from matplotlib.figure import Figure

from sdc_cvx.study.runner import (
    RESULT_COLUMNS,
    Study,
    SweepError,
    load_study,
    plot_sweep,
    read_results,
    run_study,
    solve_scenario,
    sweep,
)
from sdc_cvx.study.scenario import Scenario, ScenarioError
from tests.conftest import EXAMPLES, REPO, as_terminal_job, computed_once

pytestmark = pytest.mark.slow  # solves many missions (see tests/conftest.py)

STUDY = """\
base = "paper.toml"

[grid]                  # unquoted dotted keys: the same as "mission.n"
mission.n = [3, 4]
mission.tmax_days = [300, 365.25]

[[cases]]
label = "too short"
"mission.n" = 3
"mission.tmax_days" = 5
"""
KEYS = 5  # 2 x 2 grid + 1 case


@pytest.fixture(scope="module")
@computed_once
def study_file(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("study")
    # the sweep machinery is under test, not the method: the paper's is the quicker here
    paper = (EXAMPLES / "paper.toml").read_text()
    (folder / "paper.toml").write_text(paper.replace('method = "certified"', 'method = "paper"'))
    (folder / "study.toml").write_text(STUDY)
    return folder / "study.toml"


@pytest.fixture(scope="module")
@computed_once
def reference(study_file, tmp_path_factory) -> pd.DataFrame:
    """The study solved without interruption on the local process pool."""
    out = tmp_path_factory.mktemp("reference")
    return run_study(load_study(study_file), out, workers=2, progress=False)


def without_seconds(frame: pd.DataFrame) -> pd.DataFrame:
    return frame.drop(columns="seconds").reset_index(drop=True)


# ---------------------------------------------------------------------- study files
def test_example_study_is_the_grid_over_tmax_and_n():
    study = load_study(EXAMPLES / "study_tmax_n.toml")
    assert study.base == Scenario.load(EXAMPLES / "paper.toml")
    assert study.parameters == ("mission.tmax_days", "mission.n")
    assert len(study) == 9 and len({s.key for s in study.scenarios}) == 9
    pairs = [(s.scenario.mission.tmax_days, s.scenario.mission.n) for s in study.scenarios]
    assert pairs == [(t, n) for t in (300.0, 365.25, 450.0) for n in (4, 5, 6)]
    assert study.scenarios[0].label == "tmax_days=300 n=4"


def test_grid_then_cases_with_stable_keys(study_file):
    study = load_study(study_file)
    assert [s.label for s in study.scenarios] == [
        "n=3 tmax_days=300",
        "n=3 tmax_days=365.25",
        "n=4 tmax_days=300",
        "n=4 tmax_days=365.25",
        "too short",
    ]
    assert study.scenarios[-1].overrides == {"mission.n": 3, "mission.tmax_days": 5.0}
    again = Study.from_dict(
        {
            "base": {"mission": {"n": 5}},
            "grid": {"mission.tmax_days": [365.25, 300.0], "mission.n": [4, 3]},
        },
    )

    # a key's hash depends on the values only, not on how or in which order they were written
    def digests(scenarios):
        return {s.key.rsplit("-", 1)[1] for s in scenarios}

    assert digests(again.scenarios) == digests(study.scenarios[:4])
    # the self-contained study written out reads back the same
    assert Study.from_dict(tomllib.loads(study.to_toml())) == study


def test_invalid_key_is_rejected_before_any_solve(tmp_path):
    (tmp_path / "bad.toml").write_text(
        f'base = "{EXAMPLES / "paper.toml"}"\n[grid]\n"mission.tmax_dayz" = [300, 400]\n'
    )
    with pytest.raises(ScenarioError, match=r"mission\.tmax_dayz.*case.*tmax_dayz=300"):
        sweep(tmp_path / "bad.toml", tmp_path / "out")
    assert not (tmp_path / "out").exists()  # nothing written, nothing solved


def test_invalid_value_names_the_dotted_key_and_the_case():
    data = {"grid": {"mission.n": [4, 1]}, "cases": [{"label": "odd", "solver.mip_gap": 2.0}]}
    with pytest.raises(ScenarioError) as err:
        Study.from_dict(data)
    message = str(err.value)
    assert "mission.n must be >= 2" in message and "'n=1'" in message
    assert "solver.mip_gap" in message and "'odd'" in message


@pytest.mark.parametrize(
    "data, words",
    [
        ({"grid": {"n": [4, 5]}}, "not a dotted key"),
        ({"grid": {"mission.n": 4}}, "must be an array"),
        ({"grid": {"mission.n": []}}, "has no values"),
        ({"sweep": {"workers": 2}}, "unknown study key 'sweep'"),
        ({"grid": {"mission.n": [4, 4]}}, "'n=4' is given twice"),  # issue 48, item 20
    ],
)
def test_malformed_studies(data, words):
    with pytest.raises(ScenarioError, match=words):
        Study.from_dict(data)


def test_worker_function_never_raises():
    row = solve_scenario("[mission\nn = ", key="broken")
    assert row["key"] == "broken" and row["status"] == "error"
    assert row["error"].startswith("TOMLDecodeError") and "Traceback" in row["traceback"]
    row = solve_scenario('[catalog]\npath = "/nonexistent/debris.csv"\n')
    assert row["status"] == "error" and "debris.csv" in row["error"]


def test_worker_applies_the_scenarios_candidate_selection():
    """A [selection] table filters the sweep's candidates as it does for `run`."""
    scenario = Scenario.load(EXAMPLES / "paper.toml").with_overrides(n=3, tmax_days=200)
    free = solve_scenario(scenario.to_toml())
    assert free["status"] == "optimal" and free["certified"]  # the default method
    banned = free["path"].split("->")[0]
    filtered = scenario.with_overrides(**{"selection.exclude_ids": (banned,)})
    assert "[selection]" in filtered.to_toml()
    row = solve_scenario(filtered.to_toml())
    assert row["status"] == "optimal" and banned not in row["path"].split("->")
    assert row["lower_bound_mps"] <= row["total_dv_mps"] and row["method"] == "certified"
    study = Study.from_dict({"base": str(EXAMPLES / "paper.toml"),
                             "grid": {"selection.exclude_ids": [[banned], ["1"]]}})  # fmt: skip
    assert [item.scenario.selection.exclude_ids for item in study.scenarios] == [(banned,), ("1",)]


def test_the_worker_row_has_the_plans_propellant_against_the_tank():
    """Found as a user: a sweep of thrust against n over a 12 kg tank said "6 of 6 solved"
    and its results.csv had no propellant column.  The row has the plan's propellant
    (the rocket equation over its legs, here), the tank, the margin and the fit."""
    import json
    import math

    dry, kit, isp = 800.0, 20.0, 300.0
    scenario = Scenario.load(EXAMPLES / "paper.toml").with_overrides(
        n=3, tmax_days=200, dry_mass_kg=dry, propellant_kg=5.0, isp_s=isp, kit_mass_kg=kit)
    row = solve_scenario(scenario.to_toml())
    legs = [leg["dv_mps"] for leg in json.loads(row["solution_json"])["legs"]]
    mass = dry
    for dv in reversed(legs):  # kits left at each debris, ending dry
        mass = (mass + kit) * math.exp(dv / (9.80665 * isp))
    need = mass + kit - dry - (len(legs) + 1) * kit
    assert row["propellant_needed_kg"] == pytest.approx(need, rel=1e-9)
    assert row["capacity_kg"] == 5.0 and row["margin_kg"] == pytest.approx(5.0 - need)
    assert need > 5.0 and row["fits"] is False and row["status"] == "over_capacity"
    plain = solve_scenario(Scenario.load(EXAMPLES / "paper.toml").with_overrides(
        n=3, tmax_days=200).to_toml())  # fmt: skip
    assert all(plain[c] is None for c in ("propellant_needed_kg", "capacity_kg", "fits"))


# ---------------------------------------------------------------------- running
def test_results_table_and_files(reference, study_file):
    out = Path(reference.attrs["out_dir"])
    study = load_study(study_file)
    assert list(reference["key"]) == [s.key for s in study.scenarios]
    assert list(reference.columns) == [
        "key",
        "label",
        "mission.n",
        "mission.tmax_days",
        *RESULT_COLUMNS,
        "scenario_sha",
    ]
    solved = reference[reference["status"] == "converged"]
    assert len(solved) == 4 and solved["error"].isna().all()
    assert (solved["total_duration_days"] <= solved["mission.tmax_days"] + 1e-6).all()
    assert solved["path"].str.count("->").tolist() == [2, 2, 3, 3]
    assert (solved["iterations"] > 0).all() and (solved["backend"] == "HIGHS").all()
    pd.testing.assert_frame_equal(read_results(out), reference)
    copy = (out / "study.toml").read_text()  # self-contained, the original as comments
    assert "".join(f"# {line}\n" for line in STUDY.splitlines()) in copy
    assert load_study(out / "study.toml").scenarios == study.scenarios
    for item in study.scenarios:
        folder = out / "scenarios" / item.key
        as_run = Scenario.load(folder / "scenario.toml")
        assert as_run.mission == item.scenario.mission and as_run.solver.threads == 1
        solved = item.label != "too short"
        assert (folder / "solution.json").exists() == solved
        assert (folder / "error.txt").exists() != solved
    assert not list(out.rglob("*.tmp"))
    assert not (out / ".sweep.lock").exists()  # a finished folder keeps no lock
    umask = os.umask(0)
    os.umask(umask)
    for path in out.rglob("*"):  # readable by colleagues: 0644 under a 022 umask
        if path.is_file():
            assert path.stat().st_mode & 0o777 == 0o666 & ~umask, path


def test_infeasible_scenario_is_recorded_while_the_others_succeed(reference):
    failed = reference.set_index("label").loc["too short"]
    assert failed["status"] == "infeasible" and "T_max = 5 days" in failed["error"]
    assert pd.isna(failed["total_dv_mps"]) and failed["path"] is None
    assert (reference["status"] == "converged").sum() == KEYS - 1


def test_dask_cluster_gives_the_same_table(study_file, reference, tmp_path):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        frame = run_study(
            load_study(study_file), tmp_path, scheduler=cluster.scheduler_address, progress=False
        )
    pd.testing.assert_frame_equal(without_seconds(frame), without_seconds(reference))


def test_killed_sweep_resumes_with_every_scenario_once(study_file, reference, tmp_path):
    out = tmp_path / "out"
    code = (
        "from sdc_cvx import sweep; "
        f"sweep({str(study_file)!r}, {str(out)!r}, workers=1, progress=False)"
    )
    process = subprocess.Popen([sys.executable, "-c", code], start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and process.poll() is None:
            if (out / "results.csv").exists() and len(read_results(out)) >= 1:
                break
            time.sleep(0.05)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)  # the sweep and its worker processes
        process.wait()
    before = read_results(out)
    assert 1 <= len(before) < KEYS, "the sweep was not killed midway"

    ran = []
    resumed = run_study(
        load_study(study_file),
        out,
        resume=True,
        workers=2,
        progress=lambda p: ran.append(p.row) if p.row else None,
    )
    assert len(ran) == KEYS - len(before)  # only the missing scenarios ran
    assert resumed["key"].is_unique and len(resumed) == KEYS
    kept = resumed.set_index("key").loc[before["key"]].reset_index()
    pd.testing.assert_frame_equal(kept, before)  # rows from before untouched
    pd.testing.assert_frame_equal(without_seconds(resumed), without_seconds(reference))


def test_resume_of_a_finished_sweep_runs_nothing(study_file, reference, tmp_path):
    shutil.copytree(reference.attrs["out_dir"], tmp_path / "out")
    ran = []
    frame = run_study(
        load_study(study_file), tmp_path / "out", resume=True, progress=lambda p: ran.append(p.row)
    )
    assert ran == [None]  # the first report only
    pd.testing.assert_frame_equal(without_seconds(frame), without_seconds(reference))
    assert frame["seconds"].tolist() == reference["seconds"].tolist()


def test_folder_with_results_is_protected(study_file, reference, tmp_path):
    shutil.copytree(reference.attrs["out_dir"], tmp_path / "out")
    with pytest.raises(SweepError, match="resume=True"):
        run_study(load_study(study_file), tmp_path / "out", progress=False)
    other = Study.from_dict(
        {
            "base": str(EXAMPLES / "paper.toml"),
            "grid": {"mission.n": [3, 4], "mission.tmax_days": [300, 400]},
        }
    )
    with pytest.raises(SweepError, match="another study"):
        run_study(other, tmp_path / "out", resume=True, progress=False)
    pd.testing.assert_frame_equal(read_results(tmp_path / "out"), reference)


# ---------------------------------------------------------------------- figure
def test_plot_sweep_draws_dv_against_the_swept_parameter(reference):
    fig = plot_sweep(reference, "tmax_days", hue="n", annotate=True)
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "mission.tmax_days" and "V [m/s]" in ax.get_ylabel()
    lines = [line for line in ax.get_lines() if line.get_linestyle() == "-"]
    assert len(lines) == 2  # n = 3 and n = 4
    assert list(lines[1].get_xdata()) == [300.0, 365.25]
    crosses = [line for line in ax.get_lines() if line.get_marker() == "x"]
    assert [list(c.get_xdata()) for c in crosses if len(c.get_xdata())][0] == [5.0]
    assert any("\u2192" in text.get_text() for text in ax.texts)  # paths annotated
    fig.savefig(io.BytesIO(), format="png")
    # from the folder, into a given axes
    other = Figure()
    ax = other.add_subplot()
    assert plot_sweep(reference.attrs["out_dir"], "mission.n", ax=ax) is other
    assert ax.get_xlabel() == "mission.n"
    with pytest.raises(KeyError, match="no column 'gap'"):
        plot_sweep(reference, "gap")


@pytest.mark.slow
def test_a_script_without_a_main_guard_is_told_before_any_worker_starts(tmp_path):
    """Its workers would import the script and start the sweep again (issue 20, item 4)."""
    (tmp_path / "study.toml").write_text('[grid]\n"mission.n" = [2, 3]\n')
    unguarded = "import sdc_cvx\nsdc_cvx.sweep('study.toml', 'out', progress=False)\n"
    guarded = (
        "from sdc_cvx.study.runner import _check_main_guard\n"
        "if __name__ == '__main__':\n    _check_main_guard()\n    print('accepted')\n"
    )
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    for name, text in (("unguarded.py", unguarded), ("guarded.py", guarded)):
        (tmp_path / name).write_text(text)
    result = subprocess.run([sys.executable, "unguarded.py"], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=120)  # fmt: skip
    assert result.returncode == 1
    assert "unguarded.py, line 2: the sweep is started at the top level" in result.stderr
    assert "if __name__ ==" in result.stderr and not (tmp_path / "out").exists()
    result = subprocess.run([sys.executable, "guarded.py"], cwd=tmp_path, env=env,
                            capture_output=True, text=True, timeout=120)  # fmt: skip
    assert result.returncode == 0 and result.stdout == "accepted\n", result.stderr


@pytest.mark.slow
def test_the_study_copied_into_the_folder_resumes_that_sweep(tmp_path, monkeypatch):
    """Its relative paths pointed beside the original file: the copy is self-contained."""
    import concurrent.futures as cf

    from sdc_cvx.study.runner import run_study
    from sdc_cvx.study.study import load_study

    given = tmp_path / "given"
    given.mkdir()
    (given / "d.csv").write_text(
        "id,a_km,e,inc_deg,raan_deg\n1,7000,0.001,98,10\n2,7050,0.001,98,40\n3,7100,0.001,98,70\n"
    )
    (given / "base.toml").write_text('[catalog]\npath = "d.csv"\n')
    (given / "study.toml").write_text('base = "base.toml"\n[grid]\n"mission.n" = [2, 3]\n')
    out = tmp_path / "out"
    with cf.ThreadPoolExecutor(1) as pool:
        first = run_study(load_study(given / "study.toml"), out, executor=pool, progress=False)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    copy = load_study(out / "study.toml")
    ran = []
    with cf.ThreadPoolExecutor(1) as pool:
        again = run_study(copy, out, executor=pool, resume=True, progress=ran.append)
    assert len(first) == len(again) == 2
    assert list(again["total_dv_mps"]) == list(first["total_dv_mps"])
    assert ran and all(p.row is None and p.remaining == 0 for p in ran)  # nothing run again
    assert '# base = "base.toml"' in (out / "study.toml").read_text()  # the original, kept
    assert not (out / ".sweep.lock").exists()


@pytest.mark.slow
def test_ctrl_c_on_a_sweep_says_how_to_resume_and_ends_at_once(tmp_path):
    (tmp_path / "study.toml").write_text('[grid]\n"mission.n" = [3, 9]\n')  # n = 9: minutes
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    sweep = subprocess.Popen(
        [sys.executable, "-m", "sdc_cvx", "sweep", "study.toml", "--out", "out", "--workers", "1"],
        cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        start_new_session=True, preexec_fn=as_terminal_job,
    )  # fmt: skip
    results = tmp_path / "out" / "results.csv"
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and sweep.poll() is None:
        if results.exists() and "n=3" in results.read_text():
            break
        time.sleep(0.2)
    os.killpg(sweep.pid, signal.SIGINT)  # a terminal's Ctrl-C reaches the whole group
    try:
        _, stderr = sweep.communicate(timeout=60)  # not after the n = 9 solve
    finally:  # a sweep that did not end would compute n = 9 for an hour: end its group
        with contextlib.suppress(ProcessLookupError):
            os.killpg(sweep.pid, signal.SIGKILL)
    assert sweep.returncode == 130
    assert "finish the others with: python -m sdc_cvx sweep study.toml --resume --out out" in stderr
    assert "Traceback" not in stderr and not (tmp_path / "out" / ".sweep.lock").exists()


def test_a_notebook_cell_is_not_taken_for_a_script_without_a_guard(tmp_path):
    """ipykernel runs a cell as top-level code of __main__ from a file it keeps on disk:
    no worker imports it, so nothing to refuse (notebooks call sweep() at top level)."""
    from sdc_cvx.study.runner import _check_main_guard

    cell = tmp_path / "cell.py"
    cell.write_text("_check_main_guard()\n")
    code = compile(cell.read_text(), str(cell), "exec")
    exec(code, {"__name__": "__main__", "_check_main_guard": _check_main_guard})  # no raise
    with pytest.raises(SweepError, match="cell.py, line 1: the sweep is started"):
        exec(code, {"__name__": "__main__", "__file__": str(cell),
                    "_check_main_guard": _check_main_guard})  # fmt: skip
