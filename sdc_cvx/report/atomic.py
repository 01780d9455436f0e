"""The one atomic writer of a file: a temporary file beside it, then a rename.

The run folder (:mod:`sdc_cvx.report.run_folder`), the figures (:func:`write_figure`)
and the sweep folders all go through :func:`write_atomic`,
so a reader never sees a truncated file.  Files are created with the permissions ``open``
would give them (0666 less the umask: 0644 under the usual 022), not ``mkstemp``'s 0600.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import BinaryIO


def file_mode(mode: int = 0o666) -> int:
    """``mode`` less the process umask: the permissions ``open`` would give a new file."""
    umask = os.umask(0)
    os.umask(umask)
    return mode & ~umask


def write_atomic(
    path: Path, content: str | Callable[[BinaryIO], None], *, mode: int | None = None
) -> None:
    """Write ``content`` to ``path`` so that readers never see a truncated file.

    The one atomic writer of sdc_cvx (a temporary file in the same folder, then
    ``os.replace``).  ``content`` is text (written as UTF-8) or a function that writes
    the bytes to the binary stream it is given (a figure's ``savefig``).  ``mode``: the
    permissions of the file; default those of a new file under the umask (0644 under
    022), not the 0600 of the temporary file.
    """
    path = Path(path)
    handle, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        if callable(content):
            with os.fdopen(handle, "wb") as stream:
                content(stream)
        else:
            with os.fdopen(handle, "w", encoding="utf-8") as stream:
                stream.write(content)
        os.chmod(temp, file_mode() if mode is None else mode)
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise


PNG_COMPRESSION = 3
"""zlib level of the PNG figures.  Measured on the paper case's four figures: 0.84 s at
level 3 against 1.0-1.1 s at Pillow's default 6, for files 10 % larger; level 1 is no
faster and 13 % larger."""


_GLYPHS_SAID = []  # once per process: the first figure that lacked a glyph


def write_figure(figure, path: Path, fmt: str, dpi: int) -> None:
    """A matplotlib ``figure`` saved as ``path`` in format ``fmt`` (png, svg, pdf) at
    ``dpi`` [dots per inch], atomically (:func:`write_atomic`).

    Ids in characters the font lacks (matplotlib warns once per glyph and per figure)
    are said once per process, in one line.
    """
    options = {"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if fmt == "png" else {}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        write_atomic(path, partial(figure.savefig, format=fmt, dpi=dpi, **options))
    for warning in caught:
        if "missing from font" not in str(warning.message):
            warnings.warn_explicit(warning.message, warning.category, warning.filename,
                                   warning.lineno)  # fmt: skip
        elif not _GLYPHS_SAID:
            _GLYPHS_SAID.append(path)
            warnings.warn(f"{path.name}: some ids use characters the figures' font lacks: "
                          "they show as boxes there (the CSV and JSON files hold them whole)",
                          UserWarning, stacklevel=2)  # fmt: skip
