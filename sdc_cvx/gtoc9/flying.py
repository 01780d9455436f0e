"""GTOC9 missions flown leg by leg in GTOC9's own dynamics (issue 47).

A GTOC9 stay co-orbits its debris and is checked at its two events only ([1]_, the
equations page; :mod:`.check`), so each leg is independent: it starts exactly at debris
i's GTOC9 ephemeris state at its departure epoch and must end on debris j's at its
arrival epoch, both epochs the plan's.  :func:`fly_leg` flies one:

1. **Seed**: the paper's drift leg ([3]_ Part III; :func:`paper_drift_leg`): a Hohmann
   transfer from debris i's orbit to a circular drift orbit ``(a_drift, inc_drift)``, the
   plane change on its higher-radius impulse, the drift while J2 closes the RAAN gap, a
   Hohmann transfer to debris j's orbit.  By default the drift orbit closes the gap of
   GTOC9's elements at the departure in the leg's time (Eq. 10 inverted,
   :func:`~sdc_cvx.physics.transfer.drift_a_for_duration`), on the cheaper side, the drift
   inclination by Table 3; its cost (Eq. 11, :func:`~sdc_cvx.physics.transfer.transfer_dv`)
   is the leg's *paper estimate*.
2. **Plan and fly** in mean elements with the flight's closed-loop guidance
   (:class:`~sdc_cvx.flight.guidance.LegGuidance`: :func:`~sdc_cvx.flight.rendezvous.plan_leg`
   from :func:`~sdc_cvx.flight.rendezvous.paper_seeds`, each impulse corrected by a
   re-plan from the measured mean state, trims on the long coasts), the rendezvous held at
   the plan's arrival epoch, in the flight's propagator with GTOC9's force model
   (:data:`GTOC9_FORCE`): the same ODE as :mod:`.dynamics` (two-body + J2 about z with
   GTOC9's ``mu``, ``r_eq``, ``J2``; the flight integrates at ``rtol`` 1e-12, GTOC9's at
   1e-13).
3. **Target** the arrival in GTOC9's dynamics (:func:`sdc_cvx.gtoc9.dynamics.propagate`):
   the impulses flown so far are flown again there from the departure state; from the
   approach epoch (:data:`~sdc_cvx.flight.targeting.APPROACH_ORBITS` before the arrival,
   where an out-of-plane impulse still moves the arrival point) an approach impulse and
   the plan's impulses still to come are corrected by minimum-norm Newton steps
   (Vallado [2]_ §7.6) until the vehicle is at debris j's position at the arrival epoch
   within :data:`TARGET_M`; the arrival impulse then matches debris j's velocity.  The
   miss is measured on the leg flown again whole in GTOC9's dynamics.

:func:`fly_mission` flies a mission's legs (in parallel with a process pool's ``map``)
and writes its events in the competition's format (:class:`~.mission_file.Event`).

Units: m, m/s, rad, s; epochs MJD2000 [days]; vectors in GTOC9's frame.

References
----------
.. [1] ESA Advanced Concepts Team, "GTOC9: The Kessler Run", problem, equations and
   constants pages, https://kelvins.esa.int/gtoc9-kessler-run/ (2017).
.. [2] D. A. Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed.,
   Microcosm Press, 2013, §7.6 (targeting by differential correction).
.. [3] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
.. [4] D. Kraft, "A software package for sequential quadratic programming",
   DFVLR-FB 88-28, 1988 (the planner's SLSQP).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..errors import MissionError
from ..flight.gtoc9_ephemeris import GTOC9_J2, GTOC9_MU, GTOC9_R_EQ, Gtoc9Ephemeris
from ..flight.guidance import LegGuidance, LegWindow
from ..flight.propagation import ForceModel
from ..flight.rates import drift_factors
from ..flight.rendezvous import paper_seeds
from ..flight.track import Track
from ..physics.mean_elements import rtn_vectors
from ..physics.transfer import drift_a_for_duration, drift_inclination, transfer_dv
from .campaign_file import launch_mass
from .debris import MJD2000, DebrisTable
from .dynamics import perigee_radius, propagate
from .mission_file import Event
from .rules import DEFAULT_RULES, DSM, Gtoc9Rules

DAY = 86400.0
GTOC9_FORCE = ForceModel(mu=GTOC9_MU, r_eq=GTOC9_R_EQ, j2=GTOC9_J2)
"""The flight's force model with GTOC9's constants: :mod:`.dynamics`' ODE."""
POLE = np.array([0.0, 0.0, 1.0])
"""GTOC9's J2 axis, the z of its frame."""
BASIS = np.eye(3)
"""GTOC9's frame is its own equatorial frame (rows x, y, z)."""
TARGET_M = 1.0
"""The arrival point's distance to the debris the targeting aims at [m]."""
GOAL_M, GOAL_MPS = 50.0, 0.5
"""A leg is ``converged`` when its miss is within these [m, m/s]: half GTOC9's
tolerances, a margin for the validator's own integration."""
NEWTON_STEPS = 12
"""Newton steps of the targeting, at most."""
JACOBIAN_STEP_MPS = 1e-3
"""Forward-difference step of an impulse component in the targeting [m/s]."""
SAME_EPOCH_S = 1e-3
"""An impulse this close to the departure epoch [s] is the departure's."""


