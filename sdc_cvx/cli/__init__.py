"""Command line: ``python -m sdc_cvx`` (or ``sdc-cvx``).

Commands: ``run [SCENARIO.toml]``, ``campaign SCENARIO.toml``, ``fly RUN_DIR``, ``sweep
STUDY.toml``, ``edges [SCENARIO.toml]``, ``catalog [FILE]``, ``solvers``, ``gtoc9-check
FOLDER`` (:mod:`.gtoc9`: exit 1 on a GTOC9 rule broken), ``gtoc9-plan SCENARIO.toml``
(:mod:`.gtoc9_plan`: GTOC9's Kessler Run for its cost J).  Exit codes: 0 success,
2 invalid input (nothing written), 3 infeasible mission or campaign (or a flight not flown
as planned, its files written), 4 solver failure or a full disk, 130 interrupted (Ctrl-C)
with nothing written.

The group :func:`main` gathers the commands of :mod:`.run`, :mod:`.campaign`, :mod:`.fly`,
:mod:`.sweep` and :mod:`.tables` (``edges``, ``catalog``, ``solvers``); they share
:mod:`.exits` (the exit codes), :mod:`.options`, :mod:`.reading` (the scenario, catalog
and candidates, read or exit 2) and :mod:`.progress` (a run's progress and its log).
Each command imports what it uses when it runs: ``--help`` stays light.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import click

from .campaign import campaign_command
from .exits import EXIT_CODES, INFEASIBLE, INPUT_ERROR, INTERRUPTED, SOLVER_FAILED, exit_code
from .fly import fly_command
from .gtoc9 import gtoc9_check_command
from .gtoc9_plan import gtoc9_plan_command
from .progress import RunProgress, quiet_resource_tracker
from .run import run_command
from .sweep import sweep_command
from .tables import catalog_command, edges_command, solvers_command

__all__ = [
    "EXIT_CODES",
    "INFEASIBLE",
    "INPUT_ERROR",
    "INTERRUPTED",
    "SOLVER_FAILED",
    "RunProgress",
    "exit_code",
    "main",
]


@click.group()
@click.version_option(package_name="sdc_cvx")
def main():
    """Plan active debris removal missions (Cerf's method, CVXPY + MILP)."""
    quiet_resource_tracker()
    warnings.showwarning = _show_warning


_PACKAGE = str(Path(__file__).resolve().parents[1])
_python_show = warnings.showwarning


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """sdc_cvx's own warnings as ``warning: ...`` lines, as the commands say theirs (not
    Python's ``path:line: UserWarning:`` and the source line); others as Python shows them."""
    if issubclass(category, UserWarning) and str(filename).startswith(_PACKAGE):
        click.echo(f"warning: {message}", err=True)
    else:
        _python_show(message, category, filename, lineno, file, line)


main.add_command(run_command)
main.add_command(campaign_command)
main.add_command(fly_command)
main.add_command(sweep_command)
main.add_command(edges_command)
main.add_command(catalog_command)
main.add_command(solvers_command)
main.add_command(gtoc9_check_command)
main.add_command(gtoc9_plan_command)
