"""The brute forces' physics (``tests/paper_physics.py``, re-derived from the paper) against
the package's (``sdc_cvx.physics``), and both against the paper's printed numbers.

Two implementations written independently from Eq. 7-13 and Table 3 that agree to 1e-9 on a
few hundred random LEO inputs are the check of each other (issue 27): the brute forces use
the first, the solver the second.
"""

import ast
import itertools
from pathlib import Path

import numpy as np
import pytest

import tests.paper_physics as paper
from sdc_cvx.physics import orbits as pkg_orbits
from sdc_cvx.physics import transfer as pkg

RTOL = 1e-9
COUNT = 400
DAY = 86400.0
A_KM = (6778.0, 7578.0)  # 400-1200 km altitudes
INC_DEG = (0.0, 110.0)
E_MAX = 0.02


def random_orbits(rng, count=COUNT):
    """Elements (a [m], e, inc [rad], raan [rad]) of ``count`` random LEO debris."""
    return (
        rng.uniform(*A_KM, count) * 1e3,
        rng.uniform(0.0, E_MAX, count),
        np.radians(rng.uniform(*INC_DEG, count)),
        rng.uniform(0.0, 2.0 * np.pi, count),
    )


def both_node_orbits(elements):
    return paper.NodeOrbits.from_elements(*elements), pkg.NodeOrbits.from_elements(*elements)


