"""The campaign master's LP with its prices kept in a box (the boxstep method), against
its dual written out independently and solved by SciPy's linprog:

    max  sum_k sigma_k - sum_i y_i
    s.t. sigma_k(c) - sum_{i in c} y_i <= cost_c      for every column c
         y_i >= 0                                    for a debris that may stay
         centre_i - width <= y_i <= centre_i + width  (the box; a packing row: the top)
         sigma_k <= 1e5, -y_i <= 1e5 (must)           (the artificial columns)
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import linprog

from sdc_cvx.campaign.master import ARTIFICIAL_MPS, solve_lp


def random_pool(seed: int):
    rng = np.random.default_rng(seed)
    launches, debris = int(rng.integers(2, 4)), int(rng.integers(5, 9))
    columns = []
    for _ in range(int(rng.integers(6, 16))):
        size = int(rng.integers(1, 4))
        chosen = tuple(sorted(rng.choice(debris, size, replace=False).tolist()))
        columns.append(SimpleNamespace(launch=int(rng.integers(launches)), debris=chosen,
                                       dv_mps=float(rng.uniform(50, 300))))  # fmt: skip
    for k in range(launches):  # every launch has a column
        columns.append(SimpleNamespace(launch=k, debris=(k,), dv_mps=float(rng.uniform(50, 300))))
    must = tuple(sorted(rng.choice(debris, int(rng.integers(0, 3)), replace=False).tolist()))
    return columns, launches, debris, must, rng


def dual_by_linprog(columns, launches, debris, must, box):
    """The master's dual, variables (sigma, y), its optimum value."""
    covered = {i for c in columns for i in c.debris} | set(must)
    a_ub, b_ub = [], []
    for c in columns:
        row = np.zeros(launches + debris)
        row[c.launch] = 1.0
        row[launches + np.asarray(c.debris)] = -1.0
        a_ub.append(row)
        b_ub.append(c.dv_mps)
    bounds = [(None, ARTIFICIAL_MPS)] * launches
    for i in range(debris):
        low, high = (-ARTIFICIAL_MPS, None) if i in must else (0.0, None)
        if i not in covered:
            low, high = 0.0, 0.0
        elif box is not None:
            centre, width = box
            high = centre[i] + width
            if i in must:
                low = centre[i] - width
        bounds.append((low, high))
    objective = -np.r_[np.ones(launches), -np.ones(debris)]
    out = linprog(objective, A_ub=np.array(a_ub), b_ub=b_ub, bounds=bounds, method="highs")
    assert out.status == 0
    return -out.fun


@pytest.mark.parametrize("seed", range(12))
def test_the_box_lp_is_its_dual_and_keeps_the_prices_in_the_box(seed):
    columns, launches, debris, must, rng = random_pool(seed)
    plain = solve_lp(columns, launches, debris, must)
    assert plain.value == pytest.approx(dual_by_linprog(columns, launches, debris, must, None),
                                        rel=1e-7, abs=1e-6)  # fmt: skip
    assert plain.boxed == 0.0
    centre = np.where(np.isin(np.arange(debris), must), -rng.uniform(0, 80, debris),
                      rng.uniform(0, 20, debris))  # fmt: skip
    width = float(rng.uniform(1, 30))
    boxed = solve_lp(columns, launches, debris, must, box=(centre, width))
    assert boxed.value == pytest.approx(
        dual_by_linprog(columns, launches, debris, must, (centre, width)), rel=1e-7, abs=1e-6)
    assert boxed.value <= plain.value + 1e-6  # the box restricts the prices
    covered = sorted({i for c in columns for i in c.debris} | set(must))
    assert np.all(boxed.prices[covered] <= centre[covered] + width + 1e-6)
    assert np.all(boxed.prices[list(must)] >= centre[list(must)] - width - 1e-6)
    # every column's reduced cost at the box's prices is >= 0 (they are dual feasible)
    for c in columns:
        reduced = c.dv_mps + boxed.prices[list(c.debris)].sum() - boxed.sigma[c.launch]
        assert reduced >= -1e-6
    # a box wide enough not to bind: the plain LP again
    wide = solve_lp(columns, launches, debris, must, box=(np.zeros(debris), 1e6))
    assert wide.boxed == pytest.approx(0.0, abs=1e-9)
    assert wide.value == pytest.approx(plain.value, rel=1e-7, abs=1e-6)


def test_a_packing_rows_price_is_never_negative():
    """A debris that may stay has a row "removed at most once": its multiplier must be
    >= 0 for the Lagrangian bound ``sum_k min_c (cost_c + sum_{i in c} y_i) - sum_i y_i``
    to bound every campaign (a negative y_i counts a debris no campaign removes as a
    prize).  HiGHS gives debris 6 a price of -7.4e-13 on this pool (found by a search
    over random pools; the artificial columns are at the optimum), which the master must
    not pass on to the pricing."""
    pool = [(0, (0, 3, 6), 20.0), (0, (2, 4, 5), 30.0), (0, (2, 4, 5), 134.4029767792666),
            (0, (0, 2, 3), 964.4502206741796), (1, (2, 3, 5), 20.0),
            (1, (0, 2, 3), 342.7277586778015), (2, (1, 3, 6), 792.4388520699708),
            (2, (0, 1, 4), 678.7626759024807), (2, (1, 3, 6), 20.0),
            (2, (2, 3, 4), 812.9636535970384), (2, (2, 3, 5), 350.61174793055784),
            (2, (4, 5, 6), 30.0), (2, (0, 1, 4), 288.17533259215924)]  # fmt: skip
    columns = [SimpleNamespace(launch=k, debris=debris, dv_mps=dv) for k, debris, dv in pool]
    lp = solve_lp(columns, 3, 7)
    assert lp.value == pytest.approx(dual_by_linprog(columns, 3, 7, (), None), rel=1e-9)
    assert np.all(lp.prices >= 0.0), lp.prices
