"""The paper case solved once for every report test (by the paper's method: the figures
of its iterations, Table 7, are among those checked)."""

import pytest

from sdc_cvx import Catalog, SolverOptions, solve


@pytest.fixture(scope="session")
def solution():
    return solve(solver=SolverOptions(method="paper"))


@pytest.fixture(scope="session")
def catalog():
    return Catalog.paper_case()