def test_the_re_derivation_imports_nothing_of_the_package():
    tree = ast.parse(Path(paper.__file__).read_text(encoding="utf-8"))
    modules = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import)
               for alias in node.names}  # fmt: skip
    modules |= {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    assert not {m for m in modules if m and m.split(".")[0] == "sdc_cvx"}


def test_constants_are_the_packages():
    assert paper.R_EARTH == pkg_orbits.R_EARTH
    assert paper.MU == pkg_orbits.MU_EARTH
    assert paper.J2 == pkg_orbits.J2
    assert paper.SECONDS_PER_DAY == pkg_orbits.SECONDS_PER_DAY
    assert paper.CLOSED_GAP_RAD == pkg.CLOSED_GAP_RAD
    assert pytest.approx(1.318e18, rel=1e-3) == paper.C_J2  # printed below Eq. 7


# ---------------------------------------------------------------------------------------
# The two implementations agree
# ---------------------------------------------------------------------------------------


def test_raan_rates_agree():
    """Eq. 7 with the debris' eccentricity (NodeOrbits), and Eq. 8 for drift orbits."""
    rng = np.random.default_rng(27)
    elements = random_orbits(rng)
    ours, theirs = both_node_orbits(elements)
    np.testing.assert_allclose(ours.rate, theirs.rate, rtol=RTOL, atol=0)
    np.testing.assert_allclose(paper.raan_rate(*elements[:3]), theirs.rate, rtol=RTOL, atol=0)
    a, _, inc, _ = elements
    np.testing.assert_allclose(paper.drift_rate(a, inc), pkg.drift_rate(a, inc), rtol=RTOL, atol=0)
    assert ((ours.rate > 0) == (elements[2] > np.pi / 2)).all()  # retrograde: eastwards
    t = rng.uniform(0.0, 400.0, COUNT) * DAY
    np.testing.assert_allclose(ours.raan_at(t), theirs.raan_at(t), rtol=RTOL, atol=0)
    for field, other in zip(ours.take([3, 1]), theirs.take([3, 1]), strict=True):
        np.testing.assert_allclose(field, other, rtol=RTOL, atol=0)


def test_table_3_inclinations_agree():
    rng = np.random.default_rng(3)
    inc_from, inc_to = np.radians(rng.uniform(*INC_DEG, (2, COUNT)))
    inc_to[:20] = inc_from[:20]  # equal inclinations
    for side in (1.0, -1.0):
        np.testing.assert_array_equal(
            paper.drift_inclination(inc_from, inc_to, side),
            pkg.drift_inclination(inc_from, inc_to, side),
        )
    side = rng.choice([1.0, -1.0], COUNT)
    np.testing.assert_array_equal(
        paper.drift_inclination(inc_from, inc_to, side),
        pkg.drift_inclination(inc_from, inc_to, side),
    )


@pytest.mark.parametrize("rule", ["table3", "free", "any"])
def test_transfer_costs_agree(rule):
    """Eq. 11-13 for drift orbits below, between and above the two debris, both sides."""
    rng = np.random.default_rng(11)
    a_i, _, inc_i, _ = random_orbits(rng)
    a_j, _, inc_j, _ = random_orbits(rng)
    a_d = rng.uniform(*A_KM, COUNT) * 1e3
    a_d[:40] = a_i[:40]  # drift on the departure orbit
    a_d[40:80] = a_j[40:80]  # drift on the target's radius
    if rule == "table3":
        side = rng.choice([1.0, -1.0], COUNT)
        inc_d = paper.drift_inclination(inc_i, inc_j, side)
    elif rule == "free":
        inc_d = np.where(rng.random(COUNT) < 0.5, inc_i, inc_j)
    else:  # a plane change on both Hohmann transfers
        inc_d = np.radians(rng.uniform(*INC_DEG, COUNT))
    ours = paper.transfer_dv(a_i, inc_i, a_j, inc_j, a_d, inc_d)
    theirs = pkg.transfer_dv(a_i, inc_i, a_j, inc_j, a_d, inc_d)
    np.testing.assert_allclose(ours, theirs, rtol=RTOL, atol=0)
    low, high = np.minimum(a_i, a_j), np.maximum(a_i, a_j)
    assert (a_d < low).any() and ((a_d > low) & (a_d < high)).any() and (a_d > high).any()


def test_hohmann_transfers_agree():
    """Each half of Fig. 9, up and down, small and large plane changes, equal radii."""
    rng = np.random.default_rng(12)
    a_1, a_2 = rng.uniform(*A_KM, (2, COUNT)) * 1e3
    a_2[:30] = a_1[:30]
    di = np.radians(rng.uniform(0.0, 20.0, COUNT) * rng.choice([1e-3, 1.0], COUNT))
    ours = paper.hohmann(a_1, a_2, di)
    np.testing.assert_allclose(ours, pkg_orbits.hohmann_dv(a_1, a_2, di), rtol=RTOL, atol=0)
    np.testing.assert_allclose(ours, paper.hohmann(a_2, a_1, di), rtol=1e-12)  # symmetric


@pytest.mark.parametrize("wraps", [-3, -1, 0, 1, 3])
def test_transfer_durations_agree(wraps):
    """Eq. 10 on both sides of the asymptote, RAAN gaps of several turns, late departures."""
    rng = np.random.default_rng(100 + wraps)
    elements_i, elements_j = random_orbits(rng), random_orbits(rng)
    elements_j = (*elements_j[:3], elements_j[3] + 2.0 * np.pi * wraps)
    (o_ours, o_pkg), (t_ours, t_pkg) = both_node_orbits(elements_i), both_node_orbits(elements_j)
    a_d = rng.uniform(*A_KM, COUNT) * 1e3
    side = rng.choice([1.0, -1.0], COUNT)
    inc_d = paper.drift_inclination(o_ours.inc, t_ours.inc, side)
    t = rng.uniform(0.0, 400.0, COUNT) * DAY
    ours = paper.transfer_duration(o_ours, t_ours, a_d, inc_d, t)
    theirs = pkg.transfer_duration(o_pkg, t_pkg, a_d, inc_d, t)
    np.testing.assert_allclose(ours, theirs, rtol=RTOL, atol=0)
    relative = paper.drift_rate(a_d, inc_d) - t_ours.rate
    assert (relative > 0).sum() > COUNT / 4 and (relative < 0).sum() > COUNT / 4  # both sides
    # the duration closes the gap (Eq. 9), and within one relative turn
    closing = paper.raan_gap(o_ours, t_ours, t) - relative * ours
    assert np.allclose(np.cos(closing), 1.0, atol=1e-12, rtol=0)
    assert (ours * np.abs(relative) < 2.0 * np.pi).all()


def test_duration_conventions_agree():
    """Gaps of whole turns (and a rounding error off) take 0; on the asymptote, inf."""
    a, inc = 7100e3, np.radians(98.5)
    turn = 2.0 * np.pi
    gaps = [0.0, turn, -2 * turn, turn - 1e-12, 1e-12, -1e-12, 1e-3, turn - 1e-3, 1.0]
    for gap, a_d, inc_d in itertools.product(gaps, [a, 6900e3, 7300e3], [inc, np.radians(98)]):
        elements = ([a, a], [0.0, 0.0], [inc, inc], [0.0, gap])
        ours, theirs = both_node_orbits(elements)
        expected = pkg.transfer_duration(theirs.take(0), theirs.take(1), a_d, inc_d, 0.0)
        got = paper.transfer_duration(ours.take(0), ours.take(1), a_d, inc_d, 0.0)
        assert got == pytest.approx(expected, rel=RTOL), (gap, a_d, inc_d)
        if a_d == a and inc_d == inc:  # the target's own orbit: on the asymptote
            wrapped = gap % turn
            closed = min(wrapped, turn - wrapped) < paper.CLOSED_GAP_RAD
            assert got == (0.0 if closed else np.inf), gap


def test_broadcasting_as_the_brute_force_uses_it():
    """Departure dates (D, 1) against drift radii (K,), as ``Candidates.duration_days``."""
    rng = np.random.default_rng(5)
    (o_ours, o_pkg), (t_ours, t_pkg) = (both_node_orbits(random_orbits(rng, 1)) for _ in range(2))
    a_d = np.linspace(*A_KM, 50) * 1e3
    t = np.linspace(0.0, 365.0, 7)[:, None] * DAY
    ours = paper.transfer_duration(o_ours.take(0), t_ours.take(0), a_d, o_ours.inc[0], t)
    theirs = pkg.transfer_duration(o_pkg.take(0), t_pkg.take(0), a_d, o_pkg.inc[0], t)
    assert ours.shape == theirs.shape == (7, 50)
    np.testing.assert_allclose(ours, theirs, rtol=RTOL, atol=0)


# ---------------------------------------------------------------------------------------
# The paper's printed numbers
# ---------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("a_km", "inc_deg", "deg_per_day"),
    [(7000.0, 98.0, 1.002), (7200.0, 98.0, 0.908), (7000.0, 99.0, 1.126), (7200.0, 99.0, 1.020)],
)
def test_table_2_rates(a_km, inc_deg, deg_per_day):
    rate = paper.raan_rate(a_km * 1e3, 0.0, np.radians(inc_deg))
    assert np.degrees(rate) * DAY == pytest.approx(deg_per_day, abs=1e-3)


