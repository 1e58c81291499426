"""Where a campaign's runs execute: a local process pool, or a Dask cluster.

A run is a :class:`Job` (picklable: the file, its digest, the setting) executed by
:func:`run_job` in a worker, which compiles the mission once (at its first run; a forked pool
inherits the campaign's compiled mission) and then only plans and runs each setting.

**Failures.** A run whose code raises (a crash: an internal error, never a mission outcome)
and a run whose worker dies (the pool breaks, or Dask reports the worker lost) come back as a
``crashed`` record; the campaign retries it once, then records it ``crashed`` — the other runs
are never lost. A broken pool is replaced.

**No process left behind.** A pool worker dies with the campaign: on Linux it asks the kernel
for ``SIGKILL`` when its parent dies (``prctl(PR_SET_PDEATHSIG)``, so even a ``SIGKILL`` of
the campaign ends its workers); elsewhere a thread of the worker watches its parent and ends
the worker when the parent is gone.
"""

from __future__ import annotations

import concurrent.futures as cf
import gc
import multiprocessing
import os
import signal
import sys
import threading
import time
import traceback
from dataclasses import dataclass
from typing import Any, Iterable

from orccad_app.campaign.adapter import CRASHED, RunRecord, compiled_for, execute
from orccad_app.campaign.setting import RunSetting
from orccad_app.diagnostics import OrccadError

__all__ = ["Job", "run_job", "crashed", "PoolBackend", "DaskBackend", "make_backend"]


@dataclass(frozen=True)
class Job:
    """One run to execute (see the module docstring)."""

    file: str
    mission: str
    digest: str
    setting: RunSetting
    signals: tuple[str, ...] = ()
    checks: tuple = ()
    attempt: int = 1


def crashed(job: Job, error: str) -> RunRecord:
    """The record of a run that could not complete (``error``: what happened)."""
    return RunRecord(job.setting, CRASHED, error, CRASHED, 0.0, 0.0, attempts=job.attempt,
                     error=error)


def run_job(job: Job) -> RunRecord:
    """Execute ``job`` in this process (a worker); a crash becomes a ``crashed`` record."""
    try:
        compiled = compiled_for(job.file, job.mission, job.digest)
        record = execute(compiled, job.setting, job.signals, job.checks)
    except OrccadError as error:
        return crashed(job, error.message)
    except Exception as error:  # noqa: BLE001 - a crash of the run's code, recorded
        last = traceback.format_exception_only(type(error), error)[-1].strip()
        return crashed(job, f"internal error: {last}")
    finally:
        _collect()
    record.attempts = job.attempt
    return record


_FROZEN = False


def _collect() -> None:
    """Free what the run left behind, so that a worker's memory stays flat over thousands of
    runs. A run's objects form reference cycles (the executive, its observers and plants)
    that hold MuJoCo's models and data in C memory, which Python's collector sees only as
    small objects: left to the automatic collector, a worker grew by some 50 kB per run.
    After its first run a worker *freezes* what it has built so far (modules, the compiled
    mission, caches: ``gc.freeze``), so the full collection after each run only looks at the
    run's own objects (about 1 ms instead of 200 ms)."""
    global _FROZEN
    gc.collect()
    if not _FROZEN:
        gc.freeze()
        _FROZEN = True


def _die_with(parent: int) -> None:
    """Pool initializer: end this worker when the process ``parent`` is gone; ``SIGTERM`` (the
    parent's ``terminate`` of an interrupted campaign) ends it at once, whatever handler the
    parent had installed when it forked."""
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if sys.platform.startswith("linux"):
        import ctypes

        try:
            libc = ctypes.CDLL(None, use_errno=True)
            pr_set_pdeathsig = 1
            if libc.prctl(pr_set_pdeathsig, int(signal.SIGKILL), 0, 0, 0) == 0:
                if os.getppid() != parent:  # the parent died before the request
                    os._exit(1)
                return
        except (OSError, AttributeError):
            pass

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="orccad-parent-watch", daemon=True).start()