@dataclass(frozen=True)
class DriftLeg:
    """The paper's drift leg between two debris for fixed dates ([3]_ Part III).

    ``a_drift`` [m], ``inc_drift`` [rad], ``side`` (+1 the drift orbit precesses faster
    than the target), ``dv_mps`` (Eq. 11: the two Hohmann transfers with the plane
    changes), ``gap_rad`` (target RAAN less the origin's at the departure)."""

    a_drift: float
    inc_drift: float
    side: float
    dv_mps: float
    gap_rad: float


@dataclass(frozen=True)
class FlownLeg:
    """One leg flown in GTOC9's dynamics (module docstring).

    Attributes
    ----------
    from_id, to_id : int
        The debris left and reached.
    t_depart, t_arrive : float
        Departure and arrival epochs [MJD2000].
    epochs : ndarray (k,)
        The impulses' epochs [MJD2000], the departure first, the arrival last.
    dv : ndarray (k, 3)
        The impulses [m/s], GTOC9's frame.
    r_before, v_before : ndarray (k, 3)
        The spacecraft's position [m] and velocity [m/s] just before each impulse, flown
        in GTOC9's dynamics from debris ``from_id``'s ephemeris state at ``t_depart``.
    dv_total_mps : float
        ``sum |dv|`` [m/s].
    miss_m, miss_mps : float
        Distance [m] and velocity difference [m/s] after the arrival impulse to debris
        ``to_id``'s GTOC9 ephemeris at ``t_arrive``.
    min_perigee_m : float
        The lowest osculating perigee radius along the leg's arcs [m].
    paper : DriftLeg
        The paper's drift leg that seeded it (its cost the *paper estimate*).
    plan_dv_mps : float
        The mean-element plan's total [m/s].
    seconds : float
        Wall-clock time of the leg [s].
    notes : tuple of str
        What the reader must know: a miss beyond :data:`GOAL_M`/:data:`GOAL_MPS`, a
        perigee below GTOC9's.
    """

    from_id: int
    to_id: int
    t_depart: float
    t_arrive: float
    epochs: np.ndarray
    dv: np.ndarray
    r_before: np.ndarray
    v_before: np.ndarray
    dv_total_mps: float
    miss_m: float
    miss_mps: float
    min_perigee_m: float
    paper: DriftLeg
    plan_dv_mps: float
    seconds: float
    notes: tuple = ()

    @property
    def converged(self) -> bool:
        """The miss within :data:`GOAL_M` and :data:`GOAL_MPS`."""
        return self.miss_m <= GOAL_M and self.miss_mps <= GOAL_MPS

    @property
    def ratio_to_paper(self) -> float:
        """Flown ΔV over the paper estimate."""
        return self.dv_total_mps / self.paper.dv_mps

    def events(self) -> list[Event]:
        """The leg's events: its departure (``from_id``), deep-space manoeuvres (``-1``),
        its arrival (``to_id``)."""
        idents = [self.from_id] + [DSM] * (len(self.epochs) - 2) + [self.to_id]
        rows = zip(self.epochs, self.r_before, self.v_before, self.dv, idents, strict=True)
        return [Event(t, r, v, dv, ident) for t, r, v, dv, ident in rows]


