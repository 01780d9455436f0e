"""The run folder: whole or not at all, readable by colleagues, and its numbers agree."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from sdc_cvx.report.atomic import write_atomic
from sdc_cvx.report.out_folder import out_folder_problem
from sdc_cvx.report.plots import plot_cost
from sdc_cvx.report.run_folder import write_run
from sdc_cvx.study.scenario import load
from tests.conftest import EXAMPLES, REPO

RUN_FILES = {"solution.json", "legs.csv", "iterations.csv", "edges.csv", "orbits.png",
             "raan.png", "cost.png", "iterations.png"}  # fmt: skip


def snapshot(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    yield
    os.umask(old)


def test_files_are_0644_under_umask_022(solution, tmp_path, umask_022):
    written = solution.save(tmp_path / "run")
    assert {p.name for p in written} == RUN_FILES
    for path in written:
        assert path.stat().st_mode & 0o777 == 0o644, path
    assert (tmp_path / "run").stat().st_mode & 0o777 == 0o755
    write_atomic(tmp_path / "one.txt", "x")
    assert (tmp_path / "one.txt").stat().st_mode & 0o777 == 0o644


def test_files_follow_a_stricter_umask(solution, tmp_path):
    old = os.umask(0o077)
    try:
        written = solution.save(tmp_path / "run", formats=())
    finally:
        os.umask(old)
    assert all(p.stat().st_mode & 0o777 == 0o600 for p in written)


def test_an_earlier_run_folder_is_replaced_whole_and_no_stale_svg_stays(solution, tmp_path):
    folder = tmp_path / "run"
    solution.save(folder, formats=("svg",))
    assert (folder / "cost.svg").exists()
    solution.save(folder, formats=())  # again, without svg
    assert {p.name for p in folder.iterdir()} == {n for n in RUN_FILES if ".png" not in n}
    assert not list(tmp_path.glob(".*partial"))  # nothing aside left


def test_a_flown_run_folder_is_replaced_but_not_a_file_of_the_users_in_its_flight(solution,
                                                                                   tmp_path):
    """``fly`` writes ``flight/`` in the run folder: a run again into it replaces it (the
    flight was the old plan's), unless ``flight/`` holds a file sdc_cvx does not write."""
    folder = tmp_path / "run"
    solution.save(folder, formats=())
    flight = folder / "flight"
    flight.mkdir()
    for name in ("maneuvers.csv", "rendezvous.csv", "flight.json", "trajectory.oem"):
        (flight / name).write_text("")
    assert out_folder_problem(folder) is None
    (flight / "mine.txt").write_text("the user's")
    with pytest.raises(FileExistsError, match="flight"):
        solution.save(folder, formats=())
    assert (flight / "mine.txt").read_text() == "the user's"
    (flight / "mine.txt").unlink()
    solution.save(folder, formats=())
    assert not flight.exists()


def test_a_folder_that_is_not_a_run_folder_is_refused(solution, tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    assert "not empty and is not an earlier run folder" in out_folder_problem(tmp_path)
    with pytest.raises(FileExistsError, match="not an earlier run folder"):
        solution.save(tmp_path)
    assert [p.name for p in tmp_path.iterdir()] == ["notes.txt"]
    (tmp_path / "file").write_text("")
    assert "is a file" in out_folder_problem(tmp_path / "file")
    assert "which is a file" in out_folder_problem(tmp_path / "file" / "run")
    assert out_folder_problem(tmp_path / "new" / "run") is None


def test_csv_files_carry_no_float_noise(solution, tmp_path):
    solution.save(tmp_path / "run", formats=())
    for name in ("legs.csv", "iterations.csv", "edges.csv"):
        text = (tmp_path / "run" / name).read_text()
        assert "00000000" not in text and "99999999" not in text, name


def test_save_and_plot_for_python_users(solution, tmp_path):
    figures = solution.plot()
    assert list(figures) == ["orbits", "raan", "cost", "iterations"]
    assert all(hasattr(fig, "savefig") for fig in figures.values())
    written = solution.save(tmp_path / "run", formats=())
    assert (tmp_path / "run" / "solution.json") in written
    data = json.loads((tmp_path / "run" / "solution.json").read_text())
    assert data["path"] == list(solution.path)


@pytest.mark.slow
def test_summary_legs_cost_figure_and_json_agree_on_total_dv(options_by_the_paper, tmp_path):
    """examples/options.toml by the paper's method: the vehicle deorbits each debris
    (operations ΔV), and its driver rejects steps (what the iteration table must show)."""
    scenario, (_, _, solution) = load(EXAMPLES / "options.toml"), options_by_the_paper
    assert solution.operations_dv_mps > 0  # the case of the issue: 2985.8 against 995.8
    solution.save(tmp_path / "run", formats=(), scenario_toml=scenario.to_toml())
    total = f"{solution.total_dv_mps:.1f}"
    summary = solution.summary()
    assert f"total dV  {solution.total_dv_mps:.2f} m/s" in summary
    legs = pd.read_csv(tmp_path / "run" / "legs.csv")
    assert legs["cumulative_dv_mps"].iloc[-1] == pytest.approx(solution.total_dv_mps, abs=1e-6)
    parts = legs["dv_mps"].sum() + legs["operations_dv_mps"].sum()
    assert parts == pytest.approx(solution.total_dv_mps, abs=1e-6)
    data = json.loads((tmp_path / "run" / "solution.json").read_text())
    assert data["total_dv_mps"] == pytest.approx(solution.total_dv_mps, abs=1e-9)
    labels = [t.get_text() for t in plot_cost(solution).axes[0].get_legend().get_texts()]
    assert any(f"= {total} m/s" in label for label in labels), labels
    # rejected steps are marked, in the table and in the summary's count
    iterations = pd.read_csv(tmp_path / "run" / "iterations.csv")
    rejected = iterations["step"].str.startswith("rejected")
    assert rejected.sum() == sum(1 for r in solution.iterations if r.rejected) > 0
    assert iterations.loc[rejected, "rejected"].str.len().gt(0).all()
    assert f"{int(rejected.sum())} rejected" in summary
    assert "path from the seeding" in summary  # the plan was held before the first MILP


def run_cli(out: Path, env: dict | None = None) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "sdc_cvx", "run", "--n", "3", "--quiet", "--out", str(out)],
        cwd=REPO, env={**os.environ, **(env or {})},
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip


def whole(folder: Path) -> bool:
    """Every file of a run folder, and legs.csv is that of solution.json."""
    names = {p.name for p in folder.iterdir()}
    if not RUN_FILES | {"scenario.toml", "run.log"} <= names:
        return False
    data = json.loads((folder / "solution.json").read_text())
    legs = pd.read_csv(folder / "legs.csv")
    return list(legs["dv_mps"]) == pytest.approx([leg["dv_mps"] for leg in data["legs"]])


@pytest.mark.slow
def test_a_kill_while_writing_leaves_the_old_folder_or_the_new_one_whole(tmp_path):
    out = tmp_path / "run"
    first = run_cli(out)
    assert first.wait(timeout=120) == 0
    old = snapshot(out)
    # killed with every file written aside, just before the swap: the old folder, whole
    second = run_cli(out, {"SDC_CVX_PAUSE_BEFORE_SWAP": "60"})
    deadline = time.monotonic() + 120
    staged = []
    while time.monotonic() < deadline and second.poll() is None:
        staged = [p for p in tmp_path.glob(".run.*.partial") if (p / "solution.json").exists()]
        if staged:
            break
        time.sleep(0.1)
    assert staged, "the run never reached the swap"
    second.send_signal(signal.SIGKILL)
    second.wait()
    assert snapshot(out) == old
    # killed at moments spread over the writing: always one folder or the other, whole
    for delay in (3.0, 5.0):
        third = run_cli(out)
        time.sleep(delay)
        third.send_signal(signal.SIGKILL)
        third.wait()
        assert snapshot(out) == old or whole(out), f"mixed folder after a kill at {delay} s"
        old = snapshot(out)
    # the next run cleans what the kills left aside
    assert run_cli(out).wait(timeout=120) == 0 and whole(out)
    assert not list(tmp_path.glob(".run.*.partial"))


@pytest.mark.slow
def test_a_killed_run_leaves_its_progress_beside_the_folder(tmp_path):
    """The progress goes to OUT.log as it happens; on success it moves into the folder."""
    out = tmp_path / "run"
    live = tmp_path / "run.log"
    run = subprocess.Popen(
        [sys.executable, "-m", "sdc_cvx", "run", "--n", "6", "--quiet", "--out", str(out)],
        cwd=REPO, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )  # fmt: skip
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and run.poll() is None:
        if live.exists() and "cost tables done" in live.read_text():
            break
        time.sleep(0.1)
    run.send_signal(signal.SIGKILL)
    run.wait()
    text = live.read_text()
    assert "Choosing 6 of 11 debris from paper Table 5" in text
    assert "certified search: 11 debris" in text and "cost tables done" in text
    assert not out.exists()
    # a run that ends writes run.log into its folder and leaves nothing beside it
    assert run_cli(out).wait(timeout=120) == 0
    assert "certified search" in (out / "run.log").read_text() and not live.exists()


def test_write_run_refuses_before_writing(solution, tmp_path):
    (tmp_path / "keep.txt").write_text("x")
    with pytest.raises(FileExistsError):
        write_run(tmp_path, solution)
    assert [p.name for p in tmp_path.iterdir()] == ["keep.txt"]


def test_a_run_without_a_relaxation_row_still_writes_its_folder(solution, tmp_path):
    """Every relaxation of a search stopped by its time limit may have been cut short by a
    cycle: no iteration row, and the run folder is still written (its table is empty)."""
    from dataclasses import replace

    bare = replace(solution, iterations=())
    write_run(tmp_path / "run", bare, formats=())
    table = pd.read_csv(tmp_path / "run" / "iterations.csv")
    assert table.empty and {"iteration", "path", "dv_true_mps"} <= set(table.columns)
    assert json.loads((tmp_path / "run" / "solution.json").read_text())["iterations"] == []


# ---------------------------------------------------------------- issue 20: files and locks
def test_the_current_folder_and_its_parents_are_refused(solution, tmp_path, monkeypatch):
    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    assert "is the current folder" in out_folder_problem(".")
    assert "is the current folder" in out_folder_problem(here)
    assert "a parent of the current folder" in out_folder_problem("..")
    with pytest.raises(FileExistsError, match="current folder"):
        solution.save(".", formats=())
    assert list(here.iterdir()) == [] and sorted(p.name for p in tmp_path.iterdir()) == ["here"]


def test_a_symlinked_folder_is_followed_and_the_link_kept(solution, tmp_path):
    target = tmp_path / "target"
    target.mkdir()
    link = tmp_path / "link"
    link.symlink_to(target)
    solution.save(link, formats=())
    assert link.is_symlink() and (target / "solution.json").exists()
    solution.save(link, formats=())  # an earlier run folder behind the link: replaced
    assert link.is_symlink() and (target / "solution.json").exists()
    assert not list(tmp_path.glob(".*partial"))


def test_an_unwritable_place_raises_a_clear_oserror_and_leaves_nothing(solution, tmp_path):
    with pytest.raises(OSError, match="cannot write the run folder /proc/sdc_cvx_nowhere/run"):
        solution.save("/proc/sdc_cvx_nowhere/run", formats=())
    assert not Path("/proc/sdc_cvx_nowhere").exists()


def test_a_write_that_fails_midway_leaves_nothing_it_created(solution, tmp_path, monkeypatch):
    import errno

    from sdc_cvx.report import run_folder

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(run_folder, "_swap_in", full)
    with pytest.raises(OSError, match="cannot write the run folder .*No space left") as caught:
        write_run(tmp_path / "new" / "deeper" / "run", solution, formats=())
    assert caught.value.errno == errno.ENOSPC
    assert list(tmp_path.iterdir()) == []  # no stage, and not the parents it made


def test_the_live_log_locks_the_folder_and_never_takes_a_file_of_the_user(tmp_path):
    from sdc_cvx.report.run_folder import (
        LIVE_LOG_SIGNATURE,
        FolderBusy,
        live_log_path,
        open_live_log,
    )

    out = tmp_path / "r"
    assert live_log_path(out) == tmp_path / "r.log"
    first = open_live_log(out)
    with pytest.raises(FolderBusy, match="another sdc_cvx run is writing"):
        open_live_log(out)
    first.write("step\n")
    first.close()  # a killed run: its log stays, unlocked, and the next run takes it over
    assert (tmp_path / "r.log").read_text() == f"{LIVE_LOG_SIGNATURE}\nstep\n"
    again = open_live_log(out)
    again.close()
    assert (tmp_path / "r.log").read_text() == f"{LIVE_LOG_SIGNATURE}\n"
    for mine in ("my notes\n", ""):
        (tmp_path / "r.log").write_text(mine)
        with pytest.raises(FileExistsError, match="is not a log of sdc_cvx"):
            open_live_log(out)
        assert (tmp_path / "r.log").read_text() == mine


def test_two_saves_into_one_folder_at_once_follow_each_other(solution, tmp_path):
    import threading

    out = tmp_path / "run"
    errors = []

    def save():
        try:
            solution.save(out, formats=())
        except Exception as err:  # noqa: BLE001 - collected, asserted below
            errors.append(err)

    threads = [threading.Thread(target=save) for _ in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert errors == []
    assert whole_without_figures(out) and not list(tmp_path.glob(".*partial"))


def whole_without_figures(folder: Path) -> bool:
    names = {p.name for p in folder.iterdir()}
    return names == {"solution.json", "legs.csv", "iterations.csv", "edges.csv"}


@pytest.mark.slow
def test_a_second_run_into_a_busy_folder_is_refused_and_a_kill_is_cleaned_at_the_next_start(
    tmp_path,
):
    out, live = tmp_path / "run", tmp_path / "run.log"
    env = {"PYTHONPATH": str(REPO)}
    first = run_cli(out, {**env, "SDC_CVX_PAUSE_BEFORE_SWAP": "60"})
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not list(tmp_path.glob(".run.*.partial/solution.json")):
        time.sleep(0.1)
    second = subprocess.run(
        [sys.executable, "-m", "sdc_cvx", "run", "--n", "3", "--quiet", "--out", str(out)],
        cwd=REPO, env={**os.environ, **env}, capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert second.returncode == 2
    assert "another sdc_cvx run is writing" in second.stderr and not out.exists()
    first.send_signal(signal.SIGKILL)
    first.wait()
    left = list(tmp_path.glob(".run.*.partial"))
    assert live.exists() and left  # what the kill left: until the next run starts
    third = run_cli(out, env)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and third.poll() is None:
        text = live.read_text() if live.exists() else ""
        if "Choosing 3 of 11" in text and "writing the run folder" not in text:
            break  # the third run's own log: it has started and not reached the writing
        time.sleep(0.05)
    assert not any(p.exists() for p in left)  # gone as the next run started
    assert third.wait(timeout=120) == 0 and whole(out) and not live.exists()


@pytest.mark.slow
def test_an_earlier_run_folder_holding_a_file_of_the_user_is_refused(solution, tmp_path):
    from sdc_cvx.report.out_folder import RUN_FOLDER_FILES
    from sdc_cvx.report.plots import FIGURE_NAMES, SUPPORTED_FORMATS

    # every file a run folder holds is known (else a rerun would refuse its own folder)
    assert {f"{n}.{f}" for n in FIGURE_NAMES for f in SUPPORTED_FORMATS} <= RUN_FOLDER_FILES
    folder = tmp_path / "run"
    solution.save(folder, formats=("png", "svg", "pdf"), scenario_toml="")
    assert {p.name for p in folder.iterdir()} <= RUN_FOLDER_FILES
    (folder / "notes.txt").write_text("mine")
    with pytest.raises(FileExistsError, match="also holds notes.txt, which sdc_cvx did not"):
        solution.save(folder, formats=())
    assert (folder / "notes.txt").read_text() == "mine"
