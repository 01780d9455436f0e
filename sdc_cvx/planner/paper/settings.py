"""The settings of the paper's method, and the defaults it takes from the mission.

:class:`SequentialSettings` holds the trust intervals of the iterations (Part IV-C: wide
while the path changes, halved once it is stable), when the iterations stop, and the
driver's additions to the paper (departure-date windows, seed paths, side and inclination
rounds, confirmations).  :func:`default_date_windows` chooses how many date windows
replicate each edge when the settings leave it open, from how far the RAAN gaps move over
the mission (:func:`frozen_gaps`).

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...inputs.catalog import Catalog
from ...inputs.mission import Mission
from ...network.edges import node_orbits
from ...physics.orbits import SECONDS_PER_DAY

FROZEN_GAP_DEG = 0.1
MAX_WINDOW_COPIES = 120


@dataclass(frozen=True)
class SequentialSettings:
    """Settings of the sequential linearisation.

    Parameters
    ----------
    alpha_km : float
        Initial (and restored) half-width of the drift-radius trust interval [km].
    tau_days : float, optional
        Initial half-width of the departure-date trust interval [days]; default T_max.
    shrink : float
        Factor applied to both half-widths once the path is stable (paper: halve).
    min_alpha_km : float
        Narrowest radius half-width [km]; reaching it ends phase 2.
    dv_tol_mps : float
        Convergence when the path is unchanged and the true ΔV moved less than this
        [m/s].  The re-optimisation in the true model (Part IV-D) then settles the
        radii, so phase 2 need not: with 0.5 instead of 0.05 the paper case takes 8
        iterations instead of 10 to the same plan, and the enumeration cases end the same.
    max_iterations : int
    max_repeats : int
        The run stops (status ``stalled``) when this many iterations in a row return the
        solution of the one before them (same path, copies, radii and true ΔV): the
        steps between them changed nothing.  On the enumeration catalogs 5 of 8 runs
        otherwise spent up to 39 of their 40 iterations repeating one solution.
    max_assumption_rounds : int
        How many times the side/inclination check may resume the iterations.
    max_confirmations : int
        How many times a re-optimised point is confirmed by one more MILP.
    initial_retries : int
        How many times the first MILP is retried with halved radius intervals before
        the mission is declared infeasible.
    date_windows : int, optional
        Number of departure-date windows over which every edge is replicated, each with
        its own reference (:func:`~sdc_cvx.network.edges.preoptimize_windows`); default
        :func:`default_date_windows`.  1 is the paper's single reference per edge.
    duration_model : {"secant", "two_segments"}
        The paper's secant duration (Eq. 17-18) or its two half-segments (Fig. 14),
        tighter at the cost of one more binary per edge (see ``benchmarks``).
    seed_paths : int
        Before the first MILP, the cheapest ``seed_paths`` paths of each of two rankings
        are re-optimised in the true model
        (:meth:`~sdc_cvx.planner.paper.incumbents.IncumbentSteps.seed`); the cheapest
        plan that ends by T_max is held from the start, bounds the answer (dominated edges
        leave the first MILP) and is the first MILP's starting point.  0: none.
    """

    alpha_km: float = 50.0
    tau_days: float | None = None
    shrink: float = 0.5
    min_alpha_km: float = 0.01
    dv_tol_mps: float = 0.5
    max_iterations: int = 40
    max_repeats: int = 3
    max_assumption_rounds: int = 2
    max_confirmations: int = 3
    initial_retries: int = 3
    date_windows: int | None = None
    duration_model: str = "secant"
    seed_paths: int = 5


def frozen_gaps(catalog: Catalog, mission: Mission) -> bool:
    """True if no RAAN gap moves by more than ``FROZEN_GAP_DEG`` over the mission."""
    rates = node_orbits(catalog, mission).rate * SECONDS_PER_DAY  # rad/day
    return bool(np.rad2deg(rates.max() - rates.min()) * mission.tmax_days < FROZEN_GAP_DEG)


def default_date_windows(catalog: Catalog, mission: Mission, kept_edges: int, legs: int) -> int:
    """One departure-date window per leg on small date-sensitive cases, else one.

    - If no RAAN gap moves by more than ``FROZEN_GAP_DEG`` over the mission (the
      paper's case: 0.02 deg), a leg's date does not change its transfer: one window.
    - Windows multiply the model by n - 1.  Measured: on small catalogs whose J2 rates
      differ they find the enumerated optimum more often (3 of 8 cases against 1 of 8,
      ``tests/test_enumeration.py``); on a synthetic N = 30 catalog (83 edges, n = 5)
      they took 246 s against 5.5 s and ended 16 m/s worse.  So they are the default
      only while the time-expanded model stays under ``MAX_WINDOW_COPIES`` edge copies.
    """
    windows = legs
    if frozen_gaps(catalog, mission) or kept_edges * windows > MAX_WINDOW_COPIES:
        return 1
    return windows
