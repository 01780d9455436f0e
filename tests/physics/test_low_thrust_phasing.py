"""Phasing of the low-thrust leg (issue 26 for low-thrust plans) against the averaged
equations of motion integrated here with scipy, their rates written again from the
textbook (first-order secular J2, circular orbits; Vallado §9.6), nothing of the
package's physics imported to compute a reference."""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from sdc_cvx.physics.low_thrust_phasing import (
    low_thrust_leg_at,
    phase_low_thrust_leg,
    spiral_arglat,
)
from sdc_cvx.physics.phasing import MeanOrbit

R = 6378137.0
MU = 3.986e14
J2 = 1.08263e-3
DAY = 86400.0
F = 1e-4


def raan_rate(a, inc):
    """dOmega/dt [rad/s], circular (Eq. 7, e = 0)."""
    return -1.5 * J2 * np.sqrt(MU) * R**2 * a**-3.5 * np.cos(inc)


def arglat_rate(a, inc):
    """d(omega + M)/dt [rad/s], circular: n (1 + 3/2 J2 (R/a)^2 (4 cos^2 i - 1))."""
    n = np.sqrt(MU / a**3)
    return n * (1.0 + 1.5 * J2 * (R / a) ** 2 * (4.0 * np.cos(inc) ** 2 - 1.0))


def fly_averaged(a0, i0, raan0, u0, t0, phases):
    """Integrate (a, i, Omega, u) through ``phases``: (kind, seconds, goal) with kind
    "spiral" (tangential, da/dt = +-2 f sqrt(a^3/mu)), "plane" (di/dt = +-(2/pi) f/V) or
    "coast"; returns the state and the date at the end."""
    y, t = np.array([a0, i0, raan0, u0]), t0
    for kind, seconds, goal in phases:
        if seconds <= 0.0:
            continue
        sign = np.sign(goal - (y[0] if kind == "spiral" else y[1]))

        def rhs(_, s, kind=kind, sign=sign):
            a, i = s[0], s[1]
            da = sign * 2.0 * F * np.sqrt(a**3 / MU) if kind == "spiral" else 0.0
            di = sign * 2.0 / np.pi * F / np.sqrt(MU / a) if kind == "plane" else 0.0
            return [da, di, raan_rate(a, i), arglat_rate(a, i)]

        y = solve_ivp(rhs, (0.0, seconds), y, rtol=1e-12, atol=[1e-6, 1e-13, 1e-12, 1e-9],
                      method="DOP853").y[:, -1]  # fmt: skip
        t += seconds
    return y, t


def orbit(alt_km, inc_deg, raan_deg, arglat_deg):
    return MeanOrbit.from_elements(R + alt_km * 1e3, 0.0, np.radians(inc_deg),
                                   np.radians(raan_deg), np.radians(arglat_deg), j2=J2,
                                   mu=MU, r_eq=R)  # fmt: skip


def test_the_argument_of_latitude_of_a_spiral_is_its_rate_integrated_along_it():
    a0, a1, inc = R + 800e3, R + 700e3, np.radians(98.6)
    v0, v1 = np.sqrt(MU / a0), np.sqrt(MU / a1)
    seconds = (v1 - v0) / F

    def along(t):  # the circular speed is linear in time under tangential thrust
        return arglat_rate(MU / (v0 + F * t) ** 2, inc)

    expected = quad(along, 0.0, seconds, epsabs=0.0, epsrel=1e-13, limit=200)[0]
    assert spiral_arglat(a0, a1, inc, F, j2=J2, mu=MU, r_eq=R) == pytest.approx(expected,
                                                                              rel=1e-12)


