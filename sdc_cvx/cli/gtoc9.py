"""``gtoc9-check FOLDER``: validate GTOC9 mission files as the competition did.

Exit 0 when every file is valid (one line per mission: debris, ΔV, m0, cost; then J),
1 on any rule broken, 2 when a file is unreadable (a malformed line included) or the
debris file cannot be read; each violation on stderr as ``FILE:LINE: RULE: message``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

from .exits import INPUT_ERROR, fail

RULES_BROKEN = 1


@click.command("gtoc9-check")
@click.argument("folder", type=click.Path(exists=True, file_okay=False))
@click.option("--debris", "debris_path", type=click.Path(dir_okay=False), default=None,
              help="GTOC9's debris file (debris.csv or debris_data.txt). Default: "
                   "$SDC_CVX_GTOC9_DEBRIS, else one in FOLDER or its parent, else the "
                   "project's shared data.")
@click.option("--all", "require_all", is_flag=True,
              help="Require every one of the 123 debris removed exactly once.")
@click.option("--dt-r", "dt_r", type=click.FloatRange(min=0.0), default=30.0, show_default=True,
              help="Δt_R [days]: most time between consecutive rendezvous of a mission, "
                   "measured from the arrival at a debris to the arrival at the next (the "
                   "stay included; see --dt-r-from).")
@click.option("--dt-r-from", type=click.Choice(["arrival", "departure"]), default="arrival",
              show_default=True,
              help="Measure Δt_R from the arrival at a debris (the stricter reading) or from "
                   "the departure from it (the transfer time alone).")
def gtoc9_check_command(folder, debris_path, require_all, dt_r, dt_r_from):
    """Check the GTOC9 mission files FOLDER/gtoc9/mission_*.txt (or FOLDER/mission_*.txt)
    against GTOC9's rules: each arc propagated in two-body + J2, rendezvous within 100 m
    and 1 m/s of GTOC9's ephemeris, stays >= 5 days, consecutive rendezvous <= Δt_R apart,
    missions >= 30 days apart within MJD2000 23467-26419, perigee >= 6600 km, launch mass
    m0 - 2000 kg <= 5000 kg, each debris at most once (--all: all 123 exactly once).
    Prints each mission's debris, ΔV, m0 and cost, then J = Σ [55 + 2e-6 (m0 - 2000)²]
    MEUR. Exit 0 valid, 1 a rule broken, 2 a file unreadable."""
    from ..errors import SdcError
    from ..gtoc9 import DebrisTable, Gtoc9Rules, check_folder, find_debris_file
    from ..gtoc9.check import mission_files

    if not mission_files(folder):
        fail(f"{folder}: no mission_*.txt file in it nor in its gtoc9/ sub-folder")

    path = Path(debris_path) if debris_path else find_debris_file(folder)
    try:
        debris = DebrisTable.read(path)
    except SdcError as err:
        fail(f"GTOC9 debris file: {err}")
    except OSError as err:
        fail(f"GTOC9 debris file {path}: cannot read it ({err}); give one with --debris")
    rules = Gtoc9Rules(dt_r_days=dt_r, dt_r_from=dt_r_from)
    report = check_folder(folder, debris, rules, require_all=require_all)
    for mission in report.missions:
        if mission.unreadable:
            click.echo(f"{Path(mission.file).name}: unreadable")
            continue
        ids = " ".join(map(str, mission.debris))
        click.echo(f"{Path(mission.file).name}: debris {ids}; ΔV {mission.dv_mps:.3f} m/s; "
                   f"m0 {mission.m0_kg:.3f} kg; cost {mission.cost_meur:.4f} MEUR")  # fmt: skip
    removed = sum(len(m.debris) for m in report.missions)
    click.echo(f"{len(report.missions)} missions, {removed} debris; J = "
               f"{report.cost_meur:.4f} MEUR")  # fmt: skip
    violations = report.all_violations
    for violation in violations:
        click.echo(f"error: {violation}", err=True)
    if violations:
        click.echo(f"{len(violations)} violation(s): not valid", err=True)
        sys.exit(INPUT_ERROR if report.unreadable else RULES_BROKEN)
    click.echo("valid")
