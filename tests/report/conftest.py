"""The paper case solved once for every report test."""

import pytest

from sdc_cvx import Catalog, solve


@pytest.fixture(scope="session")
def solution():
    return solve()


@pytest.fixture(scope="session")
def catalog():
    return Catalog.paper_case()
