"""Candidate selection: keep the debris a mission should consider, and say why others go.

:func:`select` filters a :class:`~sdc_cvx.inputs.catalog.Catalog` by altitude, inclination,
eccentricity and id or name patterns, and also drops the orbits the transfer model does
not cover:

- eccentric orbits: the cost model treats every orbit as circular of radius ``a``
  (``sdc_cvx.physics.transfer``), so ``e > 0.05`` is dropped unless asked otherwise;
- near-polar orbits (inclination within 0.5 deg of 90 deg): their J2 RAAN rate is
  about zero (Eq. 7, ``cos i ~ 0``), so the drift strategy cannot close a RAAN gap
  with them.  Prograde and retrograde orbits are both fine (the drift sides of
  Table 3 are stated by precession rate);
- orbits above low Earth orbit (apogee altitude above :data:`LEO_MAX_APOGEE_KM`, 2,000
  km): the J2 drift strategy is a LEO strategy (the RAAN rate falls as a^-3.5: a
  drift at GEO would take centuries).  Together with the catalog's own checks (perigee
  altitude at least 150 km, a at most 100,000 km: refused when read) this is the
  physical domain of the model (docs/guide/catalogues.md, "Physical domain").

Every dropped debris is reported with its reasons, in words, in a table.

The filters act first: a catalog read with ``on_invalid="set aside"`` holds the element
sets that are not orbits of this model in ``Catalog.invalid``
(:data:`sdc_cvx.inputs.catalog.ON_INVALID`); those the filters drop are reported as
dropped by the filters, like any other, and those the filters keep are dropped with the
check ``invalid`` and the reader's reason (file, line, catalogue number), or refused
with ``strict=True``.  So a selection inside a whole public catalogue works whatever
else the file holds.

Object types come from the names of a public catalogue (:func:`object_type`):
``R/B`` is a rocket body, ``DEB`` a fragment, anything else a payload.
"""

from __future__ import annotations

import dataclasses
import fnmatch
import math
import re
from collections import Counter
from collections.abc import Iterable

import numpy as np
import pandas as pd

from ..errors import CatalogError
from ..physics.orbits import DEFAULT_MAX_ECCENTRICITY, SECONDS_PER_DAY, raan_rate
from .catalog import R_EARTH_KM, Catalog

__all__ = [
    "CHECKS",
    "DEFAULT_MAX_ECCENTRICITY",
    "LEO_MAX_APOGEE_KM",
    "OBJECT_TYPES",
    "POLAR_MARGIN_DEG",
    "object_type",
    "select",
    "summary",
]

POLAR_MARGIN_DEG = 0.5
"""Orbits with ``|inclination - 90 deg|`` below this are dropped (RAAN rate ~ 0)."""

LEO_MAX_APOGEE_KM = 2000.0
"""Orbits with an apogee altitude above this [km] are dropped (outside low Earth orbit)."""

CHECKS = ("ids", "names", "type", "excluded", "altitude", "inclination", "eccentricity",
          "near-polar", "above-leo", "invalid")  # fmt: skip
"""Names of the checks, as in the ``checks`` column of the report."""

OBJECT_TYPES = ("rocket-body", "debris", "payload")
"""Object types :func:`object_type` tells from a name (``types`` of :func:`select`)."""

_ROCKET_BODY = re.compile(r"R/B")
_DEBRIS = re.compile(r"\bDEB\b")


def object_type(name: str) -> str:
    """The type of a catalogued object from its name, one of :data:`OBJECT_TYPES`.

    ``"rocket-body"`` when the name holds ``R/B`` (``"SL-8 R/B"``, ``"SL-12 R/B(AUX
    MOTOR)"``), ``"debris"`` when it holds the word ``DEB`` (``"COSMOS 2251 DEB"``,
    ``"ARIANE 5 DEB (SYLDA)"``), else ``"payload"`` (the US catalogue's convention: a
    payload goes by its own name).  Case-insensitive.
    """
    upper = str(name).upper()
    if _ROCKET_BODY.search(upper):
        return "rocket-body"
    if _DEBRIS.search(upper):
        return "debris"
    return "payload"


