"""A Dask nanny's MALLOC_TRIM_THRESHOLD_ no longer slows the pricing 2-3 times (issue 27, 3).

With the variable set (``distributed`` sets it for its workers, and it reaches every
process started after), glibc maps every allocation above 128 kB afresh: each numpy
temporary costs its pages' faults again.  ``restore_malloc`` gives the process the
thresholds of glibc's dynamic rule back.  Measured here by what it changes, the page
faults of repeated 1 MB temporaries (times are the benchmarks' business).
"""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import REPO

FAULTS = """
import resource, sys
import numpy as np
from sdc_cvx.study.executors import restore_malloc
if sys.argv[1] == "restored":
    restore_malloc()
for _ in range(50):  # warm up
    np.ones(2**17).sum()
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(400):
    np.ones(2**17).sum()  # 1 MB temporaries, made and freed
print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
"""


def faults(mode: str) -> int:
    env = {"PYTHONPATH": str(REPO), "PATH": "/usr/bin:/bin", "MALLOC_TRIM_THRESHOLD_": "65536"}
    done = subprocess.run([sys.executable, "-c", FAULTS, mode], capture_output=True, text=True,
                          env=env, timeout=120, check=True)  # fmt: skip
    return int(done.stdout.split()[-1])


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="glibc's mallopt")
def test_restored_thresholds_stop_the_page_faults_of_every_temporary():
    fixed, left = faults("restored"), faults("as set")
    assert left > 400 * 100  # about 256 pages afresh for each 1 MB temporary
    assert fixed < left / 20
