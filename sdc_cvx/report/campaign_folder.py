"""Writing a campaign's results to a folder, atomically (as a run folder is written).

A campaign folder::

    campaign.json      status, certified, total_dv_mps, lower_bound_mps, gap_rel,
                       greedy_dv_mps, start_utc, missions [{launch_day, path,
                       total_dv_mps, folder}], and more (CampaignSolution.to_dict)
    missions.csv       one row per mission
    history.csv        the bound and the plan after each step of the search
    campaign.log       the progress of the search (if given)
    scenario.toml      the scenario as used (if given)
    timeline.png, raan.png, dv.png, bound.png   the figures
    pareto.csv, pareto.png   with --pareto: campaigns of value against ΔV
    mission_01/ ...    one run folder per mission: its solution.json has the mission's
                       own start date (the campaign's plus its launch day) and its legs
                       from it; its run.log points to the campaign's log, its figures
                       say which mission they show

The whole folder is written aside and swapped in at once
(:func:`~sdc_cvx.report.run_folder.write_staged`): an earlier campaign folder (one with
``campaign.json``, ``campaign.log`` or ``missions.csv``) is replaced whole, any other
non-empty folder is refused.  An infeasible campaign gets a folder too, with
``campaign.json`` saying so and why (:func:`write_infeasible_campaign`).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from .atomic import write_atomic
from .out_folder import RUN_FOLDER_FILES, is_ours
from .run_folder import CSV_FLOAT_FORMAT, _write_files, write_staged

CAMPAIGN_FOLDER_MARKERS = ("campaign.json", "campaign.log", "missions.csv")
"""A folder holding one of these is an earlier campaign folder, which is replaced."""
CAMPAIGN_FIGURE_NAMES = ("timeline", "raan", "dv", "bound", "pareto")
"""The campaign's figures (:mod:`sdc_cvx.report.campaign_plots` draws them)."""
KIND = "campaign folder"


class _CampaignFiles:
    """What a campaign folder may hold: its files, and the mission folders its
    ``campaign.json`` lists, each holding only run-folder files.  An earlier campaign
    folder holding anything else (a file of the user's, in it or in a mission folder, or a
    mission folder it does not list) is refused rather than replaced."""

    names = frozenset(
        {"campaign.json", "campaign.log", "missions.csv", "history.csv", "scenario.toml",
         "pareto.csv"}
        | {f"{name}.{ext}" for name in CAMPAIGN_FIGURE_NAMES for ext in ("png", "svg", "pdf")}
    )

    def foreign(self, folder: Path) -> list[str]:
        """Paths in ``folder`` (relative to it) that sdc_cvx did not write."""
        listed = _listed_missions(folder)
        out = []
        for path in sorted(folder.iterdir()):
            if path.name in self.names and path.is_file():
                continue
            ours = (re.fullmatch(r"mission_\d{2,}", path.name) is not None and path.is_dir()
                    and (listed is None or path.name in listed))  # fmt: skip
            if not ours:
                out.append(path.name)
                continue
            out += [f"{path.name}/{inner.name}" for inner in sorted(path.iterdir())
                    if not is_ours(inner, RUN_FOLDER_FILES)]  # fmt: skip
        return out


def _mission_log(title: str, mission) -> str:
    """``run.log`` of a campaign's mission: what it is, and where its search is told."""
    start = mission.catalog.start if mission.catalog is not None else None
    when = f" ({start.isoformat()})" if start is not None else ""
    return (f"{title}{when}\n"
            "found by the campaign's search, not by a run of its own: the steps are in "
            "../campaign.log, the scenario in ../scenario.toml\n"
            f"{mission.summary()}\n")  # fmt: skip


def _listed_missions(folder: Path) -> set[str] | None:
    """The mission folders an earlier ``campaign.json`` lists (None if it cannot be read:
    then any ``mission_NN`` folder of run-folder files counts as one)."""
    path = folder / "campaign.json"
    if not path.is_file():  # absent, or a pipe that would block the read
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return {str(m["folder"]) for m in data.get("missions") or []}
    except (OSError, ValueError, TypeError, KeyError, AttributeError):
        return None


CAMPAIGN_FOLDER_FILES = _CampaignFiles()


