"""MILP: solver options, normalised results, the backend table and the solve with fallback.

With :mod:`sdc_cvx.planner` and :mod:`sdc_cvx.campaign`, the only places that import CVXPY
(:mod:`.types` names the backends without it).
"""
