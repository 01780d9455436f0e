"""Pre-optimised edge table: the paper's Table 6, filtering, and speed-independent checks."""

import numpy as np
import pandas as pd
import pytest

from sdc_cvx import Catalog, Mission, preoptimize
from sdc_cvx.network.edges import KEPT, TOO_COSTLY, TOO_SLOW
from sdc_cvx.physics.orbits import R_EARTH, SECONDS_PER_DAY
from sdc_cvx.physics.transfer import NodeOrbits, transfer_duration, transfer_dv

# Table 6: leg, departure day, drift a [km], drift inc [deg], dv [m/s] (61-day transfers)
TABLE_6 = [
    ("5", "8", 0.0, 7019.6, 98.7, 173.3),
    ("8", "2", 61.0, 6947.9, 98.7, 246.9),
    ("2", "10", 122.0, 7140.9, 98.9, 176.5),
    ("10", "6", 183.0, 7125.5, 98.9, 114.1),
]


@pytest.fixture(scope="module")
def paper():
    return Catalog.paper_case()


def table6_legs(paper, j2=None):
    mission = Mission() if j2 is None else Mission(j2=j2)
    day = np.zeros((11, 11))
    index = {k: n for n, k in enumerate(paper.ids)}
    for a, b, t, *_ in TABLE_6:
        day[index[a], index[b]] = t
    frame = preoptimize(paper, mission, departure_day=day).frame.set_index(["from_id", "to_id"])
    return frame.loc[[(a, b) for a, b, *_ in TABLE_6]]


def test_table_6_total_within_one_percent(paper):
    legs = table6_legs(paper)
    assert (legs["status"] == KEPT).all()
    assert legs["dv_mps"].sum() == pytest.approx(710.8, rel=0.01)
    # Each leg is pre-optimised with an active duration constraint: exactly 61 days.
    assert np.allclose(legs["duration_days"], 61.0)
    assert (legs["side"] == 1).all()  # all drift orbits below the targets (Part V-B)
    assert np.allclose(legs["drift_inc_deg"], [row[4] for row in TABLE_6])


def test_table_6_first_two_legs_within_one_percent(paper):
    legs = table6_legs(paper)
    for (_, _, _, a_km, _, dv), (_, row) in zip(TABLE_6[:2], legs.iloc[:2].iterrows(), strict=True):
        assert row["drift_a_km"] == pytest.approx(a_km, rel=1e-3)
        assert row["dv_mps"] == pytest.approx(dv, rel=0.01)


def test_table_6_last_two_legs_differ_and_why(paper):
    """Legs 2->10 and 10->6 differ by 2-5 % from Table 6 (180.6 vs 176.5, 108.2 vs 114.1 m/s).

    The reason is in the paper's inputs, not in the physics: at the drift radius the
    paper prints (7140.9 and 7125.5 km), Eq. 10 with Table 5's RAANs gives about 52
    days, not the 61 of Table 6, for both legs (gaps of 2.70 and 3.10 deg; 61 days would
    need about 3.2 and 3.6 deg).  No choice of J2 or of drift inclination closes it
    (checked for J2 = 1.0826e-3 and 1.086e-3, both inclinations), so Table 6 used RAANs
    for debris 2, 6, 10 that differ from Table 5.  The first two legs agree to 0.5 %.
    """
    legs = table6_legs(paper)
    orbits = NodeOrbits.from_elements(paper.a_m, paper.e, paper.inc_rad, paper.raan_rad)
    index = {k: n for n, k in enumerate(paper.ids)}
    for a, b, t, a_km, inc_deg, dv in TABLE_6[2:]:
        origin, target = orbits.take([index[a]]), orbits.take([index[b]])
        days = transfer_duration(
            origin, target, a_km * 1e3, np.deg2rad(inc_deg), t * SECONDS_PER_DAY
        )
        assert days[0] / SECONDS_PER_DAY == pytest.approx(52.0, abs=0.5)
        row = legs.loc[(a, b)]
        assert abs(row["dv_mps"] / dv - 1) > 0.01  # the documented difference is real
        assert row["dv_mps"] == pytest.approx(dv, rel=0.06)


def test_paper_j2_reproduces_table_6_radii_better(paper):
    """With the printed J2 = 1.086e-3 the first legs' radii match Table 6 closer
    (docs/design.md §3)."""
    ours, printed = table6_legs(paper), table6_legs(paper, j2=1.086e-3)
    for leg in range(2):
        paper_a = TABLE_6[leg][3]
        assert abs(printed["drift_a_km"].iloc[leg] - paper_a) < abs(
            ours["drift_a_km"].iloc[leg] - paper_a
        )


def test_edge_table_is_consistent_with_the_physics(paper):
    table = preoptimize(paper, Mission())
    kept = table.kept
    assert len(table.frame) == 11 * 10
    assert set(kept["status"]) == {KEPT}
    orbits = NodeOrbits.from_elements(paper.a_m, paper.e, paper.inc_rad, paper.raan_rad)
    o, t = orbits.take(kept["i"].to_numpy()), orbits.take(kept["j"].to_numpy())
    a, inc = kept["drift_a_km"].to_numpy() * 1e3, np.deg2rad(kept["drift_inc_deg"].to_numpy())
    assert np.allclose(transfer_dv(o.a, o.inc, t.a, t.inc, a, inc), kept["dv_mps"])
    days = transfer_duration(o, t, a, inc, 0.0) / SECONDS_PER_DAY
    assert np.all(days <= 61.0 + 1e-6)
    assert np.all((a >= R_EARTH + 400e3 - 1e-3) & (a <= R_EARTH + 1200e3 + 1e-3))


def test_statuses_follow_the_filters(paper):
    cheap = preoptimize(paper, Mission(dv_max_mps=200.0))
    assert (cheap.kept["dv_mps"] <= 200.0).all()
    costly = cheap.frame[cheap.frame["status"] == TOO_COSTLY]
    assert len(costly) > 0 and (costly["dv_mps"] > 200.0).all()
    slow = cheap.frame[cheap.frame["status"] == TOO_SLOW]
    assert slow["dv_mps"].map(np.isinf).all()
    # a longer T0 can only make more edges feasible
    longer = preoptimize(paper, Mission(preopt_days=120.0))
    assert longer.counts()[KEPT] > preoptimize(paper, Mission()).counts()[KEPT]
    assert "edges kept" in cheap.summary()


def test_ids_and_units(paper):
    frame = preoptimize(paper, Mission()).frame
    assert frame["from_id"].map(type).eq(str).all()
    assert {"drift_a_km", "drift_inc_deg", "duration_days", "dv_mps", "departure_day"} <= set(frame)
    assert isinstance(frame, pd.DataFrame)
