"""The one TOML reader and value writer of scenario and study files."""

from __future__ import annotations

import os
import tomllib
from pathlib import Path

import tomli_w

from ..errors import ScenarioError


def read_toml(path: str | os.PathLike, what: str) -> tuple[str, dict]:
    """Text and parsed content of a TOML file, or a ScenarioError saying what is wrong."""
    where = os.fspath(path)
    try:
        text = Path(path).read_bytes().decode("utf-8-sig")  # a BOM (some editors add it) is no key
    except FileNotFoundError:
        raise ScenarioError.collect(where, ["file not found"]) from None
    except IsADirectoryError:
        raise ScenarioError.collect(where, [f"is a directory, not a {what}"]) from None
    except UnicodeDecodeError as exc:
        raise ScenarioError.collect(
            where, [f"not a UTF-8 text file (undecodable byte at offset {exc.start})"]
        ) from None
    except OSError as exc:
        raise ScenarioError.collect(where, [f"not readable ({exc.strerror or exc})"]) from None
    try:
        return text, tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        hint = ""
        if what == "scenario file" and _looks_like_a_catalog(path, text):
            hint = (f" (this looks like a debris catalog, not a {what}: pass it with "
                    f"--catalog {where})")  # fmt: skip
        raise ScenarioError.collect(where, [f"invalid TOML: {exc}{hint}"]) from None


CATALOG_SUFFIXES = (".csv", ".tle", ".txt", ".xml", ".json", ".kvn", ".omm", ".3le")
"""Extensions of catalog files (``inputs/formats``) that a scenario never has."""


def _looks_like_a_catalog(path, text: str) -> bool:
    """A CSV header with ``a_km``, TLE lines, or a catalog's extension."""
    first = next((line.strip() for line in text.splitlines() if line.strip()), "")
    lines = [line for line in text.splitlines() if line.strip()]
    tle = sum(1 for line in lines if line[:2] in ("1 ", "2 ") and len(line) >= 60)
    return (
        Path(path).suffix.lower() in CATALOG_SUFFIXES
        or ("," in first and "a_km" in first)
        or tle >= 2
    )


def toml_value(value) -> str:
    """A TOML value; arrays (lists and tuples) inline."""
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(item) for item in value) + "]"
    return tomli_w.dumps({"v": value}).removeprefix("v = ").rstrip("\n")


def toml_line(key: str, value) -> str:
    """``key = value`` with arrays inline; a dotted key is quoted (one key, not tables)."""
    quoted = tomli_w.dumps({key: 0}).rstrip("\n").removesuffix(" = 0")
    return f"{quoted} = {toml_value(value)}"
