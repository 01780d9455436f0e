"""The last impulses of a leg, targeted in the flight's own force model (issue 46, item 1).

A mean-element plan (:mod:`~sdc_cvx.flight.rendezvous`) brings the vehicle within
hundreds of metres of the debris; the rendezvous must be met within 100 m and 0.1 m/s.
So the approach is shot in the numerical model itself: from the vehicle's state at an
*approach* epoch three quarters of an orbit before the rendezvous (where an out-of-plane
impulse still moves the arrival point out of plane: one at a whole or half orbit before
would not), an approach impulse, the plan's impulses still to come before the rendezvous
(free vectors, fixed epochs) and the rendezvous epoch ``t_m`` (free) minimise

``|dv_approach| + sum |dv_k| + |v_debris(t_m) - v(t_m)|``  subject to  ``r(t_m) = r_debris(t_m)``,

the last term being the arrival impulse, which matches the debris' velocity exactly.
SLSQP with forward differences (each evaluation a propagation of under an orbit), then
Newton steps on the approach impulse alone until the arrival point is within
:data:`POSITION_TOL_M` (the velocity miss is zero by construction).

SI units throughout; states in the flight's frame.

References
----------
.. [1] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., Microcosm
   Press, 2013, §7.6 (targeting by differential correction).
.. [2] D. Kraft, "A software package for sequential quadratic programming",
   DFVLR-FB 88-28, 1988.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from ..physics.mean_elements import rtn_vectors
from .propagation import ForceModel, propagate

APPROACH_ORBITS = 0.75
"""The approach impulse this many orbits before the rendezvous."""
POSITION_TOL_M = 0.5
"""The arrival point's largest distance to the debris after the Newton steps [m]."""
NEWTON_STEPS = 8
SHOOT_ITERATIONS = 60
TIME_SCALE_S = 60.0
"""The rendezvous epoch's unit in the shooting [s]."""
MIN_COAST_S = 60.0
"""The rendezvous at least this long [s] after the impulse before it."""
DV_STEP, TIME_STEP = 1e-5, 1e-4
"""Forward-difference steps: of an impulse component [m/s], of the epoch [TIME_SCALE_S]."""


@dataclass(frozen=True)
class Approach:
    """The shot approach: the approach impulse [m/s] (3,) and the impulses to come before
    the rendezvous [m/s] (k, 3), as GCRF/flight-frame vectors, each applied in the
    direction it has here (not re-pointed along a turning local frame); the rendezvous
    epoch [s]; the arrival impulse [m/s] (3,) and the arrival point's distance [m]."""

    dv_approach: np.ndarray
    dv_between: np.ndarray
    t_arrive: float
    dv_arrive: np.ndarray
    miss_m: float

    @property
    def total_mps(self) -> float:
        between = np.linalg.norm(self.dv_between, axis=1).sum()
        return float(np.linalg.norm(self.dv_approach) + between + np.linalg.norm(self.dv_arrive))


def _to_frame(r, v, rtn):
    radial, transverse, normal = rtn_vectors(r, v)
    return rtn[0] * radial + rtn[1] * transverse + rtn[2] * normal


