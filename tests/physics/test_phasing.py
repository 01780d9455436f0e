"""Rendezvous phasing (issue 26, item 1): the phased leg arrives at the debris itself.

The checks re-derive the mean motion of the vehicle along the leg from the textbook J2
secular rates written again here (Vallado, *Fundamentals of Astrodynamics*, 4th ed.,
Eq. 9-41), not from :mod:`sdc_cvx.physics.elements`: the vehicle leaves at a node of its
orbit, reaches the opposite node after half a transfer orbit, coasts on the drift orbit
until the RAANs meet, leaves it at a node and arrives half a transfer orbit later, where
the target must be.
"""

import numpy as np
import pytest

from sdc_cvx.physics.orbits import hohmann_dv
from sdc_cvx.physics.phasing import MeanOrbit, _hohmann_impulses, phase_leg

MU = 3.986004418e14
R_EQ = 6378137.0
J2 = 1.08262668e-3
DAY = 86400.0


def rates(a, e, inc):
    """(RAAN rate, argument-of-latitude rate) [rad/s], Vallado Eq. 9-41, written again."""
    n = np.sqrt(MU / a**3)
    p = a * (1 - e**2)
    factor = J2 * (R_EQ / p) ** 2
    raan = -1.5 * n * factor * np.cos(inc)
    argp = 0.75 * n * factor * (4 - 5 * np.sin(inc) ** 2)
    mean_anomaly = n + 0.75 * n * factor * np.sqrt(1 - e**2) * (2 - 3 * np.sin(inc) ** 2)
    return raan, argp + mean_anomaly


def orbit(alt_km, inc_deg, raan_deg, arglat_deg):
    a, inc = R_EQ + 1e3 * alt_km, np.radians(inc_deg)
    raan_rate, arglat_rate = rates(a, 0.0, inc)
    return MeanOrbit(a, 0.0, inc, np.radians(raan_deg), np.radians(arglat_deg), raan_rate,
                     arglat_rate)  # fmt: skip


def half_transfer(r1, r2, inc):
    """Time [s] and RAAN drift [rad] of half a Hohmann ellipse (node to node)."""
    a_t, e_t = (r1 + r2) / 2, abs(r2 - r1) / (r1 + r2)
    raan_rate, arglat_rate = rates(a_t, e_t, inc)
    return np.pi / arglat_rate, raan_rate * np.pi / arglat_rate


def wrap(angle):
    return (angle + np.pi) % (2 * np.pi) - np.pi


@pytest.mark.parametrize(("r_from", "r_to", "plane"), [(7178e3, 7228e3, 0.01),
                                                        (7228e3, 7178e3, 0.02),
                                                        (7178e3, 7178e3, 0.003)])  # fmt: skip
def test_hohmann_impulses_add_up_to_the_transfer(r_from, r_to, plane):
    first, second, p1, p2 = _hohmann_impulses(np.array(r_from), np.array(r_to), np.array(plane),
                                              MU)  # fmt: skip
    assert first + second == pytest.approx(hohmann_dv(r_from, r_to, plane, mu=MU), rel=1e-12)
    # the plane change rides on the impulse at the higher radius (Eq. 13)
    assert (p2 if r_to >= r_from else p1) == plane and (p1 if r_to >= r_from else p2) == 0


