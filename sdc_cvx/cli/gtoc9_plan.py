"""``gtoc9-plan SCENARIO.toml``: GTOC9's Kessler Run searched for its cost J (issue 47).

Reads a Kessler Run scenario (:mod:`sdc_cvx.gtoc9.scenario`), prices every leg on its
dates (:mod:`sdc_cvx.gtoc9.legs`), searches campaigns (:mod:`sdc_cvx.gtoc9.search`) and
writes the folder: ``plan.json`` (status, J, the lower bound and the gap, each mission's
debris, dates [MJD2000], leg ΔV, m0 and cost, the rules and the search's settings, the
seconds) and ``missions.csv`` (one row a mission).  Progress on stderr.  Exit 0 with a
campaign removing every debris, 3 when the search found none in its limits (``plan.json``
then holds the campaign that removed the most, status ``incomplete``), 2 invalid input.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import sys
import time
from pathlib import Path

import click

from .exits import INFEASIBLE, fail


@click.command("gtoc9-plan")
@click.argument("scenario_file", metavar="SCENARIO.toml", type=click.Path(dir_okay=False))
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Output folder [a new sdc_gtoc9_* folder here].")  # fmt: skip
@click.option("--time-limit", "time_limit_s", type=click.FloatRange(min=0.0, min_open=True),
              default=None, help="Seconds of search [the scenario's time_limit_s].")
@click.option("--fly", is_flag=True,
              help="Fly every planned mission leg by leg in GTOC9's dynamics and write "
                   "gtoc9/mission_NN.txt and campaign.json (then check them with gtoc9-check).")
@click.option("--workers", type=click.IntRange(min=1), default=None,
              help="Processes flying legs at once with --fly [one per core].")
@click.option("--quiet", is_flag=True, help="No progress, only the summary.")
def gtoc9_plan_command(scenario_file, out_dir, time_limit_s, fly, workers, quiet):
    """Plan GTOC9's Kessler Run: all debris removed by missions in sequence, at least J.

    SCENARIO.toml: [catalog] path (GTOC9's debris file), [campaign] objective =
    "gtoc9-cost" and remove_all = true, [rules] (GTOC9's constants, each its default),
    [search] (beam, day_price_mps, waits_days, launch_window_days, launch_step_days,
    max_debris, time_limit_s, rounds, prize_step_mps); see
    examples/gtoc9_kessler_run.toml.  Writes plan.json and missions.csv; with --fly also
    the GTOC9 mission files and campaign.json, every mission flown.  Exit 0 a complete
    campaign, 3 none found in the limits (the best incomplete one written, flown with
    --fly), 2 invalid input.
    """
    from ..errors import SdcError
    from ..gtoc9.legs import Gtoc9Legs
    from ..gtoc9.scenario import read_kessler_scenario
    from ..gtoc9.search import search_campaign

    started = time.perf_counter()
    try:
        scenario = read_kessler_scenario(scenario_file)
    except SdcError as err:
        fail(str(err))
    run = dict(scenario.run)
    if time_limit_s is not None:
        run["time_limit_s"] = time_limit_s
    out = Path(out_dir) if out_dir else Path(f"sdc_gtoc9_{time.strftime('%Y%m%d_%H%M%S')}")
    if out.exists() and not out.is_dir():
        fail(f"--out: {out} is a file, not a folder")

    def say(text: str) -> None:
        if not quiet:
            click.echo(text, err=True)

    try:
        legs = Gtoc9Legs.build(scenario.debris_path, rules=scenario.rules)
    except SdcError as err:
        fail(f"{scenario_file}: [catalog] {err}")
    except OSError as err:
        fail(f"{scenario_file}: [catalog] path: cannot read it ({err})")
    say(f"{legs.count} debris, {len(legs.origin)} legs priced "
        f"({time.perf_counter() - started:.0f} s)")
    campaign = search_campaign(legs, rules=scenario.rules, settings=scenario.settings,
                               time_limit_s=run["time_limit_s"], rounds=run["rounds"],
                               prize_step_mps=run["prize_step_mps"], say=say)  # fmt: skip
    seconds = time.perf_counter() - started
    summary = campaign.as_dict(scenario.rules, legs.start_mjd2000, legs.count)
    summary |= {"objective": "gtoc9-cost", "model": "impulsive drift legs, eccentricity priced "
                "(planned, not flown)", "seconds": round(seconds, 3),
                "scenario": str(scenario_file),
                "rules": dataclasses.asdict(scenario.rules),
                "search": dataclasses.asdict(scenario.settings) | run}  # fmt: skip
    out.mkdir(parents=True, exist_ok=True)
    (out / "plan.json").write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    with open(out / "missions.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["mission", "debris", "ids", "launch_mjd2000", "end_mjd2000", "dv_mps",
                         "m0_kg", "cost_meur"])  # fmt: skip
        for k, m in enumerate(campaign.missions, start=1):
            writer.writerow([k, len(m.debris), " ".join(map(str, m.debris)),
                             f"{legs.start_mjd2000 + m.launch:.6f}",
                             f"{legs.start_mjd2000 + m.end:.6f}", f"{m.dv:.3f}",
                             f"{m.m0(scenario.rules):.3f}", f"{m.cost(scenario.rules):.4f}"])
    if fly:
        _fly(campaign, legs.start_mjd2000, out, scenario.rules, workers, say)
    bound = summary["lower_bound_meur"]
    click.echo(f"{summary['status']}: {summary['removed']} of {legs.count} debris, "
               f"{len(campaign.missions)} missions, ΔV {campaign.dv:.0f} m/s, J = "
               f"{summary['J_meur']:.2f} MEUR (lower bound {bound:.2f}, gap "
               f"{100 * summary['gap']:.1f} %), {seconds:.0f} s; planned, not flown -> {out}")
    if summary["status"] != "complete":
        sys.exit(INFEASIBLE)


def _fly(campaign, start_mjd2000, out, rules, workers, say) -> None:
    """Fly each mission (:func:`sdc_cvx.gtoc9.flying.fly_mission`) and write the GTOC9
    folder (:func:`sdc_cvx.gtoc9.write_campaign`)."""
    import math
    from concurrent.futures import ProcessPoolExecutor

    from ..errors import SdcError
    from ..flight.guidance import GuidanceError
    from ..gtoc9 import write_campaign
    from ..gtoc9.flying import fly_mission

    flown = []
    with ProcessPoolExecutor(workers) as pool:
        for number, m in enumerate(campaign.missions, start=1):
            clock = time.perf_counter()
            seeds = [(a, inc) if math.isfinite(a) and math.isfinite(inc) else None
                     for a, inc in zip(m.a_drift, m.inc_drift, strict=True)]  # fmt: skip
            try:
                mission = fly_mission(m.debris, [start_mjd2000 + t for t in m.departures],
                                      [start_mjd2000 + t for t in m.arrivals], seeds,
                                      map=pool.map, rules=rules)  # fmt: skip
            except (SdcError, GuidanceError) as err:
                say(f"  mission {number} NOT flown: {err}")
                continue
            flown.append(mission.events)
            worst = max((leg.miss_m for leg in mission.legs), default=0.0)
            say(f"  mission {number} flown: {mission.dv_total_mps:.1f} m/s (planned "
                f"{m.dv:.1f}), m0 {mission.m0_kg:.1f} kg, worst miss {worst:.2f} m "
                f"({time.perf_counter() - clock:.0f} s)")  # fmt: skip
    if not flown:
        say("no mission flown: no GTOC9 mission file written")
        return
    if len(flown) < len(campaign.missions):
        say(f"{len(campaign.missions) - len(flown)} mission(s) not flown: the files hold the "
            "others, renumbered in order")  # fmt: skip
    path = write_campaign(out, flown, rules=rules)
    say(f"flown: {path}; check it with 'python -m sdc_cvx gtoc9-check {out}'")
