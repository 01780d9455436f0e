"""Backends write nothing to stdout unless asked (``--json`` promises JSON only there)."""

import os
import subprocess
import sys

import pytest

from tests.conftest import REPO

pytestmark = pytest.mark.requires_backend("HIGHS")

CODE = """
import highspy
from sdc_cvx.milp.output import backend_stdout
print("before", flush=True)
with backend_stdout({verbose}):
    highspy.Highs()
print("after", flush=True)
"""


def run(verbose: bool) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(REPO)}
    code = CODE.format(verbose=verbose)
    return subprocess.run([sys.executable, "-c", code], cwd=REPO, env=env, capture_output=True,
                          text=True, timeout=60, check=True)  # fmt: skip


def test_a_highs_banner_does_not_reach_stdout():
    bare = subprocess.run([sys.executable, "-c", "import highspy; highspy.Highs()"],
                          capture_output=True, text=True, timeout=60, check=True)  # fmt: skip
    result = run(verbose=False)
    assert result.stdout == "before\nafter\n"
    if bare.stdout:  # this HiGHS prints a banner: it is silenced, not moved
        assert bare.stdout.strip() not in result.stderr


def test_verbose_sends_the_backend_output_to_stderr():
    bare = subprocess.run([sys.executable, "-c", "import highspy; highspy.Highs()"],
                          capture_output=True, text=True, timeout=60, check=True)  # fmt: skip
    result = run(verbose=True)
    assert result.stdout == "before\nafter\n"
    assert bare.stdout.strip() in result.stderr


def test_nested_and_parallel_runs_restore_stdout_only_when_the_last_one_ends():
    from sdc_cvx.milp.output import backend_stdout

    def where() -> tuple[int, int]:
        stat = os.fstat(1)
        return stat.st_dev, stat.st_ino

    null = os.stat(os.devnull)
    before = where()
    with backend_stdout():
        assert where() == (null.st_dev, null.st_ino)
        with backend_stdout():
            pass
        assert where() == (null.st_dev, null.st_ino)  # the outer run is still under way
    assert where() == before
