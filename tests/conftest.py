"""Paths, markers and fixtures shared by the test modules.

The tests mirror the package: ``tests/physics/`` tests ``sdc_cvx/physics/`` and so on.

Markers (registered in ``pyproject.toml``):

* ``slow``: more than a few seconds (the enumeration cross-check, sweeps, CLI runs end
  to end, notebooks); ``pytest -m "not slow"`` is the fast subset;
* ``requires_shared_data(*files)``: skipped, with the reason, when the public data of
  ``SHARED_DATA`` (or one of ``files``, relative to it) is absent;
* ``requires_backend(name)``: skipped unless CVXPY can call the MILP backend ``name``.
"""

import functools
from pathlib import Path

import pytest

from sdc_cvx.milp import solve as milp_solve

REPO = Path(__file__).resolve().parents[1]
"""The repository's root."""
EXAMPLES = REPO / "examples"
"""The example scenario and study files."""
PAPER_CSV = REPO / "sdc_cvx" / "data" / "paper_table5.csv"
"""The paper's Table 5, bundled with the package."""
SHARED_DATA = REPO.parent / "shared" / "data"
"""Public catalogs (TLE, OMM, GTOC9) kept beside the repository, never copied into it
(docs/design.md §8)."""


def as_terminal_job() -> None:
    """``preexec_fn`` for a command a test then interrupts: Ctrl-C as a terminal's foreground
    job has it (``SIG_DFL``), whatever the test runner inherited.

    A runner started in the background of a script ignores SIGINT, its children inherit
    that, and Python then installs no KeyboardInterrupt handler: the command would rightly
    stay deaf to the test's Ctrl-C (why the sweep's Ctrl-C test once hung in CI-like runs).
    """
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def shared_file(relative: str) -> Path:
    """``SHARED_DATA / relative``, or skip the test saying which file is missing."""
    path = SHARED_DATA / relative
    if not path.is_file():
        pytest.skip(f"public data file {relative} not found in {SHARED_DATA} (docs/design.md §8)")
    return path


def computed_once(fixture):
    """Decorate a module fixture (under ``@pytest.fixture(scope="module")``) so that it is
    computed once per test process.

    Under ``-n 2`` a worker runs a module's tests among other modules' and tears a module
    fixture down each time it leaves the module: a fixture that plans or flies a mission
    (tens of seconds) was computed again each time it came back.  Only for fixtures
    without teardown and parameters, whose value the tests read and do not change.
    """
    cache: dict = {}

    @functools.wraps(fixture)
    def once(*args, **kwargs):
        if "value" not in cache:
            cache["value"] = fixture(*args, **kwargs)
        return cache["value"]

    return once


def pytest_runtest_setup(item):
    for marker in item.iter_markers("requires_shared_data"):
        if not SHARED_DATA.is_dir():
            pytest.skip(f"the public data folder {SHARED_DATA} is absent (docs/design.md §8)")
        for relative in marker.args:
            shared_file(relative)
    for marker in item.iter_markers("requires_backend"):
        from sdc_cvx.milp.backends import BACKENDS, installed_backends

        name = marker.args[0]
        if name not in installed_backends():
            package = BACKENDS[name].package if name in BACKENDS else "?"
            pytest.skip(f"{name} is not installed (pip install {package})")


@pytest.fixture
def crash_backend(monkeypatch):
    """``crash_backend(NAME)``: every solve by backend NAME raises, the others run as usual."""

    def crash(name):
        real = milp_solve.solve_milp

        def solve_milp(problem, options, *, warm_start=False):
            if options.backend == name:
                raise RuntimeError("simulated crash")
            return real(problem, options, warm_start=warm_start)

        monkeypatch.setattr(milp_solve, "solve_milp", solve_milp)

    return crash


@pytest.fixture(scope="session")
def options_by_the_paper(tmp_path_factory):
    """``examples/options.toml`` by the paper's method, run once through the command line
    (in process: ``run FILE --progress --method paper --out DIR``): the CLI's result, its
    run folder, and the :class:`~sdc_cvx.solution.Solution` it solved.

    The vehicle deorbits each debris (operations ΔV) and the paper's driver rejects
    steps: what the progress lines, the run log and the iteration table must all show.
    One run serves both the command's tests and the run folder's (14 s each).
    """
    from unittest import mock

    from click.testing import CliRunner

    from sdc_cvx.cli import main
    from sdc_cvx.planner import api

    solved, real = [], api.solve

    def keeping(*args, **kwargs):
        solved.append(real(*args, **kwargs))
        return solved[-1]

    out = tmp_path_factory.mktemp("options_by_the_paper") / "out"
    with mock.patch.object(api, "solve", keeping):
        result = CliRunner().invoke(main, ["run", str(EXAMPLES / "options.toml"), "--progress",
                                           "--method", "paper", "--out", str(out)])  # fmt: skip
    assert result.exit_code == 0 and len(solved) == 1, result.output
    return result, out, solved[0]
