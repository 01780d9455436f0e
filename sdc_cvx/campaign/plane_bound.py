"""A value bound from the plane changes no budget can pay.

Between two debris of inclinations I_i and I_j the vehicle must turn its orbital plane
by at least ``|I_i - I_j|`` (the angle between two planes is at least the difference of
their inclinations).  Only burns turn it (J2 moves the node, not the inclination), and in
the model every burn is at an apsis (of a circular orbit or a Hohmann ellipse), where the
plane turns by the angle theta between the velocities before and after; a burn from
speed v1 to v2 costs ``sqrt((v1 - v2)^2 + 4 v1 v2 sin^2(theta / 2)) >= 2 v_min
sin(theta / 2)``.  The turns of several burns (each at most pi) add up to at least the
whole turn, and ``g(x) = sin(min(x, pi) / 2)`` is concave, nondecreasing and 0 at 0, so
``sum g(theta_k) >= g(sum theta_k) >= g(|I_i - I_j|)``: every mission removing both costs
at least::

    2 V_min sin(|I_i - I_j| / 2),
    V_min = sqrt(mu / a_high) sqrt(2 a_low / (a_low + a_high)),

the apoapsis speed of the widest transfer ellipse, the slowest the vehicle flies
(``a_low``, ``a_high``: the lowest and highest radii it may fly, the drift band's or a
debris').  The low-thrust plane change costs ``(pi / 2) V dI`` at a circular speed V, more.
Where that exceeds every mission's ΔV budget, no mission removes both: the debris
split into *groups* (connected components of "may share a mission") and every mission
draws from one group.  A campaign is then worth at most the best way of giving each
mission a group, each group's missions taking its most valuable debris (a small search
over slot counts).  When that best is reached by one choice only, every campaign of that
value removes the same debris (``forced``): its least ΔV is the min-ΔV campaign that
must remove exactly them.

References
----------
.. [1] H. D. Curtis, *Orbital Mechanics for Engineering Students*, 3rd ed., Elsevier,
   2014, §6.12 (the ΔV of a plane change, 2 v sin(dI / 2)).
.. [2] M. Cerf, "Multiple space debris collecting mission - Debris selection and
   trajectory optimization", Journal of Optimization Theory and Applications,
   156(3), 761-796, 2013.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import connected_components

from ..physics.orbits import MU_EARTH, R_EARTH

MAX_STATES = 200_000
"""Slot-count vectors the search visits at most (beyond, no bound: the others hold)."""
TIE_REL = 1e-9
"""Relative margin under which two campaign values count as equal."""


class PlaneBound(NamedTuple):
    """The most value any campaign can remove, and the debris it must remove for it."""

    value: float  # [value units]; inf when not computed
    forced: tuple[int, ...] | None  # catalog rows every campaign of that value removes
    groups: int  # groups of debris that may share a mission
    v_min_mps: float = np.nan  # the slowest speed the vehicle flies [m/s]
    max_turn_rad: float = np.nan  # the widest plane change a budget pays [rad]


def least_plane_change_dv(inc_a, inc_b, a_low_m: float, a_high_m: float):
    """Least ΔV [m/s] of any mission removing debris of inclinations ``inc_a``, ``inc_b``
    [rad] when the vehicle flies between radii ``a_low_m`` and ``a_high_m`` [m]."""
    v_min = np.sqrt(MU_EARTH / a_high_m) * np.sqrt(2.0 * a_low_m / (a_low_m + a_high_m))
    return 2.0 * v_min * np.sin(np.abs(np.asarray(inc_a) - np.asarray(inc_b)) / 2.0)


def plane_value_bound(inc_rad, a_m, values, counts, budget_mps: float,
                      band_km: tuple[float, float]) -> PlaneBound:  # fmt: skip
    """:class:`PlaneBound` of debris ``inc_rad``, ``a_m`` worth ``values`` for missions of
    at most ``counts`` debris within ``budget_mps`` (the largest budget) [m/s], the drift
    band ``band_km`` [km of altitude]."""
    values = np.maximum(np.asarray(values, dtype=float), 0.0)
    a_low = min(R_EARTH + 1e3 * band_km[0], float(np.min(a_m)))
    a_high = max(R_EARTH + 1e3 * band_km[1], float(np.max(a_m)))
    inc = np.asarray(inc_rad, dtype=float)
    least = least_plane_change_dv(inc[:, None], inc[None, :], a_low, a_high)
    may = least <= budget_mps * (1 + 1e-9)
    groups, label = connected_components(csr_matrix(may), directed=False)
    v_min = float(least_plane_change_dv(0.0, np.pi, a_low, a_high)) / 2.0
    turn = 2.0 * np.arcsin(min(budget_mps / (2.0 * v_min), 1.0))
    members = [np.flatnonzero(label == g) for g in range(groups)]
    members = [m[np.argsort(-values[m], kind="stable")] for m in members]
    prefix = [np.concatenate([[0.0], np.cumsum(values[m])]) for m in members]

    def worth(slots):
        return sum(p[min(s, len(p) - 1)] for p, s in zip(prefix, slots, strict=True))

    states = {tuple([0] * groups)}
    for n in counts:  # each mission takes one group's slots
        states = {s[:g] + (s[g] + n,) + s[g + 1:] for s in states for g in range(groups)}
        if len(states) > MAX_STATES:
            return PlaneBound(np.inf, None, groups, v_min, turn)
    ranked = sorted(((worth(s), s) for s in states), reverse=True)
    best, slots = ranked[0]
    tie = best * TIE_REL + 1e-12
    unique = len(ranked) == 1 or ranked[1][0] < best - tie
    for m, s in zip(members, slots, strict=True):  # the top of each group must be strict
        if 0 < s < len(m) and values[m[s - 1]] <= values[m[s]] + tie:
            unique = False
    forced = tuple(sorted(int(i) for m, s in zip(members, slots, strict=True)
                          for i in m[:s])) if unique else None  # fmt: skip
    return PlaneBound(float(best), forced, groups, v_min, turn)


def campaign_plane_bound(catalog, campaign, values) -> PlaneBound:
    """:func:`plane_value_bound` of a max-value campaign over ``catalog``."""
    counts = [mission.n for mission in campaign.missions]
    band = (min(m.drift_altitude_km[0] for m in campaign.missions),
            max(m.drift_altitude_km[1] for m in campaign.missions))
    return plane_value_bound(catalog.inc_rad, catalog.a_m, values, counts,
                             float(max(campaign.dv_budget_mps)), band)  # fmt: skip
