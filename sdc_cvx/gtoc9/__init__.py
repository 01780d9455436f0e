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
  :mod:`.debris` - its debris by id and MJD2000 epoch (:class:`DebrisTable`).

References
----------
.. [1] ESA Advanced Concepts Team, "GTOC9: The Kessler Run", problem, equations,
   constants and submission-format pages, https://kelvins.esa.int/gtoc9-kessler-run/ (2017).
"""

from .campaign_file import launch_mass, write_campaign
from .check import FolderReport, MissionReport, Violation, check_folder, check_mission
from .debris import DebrisTable, find_debris_file
from .from_flight import flight_events
from .mission_file import Event, read_mission_file, write_mission_file
from .rules import Gtoc9Rules

__all__ = [
    "DebrisTable",
    "Event",
    "FolderReport",
    "Gtoc9Rules",
    "MissionReport",
    "Violation",
    "check_folder",
    "check_mission",
    "find_debris_file",
    "flight_events",
    "launch_mass",
    "read_mission_file",
    "write_campaign",
    "write_mission_file",
]
