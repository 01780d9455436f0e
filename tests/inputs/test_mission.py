"""Mission parameters: defaults of the paper and clear errors."""

import pytest

from sdc_cvx import Mission, MissionError
from sdc_cvx.inputs.mission import INJECTION_MIN_PERIGEE_KM
from sdc_cvx.physics.orbits import R_EARTH


def test_defaults_are_the_paper_case():
    m = Mission()
    assert (m.n, m.tmax_days, m.deorbit_days, m.drift_altitude_km) == (5, 365.25, 0.0, (400, 1200))
    assert m.preopt_days == 61.0  # "2 months" (Part V-B, Table 6: 61-day transfers)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"n": 1}, "n must be >= 2"),
        ({"n": 2.5}, "n must be an integer"),
        ({"tmax_days": 0}, "tmax_days must be > 0"),
        ({"preopt_days": -1}, "preopt_days must be > 0"),
        ({"deorbit_days": -1}, "deorbit_days must be >= 0"),
        ({"drift_altitude_km": (1200, 400)}, "0 < low < high"),
        ({"drift_altitude_km": (400,)}, "(low, high)"),
        ({"drift_inclination": "best"}, "drift_inclination must be one of"),
        ({"n": 5, "deorbit_days": 73.05}, "leaves no time for transfers"),  # 5 x 73.05 = Tmax
        ({"tmax_days": "365"}, "tmax_days must be a number"),
    ],
)
def test_invalid_missions_name_the_field(changes, message):
    with pytest.raises(MissionError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Mission(**changes)


def test_all_problems_reported_together():
    with pytest.raises(MissionError) as err:
        Mission(n=1, tmax_days=-3)
    assert "n must be" in str(err.value) and "tmax_days" in str(err.value)


def test_operations_at_every_debris_count_in_the_floor():
    """n operations (the last debris' too) plus n - 1 transfers must fit in T_max."""
    Mission(n=3, tmax_days=100.0, deorbit_days=30.0)  # 90 days of operations: legal
    with pytest.raises(MissionError, match="leaves no time"):
        Mission(n=3, tmax_days=100.0, deorbit_days=30.0, min_transfer_days=5.0)  # 90 + 10


def test_numpy_integers_are_integers():
    import numpy as np

    assert Mission(n=np.int64(4)).n == 4


def test_more_debris_than_candidates():
    with pytest.raises(MissionError, match="n = 5 exceeds the 4 candidate debris"):
        Mission().check_candidates(4)


def test_frozen_and_replace():
    m = Mission()
    with pytest.raises(AttributeError):
        m.n = 3
    assert m.replace(n=4).n == 4 and m.n == 5
    with pytest.raises(MissionError):
        m.replace(n=0)


def test_a_single_string_is_one_debris_id_not_its_characters():
    assert Mission(must_include="35").must_include == ("35",)
    assert Mission(exclude="10").exclude == ("10",)
    assert Mission(must_include=["3", "5"]).must_include == ("3", "5")


def test_a_deorbit_perigee_above_a_candidate_perigee_is_refused_before_any_solve():
    from sdc_cvx import Catalog, solve

    catalog = Catalog.paper_case()
    perigees = (catalog.a_m * (1 - catalog.e) - R_EARTH) / 1e3
    for km in (5000.0, float(perigees.min()) + 1.0):
        mission = Mission(n=3, deorbit_by="vehicle", deorbit_perigee_km=km)
        with pytest.raises(MissionError, match="deorbit_perigee_km .* is not below the perigee"):
            mission.check_candidates(catalog)
        with pytest.raises(MissionError, match="deorbit_perigee_km"):
            solve(catalog, mission)
    # the debris below it excluded: accepted; a kit needs no perigee
    low = [k for k, p in zip(catalog.ids, perigees, strict=True) if p <= perigees.min() + 1.0]
    Mission(n=3, deorbit_by="vehicle", deorbit_perigee_km=float(perigees.min()) + 1.0,
            exclude=low).check_candidates(catalog)  # fmt: skip
    Mission(n=3, deorbit_perigee_km=5000.0).check_candidates(catalog)


def test_the_vehicle_deorbit_cost_is_positive_at_every_debris():
    from sdc_cvx import Catalog
    from sdc_cvx.planner.nodes import MissionNodes

    catalog = Catalog.paper_case()
    perigees = (catalog.a_m * (1 - catalog.e) - R_EARTH) / 1e3
    mission = Mission(n=3, deorbit_by="vehicle", deorbit_perigee_km=float(perigees.min()) - 1.0)
    mission.check_candidates(catalog)
    assert (MissionNodes.of(catalog, mission).cost_mps > 0).all()


def test_an_injection_orbit_is_checked_like_a_catalog_orbit():
    from sdc_cvx.inputs.catalog import MIN_PERIGEE_KM

    assert INJECTION_MIN_PERIGEE_KM == MIN_PERIGEE_KM
    with pytest.raises(MissionError, match="below the Earth's surface"):
        Mission(injection=(7000.0, 0.1, 98.0, 0.0))
    with pytest.raises(MissionError, match="raan_deg must be an angle in"):
        Mission(injection=(7000.0, 0.001, 98.0, 1e308))
    Mission(injection=(7000.0, 0.001, 98.0, -30.0))