def write_campaign(folder, solution, *, formats=("png",), scenario_toml: str | None = None,
                   log: str | None = None, edges: bool = True) -> list[Path]:  # fmt: skip
    """Write the campaign folder of ``solution`` (a ``CampaignSolution``), atomically.

    Parameters
    ----------
    folder : path-like
    solution : CampaignSolution
    formats : tuple of str
        Figure formats; empty for no figures (the missions' folders included).
    scenario_toml, log : str, optional
        ``scenario.toml`` and ``campaign.log``.
    edges : bool
        Write each mission's ``edges.csv`` (the pre-optimised edge table of its launch).

    Returns
    -------
    list of Path

    Raises
    ------
    FileExistsError
        ``folder`` is refused.
    OSError
        The folder cannot be written.
    """

    def fill(stage: Path) -> list[str]:
        names = []
        mission_files = []
        for entry, mission in zip(solution.to_dict()["missions"], solution.missions, strict=True):
            sub = stage / entry["folder"]
            sub.mkdir()
            table = None
            if edges:
                from ..network.edges import preoptimize

                table = preoptimize(mission.catalog, mission.mission,
                                    departure_day=mission.mission.deorbit_days)  # fmt: skip
            title = (f"mission {entry['folder'][-2:].lstrip('0')} of the campaign, launched on "
                     f"day {entry['launch_day']:g}")  # fmt: skip
            written = _write_files(sub, solution=mission, edges=table, scenario_toml=None,
                                   catalog=mission.catalog, formats=tuple(formats),
                                   log=_mission_log(title, mission), title=title)  # fmt: skip
            mission_files += [f"{entry['folder']}/{name}" for name in written]
        names += _write_texts(stage, {
            "missions.csv": solution.missions_frame().to_csv(
                index=False, float_format=CSV_FLOAT_FORMAT),
            "history.csv": solution.history_frame().to_csv(
                index=False, float_format=CSV_FLOAT_FORMAT),
        } | ({"pareto.csv": solution.pareto_frame().to_csv(
                index=False, float_format=CSV_FLOAT_FORMAT)} if solution.pareto else {}),
            scenario_toml, log)  # fmt: skip
        if formats:
            from .campaign_plots import save_campaign_figures  # matplotlib when drawn

            names += [p.name for p in save_campaign_figures(solution, stage, tuple(formats))]
        write_atomic(stage / "campaign.json", solution.to_json())
        return names + ["campaign.json"] + mission_files

    return write_staged(
        folder, fill, markers=CAMPAIGN_FOLDER_MARKERS, files=CAMPAIGN_FOLDER_FILES, kind=KIND
    )


def write_infeasible_campaign(folder, reason: str, *, start_utc: str | None,
                              campaign: dict | None = None, scenario_toml: str | None = None,
                              log: str | None = None) -> list[Path]:  # fmt: skip
    """A campaign folder for a proven infeasible campaign: ``campaign.json`` with status
    ``infeasible`` (certified: the proof is the certified search's), the reason, no
    missions; ``campaign.log`` and ``scenario.toml`` when given."""
    data = {
        "status": "infeasible",
        "certified": True,
        "total_dv_mps": None,
        "lower_bound_mps": None,
        "gap_mps": None,
        "gap_rel": None,
        "greedy_dv_mps": None,
        "start_utc": start_utc,
        "missions": [],
        "campaign": campaign,
        "reason": reason,
    }

    def fill(stage: Path) -> list[str]:
        text = json.dumps(data, indent=2, allow_nan=False)
        return _write_texts(stage, {"campaign.json": text}, scenario_toml, log)

    return write_staged(
        folder, fill, markers=CAMPAIGN_FOLDER_MARKERS, files=CAMPAIGN_FOLDER_FILES, kind=KIND
    )


def _write_texts(stage: Path, files: dict, scenario_toml: str | None, log: str | None):
    """Write ``files`` (name: text), ``scenario.toml`` and ``campaign.log`` when given;
    the names written."""
    files = dict(files)
    if scenario_toml is not None:
        files["scenario.toml"] = scenario_toml
    if log is not None:
        files["campaign.log"] = log
    for name, text in files.items():
        write_atomic(stage / name, text)
    return list(files)


def campaign_folder_problem(folder) -> str | None:
    """Why ``folder`` cannot take a campaign folder, or None (checked before the search)."""
    from .out_folder import out_folder_problem

    return out_folder_problem(Path(folder), CAMPAIGN_FOLDER_MARKERS, CAMPAIGN_FOLDER_FILES, KIND)
