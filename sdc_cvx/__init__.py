"""sdc_cvx: plan active debris removal missions (Cerf's method) as a CVXPY mixed-integer program.

Data flow: :class:`Catalog` + :class:`Mission` -> :func:`preoptimize` (edge table)
-> linearisation -> CVXPY model -> sequential driver -> nonlinear re-optimisation.
"""

from .catalog import Catalog, CatalogError
from .edges import EdgeTable, preoptimize
from .mission import Mission, MissionError

__all__ = ["Catalog", "CatalogError", "EdgeTable", "Mission", "MissionError", "preoptimize"]
__version__ = "0.1.0"
