"""The pricing search with prices on the debris, prizes (negative costs) included,
against the mission brute force.

A pricing problem is the certified single-mission search with a price added to each
debris' cost; a ``must_remove`` debris' price can be negative (a prize), which no
single mission has.  Every pruning rule of the search must stay valid then
(``docs/design.md`` §10).  For random prices in [-150, 100] m/s, on the catalog carried
to a launch day, the brute force (every ordered path, a grid over every drift orbit,
the true physics, each plan replayed) gives ``min over paths of (ΔV + prices)``:

* the pricing's proven bound is not above it (``lower <= brute + EPS``);
* its best column is at it (within its tolerance and the grid error);
* enumerating under a ceiling returns every path the brute force puts under it;
* a stop threshold is honoured: the bound reaches it, or a column below it is returned.
"""

from __future__ import annotations

import numpy as np
import pytest

from sdc_cvx import Mission
from sdc_cvx.campaign.pricing import Launch, price
from sdc_cvx.inputs.campaign import Campaign
from sdc_cvx.inputs.synthetic import sso_catalog
from tests.campaign.bruteforce import GRID, advanced
from tests.planner.bruteforce import Enumeration

EPS_MPS = 1e-3
GRID_TOL_MPS = 0.05
TOL_MPS = 0.01


def priced_brute(catalog, day, n, tmax, prices, rule="table3"):
    """Per path (ids), ΔV + prices of its best plan, by brute force; cheapest first."""
    middle, zoom = GRID[n]
    en = Enumeration(advanced(catalog, day), n, tmax, middle_count=middle, zoom_count=zoom,
                     walk=8)  # fmt: skip
    price_of = dict(zip(catalog.ids, prices, strict=True))
    out = [(plan.dv + sum(price_of[d] for d in en.ids(plan)), en.ids(plan))
           for plan in en.plans[rule] if np.isfinite(plan.dv)]  # fmt: skip
    return sorted(out)


def launch_of(catalog, day, n, tmax, rule="table3"):
    campaign = Campaign.of([day], Mission(n=n, tmax_days=tmax, drift_inclination=rule))
    return Launch.all_of(campaign, catalog)[0]


CASES = [  # size, catalog seed, price seed, launch day, n, tmax, rule
    pytest.param(7, 3, 1, 0.0, 2, 150.0, "table3", id="n2-day0"),
    pytest.param(7, 11, 2, 200.0, 3, 365.0, "table3", id="n3-day200", marks=pytest.mark.slow),
    pytest.param(8, 17, 3, 500.0, 3, 400.0, "free", id="n3-day500-free", marks=pytest.mark.slow),
]


def column_ids(launch, column):
    return tuple(launch.catalog.ids[k] for k in column.nodes)


@pytest.mark.parametrize(("size", "seed", "price_seed", "day", "n", "tmax", "rule"), CASES)
def test_pricing_with_prizes_is_the_brute_force_minimum(size, seed, price_seed, day, n, tmax,
                                                          rule):  # fmt: skip
    catalog = sso_catalog(size, seed=seed, inclination_spread_deg=0.8)
    prices = np.random.default_rng(price_seed).uniform(-150.0, 100.0, size)
    assert (prices < 0).any()  # prizes are exercised
    brute = priced_brute(catalog, day, n, tmax, prices, rule)
    best_value, best_path = brute[0]
    launch = launch_of(catalog, day, n, tmax, rule)
    result = price(launch, prices, tol_mps=TOL_MPS)
    found = (
        f"pricing {result.lower_mps:.3f}..{result.upper_mps:.3f}; "
        f"brute {best_value:.3f} {best_path}"
    )
    assert result.lower_mps <= best_value + EPS_MPS, found
    assert result.upper_mps <= best_value + TOL_MPS + EPS_MPS, found
    assert result.upper_mps >= best_value - GRID_TOL_MPS, found
    # the columns carry ΔV without the prices: their priced value is the search's
    top = result.columns[0]
    priced = top.dv_mps + float(np.sum(prices[list(top.debris)]))
    assert priced == pytest.approx(result.upper_mps, abs=1e-6)

    # enumeration: every path the brute force puts within 250 m/s of the best is returned
    ceiling = best_value + 250.0
    listed = price(launch, prices, tol_mps=TOL_MPS, ceiling_mps=ceiling)
    assert listed.complete
    got = {column_ids(launch, c) for c in listed.columns}
    wanted = {path for value, path in brute if value <= ceiling - GRID_TOL_MPS - TOL_MPS}
    assert len(wanted) >= 2  # the ceiling holds more than the best path
    assert wanted <= got, sorted(wanted - got)

    # a stop threshold: proven above it, or a column below it
    threshold = best_value + 5.0
    early = price(launch, prices, tol_mps=TOL_MPS, stop_above_mps=threshold)
    assert early.upper_mps < threshold or early.lower_mps >= threshold
    assert early.lower_mps <= best_value + EPS_MPS
