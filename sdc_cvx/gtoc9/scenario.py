"""GTOC9's Kessler Run as a scenario file (issue 47, item 1): :func:`read_kessler_scenario`.

``examples/gtoc9_kessler_run.toml`` holds the whole problem: ``[catalog] path`` (GTOC9's
debris file, relative to the scenario), ``[campaign]`` with ``objective = "gtoc9-cost"``
(J) and ``remove_all = true`` (GTOC9 removes all 123), ``[rules]`` (every field of
:class:`~sdc_cvx.gtoc9.rules.Gtoc9Rules`, each GTOC9's value when left out: the window,
the stays, Δt_R and its reading, Δt_M, the perigee, the tolerances, the masses, c and α)
and ``[search]`` (:class:`~sdc_cvx.gtoc9.search.SearchSettings`' fields, ``time_limit_s``,
``rounds``, ``prize_step_mps``).  Every problem is reported at once, naming the file, the
table and the key.
"""

from __future__ import annotations

import dataclasses
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import MissionError
from .rules import Gtoc9Rules
from .search import SearchSettings

OBJECTIVE = "gtoc9-cost"
"""The objective of a Kessler Run scenario: GTOC9's cost J [MEUR]."""
RUN_KEYS = {"time_limit_s": float, "rounds": int, "prize_step_mps": float}
"""``[search]`` keys beyond :class:`SearchSettings`'."""


@dataclass(frozen=True)
class KesslerScenario:
    """A Kessler Run scenario (module docstring); ``debris_path`` None: the default file."""

    source: str
    debris_path: Path | None
    rules: Gtoc9Rules = Gtoc9Rules()
    settings: SearchSettings = SearchSettings()
    run: dict = field(default_factory=lambda: {"time_limit_s": 900.0, "rounds": 1000,
                                               "prize_step_mps": 80.0})  # fmt: skip


def _typed(value, kind, where: str, problems: list[str]):
    """``value`` as ``kind`` (int, float, str, bool or a tuple of floats), or a problem."""
    if kind is bool or kind is str:
        if isinstance(value, kind):
            return value
    elif kind is int:
        if isinstance(value, int) and not isinstance(value, bool):
            return value
    elif kind is float:
        if isinstance(value, int | float) and not isinstance(value, bool):
            return float(value)
    elif isinstance(value, list) and all(isinstance(v, int | float) for v in value):
        return tuple(float(v) for v in value)
    problems.append(f"{where}: expected {getattr(kind, '__name__', 'a list of numbers')}, "
                    f"got {value!r}")  # fmt: skip
    return None


def _table(data: dict, name: str, kinds: dict, source: str, problems: list[str]) -> dict:
    table = data.get(name, {})
    if not isinstance(table, dict):
        problems.append(f"{source}: [{name}] must be a table")
        return {}
    values = {}
    for key, value in table.items():
        where = f"{source}: [{name}] {key}"
        if key not in kinds:
            problems.append(f"{where}: unknown key (known: {', '.join(kinds)})")
            continue
        typed = _typed(value, kinds[key], where, problems)
        if typed is not None:
            values[key] = typed
    return values


def _kinds(cls) -> dict:
    hints = {"float": float, "int": int, "str": str, "bool": bool}
    return {f.name: hints.get(str(f.type), tuple) for f in dataclasses.fields(cls)}


def read_kessler_scenario(path: str | os.PathLike) -> KesslerScenario:
    """Read a Kessler Run scenario (module docstring).

    Raises
    ------
    MissionError
        Every problem of the file at once (file, table, key, what was expected).
    """
    path = Path(path)
    source = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as err:
        raise MissionError(f"{source}: cannot read it ({err.strerror or err})") from err
    except tomllib.TOMLDecodeError as err:
        raise MissionError(f"{source}: not valid TOML ({err})") from err
    problems: list[str] = []
    known = {"catalog", "campaign", "rules", "search"}
    problems += [f"{source}: unknown table [{name}] (known: {', '.join(sorted(known))})"
                 for name in data if name not in known]  # fmt: skip
    catalog = _table(data, "catalog", {"path": str, "format": str}, source, problems)
    if catalog.get("format", "gtoc9") != "gtoc9":
        problems.append(f"{source}: [catalog] format: expected 'gtoc9', got {catalog['format']!r}")
    campaign = _table(data, "campaign", {"objective": str, "remove_all": bool}, source, problems)
    if campaign.get("objective", OBJECTIVE) != OBJECTIVE:
        problems.append(f"{source}: [campaign] objective: expected {OBJECTIVE!r} (J), got "
                        f"{campaign['objective']!r}")  # fmt: skip
    if campaign.get("remove_all", True) is not True:
        problems.append(f"{source}: [campaign] remove_all: GTOC9 removes every debris "
                        "(true), got false")  # fmt: skip
    rules = _table(data, "rules", _kinds(Gtoc9Rules), source, problems)
    search = _table(data, "search", _kinds(SearchSettings) | RUN_KEYS, source, problems)
    run = {key: search.pop(key) for key in list(search) if key in RUN_KEYS}
    built = {}
    for name, cls, values in (("rules", Gtoc9Rules, rules), ("search", SearchSettings, search)):
        try:
            built[name] = cls(**values)
        except MissionError as err:
            problems.append(f"{source}: [{name}] {err}")
    if problems:
        raise MissionError("\n".join(problems))
    debris = catalog.get("path")
    return KesslerScenario(source, None if debris is None else (path.parent / debris),
                           built["rules"], built["search"],
                           KesslerScenario(source, None).run | run)  # fmt: skip
