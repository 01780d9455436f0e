"""Writing a run's results to a folder, atomically (temp file then rename).

:func:`write_atomic` is the one atomic writer: the run folder, the figures
(:mod:`sdc_cvx.report.plots`) and the sweep folders all go through it.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from datetime import datetime
from pathlib import Path
from typing import BinaryIO

from ..inputs.catalog import Catalog
from ..network.edges import EdgeTable
from ..solution import Solution


def write_atomic(
    path: Path, content: str | Callable[[BinaryIO], None], *, mode: int | None = None
) -> None:
    """Write ``content`` to ``path`` so that readers never see a truncated file.

    The one atomic writer of sdc_cvx (a temporary file in the same folder, then
    ``os.replace``).  ``content`` is text (written as UTF-8) or a function that writes
    the bytes to the binary stream it is given (a figure's ``savefig``).  ``mode``: the
    permissions of the file (the temporary file is created 0600), e.g. 0o644 for images.
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
        if mode is not None:
            os.chmod(temp, mode)
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise


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


def write_run(
    folder: Path | str,
    solution: Solution,
    edges: EdgeTable | None = None,
    *,
    scenario_toml: str | None = None,
    catalog: Catalog | None = None,
    formats: tuple[str, ...] = ("png",),
) -> list[Path]:
    """Write a run's files to ``folder``, each atomically, ``solution.json`` last.

    Files: ``legs.csv``, ``iterations.csv``, ``edges.csv`` (if ``edges`` is given),
    ``scenario.toml`` (if ``scenario_toml`` is given: the scenario as used), the
    figures ``orbits``, ``raan``, ``cost``, ``iterations`` in each of ``formats`` (if
    ``catalog`` is given, :func:`~sdc_cvx.report.plots.save_figures`), then
    ``solution.json``, whose presence means the run is complete.

    Parameters
    ----------
    catalog : Catalog, optional
        The solution's catalog, needed by the orbit and RAAN figures.
    formats : tuple of str
        Figure formats (e.g. ``("png", "svg")``); empty for no figures.

    Returns
    -------
    list of Path
        The files written.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    files = {
        "legs.csv": solution.legs_frame().to_csv(index=False),
        "iterations.csv": solution.iterations_frame().to_csv(index=False),
    }
    if edges is not None:
        files["edges.csv"] = edges.frame.to_csv(index=False)
    if scenario_toml is not None:
        files["scenario.toml"] = scenario_toml
    written = []
    for name, text in files.items():
        write_atomic(folder / name, text)
        written.append(folder / name)
    catalog = solution.catalog if solution.catalog is not None else catalog
    if catalog is not None and formats:
        from .plots import save_figures  # matplotlib only when figures are drawn

        written += save_figures(solution, catalog, folder, formats=tuple(formats))
    write_atomic(folder / "solution.json", solution.to_json())  # last: the run is complete
    return written + [folder / "solution.json"]