@pytest.mark.parametrize(("drift_alt", "target_alt"), [(760.0, 850.0), (900.0, 850.0)])
def test_phased_leg_arrives_at_the_target(drift_alt, target_alt):
    origin = orbit(800.0, 98.6, 20.0, 57.0)
    target = orbit(target_alt, 98.7, 32.0, 300.0)
    t_ready = 3.0 * DAY
    a_plan, i_drift = R_EQ + 1e3 * drift_alt, np.radians(98.7)
    leg, in_time = phase_leg(origin, target, t_ready, a_plan, i_drift, j2=J2, mu=MU, r_eq=R_EQ)
    b1, b2, b3, b4 = leg.epochs
    assert in_time and b1 >= t_ready and b1 - t_ready < 2 * DAY
    assert abs(leg.a_drift - a_plan) < 12e3
    # b1 at a node of the origin
    u1 = origin.arglat + origin.arglat_rate * b1
    assert abs(wrap(2 * u1) / 2) < 1e-9
    # half a transfer orbit to the drift orbit (the plane change at the higher radius)
    up = leg.a_drift >= origin.a
    half_1, raan_1 = half_transfer(origin.a, leg.a_drift, origin.inc if up else i_drift)
    assert b2 - b1 == pytest.approx(half_1, rel=1e-9)
    drift_raan_rate, drift_arglat_rate = rates(leg.a_drift, 0.0, i_drift)
    # b3 at a node of the drift orbit, where the RAANs meet (to within a quarter orbit)
    u3 = u1 + np.pi + drift_arglat_rate * (b3 - b2)
    assert abs(wrap(2 * u3) / 2) < 1e-6
    raan_3 = origin.raan + origin.raan_rate * b1 + raan_1 + drift_raan_rate * (b3 - b2)
    gap = wrap(target.raan + target.raan_rate * b3 - raan_3)
    quarter_orbit = 0.5 * np.pi / drift_arglat_rate
    assert abs(gap) <= abs(drift_raan_rate - target.raan_rate) * quarter_orbit * 1.01
    assert gap == pytest.approx(leg.raan_residual, abs=1e-9)
    # and the vehicle arrives where the target is
    half_2, _ = half_transfer(leg.a_drift, target.a, i_drift if target.a >= leg.a_drift
                              else target.inc)  # fmt: skip
    assert b4 - b3 == pytest.approx(half_2, rel=1e-9)
    arrival = u3 + np.pi
    assert abs(wrap(target.arglat + target.arglat_rate * b4 - arrival)) < 1e-5
    # the phasing costs little against the leg it phases (kilometres of drift radius)
    assert leg.dv < 1.2 * (hohmann_dv(origin.a, a_plan, abs(i_drift - origin.inc), mu=MU)
                           + hohmann_dv(a_plan, target.a, abs(target.inc - i_drift), mu=MU))


def test_a_leg_that_must_arrive_earlier_pays_for_it():
    origin = orbit(800.0, 98.6, 20.0, 57.0)
    target = orbit(850.0, 98.7, 32.0, 300.0)
    a_plan, i_drift = R_EQ + 760e3, np.radians(98.7)
    free, _ = phase_leg(origin, target, 0.0, a_plan, i_drift, j2=J2, mu=MU, r_eq=R_EQ)
    soon = free.epochs[3] - 2 * DAY
    rushed, in_time = phase_leg(origin, target, 0.0, a_plan, i_drift, latest_arrival=soon,
                                j2=J2, mu=MU, r_eq=R_EQ)  # fmt: skip
    assert in_time and rushed.epochs[3] <= soon
    assert rushed.dv > free.dv  # faster drift: farther from the target's altitude


def test_a_leg_with_no_drift_phases_by_moving_its_drift_orbit():
    """The plan's zero-length legs (the RAANs meet at once) phase too: the drift orbit is
    the departure orbit, so only a drift radius far from it moves the arrival's phase."""
    origin = orbit(825.0, 98.85, 20.0, 0.0)
    target = orbit(802.0, 98.87, 20.0, 250.0)
    leg, in_time = phase_leg(origin, target, 0.0, origin.a, np.radians(98.85),
                             latest_arrival=60 * DAY, j2=J2, mu=MU, r_eq=R_EQ)  # fmt: skip
    assert in_time and leg.epochs[3] <= 60 * DAY
    assert abs(leg.phase_error) < 1e-5
    assert abs(leg.a_drift - origin.a) > 12e3  # beyond the first bracket


@pytest.mark.parametrize("days_early", [0.0, 2.0, None])
def test_brackets_left_unrefined_hold_no_leg_in_time(monkeypatch, days_early):
    """Only the brackets of radii that may arrive in time are refined (the rest only if
    none does): the leg chosen is the one that refining every bracket chooses, whether
    the plan's own arrival is in time, one two days earlier, or none can be (an hour
    after the start: the least ΔV plus lateness of all)."""
    import sdc_cvx.physics.phasing as phasing

    origin = orbit(800.0, 98.6, 20.0, 57.0)
    target = orbit(850.0, 98.7, 32.0, 300.0)
    a_plan, i_drift = R_EQ + 760e3, np.radians(98.7)
    free, _ = phase_leg(origin, target, 0.0, a_plan, i_drift, j2=J2, mu=MU, r_eq=R_EQ)
    latest = 3600.0 if days_early is None else free.epochs[3] - days_early * DAY
    options = dict(latest_arrival=latest, j2=J2, mu=MU, r_eq=R_EQ, nodes=8)
    lazy, lazy_in_time = phase_leg(origin, target, 0.0, a_plan, i_drift, **options)
    monkeypatch.setattr(phasing, "ARRIVAL_SLACK_S", np.inf)  # every bracket refined
    every, every_in_time = phase_leg(origin, target, 0.0, a_plan, i_drift, **options)
    assert lazy_in_time == every_in_time == (days_early is not None)
    assert lazy.node == every.node and lazy.a_drift == every.a_drift
    np.testing.assert_array_equal(lazy.epochs, every.epochs)
