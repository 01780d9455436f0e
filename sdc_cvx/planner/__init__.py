"""Planner: linearisation, the CVXPY path model, the sequential driver, the re-optimisation."""
