"""Whether a folder may take sdc_cvx's results: the policy for ``--out``, checked before
any solve (:mod:`sdc_cvx.report.run_folder` writes the folders).

A new or empty folder is used; an earlier folder of sdc_cvx (a run folder: one holding
``solution.json``, ``run.log`` or ``legs.csv``; a campaign folder: its own markers) is
replaced whole (the ``flight/`` a flight of it wrote too), unless it also holds something
sdc_cvx did not write (a file of the user's, which replacing the folder would delete); any
other non-empty folder is refused, so a mistyped ``--out ~`` cannot replace a home
folder.  The folder one is in or one of its parents is refused too (swapping it would
leave the shell in a deleted folder), and so is a name longer than a file system takes.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from ..errors import FolderError, OutputError

RUN_FOLDER_MARKERS = ("solution.json", "run.log", "legs.csv")
"""A folder holding one of these is an earlier run folder, which ``write_run`` replaces."""
_FIGURES = ("orbits", "raan", "cost", "iterations")  # report.plots.FIGURE_NAMES, without matplotlib
FIGURE_FORMATS = ("png", "svg", "pdf")
"""The figure formats a save writes (``report.plots.SUPPORTED_FORMATS``, without matplotlib)."""
RUN_FOLDER_FILES = frozenset(
    {"solution.json", "run.log", "legs.csv", "iterations.csv", "edges.csv", "scenario.toml"}
    | {f"{name}.{ext}" for name in _FIGURES for ext in FIGURE_FORMATS}
)
"""Every file a run folder may hold: an earlier run folder with any other file in it (a
file of the user's) is refused, not replaced with it."""
FLIGHT_FOLDER = "flight"
FLIGHT_FILES = frozenset(
    {"maneuvers.csv", "rendezvous.csv", "flight.json", "trajectory.oem", "flight.png"}
)
"""What a run folder's ``flight/`` holds (``fly RUN_DIR``, :mod:`sdc_cvx.flight.result`):
such a folder is sdc_cvx's, replaced with the run folder or by the next flight."""
NAME_MAX_BYTES = 255
"""The longest file or folder name [bytes] of the usual file systems (ext4, xfs, btrfs)."""


def name_problem(path: Path | str) -> str | None:
    """Why a part of ``path`` is too long a name for the file system, or None."""
    for part in Path(path).parts:
        size = len(os.fsencode(part))
        if size > NAME_MAX_BYTES:
            return (f"the name {part[:40]}... is {size} bytes long; a file or folder name is "
                    f"at most {NAME_MAX_BYTES} bytes here")  # fmt: skip
    return None


def new_folder_problem(parent: Path | str = ".") -> str | None:
    """Why a new results folder cannot be made in ``parent`` (no ``--out``), or None:
    checked before any solve, so that a read-only folder costs no solve."""
    where = Path(parent).resolve()
    if not os.access(where, os.W_OK | os.X_OK):
        return (f"the current folder {where} is not writable, and the results go there "
                "without --out: choose a folder with --out")  # fmt: skip
    return None


def real_folder(folder: Path | str) -> Path:
    """``folder``, or where it points when it is a symbolic link (followed, not replaced)."""
    folder = Path(folder)
    return Path(os.path.realpath(folder)) if folder.is_symlink() else folder


def foreign_names(folder: Path, files) -> list[str]:
    """What an earlier folder holds that sdc_cvx did not write (paths relative to it).

    ``files`` names what such a folder may hold, as files; a container with its own
    ``foreign(folder)`` (a campaign folder's, whose mission folders are looked into)
    answers for itself.
    """
    if hasattr(files, "foreign"):
        return files.foreign(folder)
    return sorted(p.name for p in folder.iterdir() if not is_ours(p, files))


def is_ours(path: Path, files) -> bool:
    """Whether ``path`` is sdc_cvx's: a file named in ``files``, or a ``flight/`` folder
    holding a flight's files and nothing else."""
    if path.is_file():
        return path.name in files
    return (path.name == FLIGHT_FOLDER and path.is_dir() and not path.is_symlink()
            and all(inner.is_file() and inner.name in FLIGHT_FILES
                    for inner in path.iterdir()))  # fmt: skip


def replaced_flights(folder: Path | str) -> list[str]:
    """The ``flight/`` folders of an earlier run or campaign folder (paths relative to
    it) that replacing it removes: they flew the earlier plan, not the next one."""
    folder = real_folder(folder)
    if not folder.is_dir():
        return []
    found = [folder / FLIGHT_FOLDER] + sorted(folder.glob(f"*/{FLIGHT_FOLDER}"))
    return [str(path.relative_to(folder)) for path in found if path.is_dir()]


def out_folder_problem(folder: Path | str, markers=RUN_FOLDER_MARKERS,
                       files=RUN_FOLDER_FILES, kind: str = "run folder", *,
                       api: str | None = None) -> str | None:  # fmt: skip
    """Why ``folder`` cannot take a run folder, or None (checked before any solve).

    Refused: a path inside a file, a file, a non-empty folder that is not an earlier
    run folder (see the module docstring), the current folder or one of its parents,
    and a place the user cannot write to.  ``markers`` (what makes an earlier folder),
    ``files`` (what such a folder may hold: a container of names) and ``kind`` (its
    name in messages) are a campaign folder's when it is one.  ``api``: the method the
    folder was given to (``"Solution.save"``), for the advice to name it, not ``--out``.
    """
    given = Path(folder)
    if (problem := name_problem(given)) is not None:
        return problem
    try:
        return _out_folder_problem(given, markers, files, kind, api)
    except OSError as err:  # a path the system refuses (too long, a loop of links, ...)
        return f"{given} cannot be used: {err.strerror or err}"


def _out_folder_problem(given: Path, markers, files, kind: str, api=None) -> str | None:
    folder = real_folder(given)
    resolved = Path(os.path.realpath(folder))
    here = Path.cwd().resolve()
    if resolved == here or resolved in here.parents:
        which = "the current folder" if resolved == here else "a parent of the current folder"
        example = (f"--out {given / 'run'}" if api is None
                   else f"{api}({str(given / 'run')!r})")  # fmt: skip
        return (
            f"{given} is {which}: a {kind} is swapped in whole, which would remove the "
            f"folder you are in; choose a new folder, e.g. {example}"
        )
    if folder.exists() and not folder.is_dir():
        return f"{folder} is a file, not a folder"
    ancestor = folder if folder.exists() else folder.parent
    while not ancestor.exists() and ancestor != ancestor.parent:
        ancestor = ancestor.parent
    if not ancestor.is_dir():
        return f"{folder} is inside {ancestor}, which is a file, not a folder"
    if folder.is_dir() and any(folder.iterdir()):
        if not any((folder / name).exists() for name in markers):
            return (
                f"{folder} is not empty and is not an earlier {kind} (no "
                f"{', '.join(markers)}); choose a new or empty folder (an earlier "
                f"{kind} is replaced whole)"
            )
        foreign = foreign_names(folder, files)
        if foreign:
            more = f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
            shown = ", ".join(foreign[:5]) + more
            return (
                f"{folder} is an earlier {kind} but also holds {shown}, which sdc_cvx "
                "did not write; replacing the folder would delete them: move them out or "
                "choose another folder"
            )
        if not os.access(folder.parent, os.W_OK | os.X_OK):
            return f"cannot replace {folder}: {folder.parent} is not writable"
    parent = folder.parent if folder.exists() else ancestor
    if not os.access(parent, os.W_OK | os.X_OK):
        return f"cannot create {folder}: {parent} is not writable"
    return _probe(parent, folder, kind)


def writable_problem(folder: Path | str, kind: str) -> str | None:
    """Why nothing could be written in ``folder`` (made if need be), or None: a name too
    long, a file on the way, a place that refuses new files (``/proc``, read-only).

    For a ``flight/`` written into a run folder (:meth:`sdc_cvx.flight.Flight.save`),
    checked before anything is written; ``kind`` names what would be written there.
    """
    folder = Path(folder)
    if (problem := name_problem(folder)) is not None:
        return problem
    try:
        ancestor = folder
        while not ancestor.exists() and ancestor != ancestor.parent:
            ancestor = ancestor.parent
        if not ancestor.is_dir():
            return f"{folder} is inside {ancestor}, which is a file, not a folder"
        if not os.access(ancestor, os.W_OK | os.X_OK):
            return f"cannot write the {kind} in {folder}: {ancestor} is not writable"
        return _probe(ancestor, folder, kind)
    except OSError as err:
        return f"{folder} cannot be used: {err.strerror or err}"


def _probe(parent: Path, folder: Path, kind: str) -> str | None:
    """Why nothing can be made in ``parent`` although its permissions allow it (root in a
    file system that refuses writes: ``/sys``, ``/proc``), or None: a folder made and
    removed at once tells."""
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".sdc_probe_", dir=parent))
    except OSError as err:
        return (f"cannot write the {kind} {folder}: {parent} refuses new files "
                f"({err.strerror or err})")  # fmt: skip
    return None


