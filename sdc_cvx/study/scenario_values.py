"""``[catalog] values``: each debris' value for a max-value campaign, read or computed.

``values = "FILE.csv"`` reads a user's table (:func:`~sdc_cvx.inputs.values.read_values`);
``values = "csi"`` computes the Criticality of Spacecraft Index
(:mod:`~sdc_cvx.inputs.criticality`) of every object of the catalogue that
``masses = "FILE.csv"`` names (columns ``masses_columns``, default ``id,mass_kg``), the
spatial density from the whole catalogue file.  The candidates a campaign then chooses
among must all have a mass (:func:`candidates_without_mass`).
"""

from __future__ import annotations

from pathlib import Path

from ..errors import CatalogError
from ..inputs.criticality import csi_values
from ..inputs.formats import READERS
from ..inputs.values import read_values

CSI = "csi"
"""``[catalog] values`` computed as the Criticality of Spacecraft Index."""


def catalog_values(catalog: dict, base: Path, catalog_path, catalog_format, start,
                   problems: list[str]) -> tuple:  # fmt: skip
    """``(values, values_path, masses_path)`` of the ``[catalog]`` table: ``values`` by id
    (empty without ``values``), the values file's path (or :data:`CSI`) and the masses
    file's path, each problem appended to ``problems``."""
    if "values" not in catalog:
        if "masses" in catalog:
            problems.append('catalog.masses is for values = "csi" (the Criticality of '
                            "Spacecraft Index needs each debris' mass)")  # fmt: skip
        return {}, None, None
    if str(catalog["values"]).strip().lower() == CSI:
        return _csi(catalog, base, catalog_path, catalog_format, start, problems)
    values_path = (base / Path(catalog["values"]).expanduser()).resolve()
    columns = _columns(catalog, "values_columns", ("id", "value"), problems)
    if columns is None:
        return {}, values_path, None
    try:
        return read_values(values_path, columns), values_path, None
    except CatalogError as err:
        problems.append(f"catalog.values: {err}")
        return {}, values_path, None


def _columns(catalog: dict, key: str, default: tuple[str, str], problems) -> tuple | None:
    columns = tuple(catalog.get(key, default))
    if len(columns) != 2:
        problems.append(f"catalog.{key} must name two columns (the id's, the value's), got "
                        f"{list(columns)!r}")  # fmt: skip
        return None
    return columns


def _csi(catalog: dict, base: Path, catalog_path, catalog_format, start, problems) -> tuple:
    if "masses" not in catalog:
        problems.append('catalog.values = "csi" needs catalog.masses = "FILE.csv": each '
                        "debris' mass [kg] (columns id,mass_kg, or masses_columns), the one "
                        "input of the index the catalogue does not hold")  # fmt: skip
        return {}, CSI, None
    masses_path = (base / Path(catalog["masses"]).expanduser()).resolve()
    columns = _columns(catalog, "masses_columns", ("id", "mass_kg"), problems)
    if catalog_path is None or catalog_format not in READERS or columns is None:
        if catalog_path is None:
            problems.append('catalog.values = "csi" needs catalog.path: the spatial density '
                            "comes from the catalogue")  # fmt: skip
        return {}, CSI, masses_path
    try:
        masses = read_values(masses_path, columns, what="masses")
        whole = READERS[catalog_format](catalog_path, start=start, on_invalid="set aside")
    except CatalogError as err:
        problems.append(f"catalog.masses: {err}")
        return {}, CSI, masses_path
    return csi_values(whole, masses), CSI, masses_path


def candidates_without_mass(candidates, values: dict) -> list[str]:
    """The candidates a CSI campaign has no value for (no mass in the masses file)."""
    return [str(k) for k in candidates.ids if str(k) not in values]
