"""A plan that flies (issues 26, 46): phasing, manoeuvres, a numerical replay against the
real debris (SGP4, or GTOC9's own ephemeris), and CCSDS OEM export.

``fly(plan)`` flies a :class:`FlightPlan` (from a :class:`~sdc_cvx.solution.Solution` or a
run folder) and returns a :class:`Flight`, whose ``save(run_folder)`` writes ``flight/``.
Modules: :mod:`.plan` (what a flight needs of a plan; :mod:`.solution_file`, a run
folder's ``solution.json`` read), :mod:`.frames` (TEME, GCRF, the Earth's pole),
:mod:`.ephemeris` (the debris by SGP4; :mod:`.gtoc9_ephemeris`, GTOC9's),
:mod:`.propagation` (the vehicle by numerical integration; :mod:`.thrust`, a low-thrust
vehicle's thrust arcs; :mod:`.atmosphere`, drag's density), :mod:`.replay` (the flight;
:mod:`.guidance`, :mod:`.rendezvous` and :mod:`.targeting`, an impulsive leg in closed
loop; :mod:`.thrust_legs`, a low-thrust leg's, with :mod:`.corrections` and
:mod:`.thrust_corrections`; :mod:`.track`, :mod:`.mean_track` and :mod:`.rates`, the
vehicle's state and the mean elements measured), :mod:`.result` (its tables and files;
:mod:`.reopen`, a saved flight read back), :mod:`.oem` (CCSDS OEM), :mod:`.plot`
(``flight.png``).  The mean-element physics it needs (secular rates, phasing, impulses as
vectors) is in :mod:`sdc_cvx.physics`.
"""

from .plan import FlightError, FlightPlan, run_folder_plans, unflyable
from .replay import fly
from .result import Flight

__all__ = ["Flight", "FlightError", "FlightPlan", "fly", "run_folder_plans", "unflyable"]
