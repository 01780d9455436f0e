"""The mixed-integer program of Eq. 22 in CVXPY, over the sparse list of kept edges.

Built once per edge structure; every coefficient and bound that changes between
iterations is a ``cp.Parameter`` that :meth:`PathModel.update` re-values, so a
re-solve skips CVXPY's canonicalisation.  Scaled units: km (drift radius offsets),
days (dates), m/s (cost).

Variables (m kept edges, N debris):

=========  ======  ====================================================================
``s``      m bin   edge selected (s_ij)
``x, y``   N bin   debris has an arriving / departing edge (x_k, y_k)
``z``      N bin   ``x_k y_k`` (Eq. 19): a mid-path debris
``p``      m       ``s_ij alpha_ij`` (Eq. 19, 21), km
``d``      m       ``s_ij (t_i + T_deorb)``, the departure date of a selected edge, days;
                   with ``t_ref`` this is ``q_ij = d - s_ij t_ref`` of Eq. 21 (docs/design.md §5.3)
``w``      m       epigraph of the two-secant linearised cost, m/s
``t``      N       arrival date at each debris, days (first debris at 0)
``u``      N       position along the path (MTZ ordering, docs/design.md §5.2)
=========  ======  ====================================================================

Closures of the paper's gaps (docs/design.md §5): arrival dates follow the linearised
durations of selected edges (with equality: the paper's "leave each debris as soon
as possible", Part III-H, which makes dates a function of the path and so gives
the driver meaningful reference dates), the first debris is at t = 0, every date is within
T_max, MTZ rows forbid a disjoint cycle even with zero-length legs, one date per
debris.  Eq. 19 for ``p`` reduces to ``s alpha_lo <= p <= s alpha_hi`` because alpha
appears nowhere else, which removes alpha as a variable without changing the model.

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

import cvxpy as cp
import numpy as np
import scipy.sparse as sp

from .linearize import Coefficients


@dataclass(frozen=True)
class ModelSize:
    """Dimensions of a model: binaries, continuous variables and constraint rows."""

    binaries: int
    continuous: int
    constraints: int

    @staticmethod
    def paper(n_debris: int) -> ModelSize:
        """The paper's count for Eq. 22 before filtering (Part IV-A): N^2+3N, 3N^2-2N, 9N^2-2N+3."""
        n = n_debris
        return ModelSize(n * n + 3 * n, 3 * n * n - 2 * n, 9 * n * n - 2 * n + 3)


