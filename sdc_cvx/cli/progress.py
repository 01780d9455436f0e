"""A run's progress: its lines on stderr and in the live log beside ``--out``, the
heartbeat of a silent phase, and Ctrl-C during a solve (:class:`RunProgress`,
:func:`open_progress_log`, :func:`interruptible`)."""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import time
from datetime import UTC, datetime
from pathlib import Path

import click

from .exits import fail


def iteration_line(record) -> str:
    """The progress line of an iteration of the paper's method, or of its rejection (the
    driver tells it twice); the certified search writes its own lines."""
    if record.rejected:
        return f"  it {record.iteration:2d}  step rejected: {record.rejected}"
    dv_lin = "-" if record.dv_linearized_mps is None else f"{record.dv_linearized_mps:8.1f}"
    dv_true = "-" if record.dv_true_mps is None else f"{record.dv_true_mps:8.1f}"
    days = "-" if record.duration_true_days is None else f"{record.duration_true_days:7.1f}"
    return (
        f"  it {record.iteration:2d}  {'->'.join(record.path) or '(none)':<28} "
        f"dV lin {dv_lin}  true {dv_true} m/s  {days} d  nodes {record.nodes}  "
        f"{record.seconds:6.2f} s  {record.note}"
    ).rstrip()


def remove_empty(folders: list[Path]) -> None:
    """Remove ``folders`` (innermost first) that are empty; leave the others."""
    for folder in folders:
        with contextlib.suppress(OSError):
            folder.rmdir()


class RunProgress:
    """The progress of a run: to stderr when asked (a terminal), and always to ``run.log``.

    Every phase is named: reading, each step of the certified search (plans, refinements,
    each relaxation MILP as it starts and its bound) or of the paper's method (each MILP
    iteration, the rejection of a step with why, the re-optimisation), and the writing.
    While a phase is silent, a heartbeat line says what is running and for how long,
    every ``heartbeat_s`` seconds.  With ``live_log``, every line is also appended to that
    file as it is said, so that a killed run leaves its progress behind.
    """

    def __init__(self, show: bool, heartbeat_s: float = 5.0, live_log: Path | None = None,
                 stream=None, made: list[Path] | None = None):  # fmt: skip
        self.show, self.heartbeat_s, self._time = show, heartbeat_s, time.monotonic
        self.live_log = live_log
        self._made = list(made or [])
        self.log_failed = ""  # why the live log could not be written any more
        self._file = stream
        if live_log is not None and stream is None:
            live_log.parent.mkdir(parents=True, exist_ok=True)
            self._file = open(live_log, "w", encoding="utf-8", buffering=1)  # noqa: SIM115
        self.lines: list[str] = []
        self.started = self._last = self._time()
        self.phase = "reading the catalog"
        self.iterations = 0
        self._lock = threading.RLock()  # a Ctrl-C's handler may say while say() runs
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._beat, daemon=True)

    def __enter__(self):
        if self.show or self._file is not None:  # the heartbeat goes to the live log too
            self._thread.start()
        return self

    def __exit__(self, *exc):
        """Stop the heartbeat; the live log stays open (and locked) until discarded."""
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join()

    def discard_live_log(self) -> None:
        """The run folder now holds ``run.log`` (or nothing is kept): remove the live copy
        beside it, then release it (removed while locked: no other run's log is hit)."""
        if self.live_log is not None:
            self.live_log.unlink(missing_ok=True)
        if self._file is not None:
            with self._lock, contextlib.suppress(OSError):
                self._file.close()
        remove_empty(self._made)  # the folders made for --out, unless the run folder is there

    def say(self, line: str, *, show: bool = True) -> None:
        with self._lock:
            stamp = datetime.now(UTC).strftime("%H:%M:%S")
            self.lines.append(f"{stamp} {line}")
            if self._file is not None and not self._file.closed and not self.log_failed:
                try:
                    self._file.write(f"{stamp} {line}\n")
                except OSError as err:  # a full disk: the run goes on, the log says no more
                    self.log_failed = f"{self.live_log}: {err.strerror or err}"
            self._last = self._time()
            if self.show and show:
                click.echo(line, err=True)

    def set_phase(self, phase: str) -> None:
        self.phase = phase
        self.say(f"  ... {phase}")

    def search_step(self, line: str) -> None:
        """The certified search's log callback: one line per step, the phase it is in."""
        self.say(line)
        self.phase = f"certified search, since: {line.strip()}"

    def iteration(self, record) -> None:
        """The solver's progress callback (:func:`sdc_cvx.planner.api.solve`)."""
        if record.status == "bound":  # the certified search: its own lines tell the step
            self.iterations = record.iteration + 1
            return
        self.say(iteration_line(record))
        if not record.rejected:
            self.iterations = record.iteration + 1
            self.phase = (
                f"after MILP iteration {record.iteration}: the next MILP, or the "
                "re-optimisation of the path in the true model"
            )

    def log_text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def _beat(self) -> None:
        while not self._stop.wait(min(1.0, self.heartbeat_s)):
            now = self._time()
            if now - self._last >= self.heartbeat_s:
                self.say(f"  ... {now - self.started:5.0f} s: {self.phase}", show=self.show)


