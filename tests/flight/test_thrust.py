"""Thrust arcs in the propagator against the averaged laws they stand for (Gauss's
equations on a circular orbit, Edelbaum's plane change), written again here."""

import numpy as np
import pytest

from sdc_cvx.flight.propagation import ForceModel, propagate
from sdc_cvx.flight.thrust import Thrust
from sdc_cvx.flight.track import Track

MU = 3.986004418e14
R = 6378137.0
POLE = np.array([0.0, 0.0, 1.0])
F = 1e-4
KEPLER = ForceModel(j2=0.0)


def circular(a, inc, raan=0.3):
    """A circular orbit's state at its ascending node."""
    v = np.sqrt(MU / a)
    node = np.array([np.cos(raan), np.sin(raan), 0.0])
    along = np.array([-np.sin(raan) * np.cos(inc), np.cos(raan) * np.cos(inc), np.sin(inc)])
    return a * node, v * along


def elements(r, v):
    """Semi-major axis (vis-viva), eccentricity, inclination and RAAN of a state."""
    h = np.cross(r, v)
    a = 1.0 / (2.0 / np.linalg.norm(r) - np.dot(v, v) / MU)
    e = np.linalg.norm(np.cross(v, h) / MU - r / np.linalg.norm(r))
    return a, e, np.arccos(h[2] / np.linalg.norm(h)), np.arctan2(h[0], -h[1])


def test_tangential_thrust_raises_the_orbit_as_the_circular_speed_falls_linearly():
    a0, a1 = R + 700e3, R + 750e3
    r, v = circular(a0, np.radians(98.6))
    seconds = (np.sqrt(MU / a0) - np.sqrt(MU / a1)) / F  # dV/dt = -f on a quasi-circular spiral
    arc = propagate(r, v, 0.0, seconds, KEPLER, pole=POLE, thrust=Thrust(F, "tangential"))
    a, e, inc, raan = elements(arc.r1, arc.v1)
    assert a == pytest.approx(a1, abs=100.0)  # of a 50 km climb
    assert e < 1e-4
    assert inc == pytest.approx(np.radians(98.6), abs=1e-9)
    down = propagate(arc.r1, arc.v1, seconds, 2 * seconds, KEPLER, pole=POLE,
                     thrust=Thrust(F, "tangential", -1.0))  # fmt: skip
    assert elements(down.r1, down.v1)[0] == pytest.approx(a0, abs=100.0)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_out_of_plane_thrust_switched_at_the_antinodes_turns_the_inclination_only(sign):
    """di/dt = (2/pi) f / V on average (Edelbaum), the RAAN left where it was."""
    a, inc0 = R + 800e3, np.radians(60.0)
    r, v = circular(a, inc0)
    period = 2 * np.pi * np.sqrt(a**3 / MU)
    seconds = 20 * period
    arc = propagate(r, v, 0.0, seconds, KEPLER, pole=POLE, thrust=Thrust(F, "plane", sign))
    _, e, inc, raan = elements(arc.r1, arc.v1)
    expected = sign * 2.0 / np.pi * F / np.sqrt(MU / a) * seconds
    assert inc - inc0 == pytest.approx(expected, rel=2e-3)
    assert abs(raan - 0.3) < 1e-3 * abs(expected)
    assert e < 1e-4


@pytest.mark.parametrize("law", ["tangential", "plane"])
def test_the_scalar_right_hand_side_is_the_vectorised_acceleration(law):
    rng = np.random.default_rng(3)
    r = rng.normal(size=(5, 3)) * 7e6
    v = rng.normal(size=(5, 3)) * 7e3
    thrust = Thrust(F, law, -1.0)
    pole = np.array([0.1, -0.2, 1.0])
    rhs = thrust.added_to(lambda t, y: [y[3], y[4], y[5], 0.0, 0.0, 0.0], pole)
    scalar = np.array([rhs(0.0, np.concatenate([ri, vi]))[3:] for ri, vi in zip(r, v, strict=True)])
    assert scalar == pytest.approx(thrust.acceleration(r, v, pole / np.linalg.norm(pole)),
                                   rel=1e-12, abs=1e-18)  # fmt: skip
    assert np.linalg.norm(scalar, axis=1) == pytest.approx(F, rel=1e-12)


def test_a_thrust_arc_is_a_manoeuvre_of_its_acceleration_times_its_duration():
    r, v = circular(R + 700e3, np.radians(98.6))
    track = Track(0.0, r, v)
    arc = track.thrust(3600.0, Thrust(F, "tangential"), KEPLER, POLE, 1, "spiral_out")
    assert arc.dv_mps == pytest.approx(F * 3600.0, rel=1e-12)
    assert arc.end_s == 3600.0 and track.t == 3600.0 and len(track.segments) == 1
    assert arc.dv_rtn[1] == pytest.approx(F * 3600.0, rel=1e-3)  # along the velocity
    assert np.linalg.norm(arc.dv_gcrf) < arc.dv_mps  # the direction turns with the orbit
    assert track.thrust(3600.0, Thrust(F, "tangential"), KEPLER, POLE, 1, "x") is None


