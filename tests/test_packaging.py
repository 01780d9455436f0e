"""What a packaged sdc_cvx carries beside its code (issue 49, item 3): its version from the
package metadata, ``py.typed``, a citation file naming the paper, a changelog.

The wheel itself is built and run in a fresh virtual environment by ``.ci/run``.
"""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib

import yaml

from tests.conftest import REPO

PYPROJECT = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))


def test_the_version_is_the_installed_distributions():
    # the metadata says 9.9.9: a version typed into __init__.py would not follow it
    code = ("import importlib.metadata as m; m.version = lambda name: '9.9.9'; "
            "import sdc_cvx; print(sdc_cvx.__version__)")  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True,
                         text=True, check=True).stdout  # fmt: skip
    assert out.strip() == "9.9.9"


def test_the_package_says_it_is_typed():
    assert (REPO / "sdc_cvx" / "py.typed").is_file()
    assert "py.typed" in PYPROJECT["tool"]["setuptools"]["package-data"]["sdc_cvx"]


def test_the_citation_file_names_the_paper_the_package_implements():
    cff = yaml.safe_load((REPO / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software"
    assert cff["version"] == PYPROJECT["project"]["version"]
    paper = cff["preferred-citation"]  # Cerf, JOTA 156(3), 761-796, 2013
    assert paper["authors"][0]["family-names"] == "Cerf"
    assert (paper["volume"], paper["issue"], paper["start"], paper["end"], paper["year"]) == (
        156, 3, 761, 796, 2013)
    assert paper["doi"] == "10.1007/s10957-012-0130-6"
    assert paper in cff["references"]


def test_the_changelog_has_the_packages_version():
    text = (REPO / "CHANGELOG.md").read_text(encoding="utf-8")
    assert text.startswith("# Changelog") and "keepachangelog.com" in text
    versions = re.findall(r"^## \[([^\]]+)\]", text, re.M)
    assert versions[0] == "Unreleased" and PYPROJECT["project"]["version"] in versions
