"""Where a campaign's pricing problems run (this process, a local pool, Dask or any
executor), and the options that choose it, checked as the command line checks them."""

from __future__ import annotations

import concurrent.futures as cf
import os
import warnings

import numpy as np

from ..errors import MissionError
from ..inputs.mission import Mission
from ..milp.types import SolverOptions
from ..study.executors import open_executor, unguarded_call_site
from .pricing import Pricing, price


def check_options(solver, gap, time_limit_s, workers, scheduler, executor) -> None:
    """Refuse what :func:`solve_campaign` cannot use, as the command line does."""
    def number(value) -> bool:
        return isinstance(value, int | float) and not isinstance(value, bool)

    if not isinstance(solver, SolverOptions):
        raise MissionError(f"solver must be a SolverOptions, got {type(solver).__name__}")
    if not (number(gap) and 0 <= gap < 1):
        raise MissionError(f"gap must be a number in [0, 1) (0.001 = 0.1 %), got {gap!r}")
    if time_limit_s is not None and not (number(time_limit_s) and time_limit_s > 0):
        raise MissionError(f"time_limit_s must be a positive number of seconds or None, "
                           f"got {time_limit_s!r}")  # fmt: skip
    if workers is not None and not (isinstance(workers, int) and not isinstance(workers, bool)
                                    and workers >= 1):  # fmt: skip
        raise MissionError(f"workers must be a positive integer or None, got {workers!r}")
    if sum(x is not None for x in (executor, scheduler)) > 1 or (
            workers not in (None, 1) and (executor is not None or scheduler is not None)):
        raise MissionError("give one of workers (a local pool), scheduler or executor")


class PricingRuns:
    """``run(tasks) -> results``: the pricing tasks in this process, or on an executor;
    ``say`` hears of each one done (a long round is then never silent: the command
    line's heartbeat shows how far it is)."""

    def __init__(self, inline, executor, scheduler, workers, pending, stop=None, say=None):
        self.inline, self.stop, self.say = inline, stop, say or (lambda line: None)
        self.context = None if inline else open_executor(executor, scheduler, workers, pending)

    def done(self, count: int, total: int, launch) -> None:
        if total > 1:
            self.say(f"  pricing: {count} of {total} done (mission {launch.index + 1}, "
                     f"n = {launch.mission.n})")  # fmt: skip

    def __enter__(self):
        if self.inline:
            def run_here(tasks):
                out = []
                for launch, kwargs in tasks:
                    out.append(price(launch, stop=self.stop, **kwargs))
                    self.done(len(out), len(tasks), launch)
                return out

            return run_here
        pool = self.context.__enter__()

        def run(tasks):
            futures = {pool.submit(price, launch, **kwargs): launch for launch, kwargs in tasks}
            for count, future in enumerate(cf.as_completed(futures), start=1):
                self.done(count, len(futures), futures[future])
                if self.stop is not None and self.stop():  # Ctrl-C: none not yet started
                    for waiting in futures:
                        waiting.cancel()
            # in the tasks' order; a task cancelled before it started proved nothing
            return [_not_run(futures[future]) if future.cancelled() else future.result()
                    for future in futures]  # fmt: skip

        return run

    def __exit__(self, *exc):
        if self.context is not None:
            return self.context.__exit__(*exc)
        return False


def _not_run(launch) -> Pricing:
    """The pricing of a task cancelled before it started: no plan, no bound."""
    return Pricing(launch.index, (), -np.inf, np.inf, "no_plan", 0.0,
                   ("interrupted before this pricing started",), complete=False)  # fmt: skip


def ignored_options(campaign, solver: SolverOptions) -> list[str]:
    """The options set away from their defaults that a campaign does not use (its
    missions are always priced by the certified search), and n ranges a min-dv campaign
    with nothing to remove leaves at their n_min: each said once, before the search."""
    out = []
    if solver.method != "certified":
        out.append(f"solver.method = {solver.method!r} is ignored: a campaign prices its "
                   "missions with the certified search (its bound is what proves the "
                   "campaign's)")  # fmt: skip
    default = Mission().dv_max_mps
    capped = sorted({m.dv_max_mps for m in campaign.missions if m.dv_max_mps != default})
    if capped:
        out.append(f"mission.dv_max_mps = {', '.join(f'{v:g}' for v in capped)} is ignored: "
                   "it filters the edge table of the paper's method; the certified search "
                   "prices every transfer")  # fmt: skip
    ranged = [k for k in range(len(campaign.missions))
              if campaign.fewest(k) < campaign.missions[k].n]  # fmt: skip
    if campaign.objective == "min-dv" and ranged and not (campaign.must_remove
                                                          or campaign.remove_all):  # fmt: skip
        out.append(f"n = {campaign.counts_text()} with objective = 'min-dv' and nothing to "
                   "remove (no must_remove, no remove_all): the least ΔV as a rule takes each "
                   "mission's n_min (fewer debris cost less); give must_remove or remove_all, or "
                   "objective = 'max-value' with dv_budget_mps, to remove more")  # fmt: skip
    return out


def pricings_at_once(workers, scheduler, executor, launches: int) -> int:
    """Pricing searches this machine runs at once (1 in this process or elsewhere)."""
    if executor is not None or scheduler is not None:
        return 1
    return min(workers or os.cpu_count() or 1, launches)


def guarded_workers(workers, scheduler, executor, launches: int):
    """``workers``, or 1 where a local pool would be started from the top level of a
    script without ``if __name__ == "__main__":`` (its workers would run the script
    again and die): the launches are then priced in this process, with a warning."""
    if executor is not None or scheduler is not None or workers == 1 or launches == 1:
        return workers
    site = unguarded_call_site()
    if site is None:
        return workers
    warnings.warn(
        f"{site}: solve_campaign is called at the top level of the script, without "
        '`if __name__ == "__main__":`, so its launches are priced in this process '
        "(workers=1); put the call under that guard to price them in parallel",
        RuntimeWarning, stacklevel=3)  # fmt: skip
    return 1
