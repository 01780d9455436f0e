"""The paper's method: sequential linearisation, then re-optimisation (Cerf [1]_, Part IV).

:func:`solve` plans a mission as the paper does, a local method without a bound
(``SolverOptions(method="paper")`` in :func:`sdc_cvx.solve`); :class:`SequentialSettings`
are its settings.  The modules follow Part IV:

- ``linearize.py``: cost, duration and date terms linearised per edge (Part IV-A, Eq. 17-20);
- ``model.py``: the path problem (Eq. 22) in CVXPY, built once, re-valued each iteration;
- ``driver.py``: the iterations (Part IV-C, Table 7) and :func:`solve`;
- ``decisions.py``: the driver's rules after each iteration, as one pure function;
- ``reoptimize.py``: the fixed path re-optimised in the true model (Part IV-D).

What it shares with the certified search is in :mod:`sdc_cvx.planner.nodes`.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from .driver import SequentialSettings, solve

__all__ = ["SequentialSettings", "solve"]
