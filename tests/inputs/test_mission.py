"""Mission parameters: defaults of the paper and clear errors."""

import pytest

from sdc_cvx import Mission, MissionError


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
