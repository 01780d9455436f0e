"""The certified search against its time limit while it sets up: the edge cost tables'
clock.

:func:`cost_table_clock` is ``LegCosts.build``'s chunk callback: it says how far the
tables are, warns when they alone will outlast the limit, asks for a plan without them
first when they are late (a greedy one: :mod:`~sdc_cvx.planner.certified.greedy`), and
raises :class:`OutOfTime` at the limit or at the caller's stop.  The network raises
:class:`OutOfTime` too, when its arcs' bounds reach the limit.
"""

from __future__ import annotations

import time


class OutOfTime(Exception):
    """The time limit ran out during the setup, before any plan (``plan``: a greedy one
    found on the way, or None)."""

    def __init__(self, message: str, plan=None):
        super().__init__(message)
        self.plan = plan


FALLBACK_RESERVE = 0.5
"""With a fallback (``search.fallback``), when the cost tables are projected to end in
the last half of the time limit or past it, a plan is first found without them
(``search.find_greedy``, :mod:`~sdc_cvx.planner.certified.greedy`), then the tables go
on: after tables that took half the limit, the search itself seldom finds a first plan
in the other half (481 fragments: tables about 15 s, a first plan about as long after)."""
PROJECTION_S = 1.0
"""Seconds of tables before their projection is trusted."""


SETUP_PROGRESS_S = 5.0
"""Seconds between two progress lines of the edge cost tables."""


def cost_table_clock(search, every_s: float | None = None):
    """``LegCosts.build``'s chunk callback: the fraction done every ``every_s`` [s], a
    word up front when the tables alone will outlast the time limit, and the limit
    itself, or the caller's stop (:class:`OutOfTime`).  ``search`` has the ``deadline``
    and ``stop`` (read at each chunk) and ``say``; with ``fallback`` true, also
    ``find_greedy`` and ``greedy`` (a plan first when the tables are late)."""
    every_s = SETUP_PROGRESS_S if every_s is None else every_s
    started = last = time.perf_counter()
    warned = greedy = False
    fallback = getattr(search, "fallback", False)

    def on_chunk(done: int, total: int) -> None:
        nonlocal started, last, warned, greedy
        now = time.perf_counter()
        if done < total and (now >= search.deadline or search.stop()):
            why = "interrupted" if search.stop() else "time limit reached"
            raise OutOfTime(f"{why} while building the edge cost tables "
                            f"({done} of {total} edges in {now - started:.0f} s)",
                            getattr(search, "greedy", None))  # fmt: skip
        need = (now - started) * total / max(done, 1)
        beyond = done < total and started + need > search.deadline
        late = started + need > search.deadline - FALLBACK_RESERVE * (search.deadline - started)
        if fallback and not greedy and done < total and late and now - started >= PROJECTION_S:
            greedy = True
            search.say(
                f"  the edge cost tables need about {need:.0f} s of the "
                f"{search.deadline - started:.0f} s left: first a plan without them"
            )
            search.find_greedy()
            paused = time.perf_counter() - now  # the tables' own clock leaves it out
            started, last, now = started + paused, last + paused, now + paused
        if not warned and beyond:
            warned = True
            then = "with the plan found without them" if fallback else "without a plan"
            search.say(f"  the edge cost tables alone need about {need:.0f} s, beyond the "
                       f"time limit ({search.deadline - started:.0f} s left): the search "
                       f"will stop {then}; raise the time limit for a certified "
                       "answer")  # fmt: skip
        if done >= total:  # the heartbeat's phase moves on with this line
            search.say(f"  cost tables done ({total} edges, {now - started:.0f} s); next: the "
                       "first network of date cells, its path bounds, cheap paths")  # fmt: skip
        elif now - last >= every_s:
            last, spent = now, now - started
            search.say(f"  cost tables: {done / total:.0%} done ({done} of {total} edges, "
                       f"{spent:.0f} s, about {need - spent:.0f} s left)")  # fmt: skip

    return on_chunk
