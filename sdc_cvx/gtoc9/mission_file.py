"""A GTOC9 mission file: one event a line, ``epoch x y z vx vy vz dvx dvy dvz id``.

The competition's event format (its submission-format page): the epoch [MJD2000]; the
spacecraft's position [m] and velocity [m/s] just before the impulse, in the frame of
GTOC9's elements; the impulse ``ΔV`` [m/s], applied just after; the event id last (``-1``
a deep-space manoeuvre, the debris id at its arrival and again at its departure).  Fields
are separated by blanks; blank lines and lines starting with ``#`` are comments.

:func:`write_mission_file` writes such a file from :class:`Event` rows (every number with
17 significant digits: an epoch to the microsecond needs 11);
:func:`read_mission_file` reads one back, every malformed line named.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import MissionError
from .rules import DSM, FIELDS


@dataclass(frozen=True)
class Event:
    """One line of a mission file.

    Attributes
    ----------
    epoch : float
        MJD2000 [days].
    r, v : tuple of 3 floats
        Position [m] and velocity [m/s] just before the impulse.
    dv : tuple of 3 floats
        The impulse [m/s], applied just after the epoch.
    ident : int
        ``-1`` a deep-space manoeuvre, else the debris id (its arrival or departure).
    line : int
        The line of the file it was read from (0 when built in memory).
    """

    epoch: float
    r: tuple
    v: tuple
    dv: tuple
    ident: int
    line: int = 0

    def __post_init__(self):
        for name in ("r", "v", "dv"):
            value = tuple(float(x) for x in np.asarray(getattr(self, name), float).ravel())
            if len(value) != 3:
                raise MissionError(f"Event.{name}: expected 3 components, got {len(value)}")
            object.__setattr__(self, name, value)
        if int(self.ident) != self.ident or self.ident < DSM:
            raise MissionError(f"Event.ident: expected -1 or a debris id >= 0, got {self.ident!r}")
        object.__setattr__(self, "ident", int(self.ident))
        object.__setattr__(self, "epoch", float(self.epoch))

    @property
    def is_dsm(self) -> bool:
        return self.ident == DSM

    def fields(self) -> list[float]:
        """The 10 numbers of the line before the id."""
        return [self.epoch, *self.r, *self.v, *self.dv]


def format_event(event: Event) -> str:
    """One line of a mission file (17 significant digits, the id last)."""
    return " ".join(format(x, ".17g") for x in event.fields()) + f" {event.ident:d}"


def write_mission_file(path: str | os.PathLike, events, *, comment: str | None = None) -> Path:
    """Write ``events`` (:class:`Event`, in time order) as a GTOC9 mission file.

    ``comment`` (lines of text) goes first, each line prefixed with ``"# "``; the header
    line naming the fields follows.  Returns the path written.
    """
    path = Path(path)
    events = list(events)
    if not events:
        raise MissionError(f"{path}: a mission file needs at least one event, got none")
    lines = [f"# {text}" for text in (comment.splitlines() if comment else [])]
    lines.append("# " + " ".join(FIELDS))
    lines += [format_event(event) for event in events]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@dataclass(frozen=True)
class LineProblem:
    """A malformed line (or an unreadable file, ``line = 0``)."""

    line: int
    message: str


def read_mission_file(path: str | os.PathLike) -> tuple[list[Event], list[LineProblem]]:
    """The events of a mission file and the problems of its malformed lines.

    A line is malformed when it has not exactly 11 fields, a field is not a finite
    number, or the id is not an integer >= -1.  An unreadable file (missing, not UTF-8)
    gives one problem at line 0 and no events.
    """
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        return [], [LineProblem(0, f"cannot read the file ({err})")]
    events, problems = [], []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        fields = line.split()
        if len(fields) != len(FIELDS):
            problems.append(LineProblem(number, f"{len(fields)} fields, expected {len(FIELDS)} "
                                                f"({' '.join(FIELDS)})"))  # fmt: skip
            continue
        values, bad = [], []
        for name, field in zip(FIELDS, fields, strict=True):
            try:
                value = float(field)
            except ValueError:
                value = math.nan
            if not math.isfinite(value):
                bad.append(f"{name} {field[:20]!r} is not a finite number")
            values.append(value)
        ident = values[-1]
        if not bad and (not ident.is_integer() or ident < DSM):
            bad.append(f"id {fields[-1][:20]!r}: expected -1 or a debris id >= 0")
        if bad:
            problems.append(LineProblem(number, "; ".join(bad)))
            continue
        events.append(Event(values[0], values[1:4], values[4:7], values[7:10], int(ident),
                            line=number))  # fmt: skip
    if not events and not problems:
        problems.append(LineProblem(0, "no event lines"))
    return events, problems
