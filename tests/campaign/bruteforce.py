"""An independent brute force of a campaign's optimum, for the campaign's tests.

For each launch, the catalog's RAANs are carried to the launch day here, with the J2
rate re-derived from the paper (Eq. 7 for the debris' own a, e, I, from
``tests/paper_physics.py``: nothing of ``Catalog.advanced`` nor of the package's
``physics`` layer); every ordered path of the launch's n debris is then optimised by the
mission brute force (``tests/planner/bruteforce.py``: a grid over every leg's drift orbit
with the physics of ``tests/paper_physics.py``, each plan replayed).  The best order of
each debris set is kept per launch, and every choice of one set per launch with no debris
twice (and every ``must_remove`` debris in some set) is enumerated: the cheapest is the
campaign's optimum, up to the mission brute force's grid error (0.05 m/s per mission).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from sdc_cvx import Catalog
from tests.paper_physics import SECONDS_PER_DAY, raan_rate
from tests.planner.bruteforce import Enumeration

GRID = {2: (2, 2), 3: (1001, 101)}
"""Radii of the middle legs and of their zoom, by n (those of test_certified_property)."""


def raan_rate_deg_per_day(a_km, e, inc_deg):
    """Eq. 7: dOmega/dt = -C_J2 cos I / (a^3.5 (1 - e^2)^2), in deg/day (a in km, I in deg)."""
    a = np.asarray(a_km, dtype=float) * 1e3
    return np.degrees(raan_rate(a, e, np.radians(inc_deg))) * SECONDS_PER_DAY


def advanced(catalog: Catalog, days: float) -> Catalog:
    """The catalog ``days`` later (RAANs by Eq. 7, as re-derived above)."""
    f = catalog.frame
    raan = np.mod(
        f["raan_deg"] + raan_rate_deg_per_day(f["a_km"], f["e"], f["inc_deg"]) * days, 360.0
    )
    frame = pd.DataFrame(
        {"id": f["id"], "a_km": f["a_km"], "e": f["e"], "inc_deg": f["inc_deg"], "raan_deg": raan}
    )
    return Catalog.from_frame(frame)


@dataclass(frozen=True)
class CampaignOptimum:
    dv_mps: float
    sets: tuple[frozenset, ...]  # debris ids removed by each launch
    per_launch: tuple[dict, ...]  # launch -> {frozenset of ids: best dv}


def best_sets(catalog: Catalog, day: float, n: int, tmax: float, rule: str) -> dict:
    """Every debris set of n a mission launched on ``day`` removes: {frozenset: best dv}.

    ``n = 0``: the launch unused (0 m/s); ``n = 1``: the launch onto the debris' orbit
    alone, 0 m/s (no operations cost, no deorbit time, as the cases here have)."""
    if n == 0:
        return {frozenset(): 0.0}
    if n == 1:
        return {frozenset([str(k)]): 0.0 for k in catalog.ids}
    moved = advanced(catalog, day)
    middle, zoom = GRID[n]
    en = Enumeration(moved, n, tmax, middle_count=middle, zoom_count=zoom, walk=8)
    best: dict = {}
    for plan in en.plans[rule]:
        if np.isfinite(plan.dv):
            key = frozenset(en.ids(plan))
            best[key] = min(best.get(key, np.inf), plan.dv)
    return best


def campaign_optimum(
    catalog: Catalog, launch_days, ns, tmaxes, rule="table3", must_remove=()
) -> CampaignOptimum:
    per_launch = [best_sets(catalog, day, n, tmax, rule)
                  for day, n, tmax in zip(launch_days, ns, tmaxes, strict=True)]  # fmt: skip
    must = frozenset(str(k) for k in must_remove)
    value, sets = np.inf, ()
    options = [sorted(b.items(), key=lambda kv: kv[1]) for b in per_launch]
    for choice in itertools.product(*options):
        chosen = [c[0] for c in choice]
        union = frozenset().union(*chosen)
        if len(union) != sum(len(c) for c in chosen) or not must <= union:
            continue
        total = sum(c[1] for c in choice)
        if total < value:
            value, sets = total, tuple(chosen)
    return CampaignOptimum(float(value), sets, tuple(per_launch))


@dataclass(frozen=True)
class ValueOptimum:
    value: float
    dv_mps: float
    sets: tuple[frozenset, ...]
    margin_mps: float  # how near a set's dv comes to its launch's budget (grid error)


def value_options(catalog: Catalog, launch_days, ranges, tmaxes, budgets, rule="table3"):
    """Per launch, every debris set of its range flown within its budget (sorted by dv),
    and how near any set's dv comes to its launch's budget (the grid error's margin)."""
    options, margin = [], np.inf
    for day, (low, high), tmax, budget in zip(launch_days, ranges, tmaxes, budgets,
                                              strict=True):  # fmt: skip
        sets = {}
        for n in range(low, high + 1):
            for key, dv in best_sets(catalog, day, n, tmax, rule).items():
                margin = min(margin, abs(dv - budget))
                if dv <= budget:
                    sets[key] = dv
        options.append(sorted(sets.items(), key=lambda kv: kv[1]))
    return options, float(margin)


def campaigns_of(options, values: dict):
    """Every choice of one set per launch with no debris twice: (value, dv, sets)."""
    for choice in itertools.product(*options):
        chosen = [c[0] for c in choice]
        if len(frozenset().union(*chosen)) != sum(len(c) for c in chosen):
            continue
        worth = sum(values.get(d, 0.0) for c in chosen for d in c)
        yield worth, sum(c[1] for c in choice), tuple(chosen)


def value_optimum(catalog: Catalog, launch_days, ranges, tmaxes, budgets, values: dict,
                  rule="table3") -> ValueOptimum:  # fmt: skip
    """The most valuable campaign: one set per launch of between n_min and n_max debris,
    each flown within its launch's budget (total ΔV), no debris twice; among those of
    the most value, the least ΔV (every choice enumerated)."""
    options, margin = value_options(catalog, launch_days, ranges, tmaxes, budgets, rule)
    best = (-np.inf, np.inf, ())
    for worth, total, chosen in campaigns_of(options, values):
        if worth > best[0] + 1e-9 or (abs(worth - best[0]) <= 1e-9 and total < best[1]):
            best = (worth, total, chosen)
    return ValueOptimum(float(best[0]), float(best[1]), best[2], margin)
