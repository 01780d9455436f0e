"""GTOC9 ("The Kessler Run") mission files and their validation (issue 47, item 4).

- :mod:`.mission_file` - the competition's event format: :class:`Event`,
  :func:`write_mission_file`, :func:`read_mission_file`; :mod:`.campaign_file` - a
  campaign folder (:func:`write_campaign`: ``gtoc9/mission_NN.txt`` and ``campaign.json``);
  :mod:`.from_flight` - a flown mission's events (:func:`flight_events`);
- :mod:`.flying` - missions flown leg by leg in GTOC9's dynamics (:func:`~.flying.fly_leg`,
  :func:`~.flying.fly_mission`: the paper's drift leg as seed, the flight's guidance,
  the arrival targeted in GTOC9's ODE);
- :mod:`.check` - :func:`check_folder` / :func:`check_mission`, every rule re-checked as
  the competition did (its docstring states the readings of the ambiguous ones);
- :mod:`.rules` - GTOC9's constants (:class:`Gtoc9Rules`); :mod:`.dynamics` - its ODE;
  :mod:`.debris` - its debris by id and MJD2000 epoch (:class:`DebrisTable`);
- the Kessler Run searched for its cost J (items 1-3): :mod:`.scenario` - the problem as
  a scenario file (:func:`read_kessler_scenario`); :mod:`.legs` - every leg priced on its
  two dates (:class:`Gtoc9Legs`); :mod:`.search` - missions by beam search, campaigns
  mission after mission (:func:`search_campaign`), a lower bound of J; :mod:`.repair` -
  debris a campaign left, inserted; :mod:`.plan` - what is planned
  (:class:`PlannedMission`, :class:`PlannedCampaign`, the mass chain).

References
----------
.. [1] ESA Advanced Concepts Team, "GTOC9: The Kessler Run", problem, equations,
   constants and submission-format pages, https://kelvins.esa.int/gtoc9-kessler-run/ (2017).
"""

from .campaign_file import launch_mass, write_campaign
from .check import FolderReport, MissionReport, Violation, check_folder, check_mission
from .debris import DebrisTable, find_debris_file
from .from_flight import flight_events
from .legs import Gtoc9Legs
from .mission_file import Event, read_mission_file, write_mission_file
from .plan import PlannedCampaign, PlannedMission, chain_mass
from .repair import insert_left
from .rules import Gtoc9Rules
from .scenario import KesslerScenario, read_kessler_scenario
from .search import SearchSettings, lower_bound, plan_campaign, plan_mission, search_campaign

__all__ = [
    "DebrisTable",
    "Event",
    "FolderReport",
    "Gtoc9Legs",
    "Gtoc9Rules",
    "KesslerScenario",
    "MissionReport",
    "PlannedCampaign",
    "PlannedMission",
    "SearchSettings",
    "Violation",
    "check_folder",
    "chain_mass",
    "check_mission",
    "find_debris_file",
    "flight_events",
    "insert_left",
    "launch_mass",
    "lower_bound",
    "plan_campaign",
    "plan_mission",
    "read_kessler_scenario",
    "read_mission_file",
    "search_campaign",
    "write_campaign",
    "write_mission_file",
]
