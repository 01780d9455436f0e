"""The guide's code blocks are true: every Python block runs, every TOML block is a file the
scenario reader takes, every command names a command, flags and files that exist (issue 49).

The blocks are collected from the Markdown pages of ``docs/`` (getting started and the user
guide), so a block added to a page is tested without being named here.  The Python blocks
run as a user pastes them: in a fresh interpreter, from a folder holding the repository's
``sdc_cvx/data/`` (the paths they name are relative to the repository's root).
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
import tomllib

import pytest

from tests.conftest import REPO

PAGES = sorted([REPO / "docs" / "getting-started.md", *(REPO / "docs" / "guide").glob("*.md")])
"""The pages whose blocks a user copies."""

FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.S | re.M)


def _blocks(language: str) -> list[tuple[str, str]]:
    """``(page:line, code)`` of every fenced block of ``language`` in the pages."""
    found = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for match in FENCE.finditer(text):
            if match.group(1) == language:
                line = text.count("\n", 0, match.start()) + 1
                found.append((f"{page.relative_to(REPO)}:{line}", match.group(2)))
    return found


PYTHON = _blocks("python")
TOML = _blocks("toml")
BASH = _blocks("bash")


def test_the_guide_pages_have_blocks_to_test():
    # a renamed page or a changed fence would otherwise leave nothing tested
    assert len(PYTHON) >= 2 and len(TOML) >= 1 and len(BASH) >= 8


@pytest.mark.slow
@pytest.mark.parametrize(("where", "code"), PYTHON, ids=[w for w, _ in PYTHON])
def test_every_python_block_of_the_guide_runs(where, code, tmp_path):
    (tmp_path / "sdc_cvx" / "data").mkdir(parents=True)
    for data in (REPO / "sdc_cvx" / "data").glob("*.csv"):
        shutil.copy(data, tmp_path / "sdc_cvx" / "data")
    # -P: the folder's sdc_cvx/ (data only) must not shadow the package under test
    result = subprocess.run(
        [sys.executable, "-P", "-c", code],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        env={"MPLBACKEND": "Agg", "PATH": "/usr/bin:/bin", "PYTHONPATH": str(REPO)},
        timeout=120,
    )
    assert result.returncode == 0, f"{where}: {result.stderr[-2000:]}"
    assert "Traceback" not in result.stderr, f"{where}: {result.stderr[-2000:]}"


@pytest.mark.parametrize(("where", "code"), TOML, ids=[w for w, _ in TOML])
def test_every_toml_block_of_the_guide_is_read_by_the_scenario_reader(where, code):
    from sdc_cvx.study.scenario_tables import TABLE_KEYS

    data = tomllib.loads(code)
    for table, values in data.items():
        assert table in TABLE_KEYS, f"{where}: [{table}] is no table of a scenario"
        unknown = sorted(set(values) - set(TABLE_KEYS[table]))
        assert not unknown, f"{where}: [{table}] has no key {unknown}"


def _commands() -> list[tuple[str, list[str]]]:
    """Each ``python -m sdc_cvx ...`` or ``python benchmarks/...`` line, split as a shell would."""
    found = []
    for where, code in BASH:
        for line in code.splitlines():
            line = line.split("#", 1)[0].strip()
            for part in line.split("&&"):
                words = shlex.split(part)
                if words and words[0].endswith(("python", "python3")):
                    found.append((where, words))
    return found


COMMANDS = _commands()


@pytest.mark.parametrize(("where", "words"), COMMANDS, ids=[" ".join(w) for _, w in COMMANDS])
def test_every_command_of_the_guide_names_what_exists(where, words):
    from sdc_cvx.cli import main

    if len(words) > 1 and words[1].startswith("benchmarks/"):
        assert (REPO / words[1]).is_file(), f"{where}: no script {words[1]}"
        return
    if words[1:3] != ["-m", "sdc_cvx"]:
        return  # python3 -m venv, pytest: not ours
    name, args = words[3], words[4:]
    assert name in main.commands, f"{where}: no command {name!r}"
    command = main.commands[name]
    flags = {opt for param in command.params for opt in param.opts + param.secondary_opts}
    flags.add("--help")
    for arg in args:
        if arg.startswith("--"):
            assert arg.split("=", 1)[0] in flags, f"{where}: `{name}` has no option {arg}"
        elif arg.startswith("examples/"):
            assert (REPO / arg).is_file(), f"{where}: no file {arg}"


def test_the_api_page_has_every_public_name():
    """The API page (written by docs/conf.py at each build) names every name of every
    ``__all__`` of the package, and no package that declares one is left out."""
    import ast
    import importlib.util

    spec = importlib.util.spec_from_file_location("docs_conf", REPO / "docs" / "conf.py")
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)  # defines the page's writer; writes nothing
    declaring = sorted(
        ".".join(init.parent.relative_to(REPO).parts)
        for init in (REPO / "sdc_cvx").rglob("__init__.py")
        if any(isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "__all__"
                                                    for t in node.targets)
               for node in ast.parse(init.read_text(encoding="utf-8")).body)
    )  # fmt: skip
    assert sorted(set(conf.API_PACKAGES)) == declaring
    page = conf._api_page()
    for package in conf.API_PACKAGES:
        for name in importlib.import_module(package).__all__:
            assert f"   {name}\n" in page or f":obj:`{name} <" in page, f"{package}.{name}"
