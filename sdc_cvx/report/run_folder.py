"""Writing a run's results to a folder, atomically.

Every file is written by the one atomic writer, :func:`~sdc_cvx.report.atomic.write_atomic`
(a temporary file, then rename), with the permissions ``open`` would give it.

:func:`write_run` writes a whole run folder aside (a hidden ``.NAME.*.partial`` folder
next to it) and swaps it in at once, so ``--out`` never shows a mix of two runs: a reader
(or a kill at any moment) finds the old folder whole or the new one whole.  Which
folders it may replace is :mod:`~sdc_cvx.report.out_folder`'s policy (an earlier run
folder, stale files included; never a folder with files of the user's).  A symlinked
folder is followed: the run folder is written where the link points and the link stays.

While ``run`` lasts, its progress goes to a live log ``NAME.log`` beside the folder
(:func:`open_live_log`), which also locks the folder: a second run into the same folder
at once is refused.  The live log starts with :data:`LIVE_LOG_SIGNATURE`, so that a file
``NAME.log`` of the user's is never overwritten (the run is refused) while a log a
killed run left is replaced by the next run.  :func:`write_run` holds a lock on the
parent folder while it writes and swaps, so two saves into one folder at once follow
each other (the last one wins) instead of mixing.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import fcntl
import os
import shutil
import stat
import tempfile
from collections.abc import Callable
from datetime import datetime
from functools import partial
from pathlib import Path
from typing import TextIO

from ..errors import FolderError
from ..inputs.catalog import Catalog
from ..network.edges import EdgeTable
from .atomic import file_mode, write_atomic
from .out_folder import (
    RUN_FOLDER_FILES,
    RUN_FOLDER_MARKERS,
    out_folder_problem,
    real_folder,
)
from .plan_record import SavedPlan

LIVE_LOG_SIGNATURE = "# sdc_cvx live log: it moves into the results folder when the work ends"
"""First line of a live log: a ``NAME.log`` without it is the user's and never touched."""
_EARLIER_SIGNATURES = (
    "# sdc_cvx live run log: it moves into the run folder as run.log at the end",
)  # what earlier versions wrote: their logs, left by a killed run, are taken over too
CSV_FLOAT_FORMAT = "%.10g"
"""Floats in the CSV files: 10 significant digits (no ``98.30000000000001``)."""


def new_run_folder(parent: Path | str = ".", prefix: str = "sdc_run_") -> Path:
    """A new, empty folder ``{prefix}YYYYmmdd-HHMMSS[-k]`` under ``parent``."""
    stamp = datetime.now().strftime("%Y%m%d-%H%M%S")
    for k in range(1000):
        folder = Path(parent) / (f"{prefix}{stamp}" + (f"-{k}" if k else ""))
        try:
            folder.mkdir(parents=True)
            return folder
        except FileExistsError:
            continue
    raise FileExistsError(f"cannot create a new run folder under {parent}")


def live_log_path(folder: Path | str) -> Path:
    """The live log of a run into ``folder``: ``NAME.log`` beside it."""
    folder = real_folder(folder)
    return folder.with_name(folder.name + ".log")


class FolderBusy(FileExistsError):
    """Another run is writing the same folder now."""


def open_live_log(folder: Path | str) -> TextIO:
    """Create (or take over) the live log of a run into ``folder``, locked, and return it.

    The file is ``NAME.log`` beside the folder, opened for writing with an exclusive
    ``flock`` held until it is closed, and starts with :data:`LIVE_LOG_SIGNATURE`.  A live
    log left by a killed run (signed, unlocked) is taken over.

    Raises
    ------
    FolderBusy
        Another process holds the lock: a run into the same folder is under way.
    FileExistsError
        ``NAME.log`` exists and is not a live log of sdc_cvx (a file of the user's).
    OSError
        It cannot be created (with the reason).
    """
    path = live_log_path(folder)
    for _ in range(5):  # the file may change under us (a run ending, another starting)
        try:
            fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL, file_mode())
            created = True
        except FileExistsError:
            fd = os.open(path, os.O_RDWR | os.O_NONBLOCK)  # a named pipe must not block
            created = False
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):  # a pipe, a device: never read it
                raise FileExistsError(
                    f"{path} exists and is not a regular file (a run into {folder} keeps its "
                    f"progress there while it lasts); move {path.name} or choose another "
                    "folder"
                )
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                raise FolderBusy(
                    f"another sdc_cvx run is writing {folder} now (its progress: {path}); "
                    "wait for it to end or choose another folder"
                ) from None
            try:
                same = os.path.samestat(os.fstat(fd), os.stat(path))
            except FileNotFoundError:
                same = False
            if not same:  # removed or replaced between the open and the lock: again
                os.close(fd)
                continue
            if not created:
                with os.fdopen(os.dup(fd), "r", encoding="utf-8", errors="replace") as text:
                    first = text.readline().rstrip("\n")
                if first not in (LIVE_LOG_SIGNATURE, *_EARLIER_SIGNATURES):
                    raise FileExistsError(
                        f"{path} exists and is not a log of sdc_cvx: a run into {folder} "
                        f"keeps its progress there while it lasts, and never overwrites a file "
                        f"of yours; move {path.name} or choose another folder"
                    )
                os.ftruncate(fd, 0)
                os.lseek(fd, 0, os.SEEK_SET)
            stream = os.fdopen(fd, "w", encoding="utf-8", buffering=1)
        except BaseException:
            with contextlib.suppress(OSError):
                os.close(fd)
            if created:
                path.unlink(missing_ok=True)
            raise
        stream.write(LIVE_LOG_SIGNATURE + "\n")
        return stream
    raise FolderBusy(f"{path} keeps changing: another run into {folder} is starting or ending")