def select(
    catalog: Catalog,
    *,
    altitude_km: tuple[float, float] | None = None,
    inclination_deg: tuple[float, float] | None = None,
    eccentricity_max: float | None = None,
    ids: Iterable[str] | str | None = None,
    names: Iterable[str] | str | None = None,
    exclude_ids: Iterable[str] | str | None = None,
    polar_margin_deg: float = POLAR_MARGIN_DEG,
    types: Iterable[str] | str | None = None,
    strict: bool = False,
) -> tuple[Catalog, pd.DataFrame]:
    """Candidates of ``catalog`` that pass every check, and a report of the others.

    Parameters
    ----------
    catalog : Catalog
        The debris catalog.
    altitude_km : (low, high), optional
        Keep ``low <= a - R_T <= high`` [km] (bounds included).
    inclination_deg : (low, high), optional
        Keep ``low <= inclination <= high`` [deg].
    eccentricity_max : float, optional
        Keep ``e <= eccentricity_max``.  None means :data:`DEFAULT_MAX_ECCENTRICITY`
        (0.05); pass ``math.inf`` to keep every eccentricity.
    ids : str or iterable of str, optional
        Shell-style patterns (``fnmatch``, case-sensitive: ``"43*"``, ``"1?"``); keep
        the debris whose id matches at least one.
    names : str or iterable of str, optional
        Shell-style patterns on the ``name`` column, case-insensitive
        (``"cosmos 2251*"``); keep the debris whose name matches at least one.
    exclude_ids : str or iterable of str, optional
        Shell-style patterns; drop the debris whose id matches one.
    polar_margin_deg : float
        Drop orbits with ``|inclination - 90| < polar_margin_deg`` (default 0.5 deg;
        0 keeps them).
    types : str or iterable of str, optional
        Keep the objects of these types (:data:`OBJECT_TYPES`, told from the name by
        :func:`object_type`).
    strict : bool
        Raise when the filters keep an element set of ``catalog.invalid`` (not an orbit
        of this model); default: drop it with the check ``invalid``.

    Returns
    -------
    kept : Catalog
        The candidates kept, in catalog order, with the same ``start`` and ``source``;
        it has no rows when every debris is dropped.
    report : pandas.DataFrame
        One row per dropped debris, in catalog order: ``id``, ``name`` (when the
        catalog has names), ``altitude_km``, ``inc_deg``, ``e``, ``checks`` (the names
        of the failed checks among :data:`CHECKS`, comma-separated) and ``reason``
        (every reason in words, ``"; "``-separated, e.g. ``"altitude 950.2 km
        outside [600, 900]"``).  The rows of ``catalog.invalid`` come after the
        others; those the filters keep have the check ``invalid`` and, as reason, the
        reader's problem (file, line, catalogue number and why).

    Raises
    ------
    ValueError
        A range with low > high or a non-finite bound, a negative eccentricity limit
        or margin, a pattern in ``ids`` or ``names`` that matches no debris of the
        catalog (a typo, most likely), an unknown type, or ``names`` or ``types`` on
        a catalog without names.
    CatalogError
        With ``strict``: the filters keep element sets that are not orbits of this
        model (every one named, with its line).
    """
    frame = catalog.frame
    invalid = catalog.invalid if catalog.invalid is not None else frame.iloc[:0]
    n_valid = len(frame)
    if len(invalid):  # the filters act on both; the invalid rows are never kept
        extra = invalid.drop(columns="problem").copy()
        with np.errstate(all="ignore"):
            rate = raan_rate(extra["a_km"].to_numpy() * 1000.0, extra["e"].to_numpy(),
                             np.radians(extra["inc_deg"].to_numpy()))  # fmt: skip
        extra["raan_rate_deg_per_day"] = np.degrees(rate) * SECONDS_PER_DAY
        if "name" in frame.columns and "name" not in extra.columns:
            extra["name"] = ""
        columns = [c for c in ("id", "name") if c in frame.columns]
        columns += ["a_km", "e", "inc_deg", "altitude_km", "raan_rate_deg_per_day"]
        frame = pd.concat([frame[columns], extra[columns]], ignore_index=True)
    altitude = frame["altitude_km"].to_numpy(dtype=float)
    inc = frame["inc_deg"].to_numpy(dtype=float)
    ecc = frame["e"].to_numpy(dtype=float)
    id_values = [str(value) for value in frame["id"]]
    reasons: list[list[tuple[str, str]]] = [[] for _ in id_values]

    def drop(mask, check: str, message) -> None:
        for pos in np.flatnonzero(mask):
            reasons[pos].append((check, message(pos)))

    patterns = _patterns(ids, "ids")
    if patterns:
        matched = _matches(id_values, patterns, "ids", fold=False)
        shown = _listed(patterns)
        drop(~matched, "ids", lambda k: f"id {id_values[k]} matches none of {shown}")
    patterns = _patterns(names, "names")
    if patterns:
        if "name" not in frame.columns:
            raise ValueError(f"names patterns given, but {catalog.source} has no names")
        name_values = [str(value) for value in frame["name"]]
        matched = _matches(name_values, patterns, "names", fold=True)
        shown = _listed(patterns)
        drop(~matched, "names", lambda k: f"name {name_values[k]!r} matches none of {shown}")
    wanted = _types(types)
    if wanted:
        if "name" not in frame.columns:
            raise ValueError(f"types given, but {catalog.source} has no names to tell them by")
        name_of = [str(value) for value in frame["name"]]
        kinds = [object_type(value) for value in name_of]
        shown = ", ".join(wanted)
        other = np.array([kind not in wanted for kind in kinds], dtype=bool)
        drop(other, "type", lambda k: f"type {kinds[k]} (name {name_of[k]!r}) is not {shown}")
    for pattern in _patterns(exclude_ids, "exclude_ids"):
        excluded = np.array([fnmatch.fnmatchcase(value, pattern) for value in id_values])
        drop(excluded, "excluded", lambda k, p=pattern: f"id {id_values[k]} excluded by {p!r}")
    if altitude_km is not None:
        low, high = _range(altitude_km, "altitude_km")
        drop((altitude < low) | (altitude > high), "altitude",
             lambda k: f"altitude {altitude[k]:.1f} km outside [{low:g}, {high:g}]")  # fmt: skip
    if inclination_deg is not None:
        low, high = _range(inclination_deg, "inclination_deg")
        drop((inc < low) | (inc > high), "inclination",
             lambda k: f"inclination {inc[k]:.2f} deg outside [{low:g}, {high:g}]")  # fmt: skip
    e_max = DEFAULT_MAX_ECCENTRICITY if eccentricity_max is None else float(eccentricity_max)
    if math.isnan(e_max) or e_max < 0.0:
        raise ValueError(f"eccentricity_max must be >= 0, got {eccentricity_max!r}")
    drop(ecc > e_max, "eccentricity",
         lambda k: f"eccentricity {ecc[k]:.4f} > {e_max:g} (the cost model treats orbits "
                   f"as circular of radius a)")  # fmt: skip
    margin = float(polar_margin_deg)
    if not margin >= 0.0:
        raise ValueError(f"polar_margin_deg must be >= 0, got {polar_margin_deg!r}")
    rate = frame["raan_rate_deg_per_day"].to_numpy(dtype=float)
    drop(np.abs(inc - 90.0) < margin, "near-polar",
         lambda k: f"inclination {inc[k]:.2f} deg within {margin:g} deg of 90 (J2 RAAN rate "
                   f"{rate[k]:.4f} deg/day: drift transfers cannot close RAAN gaps)")  # fmt: skip

    apogee = frame["a_km"].to_numpy(dtype=float) * (1.0 + ecc) - R_EARTH_KM
    drop(apogee > LEO_MAX_APOGEE_KM, "above-leo",
         lambda k: f"apogee altitude {apogee[k]:,.0f} km > {LEO_MAX_APOGEE_KM:,.0f} km (the J2 "
                   "drift strategy is planned for low Earth orbits)")  # fmt: skip

    problems = []
    for pos in range(n_valid, len(frame)):
        if not reasons[pos]:  # kept by the filters, but not an orbit of this model
            problems.append(invalid["problem"].iat[pos - n_valid])
            reasons[pos].append(("invalid", problems[-1]))
    if strict and problems:
        raise CatalogError.collect(catalog.source, [
            *problems, f"{catalog.source}: {len(problems)} element set(s) in the selection are "
            "not orbits of this model (docs/guide/catalogues.md, 'Physical domain'); "
            "narrow the selection, or "
            "leave out strict (--strict) to drop them with a warning"])  # fmt: skip
    dropped = np.array([bool(found) for found in reasons], dtype=bool)
    kept_frame = catalog.frame.loc[~dropped[:n_valid]].reset_index(drop=True)
    kept = dataclasses.replace(catalog, frame=kept_frame, invalid=None)
    report = frame.loc[dropped, [c for c in ("id", "name") if c in frame.columns]].copy()
    report["altitude_km"] = altitude[dropped]
    report["inc_deg"] = inc[dropped]
    report["e"] = ecc[dropped]
    report["checks"] = [",".join(check for check, _ in reasons[k]) for k in np.flatnonzero(dropped)]
    report["reason"] = ["; ".join(text for _, text in reasons[k]) for k in np.flatnonzero(dropped)]
    return kept, report.reset_index(drop=True)