def open_progress_log(out_dir):
    """``(live_log, stream, made)``: the progress log beside ``--out`` while a run lasts.

    ``OUT.log`` beside the folder (a killed run leaves it there, the next run into OUT
    replaces it), locked, so a second run into OUT at once is refused; the hidden stages a
    killed run left are removed now that OUT is ours.  ``made``: the folders above
    ``--out`` created for it (removed if unused).  Without ``--out``: no log.  Exit 2
    when OUT is busy, the log is a file of the user's, or it cannot be written.
    """
    from ..report.run_folder import live_log_path, open_live_log, remove_stale_stages

    if out_dir is None:
        return None, None, []
    live_log = live_log_path(out_dir)
    made = [p for p in (live_log.parent, *live_log.parent.parents) if not p.exists()]
    try:
        live_log.parent.mkdir(parents=True, exist_ok=True)
        stream = open_live_log(out_dir)
        remove_stale_stages(out_dir)
    except OSError as err:  # FileExistsError: another run is writing OUT, a user's file
        remove_empty(made)
        if isinstance(err, FileExistsError):
            fail(f"--out: {err}")
        fail(f"--out: cannot write the progress log {live_log}: {err.strerror or err}")
    return live_log, stream, made


RESOURCE_TRACKER_NOISE = "ignore:resource_tracker:UserWarning"
"""The warning filter handed to multiprocessing's resource tracker (see below)."""


def quiet_resource_tracker() -> None:
    """Keep multiprocessing's resource tracker from printing, after a pool stopped at once
    by a second Ctrl-C, that it cleans up the pool's semaphores ("There appear to be 5
    leaked semaphore objects to clean up at shutdown"): it does clean them up, and the
    command has already said what it kept.  The tracker is a process of its own, started
    with this interpreter's warning options, so the filter goes there (before any pool).
    """
    if RESOURCE_TRACKER_NOISE not in sys.warnoptions:
        sys.warnoptions.append(RESOURCE_TRACKER_NOISE)


STOPPING = "stopping at the next step with the best plan so far and its gap"
"""What a first Ctrl-C during a solve does."""


@contextlib.contextmanager
def interruptible(steps: RunProgress, method: str, said: str = STOPPING):
    """Ctrl-C during a solve: the certified search stops at its next step with the best
    plan so far (a second Ctrl-C, or the paper's method, stops at once: nothing written).
    The same while the run folder is written (``said``: what the first Ctrl-C does).

    Yields the ``stop`` callable of :func:`sdc_cvx.planner.api.solve` (True once asked).
    """
    asked = threading.Event()

    def on_sigint(signum, frame):
        if asked.is_set() or method != "certified":
            raise KeyboardInterrupt
        asked.set()
        line = f"interrupted: {said} (Ctrl-C again to stop at once, writing nothing)"
        steps.say(line, show=False)
        # always answered, progress shown or not; by the descriptor, as a handler may run
        # while the interrupted code holds sys.stderr's lock (click.echo here hung a pool)
        with contextlib.suppress(OSError, ValueError, AttributeError):
            os.write(sys.stderr.fileno(), (line + "\n").encode())

    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:  # started to ignore Ctrl-C (a
        yield asked.is_set  # script's background job): it stays ignored, as for sweep
        return
    try:
        previous = signal.signal(signal.SIGINT, on_sigint)
    except ValueError:  # not the main thread: Ctrl-C keeps its usual meaning
        yield asked.is_set
        return
    try:
        yield asked.is_set
    finally:
        signal.signal(signal.SIGINT, previous)
