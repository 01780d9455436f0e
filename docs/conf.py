"""Sphinx configuration of sdc_cvx's documentation site.

Build: ``python -m sphinx -W -b html docs docs/_build/html`` (``pip install -e ".[docs]"``).

Three pages are written here at each build, under ``docs/generated/`` (not kept in git), so
that none of them is typed by hand and none can drift from what it shows:

- ``generated/api.rst``: the API reference, one autosummary entry per public name (the
  ``__all__`` of ``sdc_cvx`` and of the sub-packages that declare one, and the error family);
- ``generated/benchmarks.md``: every file of ``benchmarks/results/`` (text outputs included
  verbatim, CSV tables as tables, figures as images);
- ``generated/notebooks/``: the notebooks of ``notebooks/``, copied as they are stored
  (myst-nb renders them; nothing is executed at build time).
"""

from __future__ import annotations

import importlib
import shutil
import sys
import types
from importlib.metadata import version as _version
from pathlib import Path

DOCS = Path(__file__).resolve().parent
REPO = DOCS.parent
GENERATED = DOCS / "generated"
sys.path.insert(0, str(REPO))  # the checkout's sdc_cvx, installed or not

project = "sdc_cvx"
author = "sdc_cvx contributors"
copyright = "2026, sdc_cvx contributors"
release = _version("sdc_cvx")
version = release

extensions = [
    "myst_nb",  # Markdown pages (myst-parser) and the notebooks
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
# design.md is a page through method/design.md (README and docstrings cite docs/design.md)
exclude_patterns = ["_build", "**.ipynb_checkpoints", "design.md"]
highlight_language = "text"  # an untagged block is a program's output, not Python

myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "off"  # the notebooks are rendered as stored (see generated/notebooks)

autosummary_generate = True
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types and units
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": True}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "pydata_sphinx_theme"
html_title = f"sdc_cvx {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "github_url": None,
}
html_static_path: list[str] = []

# --- the generated pages --------------------------------------------------------------

API_PACKAGES = [
    "sdc_cvx",
    "sdc_cvx.flight",
    "sdc_cvx.planner.certified",
    "sdc_cvx.planner.paper",
    "sdc_cvx.inputs.formats",
    "sdc_cvx.gtoc9",
    "sdc_cvx.cli",
]
"""The packages whose ``__all__`` is the public API (in this order on the page)."""

ERRORS = "sdc_cvx.errors"
STUBS: set[str] = set()
"""The autosummary stubs of this build's API page (any other in generated/api is stale)."""


def _public_names(module_name: str) -> list[str]:
    """The names a package declares public, each documented where it is re-exported."""
    module = importlib.import_module(module_name)
    if module_name == ERRORS:
        return sorted(
            name
            for name, value in vars(module).items()
            if isinstance(value, type)
            and issubclass(value, Warning | Exception)
            and value.__module__ == ERRORS
        )
    return list(module.__all__)


def _api_page() -> str:
    """The API reference: the package's docstring, then a table per package."""
    lines = [
        ".. This page is written by docs/conf.py at each build; do not edit it.",
        "",
        "API reference",
        "=============",
        "",
        ".. automodule:: sdc_cvx",
        "   :no-members:",
        "",
    ]
    documented: dict[int, str] = {}  # each object once: where it is first named public
    for package in [*API_PACKAGES, ERRORS]:
        module = importlib.import_module(package)
        names, elsewhere = [], []
        for name in _public_names(package):
            value = getattr(module, name)
            key = id(value)
            if isinstance(value, type | types.FunctionType) and key in documented:
                elsewhere.append(f":obj:`{name} <{documented[key]}>`")
                continue
            documented.setdefault(key, f"{package}.{name}")
            names.append(name)
            STUBS.add(f"{package}.{name}.rst")
        title = f"``{package}``"
        lines += [title, "-" * len(title), "", f".. currentmodule:: {package}", ""]
        lines += [".. autosummary::", "   :toctree: api", ""]
        lines += [f"   {name}" for name in names]
        lines.append("")
        if elsewhere:
            lines += [f"Also public here: {', '.join(elsewhere)} (documented above).", ""]
    return "\n".join(lines)


def _csv_table(rel: str) -> list[str]:
    return ["```{csv-table}", f":file: {rel}", ":header-rows: 1", "```", ""]


def _benchmarks_page() -> str:
    """Every file of benchmarks/results/, with what its README says of it first."""
    results = REPO / "benchmarks" / "results"
    lines = [
        "<!-- This page is written by docs/conf.py at each build from benchmarks/results/. -->",
        "",
        "# Benchmarks",
        "",
        "Every file of `benchmarks/results/` as it is kept in the repository: each is the",
        "output of the script its name says (`python benchmarks/NAME.py`, options in the",
        "notes below and in the file's first lines), measured on the project's shared",
        "2-core machine. Nothing on this page is typed by hand.",
        "",
        "## Notes on the results",
        "",
        "```{include} /../benchmarks/results/README.md",
        ":start-line: 1",  # its title: this page's
        ":heading-offset: 1",
        "```",
        "",
        "## The files",
        "",
    ]
    files = sorted(p for p in results.iterdir() if p.name != "README.md")
    for path in files:
        rel = f"/../benchmarks/results/{path.name}"
        lines += [f"### `{path.name}`", ""]
        if path.suffix == ".txt":
            lines += ["```{literalinclude} " + rel, ":language: text", "```", ""]
        elif path.suffix == ".csv":
            lines += _csv_table("../../benchmarks/results/" + path.name)
        elif path.suffix == ".png":
            lines += [f"```{{image}} {rel}", f":alt: {path.name}", "```", ""]
        else:
            lines += [f"(`{path.name}` is kept in the repository, not shown here.)", ""]
    return "\n".join(lines)


def _write_if_changed(path: Path, text: str) -> None:
    """Write a generated page only when it changed (Sphinx then rebuilds only it)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _copy_notebooks() -> None:
    target = GENERATED / "notebooks"
    target.mkdir(parents=True, exist_ok=True)
    for notebook in sorted((REPO / "notebooks").glob("*.ipynb")):
        copy = target / notebook.name
        if not copy.exists() or copy.read_bytes() != notebook.read_bytes():
            shutil.copyfile(notebook, copy)


def _generate(app) -> None:
    _write_if_changed(GENERATED / "api.rst", _api_page())
    for stub in (GENERATED / "api").glob("*.rst"):  # a name no longer public: its old page
        if stub.name not in STUBS:
            stub.unlink()
    _write_if_changed(GENERATED / "benchmarks.md", _benchmarks_page())
    _copy_notebooks()


def setup(app):
    # now, before autosummary writes its stubs for the API page (at builder-inited)
    _generate(app)
