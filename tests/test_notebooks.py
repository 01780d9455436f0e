"""The notebooks run from top to bottom and show their figures (issue 28, 3.1).

Each is executed in a fresh Jupyter kernel from its own folder, as a user opens it (its
quick parameters, the ones it is stored with); an error in any cell fails the test.  A
figure returned as a cell's value shows as an image only when the inline backend is on:
without it Jupyter printed ``<Figure size 800x450 with 1 Axes>``, which a run that only
checks for errors does not notice, so the executed notebook must hold PNG outputs.
"""

from __future__ import annotations

import pytest

from tests.conftest import REPO

NOTEBOOKS = sorted((REPO / "notebooks").glob("*.ipynb"))
FIGURES = {"01_paper_case": 4}
"""Figures a notebook shows, where the count is known (at least one for the others)."""


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_the_notebook_runs_and_shows_its_figures(path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(path, as_version=4)
    where = {"metadata": {"path": str(path.parent)}}  # run from its folder, as Jupyter does
    nbclient.NotebookClient(notebook, timeout=1800, kernel_name="python3",
                            resources=where).execute()  # fmt: skip
    images = sum("image/png" in output.get("data", {}) for cell in notebook.cells
                 if cell.cell_type == "code" for output in cell.get("outputs", []))  # fmt: skip
    texts = [output["data"]["text/plain"] for cell in notebook.cells if cell.cell_type == "code"
             for output in cell.get("outputs", []) if "text/plain" in output.get("data", {})
             and "image/png" not in output["data"]]  # fmt: skip
    assert not any(text.startswith("<Figure size") for text in texts), "a figure shown as text"
    assert images >= FIGURES.get(path.stem, 1)
