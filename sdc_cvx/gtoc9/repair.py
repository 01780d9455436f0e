"""Debris a campaign left, inserted into its missions (:func:`insert_left`, issue 47).

A round of :func:`~sdc_cvx.gtoc9.search.plan_campaign` may end with debris no mission took
(the last missions run out of time).  Each is tried in every mission: between two
consecutive debris ``k`` and ``k + 1`` (the arrival at ``k + 1`` kept, so the rest of the
mission is unchanged: a departure from ``k`` after its stay, the arrival at the debris,
its stay, the departure towards ``k + 1``, each rendezvous at most Δt_R after the last),
or after the mission's last debris (the mission then ends later, still Δt_M before the
next launch and within the window).  The insertion of least added cost J (the mass chain
of the whole mission, priced again) is made, and so on while one fits.

Units: days from the window's start, m/s, MEUR.
"""

from __future__ import annotations

import math

import numpy as np

from .legs import Gtoc9Legs
from .plan import PlannedCampaign, PlannedMission
from .rules import DEFAULT_RULES, Gtoc9Rules

WAITS_DAYS = (0.0, 2.0, 5.0)
"""Extra days beyond the stay a departure may take in an insertion."""


def _between(legs: Gtoc9Legs, m: PlannedMission, k: int, x: int, rules: Gtoc9Rules):
    """The cheapest ``k -> x -> k + 1`` of mission ``m`` (ΔV of the two legs, their
    dates and drift orbits), or None."""
    t_k, t_next = m.arrivals[k], m.arrivals[k + 1]
    best = None
    for w1 in WAITS_DAYS:
        leave = t_k + rules.stay_days + w1
        arrive = np.arange(math.floor(leave) + 1.0, min(t_k + rules.dt_r_days, t_next -
                           rules.stay_days - 1.0) + 1e-9, 1.0)  # fmt: skip
        if not len(arrive):
            continue
        first = legs.cost(m.debris[k], x, leave, arrive)
        for w2 in WAITS_DAYS:
            go = arrive + rules.stay_days + w2
            ok = (go < t_next) & (t_next - arrive <= rules.dt_r_days)
            if not ok.any():
                continue
            second = legs.cost(x, m.debris[k + 1], go, t_next)
            total = np.where(ok, first.cost + second.cost, np.inf)
            n = int(np.argmin(total))
            if np.isfinite(total[n]) and (best is None or total[n] < best[0]):
                best = (float(total[n]), float(first.cost[n]), float(second.cost[n]), leave,
                        float(arrive[n]), float(go[n]), first, second, n)  # fmt: skip
    if best is None:
        return None
    _, dv1, dv2, leave, arrive, go, first, second, n = best
    return PlannedMission(
        m.debris[: k + 1] + (x,) + m.debris[k + 1:],
        m.arrivals[: k + 1] + (arrive,) + m.arrivals[k + 1:],
        m.departures[:k] + (leave, go) + m.departures[k + 1:],
        m.leg_dv[:k] + (dv1, dv2) + m.leg_dv[k + 1:],
        m.a_drift[:k] + (float(first.a_drift[n]), float(second.a_drift[n])) + m.a_drift[k + 1:],
        m.inc_drift[:k] + (float(first.inc_drift[n]), float(second.inc_drift[n]))
        + m.inc_drift[k + 1:],
    )


def _after(legs: Gtoc9Legs, m: PlannedMission, x: int, latest_end: float, rules: Gtoc9Rules):
    """Mission ``m`` with ``x`` visited after its last debris, ending by ``latest_end``."""
    t_last = m.arrivals[-1]
    best = None
    for w in WAITS_DAYS:
        leave = t_last + rules.stay_days + w
        arrive = np.arange(math.floor(leave) + 1.0, t_last + rules.dt_r_days + 1e-9, 1.0)
        arrive = arrive[arrive + rules.stay_days <= latest_end]
        if not len(arrive):
            continue
        leg = legs.cost(m.debris[-1], x, leave, arrive)
        n = int(np.argmin(leg.cost))
        if np.isfinite(leg.cost[n]) and (best is None or leg.cost[n] < best[0]):
            best = (float(leg.cost[n]), leave, float(arrive[n]), float(leg.a_drift[n]),
                    float(leg.inc_drift[n]))  # fmt: skip
    if best is None:
        return None
    dv, leave, arrive, a, inc = best
    return PlannedMission(m.debris + (x,), m.arrivals + (arrive,),
                          m.departures[:-1] + (leave, arrive + rules.stay_days),
                          m.leg_dv + (dv,), m.a_drift + (a,), m.inc_drift + (inc,))  # fmt: skip


def insert_left(legs: Gtoc9Legs, campaign: PlannedCampaign, *,
                rules: Gtoc9Rules = DEFAULT_RULES) -> PlannedCampaign:  # fmt: skip
    """``campaign`` with the debris it left inserted where they cost least (module
    docstring); those that fit nowhere stay left."""
    missions = list(campaign.missions)
    horizon = rules.end_mjd2000 - rules.start_mjd2000
    left = sorted(set(range(legs.count)) - set(campaign.removed))
    while left:
        best = None  # (added J, debris, mission index, the new mission)
        for x in left:
            for index, m in enumerate(missions):
                latest_end = (missions[index + 1].launch - rules.dt_m_days
                              if index + 1 < len(missions) else horizon)  # fmt: skip
                tries = [_between(legs, m, k, x, rules) for k in range(len(m.debris) - 1)]
                tries.append(_after(legs, m, x, latest_end, rules))
                for new in tries:
                    if new is None or not new.fits(rules):
                        continue
                    added = new.cost(rules) - m.cost(rules)
                    if best is None or added < best[0]:
                        best = (added, x, index, new)
        if best is None:
            break
        _, x, index, new = best
        missions[index] = new
        left.remove(x)
    return PlannedCampaign(tuple(missions), campaign.lower_bound)
