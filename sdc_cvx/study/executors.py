"""Where a study's scenarios run (a local process pool, a Dask cluster, any executor)
and the lock that keeps one sweep at a time per output folder."""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import ctypes
import multiprocessing
import os
import signal
from collections.abc import Iterator
from pathlib import Path

from ..errors import SweepError

_LOCK_NAME = ".sweep.lock"


@contextlib.contextmanager
def _executor(executor, scheduler, workers, pending: int) -> Iterator[cf.Executor]:
    if executor is not None:
        yield executor
        return
    if scheduler is not None:
        client, own = scheduler, False
        if isinstance(scheduler, str | os.PathLike):
            try:
                from distributed import Client
            except ImportError as err:
                raise SweepError(
                    "a Dask scheduler needs dask.distributed: pip install 'sdc_cvx[dask]'"
                ) from err
            client, own = _client(Client, os.fspath(scheduler)), True
        elif not hasattr(scheduler, "get_executor"):
            raise TypeError(
                f"scheduler must be an address or a distributed.Client, "
                f"got {type(scheduler).__name__}"
            )
        pool = client.get_executor(pure=False)
        try:
            yield pool
        except BaseException:
            pool.shutdown(wait=False)  # cancels what is still queued
            raise
        finally:
            if own:
                client.close()
        return
    size = max(1, min(workers or os.cpu_count() or 1, pending))
    pool = cf.ProcessPoolExecutor(
        max_workers=size,
        mp_context=_mp_context(),
        initializer=_init_worker,
        initargs=(os.getpid(),),
    )
    try:
        yield pool
    except BaseException as err:
        if not isinstance(err, Exception):  # Ctrl-C, exit: the running scenarios end too,
            _terminate(pool)  # or the interpreter's exit would wait for them to finish
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    else:
        pool.shutdown(wait=True)


def _terminate(pool: cf.ProcessPoolExecutor) -> None:
    """End the pool's worker processes now (what they were computing is lost: a resumed
    sweep runs those scenarios again), and the fork server they come from: stopped while
    it still started (its preload takes seconds on a loaded machine), it outlived the
    command, holding its stderr open, and a caller reading that to its end waited minutes.
    A later pool starts a new fork server."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        with contextlib.suppress(Exception):
            process.terminate()
    with contextlib.suppress(Exception):
        from multiprocessing import forkserver

        pid = forkserver._forkserver._forkserver_pid  # no public handle on it
        if pid is not None:
            os.kill(pid, signal.SIGKILL)


_THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


_OPENBLAS_SETTERS = (
    "openblas_set_num_threads",
    "scipy_openblas_set_num_threads",
    "openblas_set_num_threads64_",
    "scipy_openblas_set_num_threads64_",
)


_PR_SET_PDEATHSIG = 1  # linux/prctl.h
_WATCH_SECONDS = 0.5


def _init_worker(sweep_pid: int) -> None:
    """Initializer of the local pool's processes: die with the sweep, one BLAS thread."""

    _die_with(sweep_pid)
    _one_thread_per_worker()
    restore_malloc()
    # Ctrl-C is the sweep's to handle (it says how to resume); a worker ends with it
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _die_with(sweep_pid: int) -> None:
    """End this worker when the sweep's process dies, even by SIGKILL (no orphans computing
    results nobody will read).

    Two guards: on Linux the kernel sends SIGKILL when the worker's parent (the fork
    server) goes (``prctl(PR_SET_PDEATHSIG)``); everywhere a daemon thread checks every
    half second that the sweep's process is still running and ends the worker when it is
    not (``os._exit``).  The fork server alone is no guard: it exits when every holder of
    its "alive" pipe has closed it, and its workers hold it too.  A dead sweep that its
    own parent has not reaped yet (a zombie, as under a launcher that reads its output
    before waiting for it) still answers ``os.kill(pid, 0)``: on Linux its state in
    ``/proc`` says it is dead; otherwise its pool, fork server and resource tracker would
    live on, holding the launcher's pipes open.
    """
    import sys
    import threading
    import time

    if sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):
            pass

    def watch() -> None:
        while _process_running(sweep_pid):
            time.sleep(_WATCH_SECONDS)
        os._exit(1)

    threading.Thread(target=watch, name="sdc-sweep-watchdog", daemon=True).start()


