"""MILP: solver options, normalised results, the backend table and the solve with fallback.

The only place besides :mod:`sdc_cvx.planner` that imports CVXPY.
"""
