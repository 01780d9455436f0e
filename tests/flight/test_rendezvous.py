"""The leg as an optimised rendezvous (issue 46): known optima and the targeting.

- Without J2, between two coplanar circular orbits with the target where a Hohmann
  transfer meets it, the optimised rendezvous is the Hohmann transfer: its cost is the
  textbook one written again here (Vallado, *Fundamentals*, 4th ed., Algorithm 36).
- The plan meets all six conditions (the phase on a whole revolution of the target).
- The targeting in the force model meets a debris within a metre and leaves no velocity
  difference, from an approach a kilometre off.
"""

import numpy as np
import pytest

from sdc_cvx.flight.propagation import ForceModel, propagate
from sdc_cvx.flight.rendezvous import LegProblem, paper_seeds, plan_leg
from sdc_cvx.flight.targeting import shoot
from sdc_cvx.physics.mean_elements import advance, apply_impulse, state_of

MU = 3.986004418e14
KEPLER = {"j2": 0.0, "mu": MU, "r_eq": 6378137.0}


def hohmann(r1, r2):
    """Both impulses of a Hohmann transfer [m/s] (vis-viva, written again)."""
    a_t = 0.5 * (r1 + r2)
    return (abs(np.sqrt(MU * (2 / r1 - 1 / a_t)) - np.sqrt(MU / r1))
            + abs(np.sqrt(MU / r2) - np.sqrt(MU * (2 / r2 - 1 / a_t))))  # fmt: skip


@pytest.mark.parametrize(("r1", "r2"), [(7000e3, 7100e3), (7200e3, 7150e3)])
def test_a_coplanar_rendezvous_without_j2_is_the_hohmann_transfer(r1, r2):
    inc, raan = np.radians(98.0), 0.4
    half = np.pi * np.sqrt((0.5 * (r1 + r2)) ** 3 / MU)
    n2 = np.sqrt(MU / r2**3)
    start = np.array([r1, 0.0, 0.0, inc, raan, 0.0])
    # the target where the vehicle, leaving now, arrives half a transfer orbit later
    target0 = np.array([r2, 0.0, 0.0, inc, raan, np.pi - n2 * half])

    def target(t):
        return advance(np.repeat(target0[None, :], len(t), axis=0), np.asarray(t), **KEPLER)

    problem = LegProblem(start, 0.0, target, 0.0, half + 600.0, consts=KEPLER)
    plan = plan_leg(problem, paper_seeds(problem, r2, inc, half))
    assert plan is not None and plan.converged
    assert plan.residual_km < 1e-3
    assert plan.total_mps == pytest.approx(hohmann(r1, r2), abs=0.02)


def test_a_plan_meets_the_target_on_a_whole_revolution():
    consts = {"j2": 1.08262668e-3, "mu": MU, "r_eq": 6378137.0}
    start = np.array([7178e3, 1e-3, 0.0, np.radians(98.6), 0.5, 0.3])
    target0 = np.array([7210e3, 0.0, 2e-3, np.radians(98.7), 0.5 - 0.02, 2.0])

    def target(t):
        return advance(np.repeat(target0[None, :], len(t), axis=0), np.asarray(t), **consts)

    days = 40 * 86400.0
    problem = LegProblem(start, 0.0, target, 0.0, days, consts=consts)
    plan = plan_leg(problem, paper_seeds(problem, 7150e3, np.radians(98.7), days - 3000.0))
    assert plan is not None and plan.converged
    # fly the plan in the model itself: the six elements equal, u to a whole turn
    y, now = start.copy(), 0.0
    for epoch, dv in zip(plan.epochs, plan.dv_rtn, strict=True):
        y = apply_impulse(advance(y, epoch - now, **consts), dv, mu=MU)
        now = epoch
    goal = target(np.array([now]))[0]
    assert abs(y[0] - goal[0]) < 1.0  # m
    np.testing.assert_allclose(y[1:5], goal[1:5], rtol=0, atol=1e-7)
    turns = (y[5] - goal[5]) / (2 * np.pi)
    assert turns == pytest.approx(round(turns), abs=1e-7)
    assert plan.epochs[-1] <= days + 1e-3 and np.all(np.diff(plan.epochs) >= 0)


def test_the_approach_meets_the_debris_within_a_metre():
    force = ForceModel.named("j2")
    pole = np.array([0.0, 0.0, 1.0])
    debris0 = state_of(np.array([7180e3, 0.0, 0.0, np.radians(98.6), 0.1, 0.0]), mu=MU)
    period = 2 * np.pi * np.sqrt(7180e3**3 / MU)

    def debris(t):
        arc = propagate(debris0[0], debris0[1], 0.0, t, force, pole=pole)
        return arc.r1, arc.v1

    t_meet = 3.0 * period
    # the vehicle: the debris' orbit a kilometre behind and 300 m below, 0.75 orbit before
    r, v = debris(t_meet - 0.75 * period)
    along = v / np.linalg.norm(v)
    r_vehicle = r - 1000.0 * along - 300.0 * r / np.linalg.norm(r)
    shot = shoot(r_vehicle, v, t_meet - 0.75 * period, [], np.zeros((0, 3)), t_meet, debris,
                 force, pole)  # fmt: skip
    assert shot.miss_m < 1.0
    arc = propagate(r_vehicle, v + shot.dv_approach, t_meet - 0.75 * period, shot.t_arrive,
                    force, pole=pole)  # fmt: skip
    r_d, v_d = debris(shot.t_arrive)
    assert np.linalg.norm(arc.r1 - r_d) < 1.0
    np.testing.assert_allclose(arc.v1 + shot.dv_arrive, v_d, atol=1e-9)
    # a kilometre over most of an orbit: tenths of a metre per second
    assert shot.total_mps < 2.0
