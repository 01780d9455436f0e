"""The certified search, the default method: the optimum bracketed by a lower bound.

- :mod:`.search`: :func:`certify`, the loop (dynamic discretisation discovery), over
  :mod:`.state` (what the search holds, one method per step of the loop);
- :mod:`.clock`: the edge cost tables against the time limit (``OutOfTime``);
- :mod:`.greedy`: a plan without the cost tables, when they are late;
- :mod:`.network`: the time-expanded network of date cells, its arcs and their bounds;
- :mod:`.relaxation`: the relaxation as a MILP in CVXPY (where labels are too many);
- :mod:`.date_grid`: the first plans, from a beam search over a grid of dates;
- :mod:`.results`: what the search takes and returns.

It shares :mod:`sdc_cvx.planner.fixed_path` (a fixed path's global schedule) and
:mod:`sdc_cvx.planner.nodes` with the paper's method and imports nothing of it.
"""

from .results import CertifiedNodes, CertifiedPath, CertifiedResult
from .search import certify

__all__ = ["CertifiedNodes", "CertifiedPath", "CertifiedResult", "certify"]
