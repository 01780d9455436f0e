"""Planner: :func:`~sdc_cvx.planner.api.solve`, a mission planned by one of two methods.

- :mod:`.certified`, the default (``SolverOptions(method="certified")``): the certified
  search, the optimum bracketed by a proven lower bound;
- :mod:`.paper` (``SolverOptions(method="paper")``): the paper's method (Cerf, Part IV),
  sequential linearisation then re-optimisation, a local method without a bound; only
  :mod:`.api` imports it.

Both share :mod:`.nodes` (the mission's nodes, a plan's legs) and :mod:`.fixed_path` (a
fixed path's certified schedule); :mod:`.size_guard` refuses a catalogue too large for
the machine before the cost tables are built.
"""