@dataclass(frozen=True)
class FlownMission:
    """A mission flown: its events (competition format, time order), its legs, the total
    ΔV [m/s], the launch mass [kg] and cost [MEUR] of :func:`~.campaign_file.launch_mass`
    and :meth:`~.rules.Gtoc9Rules.cost`, and the legs' notes."""

    events: list
    legs: list
    dv_total_mps: float
    m0_kg: float
    cost_meur: float
    notes: tuple = ()

    @property
    def converged(self) -> bool:
        return all(leg.converged for leg in self.legs)


def _table(debris) -> DebrisTable:
    if isinstance(debris, DebrisTable):
        return debris
    if isinstance(debris, Gtoc9Ephemeris):
        return DebrisTable(debris)
    if debris is None:
        return DebrisTable.read()
    raise MissionError(f"expected a DebrisTable or a Gtoc9Ephemeris, got {type(debris).__name__}")


def _start_mjd2000(table: DebrisTable) -> float:
    """MJD2000 of the ephemeris' time origin (its seconds count from there)."""
    return (table.ephemeris.start - MJD2000).total_seconds() / DAY


def paper_drift_leg(debris, from_id: int, t_depart: float, to_id: int, t_arrive: float, *,
                    a_drift: float | None = None,
                    inc_drift: float | None = None) -> DriftLeg:  # fmt: skip
    """The paper's drift leg from ``from_id`` leaving at ``t_depart`` to ``to_id`` arriving
    at ``t_arrive`` [MJD2000] (module docstring, step 1).

    GTOC9's elements at the departure: ``a``, ``i``, the RAANs and their secular rates
    (:class:`~sdc_cvx.flight.gtoc9_ephemeris.Gtoc9Ephemeris`); the drift lasts the leg
    less the two Hohmann half-orbits.  Given ``a_drift`` [m] (and ``inc_drift`` [rad],
    default Table 3 for the side its rate is on), only the cost is computed.

    Returns
    -------
    DriftLeg
        ``dv_mps`` inf (``a_drift`` nan) when no drift orbit closes the gap in time.
    """
    table = _table(debris)
    eph = table.ephemeris
    seconds = (t_depart - _start_mjd2000(table)) * DAY
    k_i, k_j = (eph.ids.index(str(x)) for x in (from_id, to_id))
    a_i, _, inc_i, raan_i, _, _ = (float(x[0]) for x in eph.elements(k_i, seconds))
    a_j, _, inc_j, raan_j, _, _ = (float(x[0]) for x in eph.elements(k_j, seconds))
    rate_j = float(eph.raan_rate[k_j])
    gap = raan_j - raan_i
    consts = {"j2": GTOC9_J2, "mu": GTOC9_MU}
    total = (t_arrive - t_depart) * DAY

    def half(a_lo, a_hi):
        return np.pi * np.sqrt((0.5 * (a_lo + a_hi)) ** 3 / GTOC9_MU)

    best = DriftLeg(np.nan, np.nan, 0.0, np.inf, gap)
    for side in (1.0, -1.0):
        inc_d = float(drift_inclination(inc_i, inc_j, side)) if inc_drift is None else inc_drift
        a_d = a_drift
        if a_d is None:
            a_d = 0.5 * (a_i + a_j)
            for _ in range(4):  # the drift's length depends on a_d through the Hohmann halves
                coast = total - half(a_i, a_d) - half(a_d, a_j)
                a_d = float(drift_a_for_duration(gap, rate_j, side, inc_d, coast, **consts))
                if not np.isfinite(a_d):
                    break
        if not np.isfinite(a_d):
            continue
        dv = float(transfer_dv(a_i, inc_i, a_j, inc_j, a_d, inc_d, mu=GTOC9_MU))
        if dv < best.dv_mps:
            best = DriftLeg(float(a_d), inc_d, side, dv, gap)
        if a_drift is not None and inc_drift is not None:
            break
    return best


