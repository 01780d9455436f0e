"""What the TLE, OMM and GTOC9 readers share: the semi-major axis, the checks, the errors.

Semi-major axis convention (TLE and OMM)
----------------------------------------
A TLE or OMM mean motion is an SGP4 *Kozai* mean motion.  SGP4 itself first converts
it to the *Brouwer* (un-Kozai'd) mean motion ``no_unkozai`` and works with that, so
``a_km`` here is the semi-major axis that gives the Brouwer mean motion with this
package's gravity constant: ``a = (MU_EARTH / n_brouwer**2) ** (1/3)``, MU_EARTH =
3.986e14 m^3/s^2.  With this choice ``n = sqrt(mu / a^3)`` in the J2 rate (Eq. 7)
is the SGP4 mean motion again.  ``n_brouwer`` is read from sgp4 as
``1 / (satrec.tumin * satrec.a ** 1.5)`` [rad/min], which is exactly sgp4's
``no_unkozai`` (the compiled ``Satrec`` does not expose ``no_unkozai`` itself):
:func:`sdc_cvx.inputs.sgp4_sets.brouwer_a_km`.

Measured on the 81 sun-synchronous rocket bodies of ``sso_rb.tle`` (600-900 km,
i ~ 98-100 deg): the Brouwer ``a`` is 2.76-2.97 km (mean 2.88 km) *below* the
``a = (mu / n_kozai**2) ** (1/3)`` of the raw TLE mean motion; sgp4's own
``satrec.a`` (WGS72, mu = 398600.8 km^3/s^2) is about 5 m above ours (mu differs).

Elements other than ``a`` (e, inclination, RAAN, argument of perigee, mean anomaly)
are the file's mean elements as written, not converted.
"""

from __future__ import annotations

import math
import re

import pandas as pd
from sgp4.api import SGP4_ERRORS

from ...errors import CatalogError
from ...physics.orbits import MU_EARTH
from ..catalog import R_EARTH_KM, Catalog

_MJD2000 = pd.Timestamp("2000-01-01T00:00:00Z")
"""MJD2000 = 0, i.e. JD 2451544.5, as in the GTOC9 data."""


# ---------------------------------------------------------------------- shared
def _lines(text: str) -> list[str]:
    """Lines of ``text`` without their ends; line k of the file is item k - 1."""
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


def _sgp4_problem(satrec) -> str | None:
    """Why sgp4 rejects an initialised element set, or None."""
    if satrec.error:
        return f"sgp4 rejects the element set: {SGP4_ERRORS.get(satrec.error, satrec.error)}"
    if not (math.isfinite(satrec.a) and satrec.a > 0.0):
        return "sgp4 rejects the element set: no finite semi-major axis"
    return None


def _a_problem(a_km: float, mean_motion: float) -> str | None:
    if a_km > R_EARTH_KM:
        return None
    return (
        f"mean motion {mean_motion:g} rev/day gives a = {a_km:.1f} km, not above the "
        f"Earth's radius {R_EARTH_KM} km"
    )


def _catalog(rows: list[dict], source: str, start, problems: list[str], what: str, *,
             where: list[str], flagged: dict[int, str] | None = None,
             on_invalid: str = "raise", numbered: bool = True) -> Catalog:  # fmt: skip
    """Validated catalog of ``rows``, or every problem raised at once.

    ``where[k]`` locates row k in the file; ``flagged`` maps the rows that are not
    orbits of this model (sgp4 rejects them) to ``": reason"``.  The reader's own
    ``problems`` and those of the catalog's validation (perigee, epochs, ...) are raised
    together, sorted by line: one error names every problem of the file.
    """
    if not rows and not problems:
        problems.append(f"{source}: no {what} found")
    if not rows:
        raise CatalogError.collect(source, _by_line(problems, source))
    first = {}  # the repeats of an id are the reader's problem (_duplicates), said once
    for k, row in enumerate(rows):
        first.setdefault(row["id"], k)
    if len(first) < len(rows):
        keep = sorted(first.values())
        position = {k: i for i, k in enumerate(keep)}
        flagged = {position[k]: why for k, why in (flagged or {}).items() if k in position}
        rows, where = [rows[k] for k in keep], [where[k] for k in keep]
    frame = pd.DataFrame(rows)
    if "name" in frame.columns and not frame["name"].astype(bool).any():
        frame = frame.drop(columns="name")
    if numbered:  # the catalogue number beside the line: what people search the file for
        labels = zip(where, rows, strict=True)
        where = [f"{label} (catalog number {row['id']})" for label, row in labels]
    return Catalog._from_rows(frame, source, start, where, flagged=flagged or {},
                              on_invalid=on_invalid, reader_problems=problems)  # fmt: skip


def kozai_a_km(mean_motion_rev_per_day: float) -> float:
    """``a = (MU_EARTH / n**2) ** (1/3)`` [km] of a raw (Kozai) mean motion: the size of an
    element set sgp4 rejects, for the candidate filters only."""
    n = mean_motion_rev_per_day * 2.0 * math.pi / 86400.0
    return (MU_EARTH / n**2) ** (1.0 / 3.0) / 1000.0


def _by_line(problems: list[str], source: str) -> list[str]:
    """Problems sorted by their line number (stable; those without one last)."""

    def line(problem: str) -> float:
        found = re.match(r", line (\d+)", problem[len(source) :])
        return int(found.group(1)) if found else math.inf

    return sorted(problems, key=line)


def _duplicates(rows, where, source, problems, noun="catalog number") -> None:
    """Report ids given twice; ``where[k]`` locates row k."""
    first: dict[str, int] = {}
    for k, row in enumerate(rows):
        if row["id"] in first:
            problems.append(
                f"{source}, {where[k]}: {noun} {row['id']} again (first at "
                f"{where[first[row['id']]]}); expected one element set per object"
            )
        first.setdefault(row["id"], k)


def _element_row(norad, name, epoch, a_km, fields: dict, intl: str) -> dict:
    return {
        "id": str(norad),
        "name": name or "",
        "a_km": a_km,
        "e": fields["e"],
        "inc_deg": fields["inc_deg"],
        "raan_deg": fields["raan_deg"],
        "epoch": epoch,
        "argp_deg": fields["argp_deg"],
        "mean_anomaly_deg": fields["mean_anomaly_deg"],
        "mean_motion_rev_per_day": fields["mean_motion"],
        "intl_designator": intl,
    }


def _fail(source: str, message: str):
    raise CatalogError.collect(source, [f"{source}: {message}"])


def _short(text: str) -> str:
    return repr(text if len(text) <= 40 else text[:36] + "...")


def _blank(value) -> bool:
    return value is None or (isinstance(value, str) and not value.strip())
