"""The paper's method: sequential linearisation, then re-optimisation (Cerf [1]_, Part IV).

:func:`solve` plans a mission as the paper does, a local method without a bound
(``SolverOptions(method="paper")`` in :func:`sdc_cvx.solve`); :class:`SequentialSettings`
are its settings.  Its modules, in the order of Part IV:

- ``linearize.py``: each edge's cost, duration and date terms linearised around a
  reference (Part IV-A, Eq. 17-20);
- ``model.py``: the path problem (Eq. 22) in CVXPY, built once, re-valued each iteration;
- ``settings.py``: :class:`SequentialSettings`, and the date windows a mission gets;
- ``driver.py``: the iterations (Part IV-C, Table 7) and :func:`solve`; its steps come by
  phase from ``incumbents.py`` (the seeding and the plans held, which bound the answer),
  ``trust.py`` (references and trust intervals, phases 1 and 2), ``true_model.py``
  (evaluation, the side and inclination check, re-optimisation, the final schedule) and
  ``run_log.py`` (the iterations of Table 7, notes and timings);
- ``decisions.py``: the driver's rules after each iteration, as one pure function;
- ``reoptimize.py``: the fixed path re-optimised in the true model (Part IV-D).

What it shares with the certified search (the mission's nodes, a plan's legs) is in
:mod:`sdc_cvx.planner.nodes`; the certified search does not import this package.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from .driver import solve
from .settings import SequentialSettings

__all__ = ["SequentialSettings", "solve"]
