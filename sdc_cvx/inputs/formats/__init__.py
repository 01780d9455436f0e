"""Real debris catalogs: TLE, CCSDS OMM and the GTOC9 debris file.

Every reader returns a :class:`~sdc_cvx.inputs.catalog.Catalog` built with
:meth:`Catalog.from_frame`, so validation and the propagation of each RAAN from its
epoch to the mission start (default: the latest epoch, paper Eq. 7) are the catalog's.
Bad input never gives a traceback: every problem of a file is collected and raised at
once in a :class:`~sdc_cvx.errors.CatalogError` that names the file, the line (or the
record) and what was expected.

Formats
-------
:data:`FORMAT_TABLE` is the one table of the catalog formats: each format's reader (one
module per format: :mod:`.csv`, :mod:`.tle`, :mod:`.omm`, :mod:`.gtoc9`) and the file
extensions it is assumed from.  :func:`read_catalog`, the scenario files
(:meth:`sdc_cvx.study.scenario.Scenario.load_catalog`) and the command line all read
through it, so a file gets the same answer whichever way it is read: when a reader
fails on a file whose content looks like another format (:func:`sniff_format`), the
error says so first.  The semi-major axis convention of TLE and OMM is in
:mod:`._common`.
"""

from __future__ import annotations

import csv as stdlib_csv  # the name csv is this package's module .csv
import functools
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from ...errors import CatalogError
from ..catalog import Catalog, csv_delimiter
from ..sgp4_sets import brouwer_a_km
from . import csv as csv_format
from . import gtoc9, omm, tle
from ._common import _fail, _lines
from .tle import tle_checksum

__all__ = [
    "EXTENSION_FORMATS",
    "FORMATS",
    "FORMAT_TABLE",
    "READERS",
    "CatalogFormat",
    "brouwer_a_km",
    "read_catalog",
    "read_gtoc9",
    "read_omm",
    "read_tle",
    "sniff_format",
    "tle_checksum",
]


def _format_hint(fmt: str):
    """Decorate a reader: when it fails on a file whose content looks like another
    format, say so first (e.g. a GTOC9 ``.txt`` file read as TLE)."""

    def decorate(reader):
        @functools.wraps(reader)
        def read(path, *args, **kwargs):
            try:
                return reader(path, *args, **kwargs)
            except CatalogError as err:
                guess = sniff_format(path)
                source = os.fspath(path)
                if guess is None and len(err.problems) > NOT_A_FILE_PROBLEMS:
                    # nothing in it reads as any format: say so, not 200,000 problems
                    shown = [p if len(p) <= 160 else p[:157] + "..." for p in err.problems[:3]]
                    hint = (f"{source}: this is not a {FORMAT_NAMES[fmt]} file (nor any catalog "
                            f"format sdc_cvx reads: {', '.join(FORMATS)}); "
                            f"{len(err.problems)} problems, the first ones:")  # fmt: skip
                    raise CatalogError.collect(source, [hint, *shown]) from None
                if guess is None or guess == fmt:
                    raise
                hint = (f"{source}: the content looks like a {guess!r} catalog, not {fmt!r}; "
                        f"read it with format {guess!r}")  # fmt: skip
                raise CatalogError.collect(source, [hint, *err.problems]) from None

        return read

    return decorate


NOT_A_FILE_PROBLEMS = 5
"""A file whose content reads as no format and that gives more problems than this is
said not to be a catalog at all (a random text file read as TLE)."""
FORMAT_NAMES = {"csv": "CSV catalog", "tle": "TLE", "omm": "OMM", "gtoc9": "GTOC9 debris"}


@dataclass(frozen=True)
class CatalogFormat:
    """One catalog format: its name, its reader and the extensions it is assumed from.

    ``read(path, *, start=None) -> Catalog``; when it fails on a file whose content
    looks like another format, the error says so first.
    """

    name: str
    read: Callable[..., Catalog]
    extensions: tuple[str, ...]


def _table(*formats: CatalogFormat) -> dict[str, CatalogFormat]:
    return {f.name: replace(f, read=_format_hint(f.name)(f.read)) for f in formats}


FORMAT_TABLE: dict[str, CatalogFormat] = _table(
    CatalogFormat("csv", csv_format.read_csv, (".csv",)),
    # the content decides (sniff_format); the extension only when it cannot tell
    CatalogFormat("tle", tle.read_tle, (".tle", ".3le", ".2le", ".txt")),
    CatalogFormat("omm", omm.read_omm, (".omm", ".kvn", ".xml", ".json")),
    CatalogFormat("gtoc9", gtoc9.read_gtoc9, ()),
)
"""The catalog formats, in the order they are listed to people."""