class _FixedArrivalGuidance(LegGuidance):
    """The flight's guidance for a GTOC9 leg: the rendezvous at the arrival epoch, the
    paper's drift orbit as seed, and the approach left to :func:`_target` (in GTOC9's
    dynamics): flying stops at the approach epoch."""

    def __init__(self, track, target, window, ephemeris, drift: DriftLeg, rates):
        super().__init__(track, 1, None, target, window, ephemeris, GTOC9_FORCE, POLE, BASIS,
                         rates)  # fmt: skip
        self.drift = drift
        self.final = None

    def _problem(self):
        problem = super()._problem()
        t = self.window.t_plan
        return type(problem)(problem.start, problem.t_start, problem.target, t, t,
                             problem.rates, problem.first_fixed, problem.consts)  # fmt: skip

    def _seed(self, problem):
        half = np.pi * np.sqrt(self.drift.a_drift**3 / GTOC9_MU)
        return paper_seeds(problem, self.drift.a_drift, self.drift.inc_drift,
                           self.window.t_plan - half)  # fmt: skip

    def _approach(self, plan, kind: str) -> None:
        self.final = plan


def _fly(r, v, t, impulses, t_end):
    """Fly ``(r, v)`` from ``t`` [MJD2000] through ``impulses`` (each ``(epoch, dv)``,
    in order) to ``t_end`` in GTOC9's dynamics: the states before each impulse, the end
    state and the lowest perigee radius [m]."""
    before, lowest = [], np.inf
    for epoch, dv in [*impulses, (t_end, None)]:
        r, v, states = propagate(r, v, (epoch - t) * DAY)
        lowest = min(lowest, float(perigee_radius(states).min()))
        t = epoch
        before.append((r, v))
        if dv is not None:
            v = v + np.asarray(dv, float)
    return before, (r, v), lowest


def _target(r_a, v_a, t_a, between, t_arrive, r_goal):
    """Minimum-norm Newton steps on the approach impulse at ``t_a`` and the impulses
    ``between`` (``(epoch, dv)``, fixed epochs) until the vehicle flown from ``(r_a, v_a)``
    in GTOC9's dynamics is within :data:`TARGET_M` of ``r_goal`` at ``t_arrive``.  The
    impulses (the approach's first) and the final miss vector [m]."""
    epochs = [t_a] + [e for e, _ in between]
    x = np.concatenate([np.zeros(3)] + [np.asarray(dv, float) for _, dv in between])

    def miss(x):
        _, (r, _), _ = _fly(r_a, v_a, t_a, [(t_a, x[:3])] + list(zip(epochs[1:],
                            x[3:].reshape(-1, 3), strict=True)), t_arrive)  # fmt: skip
        return r - r_goal

    m = miss(x)
    for _ in range(NEWTON_STEPS):
        if np.linalg.norm(m) < TARGET_M:
            break
        jac = np.empty((3, len(x)))
        for i in range(len(x)):
            xi = x.copy()
            xi[i] += JACOBIAN_STEP_MPS
            jac[:, i] = (miss(xi) - m) / JACOBIAN_STEP_MPS
        x = x - np.linalg.pinv(jac) @ m
        m = miss(x)
    return [(e, dv) for e, dv in zip(epochs, x.reshape(-1, 3), strict=True)], m


