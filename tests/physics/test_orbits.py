"""Orbit physics against the paper's Table 2, Part III-B and textbook formulas."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from sdc_cvx.physics.orbits import (
    MU_EARTH,
    R_EARTH,
    SECONDS_PER_DAY,
    circular_a_for_raan_rate,
    circular_speed,
    hohmann_dv,
    impulse,
    raan_rate,
    wrap_angle,
)

DEG_PER_DAY = np.rad2deg(1.0) * SECONDS_PER_DAY
radii = st.floats(R_EARTH + 200e3, R_EARTH + 2000e3)
angles = st.floats(0.0, 0.5)


@pytest.mark.parametrize(
    ("a_km", "inc_deg", "paper_deg_per_day"),
    [(7000, 98, 1.002), (7200, 98, 0.908), (7000, 99, 1.126), (7200, 99, 1.020)],
)
def test_raan_rate_matches_table_2(a_km, inc_deg, paper_deg_per_day):
    rate = raan_rate(a_km * 1e3, 0.0, np.deg2rad(inc_deg)) * DEG_PER_DAY
    assert rate == pytest.approx(paper_deg_per_day, rel=2e-3)


def test_raan_rate_sign_and_eccentricity_factor():
    retro = raan_rate(7000e3, 0.0, np.deg2rad(98.0))
    prograde = raan_rate(7000e3, 0.0, np.deg2rad(52.0))
    assert retro > 0 > prograde
    # Eq. 7: the rate scales as 1 / (1 - e^2)^2
    assert raan_rate(7000e3, 0.1, np.deg2rad(98.0)) == pytest.approx(retro / 0.99**2)


def test_paper_part_3b_order_of_magnitude():
    """Part III-B at H = 800 km: ΔH = 100 km costs about 50 m/s, ΔI = 1 deg about 130 m/s."""
    a = R_EARTH + 800e3
    assert hohmann_dv(a, a + 100e3) == pytest.approx(50.0, rel=0.05)
    assert hohmann_dv(a, a, np.deg2rad(1.0)) == pytest.approx(130.0, rel=0.01)


def test_hohmann_leo_to_geo_textbook():
    r1, r2 = R_EARTH + 300e3, 42164e3
    dv1 = np.sqrt(MU_EARTH / r1) * (np.sqrt(2 * r2 / (r1 + r2)) - 1)
    dv2 = np.sqrt(MU_EARTH / r2) * (1 - np.sqrt(2 * r1 / (r1 + r2)))
    assert hohmann_dv(r1, r2) == pytest.approx(dv1 + dv2, rel=1e-12)
    # plane change of 28.5 deg combined with the apogee impulse, naive Eq. 13 (large angle)
    v_apo = np.sqrt(MU_EARTH * (2 / r2 - 2 / (r1 + r2)))
    v_geo = np.sqrt(MU_EARTH / r2)
    di = np.deg2rad(28.5)
    dv2_plane = np.sqrt(v_apo**2 + v_geo**2 - 2 * v_apo * v_geo * np.cos(di))
    assert hohmann_dv(r1, r2, di) == pytest.approx(dv1 + dv2_plane, rel=1e-12)
    assert hohmann_dv(r2, r1, -di) == pytest.approx(dv1 + dv2_plane, rel=1e-12)


def test_impulse_accurate_for_tiny_angles():
    v = 7500.0
    assert impulse(v, v, 1e-9) == pytest.approx(v * 1e-9, rel=1e-9)
    # the naive law of cosines loses every digit here
    naive = np.sqrt(max(2 * v * v * (1 - np.cos(1e-9)), 0.0))
    assert abs(naive - v * 1e-9) > 1e-7


def test_impulse_equals_law_of_cosines_for_moderate_angles():
    va, vb, di = 7400.0, 7550.0, np.deg2rad(3.0)
    assert impulse(vb, va, di) == pytest.approx(np.sqrt(va**2 + vb**2 - 2 * va * vb * np.cos(di)))


@given(radii, radii, angles)
def test_hohmann_nonnegative_and_symmetric(a1, a2, di):
    dv = hohmann_dv(a1, a2, di)
    assert dv >= 0.0
    assert dv == pytest.approx(hohmann_dv(a2, a1, -di), rel=1e-12, abs=1e-9)


@given(radii)
def test_hohmann_zero_for_identical_orbits(a):
    assert hohmann_dv(a, a, 0.0) == 0.0


@given(radii, st.floats(1e-3, 0.3))
def test_hohmann_equal_radii_is_pure_plane_change(a, di):
    assert hohmann_dv(a, a, di) == pytest.approx(2 * circular_speed(a) * np.sin(di / 2), rel=1e-12)


@given(radii, st.floats(np.deg2rad(91), np.deg2rad(179)))
def test_circular_a_for_raan_rate_round_trips(a, inc):
    assert circular_a_for_raan_rate(raan_rate(a, 0.0, inc), inc) == pytest.approx(a, rel=1e-12)


def test_circular_a_for_raan_rate_nan_when_unreachable():
    # a retrograde orbit never precesses westwards
    assert np.isnan(circular_a_for_raan_rate(-1e-7, np.deg2rad(98.0)))


@given(st.floats(-20.0, 20.0))
def test_wrap_angle_ranges(angle):
    pos, neg = wrap_angle(angle, 1.0), wrap_angle(angle, -1.0)
    assert 0.0 <= pos <= 2 * np.pi  # 2 pi itself only by rounding of a tiny negative angle
    assert -2 * np.pi <= neg <= 0.0
    for wrapped in (pos, neg):
        assert np.cos(wrapped) == pytest.approx(np.cos(angle), abs=1e-9)
        assert np.sin(wrapped) == pytest.approx(np.sin(angle), abs=1e-9)
