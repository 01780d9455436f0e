"""``fly RUN_DIR``: fly a run folder's plan (each mission of a campaign folder) and check it.

Writes ``RUN_DIR/flight/`` (:mod:`sdc_cvx.flight.result`) and prints one line per leg
and a summary: plan ΔV, flown ΔV, worst miss.  Exit 2 when the plan cannot be flown as
asked (no phase for a debris, not a run folder, an injection orbit), 3 when a flight is
not flown as planned (incomplete, late, missed, or burning more propellant than the
vehicle's tank holds: its ``flight/`` is written and says so) or a plan is not flown at
all (it needs more propellant than the tank holds: ``over_capacity``), 4 when the folder
cannot be written, 130 on Ctrl-C (an earlier ``flight/`` is kept whole).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import tempfile
from pathlib import Path

import click

from .exits import INFEASIBLE, INTERRUPTED, SOLVER_FAILED, fail

FORCE_MODELS = ("j2", "j2-j4", "j2-j4-drag")


@click.command("fly")
@click.argument("run_dir", type=click.Path(exists=True, file_okay=False))
@click.option("--force-model", type=click.Choice(FORCE_MODELS), default="j2", show_default=True,
              help="The vehicle's force model: J2; J2 with J3-J4; and drag.")  # fmt: skip
@click.option("--catalog", "catalog_path", type=click.Path(dir_okay=False), default=None,
              help="Fly against this catalog file instead of the one scenario.toml names "
                   "(moved since the run; a refreshed one is compared with the plan's).")
@click.option("--quiet", is_flag=True, help="Only the summary.")
def fly_command(run_dir, force_model, catalog_path, quiet):
    """Fly RUN_DIR's plan: phasing, manoeuvres, a numerical replay against the debris
    (SGP4), and CCSDS OEM export, in RUN_DIR/flight/ (each mission of a campaign folder).
    Exit 3 when a flight is incomplete, late, missed or over its vehicle's tank (its files
    are written), or a plan over the tank is not flown."""
    fly_folder(Path(run_dir), force_model, quiet=quiet, catalog_path=catalog_path)


def fly_folder(folder: Path, force_model: str = "j2", *, quiet: bool = False,
               stdout: bool = True, after_run: bool = False,
               catalog_path=None) -> None:  # fmt: skip
    """Fly every plan of ``folder`` and write its ``flight/`` (exit on failure); the
    summary on stdout, or on stderr (``stdout=False``: ``run --json`` keeps stdout JSON).
    ``after_run``: ``run --fly`` has just written ``folder`` (a Ctrl-C says it is kept);
    ``catalog_path``: the catalog to fly against, not the one the scenario names."""
    from ..errors import SdcError
    from ..flight import fly, run_folder_plans
    from ..flight.result import flight_folder_problem

    def progress(line: str) -> None:
        if not quiet:
            click.echo(line, err=True)

    unflown = []  # (folder, status) of each flight not flown as planned
    flights = []
    try:
        with _flying(folder):
            plans = run_folder_plans(folder, catalog_path)
            for sub, _ in plans:  # before any flight: a folder of the user's is never replaced
                if (problem := flight_folder_problem(sub)) is not None:
                    fail(problem)
                if (problem := _unwritable(sub)) is not None:  # before the flight, not after
                    fail(f"cannot write {sub}/flight: {problem} (nothing was flown)",
                         SOLVER_FAILED)  # fmt: skip
            for sub, plan in plans:
                if plan.over_capacity is not None:  # never called flyable (as run --fly)
                    click.echo(f"not flown: {sub}: {plan.over_capacity}", err=True)
                    unflown.append((sub, "over_capacity"))
                    continue
                progress(f"flying {sub}: {' -> '.join(plan.catalog.frame['id'])}")
                for note in plan.notes:  # a catalog changed since the run
                    click.echo(f"warning: {note}", err=True)
                before = _plan_stamp(sub)
                flight = fly(plan, force=force_model, progress=progress)
                if _plan_stamp(sub) != before:  # another plan swapped in meanwhile
                    fail(f"{sub}/solution.json changed while its plan was flown (a run into "
                         "the folder?): the flight is not written (fly it again)")  # fmt: skip
                flight.save(sub)
                flights.append(flight)
                click.echo(flight.summary(), err=not stdout)
                click.echo(f"results   {sub / 'flight'}/", err=not stdout)
                if (said := flight.warning()) is not None:
                    click.echo(f"warning: {said} (flight.json: status {flight.status})",
                               err=True)  # fmt: skip
                    unflown.append((sub, flight.status))
    except SdcError as err:
        fail(str(err))
    except KeyboardInterrupt:
        kept = (f"the run folder {folder} is written, its flight is not (python -m sdc_cvx "
                f"fly {folder} flies it)" if after_run else "the flight folders written so "
                "far are kept, the one being written is not")  # fmt: skip
        fail(f"interrupted while flying: {kept}", INTERRUPTED)
    except OSError as err:
        fail(f"cannot write {folder}/flight: {err.strerror or err}", SOLVER_FAILED)
    if len(plans) > 1 and flights:  # a campaign: its totals, over the missions flown
        planned = sum(f.planned_dv_flown_mps for f in flights)
        flown = sum(f.flown_dv_mps for f in flights)
        click.echo(f"campaign  plan {planned:.2f} m/s, flown {flown:.2f} m/s "
                   f"({100 * (flown / planned - 1):+.2f} %) over the {len(flights)} of "
                   f"{len(plans)} missions flown", err=not stdout)  # fmt: skip
    if unflown:  # written, but never called flown: a script must not carry on
        which = ", ".join(f"{sub} {status}" for sub, status in unflown)
        fail(f"{len(unflown)} of {len(plans)} plan(s) not flown as planned ({which}); "
             "see the notes in each one's flight.json (solution.json for a plan not flown)",
             INFEASIBLE)  # fmt: skip


def warn_replaced_flights(out_dir) -> None:
    """Say, before the solve, that ``--out`` is an earlier folder that was flown: it is
    replaced whole, its ``flight/`` folders too (they flew its plan, not the next one)."""
    from ..errors import listing
    from ..report.out_folder import replaced_flights

    if flights := replaced_flights(out_dir):
        click.echo(f"warning: --out {out_dir} was flown: replacing it removes "
                   f"{listing(f'{name}/' for name in flights)} (flights of its earlier "
                   f"plan); python -m sdc_cvx fly {out_dir} flies the new one",
                   err=True)  # fmt: skip


def _unwritable(folder: Path) -> str | None:
    """Why nothing can be written in ``folder`` (a file tried there), or None."""
    try:
        with tempfile.TemporaryFile(dir=folder):
            return None
    except OSError as err:
        return err.strerror or str(err)


def _plan_stamp(folder: Path) -> tuple | None:
    """What identifies the plan in ``folder``: its ``solution.json``'s inode, size, time
    and bytes (None when there is none)."""
    path = folder / "solution.json"
    try:
        status = path.stat()
        return (status.st_ino, status.st_size, status.st_mtime_ns, path.read_bytes())
    except OSError:
        return None


@contextlib.contextmanager
def _flying(folder: Path):
    """An exclusive ``flock`` on ``folder`` while it is flown; exit 2 if another ``fly``
    holds it now (two flights would write the same ``flight/``)."""
    fd = os.open(folder, os.O_RDONLY)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            fail(f"another sdc_cvx fly is flying {folder} now: wait for it to end (two "
                 "flights would write the same flight/ folder)")  # fmt: skip
        yield
    finally:
        os.close(fd)