def fly_leg(debris, from_id: int, t_depart: float, to_id: int, t_arrive: float, *,
            seed: tuple[float, float] | None = None) -> FlownLeg:  # fmt: skip
    """Fly one GTOC9 leg (module docstring).

    Parameters
    ----------
    debris : DebrisTable or Gtoc9Ephemeris or None
        GTOC9's debris (None: :meth:`DebrisTable.read`).
    from_id, to_id : int
        The debris left and reached (GTOC9 ids).
    t_depart, t_arrive : float
        Departure and arrival epochs [MJD2000], both kept.
    seed : (float, float), optional
        The drift orbit ``(a_drift [m], inc_drift [rad])`` of the paper's leg; default
        :func:`paper_drift_leg`'s.

    Returns
    -------
    FlownLeg
        Its ``notes`` say when the miss is beyond :data:`GOAL_M` / :data:`GOAL_MPS` or
        an arc's perigee below GTOC9's 6600 km.

    Raises
    ------
    MissionError
        The arrival is not after the departure, or no drift orbit closes the RAAN gap.
    ~sdc_cvx.flight.guidance.GuidanceError
        No mean-element plan converged.
    """
    started = time.perf_counter()
    if not t_arrive > t_depart:
        raise MissionError(f"leg {from_id} -> {to_id}: arrival {t_arrive} not after the "
                           f"departure {t_depart} (MJD2000)")  # fmt: skip
    table = _table(debris)
    eph = table.ephemeris
    origin = _start_mjd2000(table)
    a_d, i_d = (None, None) if seed is None else (float(seed[0]), float(seed[1]))
    drift = paper_drift_leg(table, from_id, t_depart, to_id, t_arrive, a_drift=a_d,
                            inc_drift=i_d)  # fmt: skip
    if not np.isfinite(drift.a_drift):
        raise MissionError(f"leg {from_id} -> {to_id}: no circular drift orbit closes the "
                           f"RAAN gap of {np.degrees(drift.gap_rad):.3f} deg in "
                           f"{t_arrive - t_depart:g} days")  # fmt: skip
    t0, t1 = (t_depart - origin) * DAY, (t_arrive - origin) * DAY
    r0, v0 = table.state(from_id, t_depart)
    factors = drift_factors(drift.a_drift, drift.inc_drift, t0, GTOC9_FORCE, POLE)
    guidance = _FixedArrivalGuidance(Track(t0, r0.copy(), v0.copy()), eph.ids.index(str(to_id)),
                                     LegWindow(t0, t1, t1), eph, drift,
                                     (factors[0], 1.0, factors[1]))  # fmt: skip
    maneuvers = guidance.fly()
    plan = guidance.final

    def mjd(seconds):
        return t_depart if abs(seconds - t0) < SAME_EPOCH_S else origin + seconds / DAY

    flown = [(mjd(m.epoch_s), np.asarray(m.dv_gcrf, float)) for m in maneuvers]
    if not flown or flown[0][0] != t_depart:
        flown.insert(0, (t_depart, np.zeros(3)))
    t_a = mjd(guidance.track.t)
    _, (r_a, v_a), _ = _fly(r0, v0 + flown[0][1], t_depart, flown[1:], t_a)
    # the plan's impulses after the approach, as frame vectors along a coast with them
    between, r, v, t = [], r_a, v_a, t_a
    for epoch_s, rtn in zip(plan.epochs[:-1], plan.dv_rtn[:-1], strict=True):
        if epoch_s <= guidance.track.t + SAME_EPOCH_S:
            continue
        epoch = mjd(epoch_s)
        r, v, _ = propagate(r, v, (epoch - t) * DAY)
        radial, transverse, normal = rtn_vectors(r, v)
        dv = rtn[0] * radial + rtn[1] * transverse + rtn[2] * normal
        between.append((epoch, dv))
        v, t = v + dv, epoch
    r_goal, v_goal = table.state(to_id, t_arrive)
    shot, _ = _target(r_a, v_a, t_a, between, t_arrive, r_goal)
    impulses = flown[1:]
    for epoch, dv in shot:
        if impulses and impulses[-1][0] == epoch:  # the approach at the last impulse flown
            impulses[-1] = (epoch, impulses[-1][1] + dv)
        elif epoch > t_depart or not np.any(dv):
            impulses.append((epoch, dv))
        else:  # at the departure itself
            flown[0] = (t_depart, flown[0][1] + dv)
    impulses = [(e, dv) for e, dv in impulses if np.any(dv)]
    # the leg flown again whole in GTOC9's dynamics, the arrival impulse matching the debris
    before, (r_end, v_end), lowest = _fly(r0, v0 + flown[0][1], t_depart, impulses, t_arrive)
    dv_arrive = v_goal - v_end
    epochs = np.array([t_depart] + [e for e, _ in impulses] + [t_arrive])
    dvs = np.vstack([flown[0][1]] + [dv for _, dv in impulses] + [dv_arrive])
    r_before = np.vstack([r0] + [s[0] for s in before])
    v_before = np.vstack([v0] + [s[1] for s in before])
    miss_m = float(np.linalg.norm(r_end - r_goal))
    miss_mps = float(np.linalg.norm(v_end + dv_arrive - v_goal))
    notes = []
    if miss_m > GOAL_M or miss_mps > GOAL_MPS:
        notes.append(f"leg {from_id} -> {to_id}: arrival {miss_m:.1f} m and {miss_mps:.3f} m/s "
                     f"from the debris (goal {GOAL_M:g} m, {GOAL_MPS:g} m/s)")  # fmt: skip
    if lowest < DEFAULT_RULES.min_perigee_m:
        notes.append(f"leg {from_id} -> {to_id}: perigee radius {lowest / 1e3:.3f} km on the "
                     f"way, below GTOC9's {DEFAULT_RULES.min_perigee_m / 1e3:g} km")  # fmt: skip
    return FlownLeg(int(from_id), int(to_id), float(t_depart), float(t_arrive), epochs, dvs,
                    r_before, v_before, float(np.linalg.norm(dvs, axis=1).sum()), miss_m,
                    miss_mps, lowest, drift, float(guidance.first.total_mps),
                    time.perf_counter() - started, tuple(notes))  # fmt: skip


