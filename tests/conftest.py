"""Fixtures shared by several test modules."""

import pytest

from sdc_cvx.milp import solve as milp_solve


@pytest.fixture
def crash_backend(monkeypatch):
    """``crash_backend(NAME)``: every solve by backend NAME raises, the others run as usual."""

    def crash(name):
        real = milp_solve.solve_milp

        def solve_milp(problem, options, *, warm_start=False):
            if options.backend == name:
                raise RuntimeError("simulated crash")
            return real(problem, options, warm_start=warm_start)

        monkeypatch.setattr(milp_solve, "solve_milp", solve_milp)

    return crash