def _process_running(pid: int) -> bool:
    """Whether process ``pid`` exists and has not ended: a zombie (ended, not yet reaped
    by its parent) is not running, although ``os.kill(pid, 0)`` still finds it."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            state = stat.read().rsplit(b")", 1)[1].split()[0]
    except FileNotFoundError:
        if os.path.exists("/proc/self/stat"):
            return False  # a /proc without it: gone
    except (OSError, IndexError):
        pass  # unreadable
    else:
        return state not in (b"Z", b"X")
    try:  # no /proc (not Linux): ask the kernel
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3  # glibc's mallopt parameters
_MALLOC_VARIABLES = ("MALLOC_TRIM_THRESHOLD_", "MALLOC_MMAP_THRESHOLD_")
_MALLOC_RESTORED = []


def restore_malloc() -> None:
    """Give this process back glibc's dynamic malloc thresholds where a Dask nanny (or the
    environment it left behind) fixed them.

    ``distributed`` starts its workers with ``MALLOC_TRIM_THRESHOLD_=65536`` (to hand
    freed memory back at once), and once it runs in a process the variable reaches every
    process started from it, a local pool's included.  Setting it fixes glibc's mmap
    threshold at 128 kB: every numpy temporary above that is then mapped and unmapped
    again, page faults and all, and the certified search runs 2-3 times slower (measured:
    a campaign 2.7 times slower with a LocalCluster started beside it, the low-thrust
    paper case 2 times slower with the variable set).  The thresholds the dynamic rule
    reaches (32 MB for mmap, twice that for trimming) are set instead, once per process.
    Best effort: nothing happens without glibc.
    """
    if _MALLOC_RESTORED or not any(name in os.environ for name in _MALLOC_VARIABLES):
        return
    _MALLOC_RESTORED.append(True)
    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(_M_MMAP_THRESHOLD, 32 * 2**20)
        libc.mallopt(_M_TRIM_THRESHOLD, 64 * 2**20)
    except (OSError, AttributeError):
        pass


def _one_thread_per_worker() -> None:
    """Initializer of the local pool's processes: one BLAS thread, like a Dask worker.

    Parallel scenarios should not compete for cores, and the BLAS thread count changes
    the last digits of the re-optimisation (about 1e-9 relative): with one thread
    everywhere, the local pool and a Dask cluster (whose nanny sets these variables)
    give the same numbers.  The variables cover libraries loaded later; the OpenBLAS
    copies already loaded (numpy's and scipy's, found in /proc/self/maps) are told
    directly.  Best effort: elsewhere than Linux only the variables are set.
    """
    for name in _THREAD_VARIABLES:
        os.environ[name] = "1"
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            libraries = {line.split()[-1] for line in maps if "openblas" in line.lower()}
    except OSError:
        return
    for library in sorted(libraries):
        try:
            handle = ctypes.CDLL(library)
        except OSError:
            continue
        for setter in _OPENBLAS_SETTERS:
            function = getattr(handle, setter, None)
            if function is not None:
                function(1)
                break


def _mp_context():
    """Fork server with sdc_cvx preloaded: fast workers, and no fork of a threaded process
    (a Dask client, a notebook kernel); spawn where there is no fork server."""
    if "forkserver" in multiprocessing.get_all_start_methods():
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(["sdc_cvx.study.worker"])
        return context
    return multiprocessing.get_context("spawn")


@contextlib.contextmanager
def _locked(out: Path) -> Iterator[None]:
    """One sweep at a time per folder (a POSIX record lock, released if the process dies)."""
    try:
        import fcntl
    except ImportError:  # no fcntl (Windows): no lock
        yield
        return
    handle = open(out / _LOCK_NAME, "a+b")  # noqa: SIM115 (held for the whole sweep)
    try:
        try:
            fcntl.lockf(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            raise SweepError(f"another sweep is writing to {out}") from None
        try:
            yield
        finally:  # finished, refused (a --resume of another study) or interrupted: no lock file
            (out / _LOCK_NAME).unlink(missing_ok=True)
    finally:
        handle.close()


SCHEDULER_TIMEOUT_S = 10
"""How long a Dask scheduler may take to answer a connection [s]."""


def _client(client_class, address: str):
    """A ``distributed.Client`` of ``address``, or a SweepError saying why not (a bad or
    unreachable address raises many kinds of error, none of them a user's to read)."""
    try:
        return client_class(address, timeout=f"{SCHEDULER_TIMEOUT_S}s")
    except Exception as err:  # OSError, TimeoutError, ValueError, even a MemoryError
        raise SweepError(f"cannot use the Dask scheduler {address!r}: {type(err).__name__}: "
                         f"{err}; check its address (tcp://HOST:PORT) and that it "
                         "runs") from None  # fmt: skip


def scheduler_problem(scheduler) -> str | None:
    """Why ``scheduler`` (an address) cannot be used, or None: checked once, before any
    work, so that a bad address costs no solve and leaves no half-made folder."""
    if not isinstance(scheduler, str | os.PathLike):
        return None
    try:
        from distributed import Client
    except ImportError:
        return "a Dask scheduler needs dask.distributed: pip install 'sdc_cvx[dask]'"
    try:
        _client(Client, os.fspath(scheduler)).close()
    except SweepError as err:
        return str(err)
    return None


def open_executor(executor=None, scheduler=None, workers: int | None = None,
                  pending: int = 1):  # fmt: skip
    """Where independent tasks run, as a context manager yielding a ``concurrent.futures``
    executor: ``executor`` itself if given, a Dask cluster's (``scheduler``: an address
    or a ``distributed.Client``), else a local process pool of ``workers`` processes (at
    most ``pending``) whose workers die with this process.  Sweeps and a campaign's
    pricing problems (:mod:`sdc_cvx.campaign`) run on it."""
    return _executor(executor, scheduler, workers, pending)


def unguarded_call_site() -> str | None:
    """``"PATH, line N"`` of the script line that called into sdc_cvx from the top level
    of a script, outside ``if __name__ == "__main__":``; None otherwise.

    A local pool's worker processes import the script that started the work (as
    ``__mp_main__``): a call outside that guard would start the work again in each of
    them, and they die with a traceback each.  Found by reading the script: the calling
    line must lie inside such an ``if``.  A function, a notebook cell, an interactive
    session, ``python -c`` or ``python -m`` is never unguarded.
    """
    import ast
    import inspect

    frame = inspect.currentframe()
    while frame is not None:
        module = frame.f_globals.get("__name__")
        if frame.f_code.co_name == "<module>" and module in ("__main__", "__mp_main__"):
            break
        frame = frame.f_back
    if frame is None:
        return None  # not called from a script's top level (a function, the CLI)
    spec = frame.f_globals.get("__spec__")
    name = getattr(spec, "name", None) or ""
    if name == "__main__" or name.endswith(".__main__"):
        return None  # python -m package: workers do not import it again
    path, line = frame.f_code.co_filename, frame.f_lineno
    script = frame.f_globals.get("__file__")
    if script is not None and not os.path.isfile(script):  # a script piped in (<stdin>):
        return f"{path}, line {line}"  # workers would look for a file of that name, and die
    try:
        if script is None or not os.path.samefile(script, path):
            return None  # a notebook cell, an interactive session: nothing to import
    except OSError:
        return None
    try:
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, ValueError):
        return None  # no script to read (python -c, an interactive session)

    def guard(node) -> bool:
        test = node.test
        return (
            isinstance(test, ast.Compare) and len(test.comparators) == 1
            and {type(test.left), type(test.comparators[0])} == {ast.Name, ast.Constant}
            and {getattr(test.left, "id", None), getattr(test.comparators[0], "id", None)}
            >= {"__name__"}
            and "__main__" in {getattr(test.left, "value", None),
                               getattr(test.comparators[0], "value", None)}
        )  # fmt: skip

    for node in ast.walk(tree):
        if isinstance(node, ast.If) and guard(node):
            end = max(getattr(n, "end_lineno", n.lineno) for n in node.body)
            if node.body[0].lineno <= line <= end:
                return None
    return f"{path}, line {line}"
