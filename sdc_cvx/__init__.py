"""sdc_cvx: plan active debris removal missions (Cerf's method) as a CVXPY mixed-integer program.

Data flow: :class:`Catalog` + :class:`Mission` -> :func:`preoptimize` (edge table)
-> linearisation -> CVXPY model -> sequential driver -> nonlinear re-optimisation.

The names below are imported when first used (a module-level ``__getattr__``), so
``import sdc_cvx`` loads neither CVXPY nor matplotlib nor the sweep machinery.  The
subpackages follow the pipeline: ``physics``, ``inputs``, ``network``, ``milp``,
``planner``, ``solution``, ``study``, ``report``, ``campaign`` (see docs/development.md,
"Layout").

Equation, table and part numbers are those of Cerf's paper [1]_; the design
rationale is in ``docs/design.md``.

References
----------
.. [1] M. Cerf, "Multiple Space Debris Collecting Mission — Debris Selection and Trajectory
   Optimization", Journal of Optimization Theory and Applications 156(3), 761–796, 2013.
   doi:10.1007/s10957-012-0130-6
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

_EXPORTS = {
    "Campaign": "sdc_cvx.inputs.campaign",
    "CampaignSolution": "sdc_cvx.campaign.result",
    "Catalog": "sdc_cvx.inputs.catalog",
    "CatalogError": "sdc_cvx.errors",
    "EdgeTable": "sdc_cvx.network.edges",
    "Mission": "sdc_cvx.inputs.mission",
    "MissionError": "sdc_cvx.errors",
    "MissionInfeasible": "sdc_cvx.errors",
    "SequentialSettings": "sdc_cvx.planner.paper.settings",
    "Solution": "sdc_cvx.solution",
    "SolverFailure": "sdc_cvx.errors",
    "SolverOptions": "sdc_cvx.milp.types",
    "Vehicle": "sdc_cvx.inputs.vehicle",
    "plot_sweep": "sdc_cvx.study.figure",
    "preoptimize": "sdc_cvx.network.edges",
    "read_catalog": "sdc_cvx.inputs.formats",
    "solve": "sdc_cvx.planner.api",
    "solve_campaign": "sdc_cvx.campaign.search",
    "sweep": "sdc_cvx.study.runner",
}
"""Each public name and the module it comes from."""

__all__ = [
    "Campaign",
    "CampaignSolution",
    "Catalog",
    "CatalogError",
    "EdgeTable",
    "Mission",
    "MissionError",
    "MissionInfeasible",
    "SequentialSettings",
    "Solution",
    "SolverFailure",
    "SolverOptions",
    "Vehicle",
    "plot_sweep",
    "preoptimize",
    "read_catalog",
    "solve",
    "solve_campaign",
    "sweep",
]

if TYPE_CHECKING:
    from .campaign.result import CampaignSolution
    from .campaign.search import solve_campaign
    from .errors import CatalogError, MissionError, MissionInfeasible, SolverFailure
    from .inputs.campaign import Campaign
    from .inputs.catalog import Catalog
    from .inputs.formats import read_catalog
    from .inputs.mission import Mission
    from .inputs.vehicle import Vehicle
    from .milp.types import SolverOptions
    from .network.edges import EdgeTable, preoptimize
    from .planner.api import solve
    from .planner.paper.settings import SequentialSettings
    from .solution import Solution
    from .study.figure import plot_sweep
    from .study.runner import sweep


def _version() -> str:
    """The installed distribution's version (``pyproject.toml``), not a second copy of it.

    Read when ``sdc_cvx.__version__`` is first asked for: ``importlib.metadata`` costs
    20-40 ms of a bare ``import sdc_cvx``.
    """
    from importlib import metadata

    try:
        return metadata.version("sdc_cvx")
    except metadata.PackageNotFoundError:  # a checkout on sys.path that was never installed
        return "0+unknown"


def __getattr__(name: str):
    if name == "__version__":
        globals()[name] = value = _version()
        return value
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'sdc_cvx' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # the next access does not come here
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *_EXPORTS, "__version__"})
