"""Keeping the backends' own output off stdout (``python -m sdc_cvx run --json``).

Some backends write to the process's file descriptor 1 from C, whatever their options:
HiGHS 1.16 prints a copyright banner when a solver object is built.  Stdout belongs to
the caller (``--json`` promises JSON only there), so :func:`backend_stdout` points
descriptor 1 elsewhere (the null device, or stderr when the log is asked for with
``verbose``) while a backend runs.
"""

from __future__ import annotations

import contextlib
import ctypes
import os
import sys
import threading

_LOCK = threading.Lock()
_STATE = {"depth": 0, "saved": None}
"""How many backend runs are under way in this process, and the real descriptor 1."""


def _flush_c_stdio() -> None:
    """Flush the C library's stdio buffers (a banner may sit there, not yet written)."""
    with contextlib.suppress(OSError, AttributeError):  # no C library: nothing to flush
        ctypes.CDLL(None).fflush(None)


@contextlib.contextmanager
def backend_stdout(verbose: bool = False):
    """Redirect file descriptor 1 while a backend runs.

    Parameters
    ----------
    verbose : bool
        True: the backend's output goes to stderr (the log was asked for); False: to
        the null device.  Either way nothing reaches stdout.

    Notes
    -----
    Process-wide (a file descriptor), and counted: the first of several threads solving
    at once redirects (its ``verbose`` applies to all), the last one restores, so
    parallel solves are not serialised (what another thread writes to descriptor 1
    meanwhile is redirected too).  Python's ``sys.stdout`` is flushed before and
    the C library's buffers before the descriptor is restored, so nothing written
    outside the block is lost or moved and nothing written inside leaks after it.
    """
    with _LOCK:
        if _STATE["depth"] == 0:
            try:
                saved = os.dup(1)
            except OSError:  # no descriptor 1 (a closed stdout): nothing to protect
                saved = None
            if saved is not None:
                with contextlib.suppress(Exception):
                    sys.stdout.flush()
                _flush_c_stdio()
                if verbose:
                    os.dup2(2, 1)
                else:
                    devnull = os.open(os.devnull, os.O_WRONLY)
                    try:
                        os.dup2(devnull, 1)
                    finally:
                        os.close(devnull)
            _STATE["saved"] = saved
        _STATE["depth"] += 1
    try:
        yield
    finally:
        with _LOCK:
            _STATE["depth"] -= 1
            if _STATE["depth"] == 0 and _STATE["saved"] is not None:
                _flush_c_stdio()
                os.dup2(_STATE["saved"], 1)
                os.close(_STATE["saved"])
                _STATE["saved"] = None
