"""The exceptions of sdc_cvx, in three families under one base (:class:`SdcError`).

* input errors (also :class:`ValueError`): :class:`CatalogError`, :class:`MissionError`,
  :class:`ScenarioError` - something the user gave is wrong; nothing was solved;
  :class:`OutputError` and :class:`FolderError` (also a :class:`FileExistsError`) - what
  a save was asked to write, or where, is refused; nothing was written;
* planning errors (also :class:`RuntimeError`): :class:`MissionInfeasible`,
  :class:`SolverFailure` - the inputs are valid but no plan came out;
* :class:`SweepError` (also :class:`RuntimeError`) - a parameter study cannot run in the
  folder it was given.

The command line's exit codes map from these families (:data:`sdc_cvx.cli.EXIT_CODES`).
Each class is also importable from the module that raises it (``sdc_cvx.inputs.catalog``,
``sdc_cvx.inputs.mission``, ``sdc_cvx.study.scenario``, ``sdc_cvx.planner.paper.driver``,
``sdc_cvx.study.runner``) and, except :class:`ScenarioError` and :class:`SweepError`,
from ``sdc_cvx``.  This module imports nothing of sdc_cvx.
"""

from __future__ import annotations

from collections.abc import Iterable

MAX_REPORTED = 20
"""Problems listed in a :class:`CatalogError` message (all are kept in ``problems``)."""
MAX_LISTED = 12
"""Items a message lists of a list the user controls (ids, columns): a line stays readable."""


def listing(items: Iterable, limit: int = MAX_LISTED) -> str:
    """``"a, b, c"``, or ``"a, b, c, ... and 348 more"`` past ``limit`` items.

    For messages that name what a user gave: a header of 400 columns or 360 unknown ids
    must not become one line of thousands of characters.
    """
    items = [str(item) for item in items]
    more = f", ... and {len(items) - limit} more" if len(items) > limit else ""
    return ", ".join(items[:limit]) + more


class SdcError(Exception):
    """Base of every exception sdc_cvx raises on purpose."""


# ----------------------------------------------------------------------- inputs
class InputError(SdcError, ValueError):
    """Invalid input: a catalog, a mission or a scenario file (CLI exit code 2)."""


class CatalogError(InputError):
    """A debris catalog cannot be read or fails validation.

    The message has a summary first line (``"3 problems in debris.csv:"``) and then
    one problem per line, each naming the file, the row, the line and the field.

    Attributes
    ----------
    problems : tuple of str
        Every problem found, including those left out of the message.
    """

    def __init__(self, message: str, problems: Iterable[str] = ()):
        super().__init__(message)
        self.problems = tuple(problems) or (message,)

    @classmethod
    def collect(cls, source: str, problems: list[str], advice: str = "") -> CatalogError:
        """Error listing ``problems`` found in ``source``, at most ``MAX_REPORTED`` shown,
        then ``advice`` (what to do about them: a line of its own, not a problem)."""
        count = len(problems)
        lines = [f"{count} problem{'s' if count != 1 else ''} in {source}:"]
        lines += [f"  {problem}" for problem in problems[:MAX_REPORTED]]
        if count > MAX_REPORTED:
            lines.append(f"  ... and {count - MAX_REPORTED} more")
        if advice:
            lines.append(advice)
        return cls("\n".join(lines), problems)


class MissionError(InputError):
    """A mission parameter is out of range or inconsistent with the others."""


class ScenarioError(InputError):
    """A scenario file (or an override) is invalid; the message is one line.

    Attributes
    ----------
    problems : tuple of str
        Every problem found, each naming the dotted key (``mission.n``).
    """

    def __init__(self, message: str, problems=()):
        super().__init__(message)
        self.problems = tuple(problems) or (message,)

    @classmethod
    def collect(cls, where: str, problems) -> ScenarioError:
        """One error for all ``problems`` found in ``where`` (a file name, "overrides")."""
        return cls(f"{where}: " + "; ".join(problems), problems)


class OutputError(InputError):
    """What a save was asked to write, or where, is refused: a folder that is not a path,
    a figure format, a ``scenario_toml`` that is not text (nothing was written)."""


class FolderError(OutputError, FileExistsError):
    """A folder cannot take the results: a file, a folder holding files of the user's,
    the current folder, a name too long, a place that refuses new files (nothing was
    written).  Also a :class:`FileExistsError`, what these refusals were before."""


# --------------------------------------------------------------------- planning
class CatalogWarning(UserWarning):
    """A catalog was read, but something in it is likely a mistake (an unknown column)."""


class IgnoredOptionWarning(UserWarning):
    """An option was set that the chosen method does not use (``dv_max_mps`` with the
    certified search, ``gap`` with the paper's method): said, not silently dropped."""


class PlanningError(SdcError, RuntimeError):
    """Valid inputs, but no plan: the mission is infeasible or the solver failed."""


class MissionInfeasible(PlanningError):
    """No path meets the mission's constraints; the message says what could be relaxed."""


class SolverFailure(PlanningError):
    """The MILP backend failed or stopped before finding any solution."""


# ------------------------------------------------------------------------ study
class SweepError(SdcError, RuntimeError):
    """The output folder cannot take this sweep (results of another study, a sweep
    already writing there, results present without ``resume``) or no executor."""