def _fly_one(job) -> FlownLeg:
    """:func:`fly_leg` of ``(debris, from_id, t_depart, to_id, t_arrive, seed)`` (a
    picklable function for a process pool's ``map``)."""
    debris, from_id, t_depart, to_id, t_arrive, seed = job
    return fly_leg(debris, from_id, t_depart, to_id, t_arrive, seed=seed)


def fly_mission(ids, departures, arrivals, seeds=None, *, debris=None, map=map,
                rules: Gtoc9Rules = DEFAULT_RULES) -> FlownMission:  # fmt: skip
    """Fly a GTOC9 mission leg by leg (module docstring) and build its events.

    Parameters
    ----------
    ids : sequence of int
        The debris in visit order (n >= 1).
    departures, arrivals : sequence of float
        The departure from and the arrival at each debris [MJD2000] (n each): the launch
        is ``arrivals[0]``, leg ``k`` leaves ``ids[k]`` at ``departures[k]`` and reaches
        ``ids[k + 1]`` at ``arrivals[k + 1]``, the mission ends at ``departures[-1]``.
    seeds : sequence, optional
        Per leg (n - 1), ``(a_drift [m], inc_drift [rad])`` or None (:func:`fly_leg`).
    debris : DebrisTable or Gtoc9Ephemeris, optional
        Default :meth:`DebrisTable.read`.
    map : callable, optional
        ``map(function, jobs)``: the builtin (default), or a process pool's to fly the
        legs in parallel.
    rules : Gtoc9Rules
        For the mass chain and the cost.

    Returns
    -------
    FlownMission
        The events: the arrival at ``ids[0]`` at the launch (no impulse), then per leg
        its departure, deep-space manoeuvres and arrival (:meth:`FlownLeg.events`), the
        departure from the last debris (no impulse); each state the spacecraft's just
        before its impulse.
    """
    ids = [int(x) for x in ids]
    departures, arrivals = [float(t) for t in departures], [float(t) for t in arrivals]
    if not ids or len(departures) != len(ids) or len(arrivals) != len(ids):
        raise MissionError(f"fly_mission: {len(ids)} debris, {len(departures)} departures "
                           f"and {len(arrivals)} arrivals; expected as many of each, at "
                           f"least one")  # fmt: skip
    seeds = [None] * (len(ids) - 1) if seeds is None else list(seeds)
    if len(seeds) != len(ids) - 1:
        raise MissionError(f"fly_mission: {len(seeds)} seeds for {len(ids) - 1} legs")
    table = _table(debris)
    jobs = [(table, ids[k], departures[k], ids[k + 1], arrivals[k + 1], seeds[k])
            for k in range(len(ids) - 1)]  # fmt: skip
    legs = list(map(_fly_one, jobs))
    r, v = table.state(ids[0], arrivals[0])
    events = [Event(arrivals[0], r, v, (0.0, 0.0, 0.0), ids[0])]
    for leg in legs:
        events += leg.events()
    r, v = table.state(ids[-1], departures[-1])
    events.append(Event(departures[-1], r, v, (0.0, 0.0, 0.0), ids[-1]))
    m0 = launch_mass(events, rules)
    notes = tuple(note for leg in legs for note in leg.notes)
    total = float(sum(leg.dv_total_mps for leg in legs))
    return FlownMission(events, legs, total, m0, rules.cost(m0), notes)
