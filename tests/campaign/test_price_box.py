"""The centre of the campaign master's price box: the first centre (a uniform prize on the
debris that must go) against every choice of sizes, and the moves of the centre (serious
and null steps, the box doubling at its edge)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from sdc_cvx.campaign.price_box import FIRST_WIDTH, SERIOUS, PriceCentre, uniform_centre
from tests.campaign.test_campaign_ranges import random_size_bounds


def random_bounds(seed: int):
    rng = np.random.default_rng(seed)
    bounds = random_size_bounds(rng, every_launch_flies=True)
    lowest = sum(min(b) for b in bounds.values())
    highest = sum(max(n for n, v in b.items() if v < np.inf) for b in bounds.values())
    return bounds, int(rng.integers(lowest, highest + 1))


@pytest.mark.parametrize("seed", range(20))
def test_the_uniform_prize_bounds_every_choice_of_sizes_and_is_the_best_prize(seed):
    """L(c) = sum_k min_n (b_kn - n c) + M c, at the centre: at or below the least sum of
    bounds over the sizes that remove the M debris (each campaign costs at least that),
    and at or above L at every prize of a fine grid (the best uniform prize)."""
    bounds, required = random_bounds(seed)
    must = np.arange(required)
    centre = uniform_centre(bounds, must, required + 3)
    cheapest = min(sum(bounds[k][n] for k, n in enumerate(sizes))
                   for sizes in itertools.product(*(sorted(b) for b in bounds.values()))
                   if sum(sizes) >= required)  # fmt: skip
    assert centre.value <= cheapest + 1e-9

    def at(c):
        return sum(min(v - n * c for n, v in b.items()) for b in bounds.values()) + required * c

    assert centre.value >= max(at(c) for c in np.linspace(0, 100, 20001)) - 1e-9
    # the centre: a prize on the debris that must go, nothing on the others, and each
    # launch's bound there
    prize = -centre.prices[0]
    assert prize >= 0
    np.testing.assert_allclose(centre.prices[must], -prize)
    np.testing.assert_allclose(centre.prices[required:], 0.0)
    np.testing.assert_allclose(
        centre.bounds, [min(v - n * prize for n, v in bounds[k].items())
                                  for k in sorted(bounds)])  # fmt: skip
    assert centre.value == pytest.approx(centre.bounds.sum() + required * prize)


def test_no_centre_without_debris_that_must_go_or_without_a_bound():
    bounds = {0: {2: 10.0, 3: 20.0}}
    assert uniform_centre(bounds, np.array([], dtype=int), 5).prices is None
    assert uniform_centre({0: {2: -np.inf, 3: 20.0}}, np.arange(2), 5).prices is None
    assert uniform_centre({0: {2: np.inf, 3: np.inf}}, np.arange(2), 5).prices is None


def test_the_centre_moves_on_a_serious_step_and_the_box_doubles_at_its_edge():
    centre = PriceCentre(np.array([-10.0, 0.0]), np.array([5.0, 7.0]), value=12.0, width=4.0)
    np.testing.assert_array_equal(centre.box()[0], [-10.0, 0.0])
    assert centre.box()[1] == 4.0
    # a null step: the bound gains less than SERIOUS of what the box LP promised
    promised = 32.0
    assert not centre.update(np.array([-14.0, 0.0]), np.array([1.0, 1.0]),
                             12.0 + 0.9 * SERIOUS * (promised - 12.0), promised)  # fmt: skip
    np.testing.assert_array_equal(centre.prices, [-10.0, 0.0])
    assert centre.value == 12.0 and centre.width == 4.0
    # a serious step inside the box: the centre moves, the box keeps its size
    assert centre.update(np.array([-12.0, 1.0]), np.array([2.0, 3.0]), 15.0, promised)
    np.testing.assert_array_equal(centre.prices, [-12.0, 1.0])
    np.testing.assert_array_equal(centre.bounds, [2.0, 3.0])
    assert centre.value == 15.0 and centre.width == 4.0
    # a serious step to the box's edge: the box doubles
    assert centre.update(np.array([-16.0, 1.0]), np.array([2.0, 3.0]), 30.0, 31.0)
    assert centre.width == 8.0
    # no centre: no box, nothing moves
    assert PriceCentre().box() is None
    assert not PriceCentre().update(np.zeros(2), np.zeros(1), 1.0, 2.0)


def test_the_first_box_is_a_share_of_the_prize():
    centre = uniform_centre({0: {2: 10.0, 3: 40.0}, 1: {2: 20.0, 3: 80.0}}, np.arange(5), 6)
    prize = -centre.prices[0]
    # L(c) = min(10 - 2c, 40 - 3c) + min(20 - 2c, 80 - 3c) + 5c: 30 + c up to c = 30,
    # then 60 up to c = 60, then 120 - c
    assert 30.0 - 1e-9 <= prize <= 60.0 + 1e-9
    assert centre.value == pytest.approx(60.0)
    assert centre.width == pytest.approx(FIRST_WIDTH * prize)
