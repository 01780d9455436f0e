"""The package's own CSV catalog (``id, a_km, e, inc_deg, raan_deg``; see
:meth:`~sdc_cvx.inputs.catalog.Catalog.from_csv`)."""

from __future__ import annotations

import os

from ..catalog import Catalog


def read_csv(path: str | os.PathLike, *, start=None, on_invalid: str = "raise") -> Catalog:
    """Read and validate a CSV catalog (:meth:`Catalog.from_csv`)."""
    return Catalog.from_csv(path, start=start, on_invalid=on_invalid)