@pytest.mark.parametrize(("origin", "target", "inc_rule"), [
    (orbit(800, 98.6, 10.0, 30.0), orbit(700, 98.0, 14.0, 250.0), "target"),
    (orbit(750, 98.2, 40.0, 300.0), orbit(850, 98.7, 37.0, 10.0), "origin"),
    (orbit(780, 98.4, 20.0, 0.0), orbit(780, 98.4, 23.0, 120.0), "coplanar"),
])  # fmt: skip
def test_a_phased_leg_flown_by_the_averaged_equations_meets_its_debris(origin, target,
                                                                       inc_rule):
    """The leg the phasing chooses, flown phase by phase (spiral A, plane change, coast,
    spiral D, the plane change where the coast's inclination puts it), arrives with the
    target's RAAN and argument of latitude at the date it says."""
    inc_drift = target.inc if inc_rule == "target" else origin.inc
    plan_a = 0.5 * (origin.a + target.a) + 30e3
    phased, in_time = phase_low_thrust_leg(origin, target, 2 * DAY, plan_a, inc_drift, F,
                                           a_bounds=(R + 400e3, R + 1200e3), j2=J2, mu=MU,
                                           r_eq=R)  # fmt: skip
    assert in_time and abs(phased.phase_error) < 1e-6
    assert phased.depart >= 2 * DAY and abs(phased.a_drift - plan_a) <= 12e3
    v_o, v_d, v_t = np.sqrt(MU / np.array([origin.a, phased.a_drift, target.a]))
    plane = [("plane", 0.5 * np.pi * v_d * abs(target.inc - origin.inc) / F, target.inc)]
    coast = [("coast", phased.coast_end - phased.coast_start, 0.0)]
    phases = [("spiral", abs(v_o - v_d) / F, phased.a_drift)]
    phases += plane + coast if inc_drift == target.inc else coast + plane
    phases.append(("spiral", abs(v_d - v_t) / F, target.a))
    y, t = fly_averaged(origin.a, origin.inc, origin.raan_at(phased.depart),
                        origin.arglat_at(phased.depart), phased.depart, phases)  # fmt: skip
    assert t == pytest.approx(phased.arrive, abs=1e-3)
    assert y[0] == pytest.approx(target.a, abs=1e-2)
    assert y[1] == pytest.approx(target.inc, abs=1e-9)

    def off(angle):
        return abs(np.mod(angle + np.pi, 2 * np.pi) - np.pi)

    assert off(y[2] - target.raan_at(t)) < 1e-7  # the RAAN closes
    assert off(y[3] - target.arglat_at(t)) < 1e-6  # and the vehicle is at the debris


def test_the_plan_point_is_the_leg_of_the_plan_and_its_phase_error_is_reported():
    origin, target = orbit(800, 98.6, 10.0, 30.0), orbit(700, 98.0, 14.0, 250.0)
    a_d = R + 780e3
    leg = low_thrust_leg_at(origin, target, 0.0, a_d, target.inc, F, j2=J2, mu=MU, r_eq=R)
    v = np.sqrt(MU / np.array([origin.a, a_d, target.a]))
    dv = abs(v[0] - v[1]) + 0.5 * np.pi * v[1] * abs(target.inc - origin.inc) + abs(v[1] - v[2])
    assert float(leg["dv"]) == pytest.approx(dv, rel=1e-12)
    assert float(leg["t_a"] + leg["t_b"] + leg["t_d"]) == pytest.approx(dv / F, rel=1e-12)
    assert -np.pi < float(leg["phase_error"]) <= np.pi


def test_no_phasing_within_the_brackets_is_an_error_not_a_wrong_leg():
    origin, target = orbit(800, 98.6, 10.0, 30.0), orbit(800, 98.6, 10.0, 200.0)
    with pytest.raises(ValueError, match="meets the target"):  # same plane: no coast at all
        phase_low_thrust_leg(origin, target, 0.0, origin.a, origin.inc, F, spans=(1.0,),
                             delays_days=(0.0,), j2=J2, mu=MU, r_eq=R)  # fmt: skip


def test_the_plane_change_goes_where_the_coast_inclination_says_even_off_by_a_little():
    """The plan's drift inclination is a catalog's; the flight's orbits are mean ones, a
    hundredth of a degree away: the coast at the target's inclination (the nearer) has
    its plane change first, else last (flown the other way, a 250-day coast at the wrong
    inclination turned the RAAN 3 degrees off: a 420 m/s correction)."""
    from sdc_cvx.physics.low_thrust_phasing import as_leg_plan

    origin, target = orbit(780, 98.78, 20.0, 0.0), orbit(790, 98.66, 23.0, 120.0)
    for drift, first in ((target.inc + 2e-4, True), (origin.inc - 2e-4, False)):
        leg = low_thrust_leg_at(origin, target, 0.0, R + 800e3, drift, F, j2=J2, mu=MU, r_eq=R)
        plan = as_leg_plan(origin, target, 0.0, R + 800e3, drift, leg)
        assert (plan.plane_start < plan.coast_start) is first
        assert plan.plane_seconds > 0 and plan.arrive > plan.coast_end