def shoot(r0, v0, t0: float, between_epochs, between_rtn, t_arrive: float, debris_state,
          force: ForceModel, pole, latest: float = np.inf) -> Approach:  # fmt: skip
    """Shoot the approach from ``(r0, v0)`` at ``t0`` [s] (module docstring).

    Parameters
    ----------
    r0, v0 : array_like
        The vehicle at the approach epoch ``t0`` (before the approach impulse).
    between_epochs, between_rtn : array_like
        The plan's impulses between ``t0`` and the rendezvous: epochs [s] (k,), RTN
        vectors [m/s] (k, 3) (at the planned state: the seed).
    t_arrive : float
        The planned rendezvous [s] (the seed).
    debris_state : callable
        ``debris_state(t) -> (r, v)`` of the debris [m, m/s].
    force, pole
        The flight's force model and pole.
    latest : float
        The rendezvous no later than this [s] (the leg's window).
    """
    r0, v0 = np.asarray(r0, dtype=float), np.asarray(v0, dtype=float)
    between_epochs = np.asarray(between_epochs, dtype=float).reshape(-1)
    k = len(between_epochs)

    def fly(dv_app, dvs, t_end):
        r, v, t = r0, v0 + dv_app, t0
        for epoch, dv in zip(between_epochs, dvs, strict=True):
            if epoch > t:
                arc = propagate(r, v, t, epoch, force, pole=pole)
                r, v, t = arc.r1, arc.v1, epoch
            v = v + dv
        arc = propagate(r, v, t, t_end, force, pole=pole)
        return arc.r1, arc.v1

    # the seed's impulses as frame vectors, at the states a coast with them would have
    seeds, r, v, t = [], r0, v0, t0
    for epoch, rtn in zip(between_epochs, np.asarray(between_rtn, float).reshape(k, 3),
                          strict=True):  # fmt: skip
        if epoch > t:
            arc = propagate(r, v, t, epoch, force, pole=pole)
            r, v, t = arc.r1, arc.v1, epoch
        seeds.append(_to_frame(r, v, rtn))
        v = v + seeds[-1]
    seeds = np.array(seeds).reshape(k, 3)

    def unpack(x):
        return x[:3], x[3 : 3 + 3 * k].reshape(k, 3), t_arrive + x[-1] * TIME_SCALE_S

    def outcome(x):
        dv_app, dvs, t_end = unpack(x)
        r, v = fly(dv_app, dvs, t_end)
        r_d, v_d = debris_state(t_end)
        return r - r_d, v_d - v

    cache: dict = {}

    def evaluate(x):
        key = x.tobytes()
        if key not in cache:
            miss, dv_end = outcome(x)
            _, dvs, _ = unpack(x)
            cost = (np.sqrt(x[:3] @ x[:3] + 1e-6) + np.sum(np.linalg.norm(dvs, axis=1))
                    + np.linalg.norm(dv_end))  # fmt: skip
            cache[key] = (cost, miss / 1000.0)
        return cache[key]

    steps = np.concatenate([np.full(3 + 3 * k, DV_STEP), [TIME_STEP]])

    def gradient(x, which):
        base = evaluate(x)[which]
        columns = []
        for i, h in enumerate(steps):
            xi = x.copy()
            xi[i] += h
            columns.append((evaluate(xi)[which] - base) / h)
        return np.array(columns).T

    x0 = np.concatenate([np.zeros(3), seeds.ravel(), [0.0]])
    half = 0.5 * _period(r0, v0, force)
    after = (max(between_epochs.max() if k else t0, t0) + MIN_COAST_S - t_arrive) / TIME_SCALE_S
    before = min(half, latest - t_arrive) / TIME_SCALE_S
    bounds = [(None, None)] * (3 + 3 * k) + [(min(max(-half / TIME_SCALE_S, after), before),
                                              max(before, after))]
    result = minimize(lambda x: evaluate(x)[0], x0, jac=lambda x: gradient(x, 0),
                      constraints=[{"type": "eq", "fun": lambda x: evaluate(x)[1],
                                    "jac": lambda x: gradient(x, 1)}],
                      bounds=bounds, method="SLSQP",
                      options={"maxiter": SHOOT_ITERATIONS, "ftol": 1e-6})  # fmt: skip
    x = result.x if np.all(np.isfinite(result.x)) else x0
    if np.linalg.norm(evaluate(x)[1]) * 1000.0 > np.linalg.norm(evaluate(x0)[1]) * 1000.0:
        x = x0  # SLSQP went astray: the Newton steps from the plan instead
    x = _newton(x, evaluate)
    dv_app, dvs, t_end = unpack(x)
    miss, dv_end = outcome(x)
    return Approach(dv_app, dvs, float(t_end), dv_end, float(np.linalg.norm(miss)))


def _newton(x, evaluate):
    """Newton steps on the approach impulse until the arrival point is within
    :data:`POSITION_TOL_M` (forward-difference Jacobian, 3 x 3)."""
    x = x.copy()
    for _ in range(NEWTON_STEPS):
        miss = evaluate(x)[1] * 1000.0
        if np.linalg.norm(miss) < POSITION_TOL_M:
            break
        jac = np.empty((3, 3))
        for i in range(3):
            xi = x.copy()
            xi[i] += 1e-3
            jac[:, i] = (evaluate(xi)[1] * 1000.0 - miss) / 1e-3
        x[:3] -= np.linalg.solve(jac, miss)
    return x


def _period(r, v, force: ForceModel) -> float:
    a = 1.0 / (2.0 / np.linalg.norm(r) - np.dot(v, v) / force.mu)
    return float(2.0 * np.pi * np.sqrt(a**3 / force.mu))