def summary(kept: Catalog, report: pd.DataFrame) -> str:
    """``"kept K of N candidates (dropped: 3 altitude, 1 eccentricity)"``.

    The counts are per check; a debris failing two checks counts in both (the line then
    says how many were dropped in all).
    """
    total = len(kept) + len(report)
    counts = Counter(check for checks in report.get("checks", []) for check in checks.split(","))
    if not counts:
        return f"kept {len(kept)} of {total} candidates (none dropped)"
    listed = ", ".join(f"{counts[check]} {check}" for check in CHECKS if counts[check])
    overlap = (f"; {len(report)} debris in all, one failing several checks counts in each"
               if sum(counts.values()) > len(report) else "")  # fmt: skip
    return f"kept {len(kept)} of {total} candidates (dropped: {listed}{overlap})"


def _types(value) -> list[str]:
    """The object types asked for, checked against :data:`OBJECT_TYPES`."""
    if value is None:
        return []
    wanted = [value] if isinstance(value, str) else [str(item) for item in value]
    unknown = [kind for kind in wanted if kind not in OBJECT_TYPES]
    if unknown:
        raise ValueError(f"types: unknown type(s) {_listed(unknown)}; expected "
                         f"{', '.join(OBJECT_TYPES)} (told from the name: R/B, DEB)")  # fmt: skip
    return list(dict.fromkeys(wanted))


