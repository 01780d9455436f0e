"""Stabilised prices for the campaign's column generation: a box around a centre.

The master LP of a campaign that must remove every debris is degenerate: its pool holds
about one covering, its optimum equals that campaign, and its duals jump from one vertex
of a wide optimal face to another, hundreds of m/s from any useful price.  Priced at
them, the launches return missions that do not lower the LP, and the Lagrangian bound
stays at its first value (GTOC9-all: the LP stayed at the plan for every round, the
bound at the launches alone).  The boxstep method [1]_ keeps the master's prices within
a box around a *centre*, the prices of the best Lagrangian bound so far
(:func:`~sdc_cvx.campaign.master.solve_lp` with ``box``):

- the box's LP value ``V`` is the most the pool's missions can prove at prices in the
  box; the pricing at its prices proves ``L(y)``, a bound like any other
  (``docs/design.md`` §10: any prices give one);
- where ``L(y)`` gains a tenth of ``V - L(centre)`` on the centre (a *serious step*, as
  in bundle methods [2]_), the centre moves there, and where the new prices reach the
  box's edge, the box doubles;
- otherwise (a *null step*) the missions found refine the master, and the next box LP
  is lower.

The LP is solved when the box does not bind and the pricing proves its value: the
bound is then the LP bound of the whole column generation.

The first centre needs no pricing: where debris must go, a uniform prize ``c`` on each
of them bounds each launch's missions of n debris by their bound alone less ``n c``
(:func:`uniform_centre`).  Without debris that must go there is no centre, and the
column generation prices at the LP's own duals.

References
----------
.. [1] R. E. Marsten, W. W. Hogan and J. W. Blankenship, "The BOXSTEP method for
   large-scale optimization", Operations Research 23(3), 389-405, 1975.
.. [2] O. du Merle, D. Villeneuve, J. Desrosiers and P. Hansen, "Stabilized column
   generation", Discrete Mathematics 194(1-3), 229-237, 1999.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SERIOUS = 0.1
"""Share of the box LP's promised gain a bound must make to move the centre [-]."""
FIRST_WIDTH = 0.05
"""The first box's half-width, as a share of the uniform prize [-] (GTOC9-all, prize
90 m/s: at 45 m/s the first round's prices sat at the box's corners and proved 2385 m/s,
below the centre's 3577; at 4.5 m/s, 4095 m/s, and the box doubled from there)."""
LEAST_WIDTH_MPS = 1.0
"""The first box's least half-width [m/s]."""


@dataclass
class PriceCentre:
    """The centre of the master's prices and its box.

    Attributes
    ----------
    prices : ndarray or None
        Prices of the best Lagrangian bound [m/s], shape (N,); None: no box.
    bounds : ndarray or None
        Each launch's proven bound under them [m/s], shape (K,).
    value : float
        The Lagrangian bound at the centre [m/s].
    width : float
        The box's half-width [m/s].
    """

    prices: np.ndarray | None = None
    bounds: np.ndarray | None = None
    value: float = -np.inf
    width: float = np.inf

    def box(self) -> tuple[np.ndarray, float] | None:
        """``(centre, half-width)`` for :func:`~sdc_cvx.campaign.master.solve_lp`."""
        return None if self.prices is None else (self.prices, self.width)

    def update(self, prices: np.ndarray, bounds: np.ndarray, value: float,
               promised: float) -> bool:  # fmt: skip
        """After a round priced at ``prices`` (the box LP's, whose value was
        ``promised``), whose launches' bounds were ``bounds`` and Lagrangian bound
        ``value`` [m/s]: move the centre on a serious step; True if it moved."""
        if self.prices is None or value < self.value + SERIOUS * (promised - self.value):
            return False
        reach = float(np.max(np.abs(np.asarray(prices) - self.prices), initial=0.0))
        if reach >= (1 - 1e-6) * self.width:
            self.width *= 2.0
        self.prices, self.bounds, self.value = (
            np.array(prices, dtype=float), np.array(bounds, dtype=float), float(value))
        return True


def uniform_centre(bounds: dict[int, dict[int, float]], must: np.ndarray,
                   n_debris: int) -> PriceCentre:  # fmt: skip
    """The first centre: a uniform prize on the debris that must go, the best one.

    With a prize ``c >= 0`` on each of the ``M`` debris that must go (a price of -c,
    nothing on the others), a mission of n debris of launch k costs at least its bound
    alone ``b_kn`` less ``n c`` (it removes at most n of them), so::

        L(c) = sum_k min_n (b_kn - n c) + M c

    bounds every campaign.  L is concave and piecewise linear in c: its maximum is at
    0 or where two sizes of a launch tie (``c = (b_kn - b_km) / (n - m)``), and each is
    tried.

    Parameters
    ----------
    bounds : dict
        ``bounds[k][n]``: no mission of launch k with n debris costs less, priced alone
        [m/s] (``-inf``: none proven; ``inf``: none flies).
    must : ndarray of int
        Catalog rows of the debris that must go.
    n_debris : int
        Catalog rows.

    Returns
    -------
    PriceCentre
        The centre, the launches' bounds there and its first box (:data:`FIRST_WIDTH`;
        no centre when a bound is missing, a launch flies no size or no debris must go).
    """
    by_launch = [{n: b for n, b in bounds[k].items() if b < np.inf} for k in sorted(bounds)]
    if len(must) == 0 or not all(by_launch) or any(
            b == -np.inf for by_size in by_launch for b in by_size.values()):
        return PriceCentre()  # nothing must go, a launch flies no size, or a size unproven
    sizes = [np.array(sorted(by_size), dtype=float) for by_size in by_launch]
    costs = [np.array([by_size[n] for n in sorted(by_size)]) for by_size in by_launch]
    kinks = {0.0} | {float((b[i] - b[j]) / (n[i] - n[j]))
                     for n, b in zip(sizes, costs, strict=True)
                     for i in range(len(n)) for j in range(i)}  # fmt: skip

    def launches(c: float) -> np.ndarray:
        return np.array([np.min(b - n * c) for n, b in zip(sizes, costs, strict=True)])

    best = max((c for c in kinks if c >= 0), key=lambda c: launches(c).sum() + len(must) * c)
    prices = np.zeros(n_debris)
    prices[np.asarray(must, dtype=int)] = -best
    at_best = launches(best)
    return PriceCentre(prices, at_best, float(at_best.sum() + len(must) * best),
                       max(FIRST_WIDTH * best, LEAST_WIDTH_MPS))  # fmt: skip