def eccentricity_vector(r, v):
    h = np.cross(r, v)
    return np.cross(v, h) / MU - r / np.linalg.norm(r)


def test_tangential_thrust_switched_by_a_direction_moves_the_eccentricity_along_it():
    """Gauss on a near-circular orbit: de/dt = 2 f_t r_hat / V; with f_t = f sign(r . d)
    the mean over an orbit is (4/pi) f / V along d, and a does not change."""
    a0 = R + 800e3
    r, v = circular(a0, np.radians(98.6))
    h = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    d = np.cross(h, r) / np.linalg.norm(np.cross(h, r))  # in the plane, 90 deg ahead
    seconds = 10 * 2 * np.pi * np.sqrt(a0**3 / MU)
    arc = propagate(r, v, 0.0, seconds, KEPLER, pole=POLE,
                    thrust=Thrust(F, "tangential", 1.0, tuple(d)))  # fmt: skip
    change = eccentricity_vector(arc.r1, arc.v1) - eccentricity_vector(r, v)
    expected = 4 / np.pi * F / np.sqrt(MU / a0) * seconds
    assert change @ d == pytest.approx(expected, rel=5e-3)
    assert np.linalg.norm(change - (change @ d) * d) < 0.02 * expected
    assert elements(arc.r1, arc.v1)[0] == pytest.approx(a0, abs=20.0)


def test_normal_thrust_switched_by_a_direction_turns_the_plane_towards_a_normal():
    """dh/dt = r x f: with f_n = f sign(r . (h x n)) the normal moves towards n at
    (2/pi) f / V [rad/s] on average."""
    a0 = R + 800e3
    r, v = circular(a0, np.radians(60.0))
    h = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    tilt = np.cross(h, [0.3, -0.5, 0.2])
    n = h + 0.05 * tilt / np.linalg.norm(tilt)
    n /= np.linalg.norm(n)
    towards = (n - (n @ h) * h) / np.linalg.norm(n - (n @ h) * h)
    seconds = 10 * 2 * np.pi * np.sqrt(a0**3 / MU)
    arc = propagate(r, v, 0.0, seconds, KEPLER, pole=POLE,
                    thrust=Thrust(F, "plane", 1.0, tuple(np.cross(h, towards))))  # fmt: skip
    h1 = np.cross(arc.r1, arc.v1) / np.linalg.norm(np.cross(arc.r1, arc.v1))
    turned = np.arccos(np.clip(h1 @ h, -1, 1))
    assert turned == pytest.approx(2 / np.pi * F / np.sqrt(MU / a0) * seconds, rel=5e-3)
    assert np.arccos(np.clip(h1 @ n, -1, 1)) < np.arccos(np.clip(h @ n, -1, 1)) - 0.9 * turned


def test_eccentricity_arcs_end_when_the_coast_has_no_more_room():
    """Found as a user: a GTOC9 low-thrust leg matched its eccentricity on a 7-day coast
    that needed 10 (measured from a circle, not from the vehicle's own eccentricity): the
    arcs went on past the coast's end and the leg arrived 2.3 deg of RAAN off, 1006 km
    away.  The arcs stop at ``until``, having moved e at (4/pi) f / V along the change."""
    from sdc_cvx.flight.thrust_corrections import eccentricity_change, thrust_eccentricity

    a0 = R + 800e3
    r, v = circular(a0, np.radians(98.6))
    track = Track(0.0, r, v)
    h = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    d = np.cross(h, r) / np.linalg.norm(np.cross(h, r))
    goal = 0.01 * d  # 5.6 days of thrust at 1e-4 m/s^2

    def wanted(t):
        return goal

    start = eccentricity_change(track, wanted, KEPLER, POLE)
    assert start == pytest.approx(goal, abs=1e-6)  # from a circle: all of it
    until = 2 * 86400.0
    arcs = thrust_eccentricity(track, 4, None, 4, F, KEPLER, POLE, wanted=wanted, until=until)
    assert track.t == pytest.approx(until) and arcs[-1].end_s == pytest.approx(until)
    moved = start - eccentricity_change(track, wanted, KEPLER, POLE)
    assert moved @ d == pytest.approx(4 / np.pi * F / np.sqrt(MU / a0) * until, rel=0.02)
    assert thrust_eccentricity(track, 4, None, 4, F, KEPLER, POLE, wanted=wanted,
                               until=until) == []  # fmt: skip
