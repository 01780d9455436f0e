"""The README's Python snippet runs as written (from the repository root)."""

import re
import shutil
import subprocess
import sys

import pytest

from tests.conftest import REPO


@pytest.mark.slow
def test_readme_python_snippet_runs_as_written(tmp_path):
    text = (REPO / "README.md").read_text(encoding="utf-8")
    snippet = re.search(r"## Use\n\n```python\n(.*?)```", text, re.S).group(1)
    assert "Catalog.from_csv(" in snippet and ".save(" in snippet and ".plot()" in snippet
    # the repository root as the snippet sees it, without writing into the repository
    (tmp_path / "sdc_cvx" / "data").mkdir(parents=True)
    shutil.copy(REPO / "sdc_cvx" / "data" / "paper_table5.csv", tmp_path / "sdc_cvx" / "data")
    # -P: the folder's sdc_cvx/ (data only) must not shadow the installed package
    result = subprocess.run(
        [sys.executable, "-P", "-c", snippet],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env={"MPLBACKEND": "Agg", "PATH": "/usr/bin:/bin"},
    )
    assert result.returncode == 0, result.stderr
    # n = 4 on Table 5: the certified answer, proven within its gap
    assert "5 -> 8 -> 10 -> 6" in result.stdout and ", optimal (gap" in result.stdout
    assert (tmp_path / "sdc_run_python" / "solution.json").exists()


def test_readme_is_one_page_whose_links_lead_somewhere():
    """Issue 49: README is one page (the guide holds the rest), and each file it links to
    is in the repository (a page moved or renamed would leave a dead link)."""
    text = (REPO / "README.md").read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200
    links = re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", text)
    local = [link for link in links if "://" not in link]
    assert len(local) >= 10  # the guide's map
    assert [link for link in local if not (REPO / link).exists()] == []
