"""``fly`` and the folders it writes (issue 48, items 1-4), through real processes.

- A folder being flown is not replaced by a ``run --out`` into it (one plan's
  ``solution.json`` beside another plan's ``flight/``): the run is refused.
- A ``campaign.json`` whose mission ``folder`` leads out of the campaign folder is refused;
  nothing is written there.
- A folder nothing can be written in is refused before anything is flown.
- Hand-edited files (a leg of 1e6 days; a ``campaign.json`` that is a list, or holds a
  mission that is not an object) exit 2 naming the file and the field.
"""

import contextlib
import fcntl
import json
import os
import shutil
import subprocess

import pytest

from tests.conftest import computed_once, shared_file
from tests.test_cli import cli_process

TLE = "sso_rocket_bodies_2020/sso_rb.tle"
pytestmark = [pytest.mark.slow, pytest.mark.requires_shared_data(TLE)]


@pytest.fixture(scope="module")
@computed_once
def planned(tmp_path_factory):
    """A run folder of a small plan (2 debris, 60 days), not flown."""
    folder = tmp_path_factory.mktemp("fly_folders") / "run"
    done = cli_process("run", "--catalog", str(shared_file(TLE)), "--n", "2", "--tmax-days",
                       "60", "--quiet", "--out", str(folder))  # fmt: skip
    assert done.returncode == 0, done.stderr
    return folder


def copy_of(planned, tmp_path, name="copy"):
    target = tmp_path / name
    shutil.copytree(planned, target)
    return target


def test_a_run_into_a_folder_being_flown_is_refused(planned, tmp_path):
    folder = copy_of(planned, tmp_path)
    before = (folder / "solution.json").read_bytes()
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # as fly holds it while it flies
        done = cli_process("run", "--catalog", str(shared_file(TLE)), "--n", "2",
                           "--tmax-days", "50", "--quiet", "--out", str(folder))  # fmt: skip
    finally:
        os.close(fd)
    assert done.returncode == 2, done.stderr
    assert "being flown" in done.stderr and "Traceback" not in done.stderr
    assert (folder / "solution.json").read_bytes() == before


def test_a_mission_folder_out_of_the_campaign_folder_is_refused(tmp_path):
    campaign = tmp_path / "campaign"
    victim = tmp_path / "victim"
    campaign.mkdir()
    victim.mkdir()
    for name in ("../victim", str(victim), "mission_01/../../victim"):
        (campaign / "campaign.json").write_text(json.dumps({"missions": [{"folder": name}]}))
        done = cli_process("fly", str(campaign))
        assert done.returncode == 2, (name, done.stderr)
        assert "not a sub-folder of the campaign folder" in done.stderr, done.stderr
        assert "Traceback" not in done.stderr
        assert list(victim.iterdir()) == []


@pytest.mark.parametrize(("content", "said"), [
    ([{"folder": "mission_01"}], "expected a JSON object"),
    ({"missions": ["mission_01"]}, "missions[0]: expected an object"),
    ({"missions": [{"folder": 7}]}, "missions[0], field 'folder'"),
])  # fmt: skip
def test_a_hand_edited_campaign_json_names_the_field(tmp_path, content, said):
    (tmp_path / "campaign.json").write_text(json.dumps(content))
    done = cli_process("fly", str(tmp_path))
    assert done.returncode == 2, done.stderr
    assert said in done.stderr and "campaign.json" in done.stderr, done.stderr
    assert "Traceback" not in done.stderr


def test_a_leg_of_a_million_days_is_refused_by_name(planned, tmp_path):
    folder = copy_of(planned, tmp_path)
    data = json.loads((folder / "solution.json").read_text())
    data["legs"][0]["duration_days"] = 1e6
    (folder / "solution.json").write_text(json.dumps(data))
    done = cli_process("fly", str(folder))
    assert done.returncode == 2, done.stderr
    assert "legs[0] (leg 1).duration_days" in done.stderr and "Traceback" not in done.stderr


def test_a_folder_nothing_can_be_written_in_is_refused_before_the_flight(planned, tmp_path):
    folder = copy_of(planned, tmp_path)
    if shutil.which("chattr") is None:
        pytest.skip("chattr makes a folder unwritable, for root too (e2fsprogs)")
    made = subprocess.run(["chattr", "+i", str(folder)], capture_output=True)
    if made.returncode != 0:
        pytest.skip(f"chattr +i not supported here: {made.stderr.decode().strip()}")
    try:
        done = cli_process("fly", str(folder))
    finally:
        with contextlib.suppress(OSError):
            subprocess.run(["chattr", "-i", str(folder)], check=False)
    assert done.returncode == 4, done.stderr
    assert "nothing was flown" in done.stderr
    assert "leg 1/" not in done.stderr and "Traceback" not in done.stderr
    assert not (folder / "flight").exists()
