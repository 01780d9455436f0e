"""A GTOC9 campaign searched for its cost J (issue 47, item 3): :func:`plan_campaign`.

The search, in the planner's model (:mod:`.legs`):

- **a mission by beam search** (:func:`plan_mission`): states are partial missions (the
  debris so far, the last arrival's date, the mass chain's sums); each depth adds one
  debris.  From a state, each candidate next debris is screened on a coarse grid of dates
  (departure ``t_w`` after the arrival, arrivals every few days up to Δt_R), the
  :data:`SCREEN` cheapest are priced on the fine grid (departures after stays of
  ``t_w + w``, arrivals every day up to Δt_R after the last arrival), and each child is
  scored by its ΔV plus a price of time ``day_price_mps`` per day (a campaign's missions
  share GTOC9's eight years).  The beam keeps the ``beam`` best children, one per set of
  debris and last debris.  Every depth's best mission within the propellant is a
  candidate.
- **the campaign, mission after mission** (:func:`plan_campaign`): each launch at least
  Δt_M after the previous mission's end; of the candidate missions, the one with the least
  cost per debris ``(c + α (m0 - m_dry)^2) / N`` is kept, so a mission grows while a debris
  more costs less than a launch's share.  A mission that cannot fit the debris left in the
  time left ends the campaign as incomplete (said so, never hidden).

The lower bound of J (:func:`lower_bound`) holds for every campaign of the planner's model
that removes all debris: each debris but a mission's first is reached by a leg of at
least its cheapest incoming leg at any date (:meth:`Gtoc9Legs.floor`), and by the
convexity of the cost in ``m0`` (Jensen), ``M`` missions cost at least
``M c + α (Σ (m0_i - m_dry))^2 / M``.

Units: days from the window's start, m/s, kg, MEUR.

References
----------
.. [1] ESA Advanced Concepts Team, "GTOC9: The Kessler Run" (2017), problem and
   constants pages.
.. [2] Tsinghua University's multi-tree search with dynamic programming for GTOC9
   (MTS-DP), Journal of Guidance, Control, and Dynamics (2024); its repository
   ``zhong-zh15/gtoc9_MTS-DP`` (GPL-3: read, never copied): the published campaigns this
   search is measured against.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import MissionError
from .legs import Gtoc9Legs
from .plan import PlannedCampaign, PlannedMission, chain_mass
from .repair import insert_left
from .rules import DEBRIS_COUNT, DEFAULT_RULES, Gtoc9Rules

SCREEN = 12
"""Candidates per state priced on the fine grid of dates."""


@dataclass(frozen=True)
class SearchSettings:
    """The beam search's knobs (module docstring).

    Attributes
    ----------
    beam : int
        States kept per depth.
    day_price_mps : float
        Price of a day of the mission's time [m/s per day].
    waits_days : tuple of float
        Extra days at a debris beyond ``t_w`` that a departure may take.
    launch_window_days, launch_step_days : float
        First launches searched: every ``step`` days over ``window`` from the earliest.
    max_debris : int
        Most debris in a mission.
    """

    beam: int = 300
    day_price_mps: float = 3.0
    waits_days: tuple[float, ...] = (0.0, 2.0, 5.0, 10.0)
    launch_window_days: float = 60.0
    launch_step_days: float = 5.0
    max_debris: int = 20

    def __post_init__(self):
        problems = [f"{name} must be > 0, got {getattr(self, name)!r}" for name in
                    ("beam", "launch_step_days", "max_debris") if not getattr(self, name) > 0]
        problems += [f"{name} must be >= 0, got {getattr(self, name)!r}" for name in
                     ("day_price_mps", "launch_window_days") if not getattr(self, name) >= 0]
        if not self.waits_days or min(self.waits_days) < 0:
            problems.append(f"waits_days must be days >= 0, got {self.waits_days!r}")
        if problems:
            raise MissionError("; ".join(problems))


@dataclass
class _States:
    """A beam's partial missions, as arrays (one row a state) and lists of their paths."""

    last: np.ndarray  # debris
    arrival: np.ndarray  # the last arrival [days]
    growth: np.ndarray  # E_k of the chain (plan.py)
    growth_sum: np.ndarray  # E_0 + ... + E_k
    dv: np.ndarray
    launch: np.ndarray
    visited: np.ndarray  # (S, 123) bool
    paths: list  # per state: list of (debris, arrival, departure, dv, a_drift, inc_drift)

    dv_prized: np.ndarray | None = None  # dv less the prizes of the debris visited

    def score(self, day_price: float) -> np.ndarray:
        return self.dv_prized + day_price * (self.arrival - self.launch)