class PathModel:
    """Eq. 22 for one edge structure, re-solved by assigning parameter values.

    Parameters
    ----------
    n_debris : int
        N, number of candidate debris.
    edges_from, edges_to : array_like of int
        Debris positions of the m kept edges.
    n : int
        Number of debris to visit.
    tmax_days, min_transfer_days : float
        T_max, T_min [days].
    deorbit_days : float or array_like
        T_deorb, operations time at each debris [days]: one value, or one per debris
        (an injection orbit has none).
    operations_dv_mps : float or array_like
        C_k, cost of the operations at each debris [m/s]: one value or one per debris.
    first : int, optional
        Debris fixed at the head of the path (x = 0, y = 1): the first debris asked
        for, or the injection orbit (Part II-C).
    must_visit : sequence of int
        Debris that must be on the path (s_k = x_k + y_k - z_k = 1).
    duration_model : {"secant", "two_segments"}
        One secant per edge (Eq. 17-18), or the paper's two half-segments through the
        reference (Fig. 14): ``alpha = p_up - p_down`` with a binary ``sigma`` for the
        sign of alpha, because the dates follow durations with equality, which a
        max-of-two-lines bound cannot express.
    """

    def __init__(self, n_debris, edges_from, edges_to, *, n, tmax_days, deorbit_days=0.0,
                 min_transfer_days=0.0, operations_dv_mps=0.0,
                 duration_model="secant", first=None, must_visit=()):  # fmt: skip
        self.n_debris = n_debris
        self.edges_from = np.asarray(edges_from, dtype=int)
        self.edges_to = np.asarray(edges_to, dtype=int)
        self.n = n
        m = len(self.edges_from)
        self.m = m
        big_t = float(tmax_days)
        t_deorb = np.broadcast_to(np.asarray(deorbit_days, dtype=float), (n_debris,))
        ops_cost = np.broadcast_to(np.asarray(operations_dv_mps, dtype=float), (n_debris,))
        t_deorb_from = t_deorb[self.edges_from]  # operations before each edge's departure
        n_float = float(n)

        # parameters: re-valued every iteration
        self.c0 = [cp.Parameter(m, name=f"c0_{k}") for k in range(2)]
        self.c1 = [cp.Parameter(m, name=f"c1_{k}") for k in range(2)]
        self.t0_shifted = cp.Parameter(m, name="t0_minus_t2_tref")  # T0 - T2 t_ref (DPP)
        self.t1 = cp.Parameter(m, name="t1")
        self.t2 = cp.Parameter(m, name="t2")
        self.alpha_lo = cp.Parameter(m, name="alpha_lo")
        self.alpha_hi = cp.Parameter(m, name="alpha_hi")
        self.depart_lo = cp.Parameter(m, name="depart_lo")
        self.depart_hi = cp.Parameter(m, name="depart_hi")
        self.available = cp.Parameter(m, name="available", nonneg=True)

        s = self.s = cp.Variable(m, boolean=True, name="s")
        x = self.x = cp.Variable(n_debris, boolean=True, name="x")
        y = self.y = cp.Variable(n_debris, boolean=True, name="y")
        z = self.z = cp.Variable(n_debris, boolean=True, name="z")
        p = self.p = cp.Variable(m, name="p")
        d = self.d = cp.Variable(m, name="d")
        w = self.w = cp.Variable(m, name="w")
        t = self.t = cp.Variable(n_debris, name="t")
        u = self.u = cp.Variable(n_debris, name="u")

        cols = np.arange(m)
        into = sp.csr_matrix((np.ones(m), (self.edges_to, cols)), shape=(n_debris, m))
        out_of = sp.csr_matrix((np.ones(m), (self.edges_from, cols)), shape=(n_debris, m))
        t_from, t_to = out_of.T @ t, into.T @ t  # date of each edge's ends
        u_from, u_to = out_of.T @ u, into.T @ u

        def times(param, var):
            # diag(P) @ v compiles fast with many parameters (docs/design.md §5), unlike multiply
            return cp.diag(param) @ var

        if duration_model not in ("secant", "two_segments"):
            raise ValueError(
                f"duration_model must be 'secant' or 'two_segments', got {duration_model!r}"
            )
        self.two_segments = duration_model == "two_segments"
        split_rows = []
        if self.two_segments:
            self.t1_lo = cp.Parameter(m, name="t1_lo")
            sigma = self.sigma = cp.Variable(m, boolean=True, name="sigma")  # alpha >= 0
            p_up = self.p_up = cp.Variable(m, nonneg=True, name="p_up")
            p_down = self.p_down = cp.Variable(m, nonneg=True, name="p_down")
            split_rows = [
                p == p_up - p_down,
                sigma <= s,
                p_up <= times(self.alpha_hi, sigma),
                p_down <= -times(self.alpha_lo, s - sigma),
            ]
            slopes = times(self.t1, p_up) - times(self.t1_lo, p_down)  # t1 holds t1_hi here
        else:
            slopes = times(self.t1, p)
        duration = times(self.t0_shifted, s) + slopes + times(self.t2, d)
        self.duration = duration
        start = y - z  # 1 only at the first debris (Eq. 16's counting argument)
        visited = x + y - z  # s_k of Eq. 16: 1 for the n debris on the path
        constraints = {
            "count": [cp.sum(s) == n - 1, cp.sum(z) == n - 2],
            "degree": [x == into @ s, y == out_of @ s],
            "product_z": [z <= x, z <= y, z >= x + y - 1],
            "available": [s <= self.available],
            "product_p": [p >= times(self.alpha_lo, s), p <= times(self.alpha_hi, s)],
            "product_d": [
                d >= times(self.depart_lo, s),
                d <= times(self.depart_hi, s),
                d <= t_from + cp.multiply(t_deorb_from, s),
                d >= t_from + t_deorb_from - big_t * (1 - s),
            ],
            "chronology": [
                t_to >= d + duration,
                t_to <= d + duration + big_t * (1 - s),  # leave as soon as possible (III-H)
                t_to >= d + float(min_transfer_days) * s,
            ],
            "duration": [cp.sum(duration) + t_deorb @ visited <= big_t],
            "dates": [t >= 0, t <= big_t - t_deorb, t <= big_t * (1 - start)],
            "required": [start[k] == 1 for k in ([first] if first is not None else [])]
            + [visited[k] == 1 for k in must_visit],
            "ordering": [u >= 0, u <= n_float - 1, u_to >= u_from + 1 - n_float * (1 - s)],
            "cost": [w >= times(self.c0[k], s) + times(self.c1[k], p) for k in range(2)],
            "alpha_sign": split_rows,
        }
        self.constraint_groups = constraints
        objective = cp.Minimize(cp.sum(w) + ops_cost @ visited)
        self.problem = cp.Problem(objective, [c for group in constraints.values() for c in group])

    def update(self, coefficients: Coefficients) -> None:
        """Assign the parameter values of one iteration (no recompilation)."""
        k = coefficients
        for piece in range(2):
            self.c0[piece].value = k.c0[piece]
            self.c1[piece].value = k.c1[piece]
        if self.two_segments:
            self.t0_shifted.value = k.t_mid - k.t2 * k.t_ref
            self.t1.value = k.t1_hi
            self.t1_lo.value = k.t1_lo
        else:
            self.t0_shifted.value = k.t0 - k.t2 * k.t_ref
            self.t1.value = k.t1
        self.t2.value = k.t2
        self.alpha_lo.value = k.alpha_lo
        self.alpha_hi.value = k.alpha_hi
        self.depart_lo.value = k.depart_lo
        self.depart_hi.value = k.depart_hi
        self.available.value = k.available.astype(float)

    def size(self) -> ModelSize:
        """Binaries, continuous variables and scalar constraint rows of this model."""
        binaries = sum(v.size for v in self.problem.variables() if v.attributes["boolean"])
        continuous = sum(v.size for v in self.problem.variables()) - binaries
        rows = sum(c.size for c in self.problem.constraints)
        return ModelSize(binaries, continuous, rows)
