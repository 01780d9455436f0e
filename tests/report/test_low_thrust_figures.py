"""The figures of a low-thrust run (issue 29): the spirals drawn, the RAAN gap closed."""

import numpy as np

from sdc_cvx import Catalog, Mission, solve
from sdc_cvx.report.orbit_plots import raan_gap_history, vehicle_altitude


def test_the_raan_gap_closes_at_every_arrival_and_the_spirals_take_time():
    mission = Mission(n=3, transfer="low-thrust", vehicle={"accel_mps2": 1e-4})
    solution = solve(Catalog.paper_case(), mission)
    for (days, gap), leg in zip(raan_gap_history(solution, solution.catalog), solution.legs,
                                strict=True):  # fmt: skip
        assert abs(gap[-1]) < 1e-6  # the phases' RAAN (thrust and coast) closes the gap
        assert days[0] == leg.departure_day
    days, altitude = vehicle_altitude(solution, solution.catalog)
    for leg in solution.legs:  # the altitude leaves the debris over the spiral's days
        during = (days > leg.departure_day) & (days < leg.departure_day
                                               + leg.phases["spiral_out_days"])  # fmt: skip
        assert during.sum() >= 5 and np.all(np.diff(days) >= 0)


def test_every_figure_of_a_low_thrust_run_says_so_and_an_impulsive_one_does_not():
    """Found as a user: the orbits and cost figures of a low-thrust run read as the
    paper's impulsive ones."""
    mission = Mission(n=3, transfer="low-thrust", vehicle={"accel_mps2": 1e-4})
    drawn = solve(Catalog.paper_case(), mission).plot()
    assert drawn and all(fig.get_suptitle().startswith("low-thrust vehicle, 0.0001 m/s²")
                         for fig in drawn.values())  # fmt: skip
    paper = solve(Catalog.paper_case(), Mission(n=3)).plot()
    assert all(fig.get_suptitle() == "" for fig in paper.values())
