"""sdc_cvx: plan active debris removal missions (Cerf's method) as a CVXPY mixed-integer program.

Data flow: :class:`Catalog` + :class:`Mission` -> :func:`preoptimize` (edge table)
-> linearisation -> CVXPY model -> sequential driver -> nonlinear re-optimisation.
"""

from .inputs.catalog import Catalog, CatalogError
from .inputs.mission import Mission, MissionError
from .milp.backends import SolverOptions
from .network.edges import EdgeTable, preoptimize
from .planner.sequential import MissionInfeasible, SequentialSettings, SolverFailure, solve
from .solution import Solution
from .study.runner import plot_sweep, sweep

__all__ = [
    "Catalog",
    "CatalogError",
    "EdgeTable",
    "Mission",
    "MissionError",
    "MissionInfeasible",
    "SequentialSettings",
    "Solution",
    "SolverFailure",
    "SolverOptions",
    "plot_sweep",
    "preoptimize",
    "solve",
    "sweep",
]
__version__ = "0.1.0"