class PoolBackend:
    """A local process pool of ``workers`` processes (forked: they inherit the compiled
    mission)."""

    name = "pool"

    def __init__(self, workers: int) -> None:
        self.workers = workers
        self._pool = self._new()

    def _new(self) -> cf.ProcessPoolExecutor:
        method = "fork" if "fork" in multiprocessing.get_all_start_methods() else None
        context = multiprocessing.get_context(method)
        return cf.ProcessPoolExecutor(self.workers, mp_context=context, initializer=_die_with,
                                      initargs=(os.getpid(),))

    def submit(self, job: Job) -> Any:
        try:
            return self._pool.submit(run_job, job)
        except cf.process.BrokenProcessPool:
            self.restart()
            return self._pool.submit(run_job, job)

    def wait(self, futures: Iterable[Any]) -> set[Any]:
        done, _ = cf.wait(list(futures), return_when=cf.FIRST_COMPLETED)
        return done

    def result(self, future: Any, job: Job) -> RunRecord:
        try:
            return future.result()
        except cf.process.BrokenProcessPool:
            return crashed(job, "worker died (process pool broken)")
        except Exception as error:  # noqa: BLE001 - e.g. an unpicklable result
            return crashed(job, f"worker error: {error}")

    def restart(self) -> None:
        """Replace a broken pool (its workers are gone)."""
        self._pool.shutdown(wait=False, cancel_futures=True)
        self._pool = self._new()

    @property
    def broken(self) -> bool:
        return bool(getattr(self._pool, "_broken", False))

    def worker_pids(self) -> list[int]:
        """The workers' process ids (tests kill one)."""
        return [p.pid for p in (getattr(self._pool, "_processes", None) or {}).values()]

    def close(self, cancel: bool = False) -> None:
        if cancel:
            for process in (getattr(self._pool, "_processes", None) or {}).values():
                process.terminate()  # an interrupted campaign: do not wait for their runs
        self._pool.shutdown(wait=not cancel, cancel_futures=True)


class DaskBackend:
    """A Dask cluster (``tcp://HOST:8786``) or a ``distributed.Client`` given directly."""

    name = "dask"

    def __init__(self, address: Any) -> None:
        try:
            from distributed import Client
        except ImportError:
            raise OrccadError("--cluster needs Dask: pip install 'orccad[cluster]'") from None
        if isinstance(address, str):
            try:
                self.client = Client(address, timeout="10s")
            except (OSError, TimeoutError) as error:
                raise OrccadError(f"--cluster {address}: cannot connect ({error})") from None
            self._own = True
        else:
            self.client, self._own = address, False
        self.workers = max(1, len(self.client.scheduler_info().get("workers", {})))

    def submit(self, job: Job) -> Any:
        return self.client.submit(run_job, job, pure=False)

    def wait(self, futures: Iterable[Any]) -> set[Any]:
        from distributed import wait

        done, _ = wait(list(futures), return_when="FIRST_COMPLETED")
        return set(done)

    def result(self, future: Any, job: Job) -> RunRecord:
        try:
            return future.result()
        except Exception as error:  # noqa: BLE001 - KilledWorker, lost connection
            return crashed(job, f"worker died ({type(error).__name__})")

    broken = False

    def restart(self) -> None:
        """Dask replaces lost workers itself."""

    def close(self, cancel: bool = False) -> None:
        if self._own:
            self.client.close()


def make_backend(workers: int | None, cluster: Any,
                 runs: int | None = None) -> PoolBackend | DaskBackend:
    """The Dask backend for ``cluster``, else a pool of ``workers`` (default: the cores),
    never more than the ``runs`` it will make (each worker is a forked interpreter: a
    ``--workers 256`` campaign of 3 runs starts 3)."""
    if cluster is not None:
        return DaskBackend(cluster)
    count = workers or os.cpu_count() or 1
    return PoolBackend(max(1, min(count, runs)) if runs is not None else count)