@contextlib.contextmanager
def _parent_lock(folder: Path):
    """An exclusive ``flock`` on ``folder``'s parent while a run folder is written there."""
    fd = os.open(folder.parent, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def write_run(
    folder: Path | str,
    solution: SavedPlan,
    edges: EdgeTable | None = None,
    *,
    scenario_toml: str | None = None,
    catalog: Catalog | None = None,
    formats: tuple[str, ...] = ("png",),
    log: str | None = None,
) -> list[Path]:
    """Write a run folder: all its files aside, then swapped in at once.

    Files: ``legs.csv`` (:meth:`~sdc_cvx.solution.Solution.legs_frame`), ``iterations.csv``
    (:meth:`~sdc_cvx.solution.Solution.iterations_frame`), ``edges.csv`` (if ``edges`` is
    given),
    ``scenario.toml`` (if ``scenario_toml`` is given: the scenario as used), ``run.log``
    (if ``log`` is given: the progress of the run), the figures ``orbits``, ``raan``,
    ``cost``, ``iterations`` in each of ``formats`` (if a catalog is known,
    :func:`~sdc_cvx.report.plots.save_figures`), and ``solution.json``.

    The files are written to a hidden folder next to ``folder``, which then takes
    ``folder``'s place in one rename (an earlier run folder there is replaced whole;
    see the module docstring for the policy).  A kill at any moment leaves the old
    folder or the new one, whole, and at most a hidden ``.NAME.*.partial`` folder.

    Parameters
    ----------
    catalog : Catalog, optional
        The solution's catalog, needed by the orbit and RAAN figures.
    formats : tuple of str
        Figure formats (e.g. ``("png", "svg")``); empty for no figures.

    Returns
    -------
    list of Path
        The files written (their final paths).

    Raises
    ------
    FolderError
        ``folder`` is refused (:func:`out_folder_problem`); a :class:`FileExistsError`.
    OSError
        The folder cannot be written: the message names the folder and the reason, the
        ``errno`` is the system's (``ENOSPC`` for a full disk).  Nothing is left behind:
        no folder it created, no hidden ``.partial`` folder.
    """
    return write_staged(folder, partial(_write_files, solution=solution, edges=edges,
                                        scenario_toml=scenario_toml, catalog=catalog,
                                        formats=formats, log=log))  # fmt: skip


def write_staged(folder: Path | str, fill: Callable[[Path], list[str]], *,
                 markers=RUN_FOLDER_MARKERS, files=RUN_FOLDER_FILES,
                 kind: str = "run folder") -> list[Path]:  # fmt: skip
    """Write a folder aside with ``fill(stage)`` and swap it in at once.

    The one staged writer of sdc_cvx's folders (a run folder, a campaign folder): the
    policy of :func:`out_folder_problem` (with ``markers``, ``files`` and ``kind``), a
    lock on the parent folder, a hidden ``.NAME.*.partial`` folder next to ``folder``
    filled by ``fill`` (which returns the names it wrote), then one rename.  A failure
    or a kill leaves the old folder whole; a failure leaves nothing it created.
    """
    given = Path(folder)
    folder = real_folder(given)
    problem = out_folder_problem(given, markers, files, kind)
    if problem is not None:
        raise FolderError(problem)
    created = [p for p in (folder.parent, *folder.parent.parents) if not p.exists()]
    stage = None
    try:
        folder.parent.mkdir(parents=True, exist_ok=True)
        with _parent_lock(folder):
            problem = out_folder_problem(given, markers, files, kind)  # no other save now
            if problem is not None:
                raise FolderError(problem)
            remove_stale_stages(folder)
            stage = Path(
                tempfile.mkdtemp(dir=folder.parent, prefix=f".{folder.name}.", suffix=".partial")
            )
            os.chmod(stage, file_mode(0o777))
            names = fill(stage)
            _pause_before_swap()
            _swap_in(stage, folder)
            stage = None
    except BaseException as err:
        if stage is not None:
            shutil.rmtree(stage, ignore_errors=True)
        for parent in created:  # the parents it made, innermost first, if still empty
            with contextlib.suppress(OSError):
                parent.rmdir()
        if isinstance(err, OSError) and not isinstance(err, FileExistsError):
            reason = err.strerror or str(err)
            where = f" ({err.filename})" if err.filename else ""
            message = f"cannot write the {kind} {given}: {reason}{where}"
            raise OSError(err.errno or errno.EIO, message) from err
        raise
    return [folder / name for name in names]


def _write_files(stage, *, solution, edges, scenario_toml, catalog, formats, log,
                 title=None) -> list[str]:  # fmt: skip
    files = {"legs.csv": solution.legs_frame().to_csv(index=False,
                                                      float_format=CSV_FLOAT_FORMAT)}  # fmt: skip
    if solution.has_history:
        files["iterations.csv"] = solution.iterations_frame().to_csv(
            index=False, float_format=CSV_FLOAT_FORMAT)  # fmt: skip
    if edges is not None:
        files["edges.csv"] = edges.frame.to_csv(index=False, float_format=CSV_FLOAT_FORMAT)
    if scenario_toml is not None:
        files["scenario.toml"] = scenario_toml
    if log is not None:
        files["run.log"] = log
    for name, text in files.items():
        write_atomic(stage / name, text)
    written = [*files]
    catalog = solution.catalog if solution.catalog is not None else catalog
    if catalog is not None and formats:
        from .plots import save_figures  # matplotlib only when figures are drawn

        written += [p.name for p in save_figures(solution, catalog, stage, formats=tuple(formats),
                                                 title=title)]  # fmt: skip
    write_atomic(stage / "solution.json", solution.to_json())
    return written + ["solution.json"]


def _pause_before_swap() -> None:
    """Tests only: ``SDC_CVX_PAUSE_BEFORE_SWAP=seconds`` holds the swap (to kill there)."""
    seconds = os.environ.get("SDC_CVX_PAUSE_BEFORE_SWAP")
    if seconds:
        import time

        time.sleep(float(seconds))


def remove_stale_stages(folder: Path | str) -> None:
    """Remove the hidden folders a killed write left next to ``folder``.

    ``run`` calls it as it starts, once it holds the folder's lock (:func:`open_live_log`),
    so what a kill left aside lasts until the next run into the folder starts.
    """
    folder = real_folder(folder)
    for stale in folder.parent.glob(f".{folder.name}.*.partial"):
        if stale.is_dir():
            shutil.rmtree(stale, ignore_errors=True)


_RENAME_EXCHANGE = 2  # linux/fs.h


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths in one step (Linux ``renameat2(RENAME_EXCHANGE)``); False if unsupported."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd = -100
    result = renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), _RENAME_EXCHANGE)
    return result == 0


