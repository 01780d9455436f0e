"""A sweep's workers die with it: SIGKILL of the sweep's process leaves no worker computing."""

import contextlib
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, REPO

pytestmark = pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs /proc (Linux)")


def children() -> dict[int, int]:
    """pid -> parent pid of every process."""
    table = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        table[int(entry.name)] = int(stat.rsplit(")", 1)[1].split()[1])
    return table


def descendants(root: int) -> set[int]:
    table = children()
    found, frontier = set(), {root}
    while frontier:
        frontier = {pid for pid, parent in table.items() if parent in frontier} - found
        found |= frontier
    return found


def alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except OSError:
        return False
    return state != "Z"


def start_sweep(tmp_path, output) -> subprocess.Popen:
    """A sweep of twelve paper-case scenarios on two workers, its stdout and stderr to
    ``output`` (``subprocess.DEVNULL`` or ``PIPE``)."""
    study = tmp_path / "study.toml"
    study.write_text(
        f'base = "{EXAMPLES / "paper.toml"}"\n[grid]\n'
        '"mission.tmax_days" = [300, 330, 365.25, 400, 450, 500]\n"mission.n" = [5, 6]\n'
    )
    return subprocess.Popen(
        [sys.executable, "-m", "sdc_cvx", "sweep", str(study), "--out", str(tmp_path / "out"),
         "--workers", "2"],
        cwd=REPO, stdout=output, stderr=output,
    )  # fmt: skip


@pytest.mark.slow
def test_sigkill_of_the_sweep_leaves_no_worker(tmp_path):
    sweep = start_sweep(tmp_path, subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        workers: set[int] = set()
        while time.monotonic() < deadline:  # the fork server and at least 2 workers
            workers = descendants(sweep.pid)
            if len(workers) >= 3:
                break
            time.sleep(0.2)
        assert len(workers) >= 3, "the sweep started no workers"
        time.sleep(1.0)
        workers = descendants(sweep.pid)
        os.kill(sweep.pid, signal.SIGKILL)
        sweep.wait()
        time.sleep(5.0)
        survivors = [pid for pid in workers if alive(pid)]
        assert survivors == [], f"workers still running 5 s after the sweep died: {survivors}"
    finally:
        for pid in descendants(sweep.pid) if sweep.poll() is None else ():
            os.kill(pid, signal.SIGKILL)
        if sweep.poll() is None:
            sweep.kill()


@pytest.mark.slow
def test_a_killed_sweep_not_yet_reaped_leaves_its_launchers_pipes_closed(tmp_path):
    """Issue 48, item 18: a launcher reading the sweep's output before waiting for it
    (``stdout=PIPE``, then ``communicate()``) keeps the killed sweep a zombie; the workers
    took it for alive, and they, the fork server and the resource tracker held the pipes
    open for 30-80 s: ``communicate()`` did not return."""
    sweep = start_sweep(tmp_path, subprocess.PIPE)
    family: set[int] = set()
    try:
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:  # resource tracker, fork server, 2 workers
            family = descendants(sweep.pid)
            if len(family) >= 4:
                break
            time.sleep(0.2)
        assert len(family) >= 4, "the sweep started no workers"
        os.kill(sweep.pid, signal.SIGKILL)
        time.sleep(2.0)  # not reaped: the sweep stays a zombie meanwhile
        assert not alive(sweep.pid) and Path(f"/proc/{sweep.pid}").exists()
        try:
            sweep.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            pytest.fail(f"the sweep's pipes were still open 12 s after it was killed, by "
                        f"{[pid for pid in family if alive(pid)]}")  # fmt: skip
        survivors = [pid for pid in family if alive(pid)]
        assert survivors == [], f"processes of the sweep still running: {survivors}"
    finally:
        for pid in [pid for pid in family if alive(pid)]:
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
        if sweep.poll() is None:
            sweep.kill()
        sweep.communicate()