FORMATS = tuple(FORMAT_TABLE)
"""Catalog formats :func:`read_catalog` reads (and a scenario file may name)."""
READERS: dict[str, Callable[..., Catalog]] = {f.name: f.read for f in FORMAT_TABLE.values()}
"""Reader of each format; each takes ``(path, *, start=None)``."""
EXTENSION_FORMATS: dict[str, str] = {
    ext: f.name for f in FORMAT_TABLE.values() for ext in f.extensions
}
"""Catalog format assumed from the file extension when none is given."""

read_tle = READERS["tle"]
read_omm = READERS["omm"]
read_gtoc9 = READERS["gtoc9"]


# ---------------------------------------------------------------------- dispatch
def _sniff_text(text: str) -> str | None:
    """Catalog format told from the beginning of a text, or None."""
    stripped = text.lstrip()
    if not stripped:
        return None
    if stripped[0] == "<" or re.match(r"\{|\[\s*[{\]]", stripped):  # XML, JSON (not TOML)
        return "omm"
    lines = [line.rstrip() for line in _lines(stripped) if line.strip()][:12]
    if any(line.startswith("CCSDS_OMM_VERS") for line in lines):
        return "omm"
    if any(tle._tle_pair(a, b) for a, b in zip(lines, lines[1:], strict=False)):
        return "tle"
    delimiter = csv_delimiter(lines[0])
    header = {
        field.strip() for field in next(stdlib_csv.reader([lines[0]], delimiter=delimiter), [])
    }
    if {"NORAD_CAT_ID", "MEAN_MOTION"} <= {name.upper() for name in header}:
        return "omm"
    if {"id", "a_km"} <= {name.lower() for name in header}:
        return "csv"
    for line in lines[:2]:
        fields = line.replace(",", " ").split()
        if len(fields) == len(gtoc9.GTOC9_COLUMNS) and all(
            gtoc9._gtoc9_float(f) is not None for f in fields
        ):
            return "gtoc9"
    return None


def sniff_format(path: str | os.PathLike) -> str | None:
    """Catalog format told from the content of a file, or None if it cannot be told.

    TLE: a line starting with ``"1 "`` followed by one starting with ``"2 "`` with the
    same catalog number; OMM:
    XML (``<``), JSON (``[``, ``{``), KVN (``CCSDS_OMM_VERS``) or a CSV header with
    ``NORAD_CAT_ID`` and ``MEAN_MOTION``; csv: a header with ``id`` and ``a_km`` (any
    case, separated by ``,``, or ``;`` or tabs: :func:`~sdc_cvx.inputs.catalog.csv_delimiter`);
    gtoc9: 8 numbers on one of the first two lines.
    """
    try:
        with open(path, "rb") as stream:
            head = stream.read(65536)
    except OSError:
        return None
    return _sniff_text(head.decode("utf-8-sig", errors="replace"))


def read_catalog(path: str | os.PathLike, format: str | None = None, *, start=None,
                 on_invalid: str = "raise") -> Catalog:  # fmt: skip
    """Read a debris catalog in any supported format.

    Parameters
    ----------
    path : str or path-like
        The catalog file.
    format : {"csv", "tle", "omm", "gtoc9"}, optional
        Default: told from the content (:func:`sniff_format`), else from the
        extension (``.csv``; ``.tle``, ``.3le``, ``.txt``; ``.xml``, ``.json``,
        ``.kvn``, ``.omm``).
    start : str or datetime-like, optional
        Mission start date (UTC when naive); default the latest epoch.
    on_invalid : {"raise", "set aside"}
        Element sets that are not orbits of this model (docs/guide/catalogues.md,
        "Physical domain"): problems (default), or set aside in ``Catalog.invalid``, for the
        candidate selection to report those it keeps (:func:`sdc_cvx.inputs.selection.select`).

    Raises
    ------
    CatalogError
        Unknown format, a format that cannot be told, or any problem of the file.
    """
    source = os.fspath(path)
    if format is None:
        format = sniff_format(path) or EXTENSION_FORMATS.get(Path(source).suffix.lower())
        if format is None and Path(source).is_file():
            _fail(source, f"cannot tell the catalog format from the content or the extension; "
                          f"give one of {', '.join(FORMATS)}")  # fmt: skip
        format = format or "csv"  # a missing file: let the reader say so
    reader = READERS.get(str(format).lower())
    if reader is None:
        _fail(source, f"unknown catalog format {format!r}; expected one of {', '.join(FORMATS)}")
    return reader(path, start=start, on_invalid=on_invalid)
