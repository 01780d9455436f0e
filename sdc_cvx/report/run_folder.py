"""Writing a run's results to a folder, atomically (temp file then rename)."""

from __future__ import annotations

import os
import tempfile
from datetime import datetime
from pathlib import Path

from ..inputs.catalog import Catalog
from ..network.edges import EdgeTable
from ..solution import Solution
from .plots import save_figures


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` so that readers never see a truncated file."""
    path = Path(path)
    handle, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(handle, "w", encoding="utf-8") as stream:
            stream.write(text)
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
    ``catalog`` is given, :func:`~sdc_cvx.plots.save_figures`), then
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
        written += save_figures(solution, catalog, folder, formats=tuple(formats))
    write_atomic(folder / "solution.json", solution.to_json())  # last: the run is complete
    return written + [folder / "solution.json"]