def _mission(path, rules: Gtoc9Rules) -> PlannedMission:
    debris = tuple(int(p[0]) for p in path)
    arrivals = tuple(float(p[1]) for p in path)
    departures = tuple(float(p[2]) for p in path[1:]) + (arrivals[-1] + rules.stay_days,)
    return PlannedMission(debris, arrivals, departures, tuple(float(p[3]) for p in path[1:]),
                          tuple(float(p[4]) for p in path[1:]),
                          tuple(float(p[5]) for p in path[1:]))  # fmt: skip


def _grid(rules: Gtoc9Rules, settings: SearchSettings):
    """(wait, duration) offsets from the last arrival: departure and arrival [days]."""
    pairs = []
    for wait in settings.waits_days:
        leave = rules.stay_days + wait
        for arrive in np.arange(math.floor(leave) + 1.0, rules.dt_r_days + 1e-9, 1.0):
            pairs.append((leave, float(arrive)))
    return np.array(pairs)


def plan_mission(legs: Gtoc9Legs, available, earliest: float, latest_end: float, *,
                 rules: Gtoc9Rules = DEFAULT_RULES, settings: SearchSettings = SearchSettings(),
                 prize=None) -> list[PlannedMission]:  # fmt: skip
    """Candidate missions launched from ``earliest`` [days] on and ending by ``latest_end``,
    visiting debris of ``available`` (bool, shape (123,)): the best of each depth within
    the propellant (module docstring), fewest debris first.  ``prize`` [m/s] per debris,
    subtracted from a state's score when it visits it (the campaign's price of leaving a
    debris for later), none by default."""
    available = np.asarray(available, bool)
    prize = np.zeros(legs.count) if prize is None else np.asarray(prize, float)
    starts = np.flatnonzero(available)
    launches = earliest + np.arange(0.0, settings.launch_window_days + 1e-9,
                                    settings.launch_step_days)  # fmt: skip
    launches = launches[launches + rules.stay_days <= latest_end]
    if not len(starts) or not len(launches):
        return []
    first, when = (g.ravel() for g in np.meshgrid(starts, launches, indexing="ij"))
    visited = np.zeros((len(first), legs.count), bool)
    visited[np.arange(len(first)), first] = True
    paths = [[(k, t, math.nan, 0.0, math.nan, math.nan)]
             for k, t in zip(first, when, strict=True)]
    states = _States(first, when, np.ones(len(first)), np.ones(len(first)),
                     np.zeros(len(first)), when.copy(), visited, paths, -prize[first])
    coarse = np.array([(rules.stay_days, d) for d in
                       np.arange(rules.stay_days + 5.0, rules.dt_r_days + 1e-9, 5.0)])
    fine = _grid(rules, settings)
    c = rules.isp_s * rules.g0_mps2
    found: list[PlannedMission] = []
    for _depth in range(settings.max_debris - 1):
        s_idx, j_idx = np.nonzero(~states.visited & available[None, :])
        if not len(s_idx):
            break
        # screen: the cheapest coarse date pair of each (state, candidate)
        t0 = states.arrival[s_idx]
        price = legs.cost(states.last[s_idx][:, None], j_idx[:, None], t0[:, None] + coarse[:, 0],
                          t0[:, None] + coarse[:, 1]).cost.min(axis=1)  # fmt: skip
        order = np.lexsort((price, s_idx))
        s_sorted, p_sorted = s_idx[order], price[order]
        rank = np.arange(len(order)) - np.searchsorted(s_sorted, s_sorted)
        keep = order[(rank < SCREEN) & np.isfinite(p_sorted)]
        if not len(keep):
            break
        s_idx, j_idx = s_idx[keep], j_idx[keep]
        t0 = states.arrival[s_idx]
        leave, arrive = t0[:, None] + fine[:, 0], t0[:, None] + fine[:, 1]
        leg = legs.cost(states.last[s_idx][:, None], j_idx[:, None], leave, arrive)
        value = leg.cost + settings.day_price_mps * (fine[:, 1] - fine[:, 0])
        value = np.where(arrive + rules.stay_days <= latest_end, value, np.inf)
        best = np.argmin(value, axis=1)
        rows = np.arange(len(s_idx))
        dv = leg.cost[rows, best]
        ok = np.isfinite(value[rows, best])
        s_idx, j_idx, best, dv, rows = s_idx[ok], j_idx[ok], best[ok], dv[ok], rows[ok]
        if not len(s_idx):
            break
        growth = states.growth[s_idx] * np.exp(dv / c)
        child = _States(j_idx, states.arrival[s_idx] + fine[best, 1], growth,
                        states.growth_sum[s_idx] + growth, states.dv[s_idx] + dv,
                        states.launch[s_idx], states.visited[s_idx].copy(), [])
        child.visited[np.arange(len(j_idx)), j_idx] = True
        mass = rules.m_dry_kg * child.growth + rules.m_de_kg * child.growth_sum
        fits = mass - rules.m_dry_kg <= rules.max_propellant_kg
        child.dv_prized = states.dv_prized[s_idx] + dv - prize[j_idx]
        score = np.where(fits, child.score(settings.day_price_mps), np.inf)
        # one child per (set of debris, last debris): the best
        keys = np.concatenate([np.packbits(child.visited, axis=1),
                               child.last[:, None].astype(np.uint8)], axis=1)
        order = np.argsort(score, kind="stable")
        _, first_seen = np.unique(keys[order], axis=0, return_index=True)
        chosen = order[np.sort(first_seen)]
        chosen = chosen[np.isfinite(score[chosen])]
        chosen = chosen[np.argsort(score[chosen], kind="stable")][: settings.beam]
        if not len(chosen):
            break
        paths = []
        for k in chosen:
            s, r = s_idx[k], rows[k]
            b = best[k]
            paths.append(states.paths[s] + [(int(j_idx[k]), float(child.arrival[k]),
                                             float(leave[r, b]), float(dv[k]),
                                             float(leg.a_drift[r, b]),
                                             float(leg.inc_drift[r, b]))])  # fmt: skip
        states = _States(child.last[chosen], child.arrival[chosen], child.growth[chosen],
                         child.growth_sum[chosen], child.dv[chosen], child.launch[chosen],
                         child.visited[chosen], paths, child.dv_prized[chosen])  # fmt: skip
        per_debris = [_mission(p, rules) for p in paths[: max(1, settings.beam // 10)]]
        found.append(min(per_debris, key=lambda m: m.cost(rules)))
    return found


def lower_bound(legs: Gtoc9Legs, rules: Gtoc9Rules = DEFAULT_RULES,
                debris: int = DEBRIS_COUNT) -> float:  # fmt: skip
    """A lower bound [MEUR] of J over every campaign removing ``debris`` debris in the
    planner's model (module docstring)."""
    floor = legs.floor()
    incoming = np.full(legs.count, np.inf)
    np.minimum.at(incoming, legs.target, floor)
    incoming = np.sort(incoming)
    c = rules.isp_s * rules.g0_mps2
    best = math.inf
    for missions in range(1, debris + 1):
        legs_needed = debris - missions
        dv = float(incoming[:legs_needed].sum())
        # least Σ (m0 - m_dry): packages of every debris plus m_dry (exp(ΔV/c) - 1) summed
        # over missions, least when the ΔV is spread evenly (exp is convex)
        extra = rules.m_de_kg * debris + missions * rules.m_dry_kg * math.expm1(dv / missions / c)
        if extra / missions > rules.max_propellant_kg:  # some mission over its tank
            continue
        best = min(best, missions * rules.launch_cost_meur
                   + rules.alpha_meur_per_kg2 * extra**2 / missions)  # fmt: skip
    return best


def plan_campaign(legs: Gtoc9Legs, *, rules: Gtoc9Rules = DEFAULT_RULES,
                  settings: SearchSettings = SearchSettings(), prize=None,
                  day_cost_meur: float = 0.0,
                  say: Callable[[str], None] = lambda text: None) -> PlannedCampaign:  # fmt: skip
    """A campaign, mission after mission (module docstring); it may end before every
    debris is removed (:attr:`PlannedCampaign.complete` says).

    ``prize`` [m/s per debris] goes to :func:`plan_mission`; of each launch's candidate
    missions the one of least ``(cost + day_cost_meur (duration + Δt_M)) / N`` is kept
    (``day_cost_meur`` [MEUR/day]: the price of the campaign's time).
    """
    clock = time.perf_counter()
    horizon = rules.end_mjd2000 - rules.start_mjd2000
    available = np.ones(legs.count, bool)
    earliest, missions = 0.0, []

    def key(m: PlannedMission) -> float:
        duration = m.end - earliest + rules.dt_m_days
        return (m.cost(rules) + day_cost_meur * duration) / len(m.debris)

    while available.any():
        options = plan_mission(legs, available, earliest, horizon, rules=rules,
                               settings=settings, prize=prize)  # fmt: skip
        options = [m for m in options if m.fits(rules)]
        left = int(available.sum())
        if not options:
            if left == 1 and earliest + rules.stay_days <= horizon:  # a launch and a stay
                k = int(np.flatnonzero(available)[0])
                options = [PlannedMission((k,), (earliest,), (earliest + rules.stay_days,), ())]
            else:
                say(f"no mission fits from day {earliest:.1f}: {left} debris left")
                break
        complete = [m for m in options if len(m.debris) == left]
        mission = complete[0] if complete else min(options, key=key)
        missions.append(mission)
        available[list(mission.debris)] = False
        earliest = mission.end + rules.dt_m_days
        say(f"  mission {len(missions)}: {len(mission.debris)} debris, {mission.dv:.0f} m/s, "
            f"m0 {mission.m0(rules):.0f} kg, {mission.cost(rules):.2f} MEUR, days "
            f"{mission.launch:.1f}-{mission.end:.1f}; {int(available.sum())} left "
            f"({time.perf_counter() - clock:.0f} s)")  # fmt: skip
    return PlannedCampaign(tuple(missions), lower_bound(legs, rules))


def search_campaign(legs: Gtoc9Legs, *, rules: Gtoc9Rules = DEFAULT_RULES,
                    settings: SearchSettings = SearchSettings(), time_limit_s: float = 600.0,
                    rounds: int = 1000, prize_step_mps: float = 80.0, adapt_legs: bool = True,
                    say: Callable[[str], None] = lambda text: None) -> PlannedCampaign:  # fmt: skip
    """The best complete campaign of rounds of :func:`plan_campaign` (module docstring).

    A round's campaign that leaves debris has them inserted into its missions where they
    cost least (:func:`~sdc_cvx.gtoc9.repair.insert_left`).

    After a round that leaves debris, each left debris' prize grows by ``prize_step_mps``
    (a later round takes it in an earlier mission, where its geometry allows) and the
    time is priced higher (times 1.25: the legs' ``day_price_mps``, shorter legs, and the
    missions' ``day_cost_meur``, shorter missions); after a complete round, lower (times
    0.9).  Stops after ``rounds``
    or ``time_limit_s`` [s]; returns the best complete campaign, or the round that removed
    the most debris if none was complete.
    """
    clock = time.perf_counter()
    prize = np.zeros(legs.count)
    day_cost, day_price = 0.02, settings.day_price_mps
    best: PlannedCampaign | None = None
    for number in range(1, rounds + 1):
        tuned = dataclasses.replace(settings, day_price_mps=day_price)
        campaign = plan_campaign(legs, rules=rules, settings=tuned, prize=prize,
                                 day_cost_meur=day_cost)  # fmt: skip
        if not campaign.complete(legs.count):
            campaign = insert_left(legs, campaign, rules=rules)
        removed = np.zeros(legs.count, bool)
        removed[list(campaign.removed)] = True
        j = campaign.cost(rules)
        complete = campaign.complete(legs.count)
        if best is None or _better(campaign, best, rules):
            best = campaign
        say(f"round {number}: {'complete' if complete else f'{int((~removed).sum())} left'}, "
            f"J {j:.2f} MEUR, {len(campaign.missions)} missions, {campaign.dv:.0f} m/s; best "
            f"{best.cost(rules):.2f}; legs' time {day_price:.1f} m/s/day "
            f"({time.perf_counter() - clock:.0f} s)")  # fmt: skip
        if time.perf_counter() - clock > time_limit_s:
            break
        prize[~removed] += prize_step_mps
        if adapt_legs:
            day_price *= 0.9 if complete else 1.25
        day_cost *= 0.9 if complete else 1.25
    return best


def _better(a: PlannedCampaign, b: PlannedCampaign, rules: Gtoc9Rules) -> bool:
    """More debris removed, then the lower J."""
    return (len(a.removed), -a.cost(rules)) > (len(b.removed), -b.cost(rules))


__all__ = ["SearchSettings", "chain_mass", "lower_bound", "plan_campaign", "plan_mission",
           "search_campaign"]
