"""The guidance's mean-element model (issue 46): states, impulses, secular J2.

The checks re-derive what they compare with: the vis-viva law for a tangential impulse,
the rotation of the plane by a normal one at a node, the textbook secular J2 rates
(Vallado, *Fundamentals of Astrodynamics*, 4th ed., Eq. 9-41, written again here), and
the scalar stage against the vectorised functions it mirrors.
"""

import numpy as np
import pytest

from sdc_cvx.physics.mean_elements import (
    INC,
    RAAN,
    U,
    advance,
    apply_impulse,
    mean_of,
    stage,
    state_of,
)

MU = 3.986004418e14
R_EQ = 6378137.0
J2 = 1.08262668e-3
CONSTS = {"j2": J2, "mu": MU, "r_eq": R_EQ}


def test_a_circular_state_has_the_radius_speed_and_plane_of_its_elements():
    a, inc, raan, u = 7178e3, np.radians(98.6), np.radians(40.0), np.radians(30.0)
    r, v = state_of(np.array([a, 0.0, 0.0, inc, raan, u]), mu=MU)
    assert np.linalg.norm(r) == pytest.approx(a, rel=1e-12)
    assert np.linalg.norm(v) == pytest.approx(np.sqrt(MU / a), rel=1e-12)
    h = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    assert np.degrees(np.arccos(h[2])) == pytest.approx(98.6, abs=1e-9)
    node = np.cross([0.0, 0.0, 1.0], h)
    assert np.degrees(np.arctan2(node[1], node[0])) == pytest.approx(40.0, abs=1e-9)
    # u: the angle from the node to r in the plane
    assert np.degrees(np.arccos(r @ node / (np.linalg.norm(r) * np.linalg.norm(node)))) == (
        pytest.approx(30.0, abs=1e-9))  # fmt: skip


def test_elements_survive_a_round_trip_with_their_revolutions():
    rng = np.random.default_rng(4)
    y = np.column_stack([rng.uniform(6.9e6, 7.4e6, 40), rng.uniform(-0.02, 0.02, 40),
                         rng.uniform(-0.02, 0.02, 40), rng.uniform(1.5, 1.9, 40),
                         rng.uniform(-3.0, 3.0, 40), rng.uniform(-500.0, 500.0, 40)])  # fmt: skip
    back = mean_of(*state_of(y, mu=MU), y[:, U], mu=MU)
    np.testing.assert_allclose(back[:, 0], y[:, 0], rtol=1e-12)
    np.testing.assert_allclose(back[:, 1:], y[:, 1:], atol=1e-10)


def test_a_tangential_impulse_changes_a_by_vis_viva():
    a, dv = 7178e3, 12.5
    y = np.array([a, 0.0, 0.0, 1.7, 0.3, 0.0])
    after = apply_impulse(y, np.array([0.0, dv, 0.0]), mu=MU)
    speed = np.sqrt(MU / a) + dv
    assert after[0] == pytest.approx(1.0 / (2.0 / a - speed**2 / MU), rel=1e-12)
    # the perigee where the burn was: e = (r v^2 / mu) - 1, along the node frame's x (u = 0)
    assert after[1] == pytest.approx(a * speed**2 / MU - 1.0, rel=1e-9)
    assert after[2] == pytest.approx(0.0, abs=1e-12)


def test_a_normal_impulse_at_the_node_turns_the_inclination_only():
    a, inc = 7178e3, np.radians(98.0)
    speed = np.sqrt(MU / a)
    turn = np.radians(0.3)  # at the ascending node: new velocity rotated about r
    dv_rtn = np.array([0.0, speed * (np.cos(turn) - 1.0), speed * np.sin(turn)])
    after = apply_impulse(np.array([a, 0.0, 0.0, inc, 1.0, 0.0]), dv_rtn, mu=MU)
    assert after[INC] == pytest.approx(inc + turn, abs=1e-12)
    assert after[RAAN] == pytest.approx(1.0, abs=1e-12)
    assert after[0] == pytest.approx(a, rel=1e-12)


def vallado_rates(a, e, inc):
    """RAAN, argument of perigee and mean anomaly rates [rad/s] (Eq. 9-41, again)."""
    n = np.sqrt(MU / a**3)
    factor = J2 * (R_EQ / (a * (1 - e**2))) ** 2
    return (-1.5 * n * factor * np.cos(inc), 0.75 * n * factor * (4 - 5 * np.sin(inc) ** 2),
            n + 0.75 * n * factor * np.sqrt(1 - e**2) * (2 - 3 * np.sin(inc) ** 2))  # fmt: skip


def test_advance_moves_the_node_perigee_and_latitude_at_the_secular_rates():
    a, e, inc, w = 7100e3, 0.01, np.radians(97.5), np.radians(20.0)
    y = np.array([a, e * np.cos(w), e * np.sin(w), inc, 0.2, 1.0])
    dt = 86400.0 * 10
    later = advance(y, dt, **CONSTS)
    raan_rate, argp_rate, m_rate = vallado_rates(a, e, inc)
    assert later[RAAN] - y[RAAN] == pytest.approx(raan_rate * dt, rel=1e-12)
    assert np.arctan2(later[2], later[1]) == pytest.approx(
        np.mod(w + argp_rate * dt + np.pi, 2 * np.pi) - np.pi, abs=1e-10)  # fmt: skip
    assert np.hypot(later[1], later[2]) == pytest.approx(e, rel=1e-12)
    assert later[U] - y[U] == pytest.approx((argp_rate + m_rate) * dt, rel=1e-12)
    # rate factors scale each rate (a flight's measured rates)
    scaled = advance(y, dt, (1.001, 1.0, 0.999), **CONSTS)
    assert scaled[RAAN] - y[RAAN] == pytest.approx(1.001 * raan_rate * dt, rel=1e-12)
    assert scaled[U] - y[U] == pytest.approx(0.999 * (argp_rate + m_rate) * dt, rel=1e-12)


@pytest.mark.parametrize("dt", [0.0, 3000.0, 1.5e7])
def test_the_scalar_stage_is_advance_then_the_impulse(dt):
    y = np.array([7.19e6, 1.2e-3, -3.1e-3, 1.72, -0.2, 1e4 - 2.6])
    dv = np.array([-0.3, 18.0, -9.5])
    rates = (0.9993, 1.0, 1.0000018)
    expected = apply_impulse(advance(y, dt, rates, **CONSTS), dv, mu=MU)
    np.testing.assert_allclose(stage(y, dt, dv, rates, **CONSTS), expected, rtol=1e-12,
                               atol=1e-9)  # fmt: skip
