"""The value of removing each debris, from a user's table (issue 27: removal programmes).

A programme removes the debris that matter most: ``[catalog] values = "FILE.csv"`` gives
each debris' value (a risk index, a ranking turned into a score, a mass...) as a CSV
table with a header ``id,value``: ids as in the catalog (NORAD catalog numbers for
TLE/OMM), values numbers in [0, 1e9] (:data:`MAX_VALUE`), not all 0.  Debris the file
does not name are worth 0; ids the catalog does not hold are allowed (a ranking of the
whole catalogue read beside a filtered one).  ``objective = "max-value"``
(:mod:`sdc_cvx.campaign.value`) uses them.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from ..errors import CatalogError

MAX_VALUE = 1e9
"""Largest value of a debris: the MILP takes values as coefficients, and its backends'
tolerances and limits are absolute (HiGHS: 1e-7 feasibility, coefficients above 1e15
refused): values of 1e15 and more ended in "solver failure" (issue 48), and 1e9 leaves
six orders of magnitude for sums and the value rows.  Values rescale freely: a plan of
most value is that of the values divided by any number."""
RESCALE = ("divide every value by the same number (the plan of most value is the same; "
           "with objective = 'value-per-dv', multiply price_per_value_mps by it)")
"""What to do with values above :data:`MAX_VALUE`, in the messages about them."""


def read_values(path: str | Path, columns: tuple[str, str] = ("id", "value"), *,
                what: str = "values") -> dict[str, float]:  # fmt: skip
    """``{id: value}`` from a CSV table with the ``columns`` (id, value), by default
    ``id,value`` (``[catalog] values_columns`` names others: a published ranking's own
    ``norad_id,listed_score``).  ``what`` names the file in messages (``"masses"``: the
    masses file of the criticality index).

    Raises
    ------
    CatalogError
        The file cannot be read, has no ``id`` and ``value`` columns or no rows, or a
        row whose id is blank or repeated or whose value is not a number in [0,
        :data:`MAX_VALUE`] (every such row named, with its line), or every value is 0.

    Notes
    -----
    The fields are separated by commas, or by semicolons or tabs where the header has no
    comma (a spreadsheet's export in a locale whose decimal mark is the comma; the values
    still take a decimal point).
    """
    path = Path(path)
    source = str(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as err:
        raise CatalogError(f"{source}: cannot read the {what} file: "
                           f"{getattr(err, 'strerror', None) or err}") from None  # fmt: skip
    lines = text.splitlines()
    rows = csv.reader(lines, delimiter=_delimiter(lines[0] if lines else ""))
    header = [name.strip().lower() for name in next(rows, [])]
    id_name, value_name = (name.strip().lower() for name in columns)
    if id_name not in header or value_name not in header:
        raise CatalogError(f"{source}, header: a {what} file needs the columns "
                           f"{id_name!r} and {value_name!r}, found "
                           f"{', '.join(header) or 'no header'}")  # fmt: skip
    at_id, at_value = header.index(id_name), header.index(value_name)
    values: dict[str, float] = {}
    seen: dict[str, int] = {}
    problems = []
    for line, row in enumerate(rows, start=2):
        if not any(cell.strip() for cell in row):
            continue
        where = f"{source}, line {line}"
        if len(row) <= max(at_id, at_value):
            problems.append(f"{where}: {len(row)} fields, expected {len(header)}")
            continue
        ident, text_value = row[at_id].strip(), row[at_value].strip()
        if not ident:
            problems.append(f"{where}, field {id_name}: blank")
            continue
        if ident in seen:
            problems.append(f"{where}, field {id_name}: {ident!r} repeats line {seen[ident]}")
            continue
        try:
            value = float(text_value)
        except ValueError:
            value = math.nan
        if not (math.isfinite(value) and value >= 0):
            problems.append(f"{where}, field {value_name}: expected a number >= 0, got "
                            f"{text_value!r}")
            continue
        if value > MAX_VALUE:
            problems.append(f"{where}, field {value_name}: expected a number of at most "
                            f"{MAX_VALUE:g}, got {text_value!r}: {RESCALE}")  # fmt: skip
            continue
        seen[ident] = line
        values[ident] = value
    if problems:
        raise CatalogError.collect(source, problems)
    if not values:
        raise CatalogError(f"{source}: no rows under the header: a {what} file names each "
                           f"debris with its {value_name}")  # fmt: skip
    if not any(values.values()):
        raise CatalogError(f"{source}, field {value_name}: every one of the {len(values)} "
                           f"rows is 0: such {what} mean nothing (every choice of debris "
                           f"is worth 0); give the debris that matter a {value_name} > 0")
    return values


def _delimiter(header: str) -> str:
    """The header's field separator: a comma, else a semicolon or a tab if it has one."""
    if "," in header:
        return ","
    return next((mark for mark in ";\t" if mark in header), ",")