def checked_save(api: str, folder, formats, texts: dict, markers=RUN_FOLDER_MARKERS,
                 files=RUN_FOLDER_FILES, kind: str = "run folder") -> tuple[Path, tuple]:
    """``(folder, formats)`` of a save called from Python (``api``: ``"Solution.save"``),
    its arguments checked before anything is computed or written.

    ``folder``: a str or path-like, that may take the folder (:func:`out_folder_problem`);
    ``formats``: one of :data:`FIGURE_FORMATS` or a sequence of them (``"svg"`` is
    ``("svg",)``, not its letters); ``texts``: the other arguments that must be text or
    None (``{"scenario_toml": ...}``).

    Raises
    ------
    OutputError
        An argument of the wrong type, an unknown figure format.
    FolderError
        The folder is refused (the message says why, one line).
    """
    if isinstance(folder, bytes) or not isinstance(folder, str | os.PathLike):
        raise OutputError(f"{api}(folder): folder must be a path (a str or os.PathLike), got "
                          f"{folder!r}")  # fmt: skip
    for name, text in texts.items():
        if text is not None and not isinstance(text, str):
            raise OutputError(f"{api}({name}=...): {name} must be text (a str) or None, got "
                              f"{type(text).__name__} {text!r}")  # fmt: skip
    listed = (formats,) if isinstance(formats, str) else formats
    if not isinstance(listed, list | tuple | set | frozenset) or not all(
            isinstance(fmt, str) for fmt in listed):  # fmt: skip
        raise OutputError(f"{api}(formats=...): formats must be a figure format or a sequence "
                          f"of them, from {', '.join(FIGURE_FORMATS)}, got {formats!r}")
    listed = tuple(dict.fromkeys(fmt.lower().lstrip(".") for fmt in listed))
    if unknown := [fmt for fmt in listed if fmt not in FIGURE_FORMATS]:
        raise OutputError(f"{api}(formats=...): unknown figure format(s) {', '.join(unknown)}; "
                          f"choose from {', '.join(FIGURE_FORMATS)} (() for no figures)")
    if (problem := out_folder_problem(folder, markers, files, kind, api=api)) is not None:
        raise FolderError(f"{api}: {problem}")
    return Path(folder), listed
