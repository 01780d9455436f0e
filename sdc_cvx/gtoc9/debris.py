"""GTOC9's debris by id and MJD2000 epoch (:class:`DebrisTable`), from its debris file.

A thin index over :class:`~sdc_cvx.flight.gtoc9_ephemeris.Gtoc9Ephemeris` (GTOC9's own
secular-J2 ephemeris): the file's integer ids, epochs as MJD2000 days.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pandas as pd

from ..flight.gtoc9_ephemeris import Gtoc9Ephemeris

MJD2000 = pd.Timestamp("2000-01-01T00:00:00Z")
"""MJD2000 0 (JD 2451544.5), UTC as the GTOC9 reader has it."""
DEFAULT_DEBRIS = Path(__file__).resolve().parents[2].parent / "shared/data/gtoc9/debris_data.txt"
"""Where a checkout beside the project's shared data finds GTOC9's debris file."""
ENV_DEBRIS = "SDC_CVX_GTOC9_DEBRIS"
"""The environment variable naming the debris file (before :data:`DEFAULT_DEBRIS`)."""


class DebrisTable:
    """GTOC9's debris from a debris file (``debris_data.txt`` or ``debris.csv``)."""

    def __init__(self, ephemeris: Gtoc9Ephemeris):
        self.ephemeris = ephemeris
        self.source = ephemeris.source
        self._position = {int(ident): k for k, ident in enumerate(ephemeris.ids)}
        self._start_mjd2000 = (ephemeris.start - MJD2000).total_seconds() / 86400.0

    @classmethod
    def read(cls, path: str | os.PathLike | None = None) -> DebrisTable:
        """Read the debris file ``path`` (default :func:`find_debris_file`); CatalogError
        if it is not a GTOC9 debris file."""
        from ..inputs.formats import read_gtoc9

        return cls(Gtoc9Ephemeris.from_catalog(read_gtoc9(path or find_debris_file())))

    @property
    def ids(self) -> list[int]:
        return sorted(self._position)

    def has(self, ident: int) -> bool:
        return ident in self._position

    def state(self, ident: int, mjd2000: float) -> tuple[np.ndarray, np.ndarray]:
        """Position [m] and velocity [m/s] (3,) of debris ``ident`` at ``mjd2000`` [days]."""
        seconds = (mjd2000 - self._start_mjd2000) * 86400.0
        r, v = self.ephemeris.state(self._position[ident], seconds)
        return r[0], v[0]


def find_debris_file(folder: str | os.PathLike | None = None) -> Path:
    """The debris file to check against: ``$SDC_CVX_GTOC9_DEBRIS``, else ``debris.csv`` or
    ``debris_data.txt`` in ``folder`` or its parent, else :data:`DEFAULT_DEBRIS`."""
    if os.environ.get(ENV_DEBRIS):
        return Path(os.environ[ENV_DEBRIS])
    if folder is not None:
        for where in (Path(folder), Path(folder).parent):
            for name in ("debris.csv", "debris_data.txt"):
                if (where / name).is_file():
                    return where / name
    return DEFAULT_DEBRIS