def being_flown(folder: Path | str) -> bool:
    """Whether ``sdc_cvx fly`` is flying ``folder`` now (it holds a ``flock`` on it)."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        return True
    finally:
        os.close(fd)
    return False


@contextlib.contextmanager
def _while_not_flown(folder: Path):
    """The ``flock`` ``fly`` takes on a folder, held while it is replaced: a run waits for
    a flight of the folder to end, and no flight starts meanwhile (issue 48: one plan's
    ``solution.json`` beside another plan's ``flight/``)."""
    if not folder.is_dir():
        yield
        return
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def _swap_in(stage: Path, folder: Path) -> None:
    """Put ``stage`` in ``folder``'s place at once (once no flight of it is under way);
    the old content is removed."""
    with _while_not_flown(folder):
        _swap(stage, folder)


def _swap(stage: Path, folder: Path) -> None:
    if not folder.exists():
        os.rename(stage, folder)
        return
    if folder.is_dir() and not any(folder.iterdir()):
        os.rename(stage, folder)  # replaces an empty folder
        return
    if _exchange(stage, folder):
        shutil.rmtree(stage, ignore_errors=True)  # stage now holds the old folder
        return
    old = Path(tempfile.mkdtemp(dir=folder.parent, prefix=f".{folder.name}.", suffix=".partial"))
    os.rename(folder, old / "old")  # elsewhere: two renames, a moment without the folder
    os.rename(stage, folder)
    shutil.rmtree(old, ignore_errors=True)


def save_solution(
    solution: SavedPlan,
    folder: Path | str,
    *,
    formats: tuple[str, ...] = ("png",),
    scenario_toml: str | None = None,
) -> list[Path]:
    """The run folder of ``solution``, as ``python -m sdc_cvx run --out`` writes it.

    The edge table is that of the command line (the pre-optimisation of the solution's
    catalog and mission); ``scenario.toml`` only when ``scenario_toml`` is given (a
    :class:`~sdc_cvx.study.scenario.Scenario`'s ``to_toml()``).  :meth:`Solution.save`
    calls this; the folder policy is :func:`write_run`'s.
    """
    from ..network.edges import preoptimize

    edges = None
    if solution.catalog is not None:
        mission = solution.mission
        edges = preoptimize(solution.catalog, mission, departure_day=mission.deorbit_days)
    return write_run(folder, solution, edges, scenario_toml=scenario_toml, formats=formats)
