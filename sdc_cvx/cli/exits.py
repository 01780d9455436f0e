"""The command line's exit codes, and its two ways to end: :func:`fail` and
:func:`interrupted_exit`.

Exit codes: 0 success, 2 invalid input (nothing written), 3 infeasible mission or
campaign (or a flight not flown as planned, its files written), 4 solver failure or a full
disk, 130 interrupted (Ctrl-C) with nothing written.
"""

from __future__ import annotations

import errno
import glob
import os
import signal
import sys

import click

from ..errors import InputError, MissionInfeasible, SdcError, SolverFailure, SweepError

INPUT_ERROR = 2
INFEASIBLE = 3
SOLVER_FAILED = 4
INTERRUPTED = 130  # 128 + SIGINT, the shell's convention
EXIT_CODES: dict[type[SdcError], int] = {
    InputError: INPUT_ERROR,  # CatalogError, MissionError, ScenarioError
    SweepError: INPUT_ERROR,
    MissionInfeasible: INFEASIBLE,
    SolverFailure: SOLVER_FAILED,
}
"""Exit code of each family of :mod:`sdc_cvx.errors` (0 is success)."""
SYSTEM_ERRNOS = {errno.ENOSPC, errno.EDQUOT, errno.EIO, errno.EROFS}
"""Write failures of the machine, not of the input (a full disk): exit 4, not 2."""


def exit_code(err: SdcError) -> int:
    """The exit code of an error's family (:data:`EXIT_CODES`)."""
    for family, code in EXIT_CODES.items():
        if isinstance(err, family):
            return code
    return INPUT_ERROR


def interrupted_exit(message: str):
    """Ctrl-C with worker processes about: print ``message`` and end at once (exit 130).

    The workers were terminated and die with this process anyway (``study.executors``),
    and every file was written atomically: the interpreter's exit hooks (the process
    pool's joins its manager thread) have nothing left to do but wait.
    """
    click.echo(f"error: {message}", err=True)
    sys.stdout.flush()
    sys.stderr.flush()
    _end_children()
    os._exit(INTERRUPTED)


def _end_children() -> None:
    """End this process's children now (Linux: found in ``/proc``): a pool's fork server
    or resource tracker still starting when the second Ctrl-C came is not yet known to the
    pool, and would outlive the command with its stderr open (its workers, the fork
    server's children, die with it)."""
    me = os.getpid()
    for stat in glob.glob("/proc/[0-9]*/stat"):
        try:
            with open(stat, encoding="ascii", errors="replace") as handle:
                parent = int(handle.read().rsplit(")", 1)[1].split()[1])
            if parent == me:
                os.kill(int(stat.split("/")[2]), signal.SIGKILL)
        except (OSError, ValueError, IndexError):
            continue


def fail(message: str, code: int = INPUT_ERROR):
    """Print ``message`` to stderr and exit with ``code`` (no traceback)."""
    click.echo(f"error: {message}", err=True)
    sys.exit(code)