def test_sso_at_800_km_turns_once_a_year():
    """Part III-A/B: the typical SSO (800 km, 98.6 deg) precesses at 360 deg/year."""
    rate = paper.raan_rate(paper.R_EARTH + 800e3, 0.0, np.radians(98.6))
    assert np.degrees(rate) * DAY == pytest.approx(360.0 / 365.2422, abs=2e-3)


def test_part_3b_inclination_change():
    """Part III-B: a 1 deg inclination change at the 800 km SSO costs 130 m/s."""
    a = paper.R_EARTH + 800e3
    assert paper.hohmann(a, a, np.radians(1.0)) == pytest.approx(130.0, abs=0.5)


# Table 5 (a [km], e, inc [deg], RAAN [deg]) of the debris of Table 6's first two legs
TABLE_5 = {
    "2": (7055.3, 0.0001, 98.1, 188.3),
    "5": (7128.5, 0.0000, 98.4, 174.7),
    "8": (7200.0, 0.0001, 98.7, 180.3),
}


@pytest.mark.parametrize(
    ("leg", "day", "a_km", "inc_deg", "dv_mps"),
    [(("5", "8"), 0.0, 7019.6, 98.7, 173.3), (("8", "2"), 61.0, 6947.9, 98.7, 246.9)],
)
def test_table_6_first_legs(leg, day, a_km, inc_deg, dv_mps):
    """Table 6's drift orbits cost its ΔV and last its 61 days (first two legs: the last two
    do not follow from Table 5's RAANs, see ``tests/network/test_edges.py``).  The 0.3 %
    faster precession of the printed J2 = 1.086e-3 explains most of the 0.15 day and of
    the drift radius rounding; the tolerances are those of the printed digits."""
    (a_i, e_i, i_i, r_i), (a_j, e_j, i_j, r_j) = (TABLE_5[k] for k in leg)
    origin = paper.NodeOrbits.from_elements(a_i * 1e3, e_i, np.radians(i_i), np.radians(r_i))
    target = paper.NodeOrbits.from_elements(a_j * 1e3, e_j, np.radians(i_j), np.radians(r_j))
    inc_d = np.radians(inc_deg)
    assert paper.drift_rate(a_km * 1e3, inc_d) > target.rate  # below, faster: side +1
    assert paper.drift_inclination(origin.inc, target.inc, 1.0) == inc_d  # Table 3
    dv = paper.transfer_dv(origin.a, origin.inc, target.a, target.inc, a_km * 1e3, inc_d)
    assert dv == pytest.approx(dv_mps, rel=0.01)
    days = paper.transfer_duration(origin, target, a_km * 1e3, inc_d, day * DAY) / DAY
    assert days == pytest.approx(61.0, abs=0.5)