def _patterns(value, what: str) -> list[str]:
    if value is None:
        return []
    patterns = [value] if isinstance(value, str) else [str(item) for item in value]
    if any(not pattern.strip() for pattern in patterns):
        raise ValueError(f"{what}: empty pattern")
    return [pattern.strip() for pattern in patterns]


def _matches(values: list[str], patterns: list[str], what: str, *, fold: bool) -> np.ndarray:
    """Boolean mask of values matching one of the patterns; unmatched patterns raise."""
    if fold:
        values = [value.casefold() for value in values]
    matched = np.zeros(len(values), dtype=bool)
    unmatched = []
    for pattern in patterns:
        wanted = pattern.casefold() if fold else pattern
        hits = np.array([fnmatch.fnmatchcase(value, wanted) for value in values], dtype=bool)
        if not hits.any():
            unmatched.append(pattern)
        matched |= hits
    if unmatched:
        raise ValueError(f"{what} pattern(s) {_listed(unmatched)} match no debris of the catalog")
    return matched


def _listed(patterns: list[str]) -> str:
    return ", ".join(repr(pattern) for pattern in patterns)


def _range(bounds, what: str) -> tuple[float, float]:
    try:
        low, high = (float(bound) for bound in bounds)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be two numbers (low, high), got {bounds!r}") from None
    if not (math.isfinite(low) and math.isfinite(high)) or low > high:
        raise ValueError(f"{what} must be finite with low <= high, got ({low:g}, {high:g})")
    return low, high
