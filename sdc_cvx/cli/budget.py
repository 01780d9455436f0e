"""A command's ``--time-limit`` covers the whole command: the search gets what reading
the catalog took and writing the folder will take leave of it.

The writing estimates were measured on this project's cases (a run folder's figures and
tables, about a second; its pre-optimised edge table, 1.8 s for the 230 880 ordered
pairs of 481 TLE fragments; a campaign, 0.6 s a mission folder): a user who
asks for 12 s gets the answer in about 12 s, not 12 s of search and then the folder.
They were measured on an idle machine: under a load of L processes on C cores each one
gets about C / L of a core, and the writing takes that much longer (:func:`loaded`; a
GTOC9 campaign of three missions wrote its folder in 9.5 s at a load of 8.7 on 2 cores,
where 2.4 s were planned, and overran a 90 s limit by as much).
"""

from __future__ import annotations

import os
import time

WRITE_S = 1.0
"""Figures and tables of one run folder [s]."""
MISSION_FOLDER_S = 0.6
"""One mission folder of a campaign, and the campaign's own files [s] (GTOC9, five
missions: 3.5 s in all)."""
PAIR_S = {"impulsive": 8e-6, "low-thrust": 1.2e-4}
"""The run folder's pre-optimised edge table (edges.csv), per ordered pair [s], by
transfer model (481 fragments: 1.8 s impulsive; 60 of them: 115 us a pair low-thrust)."""
EDGES_SHARE = 0.25
"""With a time limit, edges.csv is written only when it is expected to take at most this
share of the limit (it is extra: ``python -m sdc_cvx edges`` writes it on its own)."""
LEAST_SHARE = 0.25
"""The search gets at least this share of the limit, whatever the estimates say."""


def search_limit(limit_s: float | None, started: float, writing_s: float) -> float | None:
    """Seconds the search may take of a command's ``limit_s`` (None: no limit).

    Parameters
    ----------
    limit_s : float or None
        The command's time limit [s].
    started : float
        ``time.perf_counter()`` when the command started.
    writing_s : float
        Estimate of what is left to do after the search [s].
    """
    if limit_s is None:
        return None
    left = limit_s - (time.perf_counter() - started) - loaded(writing_s)
    return max(left, LEAST_SHARE * limit_s)


def loaded(seconds: float) -> float:
    """``seconds`` measured on an idle machine, on this one as loaded now (its load
    average over the last minute against its cores; never less than ``seconds``)."""
    try:
        load = os.getloadavg()[0]
    except OSError:  # not every system has it
        return seconds
    return seconds * max(1.0, load / (os.cpu_count() or 1))


def edges_s(candidates: int, transfer: str) -> float:
    """Estimate [s] of the pre-optimised edge table of ``candidates`` debris."""
    return PAIR_S.get(transfer, PAIR_S["low-thrust"]) * candidates * max(candidates - 1, 0)


def writes_edges(limit_s: float | None, candidates: int, transfer: str) -> bool:
    """Whether a run with ``limit_s`` writes edges.csv (always without a limit)."""
    return limit_s is None or edges_s(candidates, transfer) <= EDGES_SHARE * limit_s


def run_writing_s(candidates: int, transfer: str = "impulsive", edges: bool = True) -> float:
    """Estimate [s] of writing a run folder of ``candidates`` debris (``edges``: with
    edges.csv)."""
    return WRITE_S + (edges_s(candidates, transfer) if edges else 0.0)
