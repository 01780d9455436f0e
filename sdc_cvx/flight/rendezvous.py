"""A leg as an optimised multi-impulse rendezvous in mean elements (issue 46, item 1).

The problem: from the vehicle's mean elements ``y0`` at ``t0``, ``m`` impulses at free
epochs ``t1 <= ... <= tm`` with free RTN vectors, the last one the rendezvous, minimise
their total ``sum |dv_k|`` such that after the last one the vehicle's mean elements are the
target's at ``tm`` (:class:`~sdc_cvx.flight.mean_track.DebrisTrack`): semi-major axis,
eccentricity vector, inclination, RAAN and argument of latitude, the last modulo whole
revolutions (the *branch*: which revolution of the target the vehicle meets).  Between
impulses the model is secular J2 (:mod:`sdc_cvx.physics.mean_elements`).  What the
paper's leg fixes (circular drift orbit, plane change at the higher-radius impulse, nodes)
is free here: the drift orbit may be eccentric and tilted (the drift inclination moves the
phase at fixed RAAN closure, issue 46), the plane change split between the burns, the
eccentricity changed inside the large burns where it costs at second order.

Solved by SLSQP (Kraft [1]_, ``scipy.optimize.minimize``) with forward-difference
gradients computed as one batch of the vectorised model; each ``|dv|`` smoothed as
``sqrt(|dv|^2 + eps^2) - eps`` (eps = 1 cm/s) where an impulse vanishes.  Variables:
the gaps between epochs in units of ``1/n`` (a radian of the orbit) and the impulses in
m/s; the terminal residual in km (``a``, ``a de``, ``a di``, ``a sin i dRAAN``,
``a du``).  A plan is found in two stages (:func:`plan_leg`): without the phase (five
conditions), from the paper's leg as seed; then with the phase, on the nearest branches
of the first stage's phase error, keeping the cheapest.  A re-plan (:func:`replan`)
starts from the remaining impulses of a plan, on its branch.

All SI (m, m/s, rad, s).

References
----------
.. [1] D. Kraft, "A software package for sequential quadratic programming",
   DFVLR-FB 88-28, 1988.
.. [2] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013
   (the drift leg, Part III).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize

from ..physics.impulses import plane_towards, plane_with_inclination
from ..physics.mean_elements import (
    EX,
    EY,
    INC,
    RAAN,
    TWO_PI,
    UNIT_RATES,
    U,
    advance,
    apply_impulse,
    rates_of,
    rtn_vectors,
    stage,
    state_of,
    wrap,
)

SMOOTH_MPS = 0.01
"""Smoothing of ``|dv|`` near zero [m/s]."""
STEP_TIME, STEP_DV = 1e-5, 1e-6
"""Forward-difference steps: of an epoch [1/n, about 1 ms], of an impulse [m/s]."""
MAX_ITERATIONS = 150
"""SLSQP iterations of one solve (the plans of README's flights take 30 to 90)."""
FTOL = 1e-7
"""SLSQP's precision goal on the total [m/s]."""
RESIDUAL_KM = 1e-3
"""Largest terminal residual [km] of a converged plan."""
BRANCHES = 1
"""Branches tried on each side of the first stage's nearest one."""
KEEP_MPS = 10.0
"""Seeds whose first stage is within this of the cheapest [m/s] are phased too (phasing
costs tenths of m/s at the optimum, issue 46: the first stage ranks the seeds)."""
SINGULAR = 6
"""SLSQP's status for dependent equality conditions at its start ("singular matrix C")."""
_POLE = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class LegProblem:
    """A rendezvous in mean elements (module docstring).

    Attributes
    ----------
    start : ndarray
        The vehicle's mean elements at ``t_start`` (6,).
    t_start : float
        Now [s].
    target : callable
        ``target(t)`` with ``t`` (B,) [s]: the target's mean elements (B, 6).
    earliest, latest : float
        Window of the last impulse, the rendezvous [s].
    rates : tuple of float
        Rate factors of the vehicle's orbits (:func:`~sdc_cvx.physics.mean_elements.advance`).
    first_fixed : bool
        The first impulse at ``t_start`` (a departure from a debris, a trim now).
    consts : dict
        ``j2``, ``mu``, ``r_eq`` of the model.
    """

    start: np.ndarray
    t_start: float
    target: Callable[[np.ndarray], np.ndarray]
    earliest: float
    latest: float
    rates: tuple = UNIT_RATES
    first_fixed: bool = True
    consts: dict = field(default_factory=dict)

    @property
    def time_unit(self) -> float:
        """1/n of the starting orbit [s]: the unit of the gaps between epochs."""
        return float(np.sqrt(self.start[0] ** 3 / self.consts.get("mu", 3.986004418e14)))


@dataclass(frozen=True)
class LegPlan:
    """A solved rendezvous: impulse epochs [s] (m,), RTN vectors [m/s] (m, 3), their total
    [m/s], the branch (revolutions of the phase condition), the terminal residual [km] and
    whether SLSQP converged with the residual below :data:`RESIDUAL_KM`."""

    epochs: np.ndarray
    dv_rtn: np.ndarray
    total_mps: float
    branch: float
    residual_km: float
    converged: bool

    def remaining(self, after: float) -> LegPlan:
        """The impulses after ``after`` [s]."""
        keep = self.epochs > after
        return LegPlan(self.epochs[keep], self.dv_rtn[keep], float(np.linalg.norm(
            self.dv_rtn[keep], axis=1).sum()), self.branch, self.residual_km, self.converged)


class _Model:
    """The leg of a :class:`LegProblem` with ``m`` impulses, as functions of the variables
    ``x`` (module docstring), with their gradients: a chain of scalar stages
    (:func:`~sdc_cvx.physics.mean_elements.stage`), each variable's forward difference
    recomputed from its own stage on (an impulse changes nothing before it)."""

    def __init__(self, problem: LegProblem, m: int):
        self.p, self.m = problem, m
        self.unit = problem.time_unit
        self.consts = {k: problem.consts[k] for k in ("j2", "mu", "r_eq") if k in problem.consts}
        self.h = np.concatenate([np.full(m, STEP_TIME), np.full(3 * m, STEP_DV)])
        self._key, self._value, self._grad_key, self._grad = None, None, None, None

    def unpack(self, x):
        """Epochs [s] (m,) and RTN impulses [m/s] (m, 3) of ``x``."""
        x = np.asarray(x, dtype=float)
        return self.p.t_start + np.cumsum(x[: self.m] * self.unit), x[self.m :].reshape(self.m, 3)

    def _lists(self, x):
        """Epochs (the start first) and impulses of ``x`` as plain lists of floats."""
        epochs = [self.p.t_start]
        for gap in x[: self.m]:
            epochs.append(epochs[-1] + float(gap) * self.unit)
        dv = np.asarray(x[self.m :], dtype=float).reshape(self.m, 3).tolist()
        return epochs, dv

    def _run(self, epochs, dv, start: int, states):
        """``states`` (after each impulse, the start first) redone from stage ``start``."""
        states = states[: start + 1]
        for k in range(start, self.m):
            states.append(stage(states[k], epochs[k + 1] - epochs[k], dv[k], self.p.rates,
                                **self.consts))  # fmt: skip
        return states

    def _chain(self, x):
        epochs, dv = self._lists(x)
        return self._run(epochs, dv, 0, [tuple(self.p.start)]), epochs

    def _residuals(self, finals, last_epochs, branch, phase):
        y = np.asarray(finals, dtype=float)
        goal = self.p.target(np.asarray(last_epochs, dtype=float))
        a = goal[:, 0]
        columns = [y[:, 0] - goal[:, 0], a * (y[:, EX] - goal[:, EX]),
                   a * (y[:, EY] - goal[:, EY]), a * (y[:, INC] - goal[:, INC]),
                   a * np.sin(goal[:, INC]) * wrap(y[:, RAAN] - goal[:, RAAN])]  # fmt: skip
        if phase:
            columns.append(a * (y[:, U] - goal[:, U] - TWO_PI * branch))
        return np.stack(columns, axis=1) / 1000.0

    def residual(self, x, branch: float, phase: bool = True):
        key = (x.tobytes(), branch, phase)
        if key != self._key:
            states, epochs = self._chain(x)
            self._key = key
            self._value = self._residuals([states[-1]], [epochs[-1]], branch, phase)[0]
        return self._value

    def residual_jacobian(self, x, branch: float, phase: bool = True):
        key = (x.tobytes(), branch, phase)
        if key == self._grad_key:
            return self._grad
        epochs, dv = self._lists(x)
        states = self._run(epochs, dv, 0, [tuple(self.p.start)])
        finals, lasts = [states[-1]], [epochs[-1]]
        for k in range(self.m):  # the gap before impulse k: every epoch from k on moves
            moved = epochs[: k + 1] + [t + STEP_TIME * self.unit for t in epochs[k + 1 :]]
            finals.append(self._run(moved, dv, k, states)[-1])
            lasts.append(moved[-1])
        for k in range(self.m):  # impulse k's components
            for c in range(3):
                changed = [row[:] for row in dv]
                changed[k][c] += STEP_DV
                finals.append(self._run(epochs, changed, k, states)[-1])
                lasts.append(epochs[-1])
        values = self._residuals(finals, lasts, branch, phase)
        self._key, self._value = key, values[0]
        self._grad_key, self._grad = key, ((values[1:] - values[0]) / self.h[:, None]).T
        return self._grad

    def phase_turns(self, x) -> float:
        """The phase error at ``x`` in revolutions (its nearest integer: the branch)."""
        states, epochs = self._chain(x)
        return float((states[-1][U] - self.p.target(np.array([epochs[-1]]))[0, U]) / TWO_PI)


    def total(self, x) -> float:
        _, dv = self.unpack(x)
        return float((np.sqrt(np.sum(dv * dv, axis=1) + SMOOTH_MPS**2) - SMOOTH_MPS).sum())

    def total_gradient(self, x):
        _, dv = self.unpack(x)
        grad = dv / np.sqrt(np.sum(dv * dv, axis=1) + SMOOTH_MPS**2)[:, None]
        return np.concatenate([np.zeros(self.m), grad.ravel()])

    def window(self, x):
        epochs, _ = self.unpack(x)
        return np.array([epochs[-1] - self.p.earliest, self.p.latest - epochs[-1]]) / self.unit

    def window_jacobian(self, x):
        row = np.concatenate([np.ones(self.m), np.zeros(3 * self.m)])
        return np.vstack([row, -row])


def _solve(model: _Model, x0, branch: float, phase: bool) -> tuple[np.ndarray, bool]:
    """SLSQP on ``model`` from ``x0``: the solution and whether it converged."""
    m = model.m
    constraints = [
        {"type": "eq", "fun": lambda x: model.residual(x, branch, phase),
         "jac": lambda x: model.residual_jacobian(x, branch, phase)},
        {"type": "ineq", "fun": model.window, "jac": model.window_jacobian},
    ]  # fmt: skip
    bounds = [(0.0, 0.0) if (k == 0 and model.p.first_fixed) else (0.0, None) for k in range(m)]
    bounds += [(None, None)] * (3 * m)
    x0 = np.array(x0, dtype=float)
    if model.p.first_fixed:
        x0[0] = 0.0
    for attempt in range(2):
        with np.errstate(all="ignore"):
            try:
                result = minimize(model.total, x0, jac=model.total_gradient, bounds=bounds,
                                  constraints=constraints, method="SLSQP",
                                  options={"maxiter": MAX_ITERATIONS, "ftol": FTOL})  # fmt: skip
            except (ValueError, ZeroDivisionError, OverflowError):  # off the model's domain
                return x0, False
        if result.status != SINGULAR or attempt:
            break
        # dependent conditions at the start (an impulse of exactly zero, a circular orbit):
        # once more from a millimetre per second away
        x0 = x0 + np.concatenate([np.zeros(m), np.full(3 * m, 1e-3)])
    x = result.x
    ok = bool(result.success) and bool(np.all(np.isfinite(x)))
    if ok:
        ok = float(np.abs(model.residual(x, branch, phase)).max()) < RESIDUAL_KM
    return x, ok


def _plan(model: _Model, x, branch: float, ok: bool) -> LegPlan:
    epochs, dv = model.unpack(x)
    residual = float(np.abs(model.residual(x, branch)).max())
    return LegPlan(epochs, dv, float(np.linalg.norm(dv, axis=1).sum()), branch, residual, ok)


def _pack(problem: LegProblem, epochs, dv_rtn) -> np.ndarray:
    gaps = np.diff(np.concatenate([[problem.t_start], epochs])) / problem.time_unit
    return np.concatenate([np.maximum(gaps, 0.0), np.asarray(dv_rtn, dtype=float).ravel()])


def plan_leg(problem: LegProblem, seeds) -> LegPlan | None:
    """The cheapest converged plan from ``seeds`` (each ``(epochs, dv_rtn)``): per seed,
    the five conditions without the phase; then, for the seeds whose first stage is within
    :data:`KEEP_MPS` of the cheapest, the phase on the nearest branches (:data:`BRANCHES`
    each side; one further while the cheapest is at the edge).  None if none converged."""
    first = []
    for epochs, dv in seeds:
        model = _Model(problem, len(epochs))
        x1, _ = _solve(model, _pack(problem, epochs, dv), 0.0, phase=False)
        total = model.total(x1)
        first.append((total if np.isfinite(total) else np.inf, model, x1))
    cheapest = min((f[0] for f in first), default=np.inf)
    best = None
    for total, model, x1 in sorted(first, key=lambda f: f[0]):
        if not total <= cheapest + KEEP_MPS:
            continue
        for candidate in _branches(model, x1):
            if candidate.converged and (best is None or candidate.total_mps < best.total_mps):
                best = candidate
    return best


def _branches(model: _Model, x1) -> list[LegPlan]:
    """The phased plans from a first-stage solution ``x1`` on the nearest branches."""
    centre = float(np.round(model.phase_turns(x1)))
    tried: dict[float, LegPlan] = {}
    queue = [centre + k for k in range(-BRANCHES, BRANCHES + 1)]
    while queue:
        branch = queue.pop(0)
        x, ok = _solve(model, x1, branch, phase=True)
        tried[branch] = _plan(model, x, branch, ok)
        good = {b: p for b, p in tried.items() if p.converged}
        if not queue and good:  # the cheapest at an edge: one more branch beyond it
            cheapest = min(good, key=lambda b: good[b].total_mps)
            for beyond in (cheapest - 1, cheapest + 1):
                if beyond not in tried and len(tried) < 2 * BRANCHES + 4:
                    queue.append(beyond)
    return list(tried.values())


def replan(problem: LegProblem, previous: LegPlan, extra_now: bool = False) -> LegPlan:
    """Re-plan the impulses of ``previous`` (all after ``problem.t_start``) from the
    problem's start, on the branch nearest the warm start's phase; with ``extra_now`` an
    impulse at the start first (a trim, zero in the warm start)."""
    epochs, dv = previous.epochs, previous.dv_rtn
    if extra_now:
        epochs = np.concatenate([[problem.t_start], epochs])
        dv = np.vstack([np.zeros(3), dv])
    model = _Model(problem, len(epochs))
    x0 = _pack(problem, epochs, dv)
    branch = float(np.round(model.phase_turns(x0)))
    x, ok = _solve(model, x0, branch, phase=True)
    return _plan(model, x, branch, ok)


# -- the paper's leg as a seed -----------------------------------------------------------
def _next_node(y, t: float, rates, consts) -> float:
    """The first epoch after ``t`` [s] where the argument of latitude is a multiple of pi."""
    u_rate = float(rates_of(y, rates, **consts)[2])
    k = np.floor(y[U] / np.pi) + 1.0
    return t + (k * np.pi - y[U]) / u_rate


def _half_orbit(a: float, mu: float) -> float:
    return float(np.pi * np.sqrt(a**3 / mu))


def _burn(y, apse_other: float, normal=None, inc=None, *, mu: float) -> np.ndarray:
    """RTN impulse [m/s] onto the orbit with an apse here and the other at radius
    ``apse_other`` [m], horizontal, in the plane ``normal`` or of inclination ``inc``
    (default: the present plane)."""
    r, v = state_of(y, mu=mu)
    radius = float(np.linalg.norm(r))
    speed = np.sqrt(mu * (2.0 / radius - 2.0 / (radius + apse_other)))
    if normal is None:
        normal = (np.cross(r, v) / np.linalg.norm(np.cross(r, v)) if inc is None
                  else plane_with_inclination(r, v, _POLE, inc))  # fmt: skip
    v_new = speed * np.cross(normal, r / radius)
    radial, transverse, normal_now = rtn_vectors(r, v)
    dv = v_new - v
    return np.array([dv @ radial, dv @ transverse, dv @ normal_now])


def _target_normal(y, mu: float) -> np.ndarray:
    r, v = state_of(y, mu=mu)
    h = np.cross(r, v)
    return h / np.linalg.norm(h)


def paper_seeds(problem: LegProblem, a_drift: float, inc_drift: float, t_leave: float) -> list:
    """Seeds of a plan from the paper's leg (:func:`paper_seed`): its departure burn at the
    first node and at the next one after the start, and (a departure from the start) at
    the start itself."""
    seeds = [paper_seed(problem, a_drift, inc_drift, t_leave, node=k) for k in (0, 1)]
    if problem.first_fixed:
        seeds.append(paper_seed(problem, a_drift, inc_drift, t_leave, node=None))
    return seeds


def paper_seed(problem: LegProblem, a_drift: float, inc_drift: float, t_leave: float,
               node: int | None = 0):  # fmt: skip
    """The paper's leg (Part III [2]_) as the impulses of a seed ``(epochs, dv_rtn)``: a
    Hohmann transfer to the circular drift orbit ``(a_drift, inc_drift)`` [m, rad] from the
    ``node``-th node after the start (None: at the start), the plane change on its
    higher-radius impulse (Eq. 13); the drift; a Hohmann transfer to the target from the
    node nearest ``t_leave`` [s].  Where the problem's first impulse is at its start and
    the departure burn is not, a zero impulse there first (the plan then moves the burn
    along the orbit as it needs)."""
    consts = problem.consts
    mu, rates = consts.get("mu", 3.986004418e14), problem.rates
    t0 = problem.t_start
    t1 = t0
    if node is not None:
        t1 = _next_node(problem.start, t0, rates, consts)
        t1 += node * np.pi / float(rates_of(problem.start, rates, **consts)[2])
    y = advance(problem.start, t1 - t0, rates, **consts)
    up = a_drift >= y[0]
    dv1 = _burn(y, a_drift, inc=None if up else inc_drift, mu=mu)
    y = apply_impulse(y, dv1, mu=mu)
    t2 = t1 + _half_orbit(y[0], mu)
    y = advance(y, t2 - t1, rates, **consts)
    dv2 = _burn(y, float(np.linalg.norm(state_of(y, mu=mu)[0])), inc=inc_drift if up else None,
                mu=mu)  # fmt: skip
    y = apply_impulse(y, dv2, mu=mu)
    # the node nearest the closure; none when there is no drift to make (a direct transfer)
    close = t_leave - t2 < _half_orbit(y[0], mu)
    t3 = t2 if close else _next_node(y, t_leave, rates, consts)
    y = advance(y, t3 - t2, rates, **consts)
    goal = problem.target(np.array([t3]))[0]
    down = goal[0] < y[0]
    normal = plane_towards(*state_of(y, mu=mu), _target_normal(goal, mu)) if down else None
    dv3 = _burn(y, goal[0], normal=normal, mu=mu)
    y = apply_impulse(y, dv3, mu=mu)
    t4 = t3 + _half_orbit(y[0], mu)
    y = advance(y, t4 - t3, rates, **consts)
    goal = problem.target(np.array([t4]))[0]
    normal = None if down else plane_towards(*state_of(y, mu=mu), _target_normal(goal, mu))
    radius = float(np.linalg.norm(state_of(y, mu=mu)[0]))
    dv4 = _burn(y, radius, normal=normal, mu=mu)
    epochs, dvs = np.array([t1, t2, t3, t4]), np.array([dv1, dv2, dv3, dv4])
    if problem.first_fixed and node is not None:
        epochs, dvs = np.concatenate([[t0], epochs]), np.vstack([np.zeros(3), dvs])
    return epochs, dvs
