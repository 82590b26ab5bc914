"""The cases side by side on Dask: ``verify --workers N`` (a local cluster of N
single-threaded worker processes) and ``verify --scheduler ADDRESS`` (an existing one).

Each case is one task. It goes to a worker pickled (a method loaded from a ``.py`` file
goes by value, so the worker needs no copy of that file), runs there through
:func:`verification.runner.run_case`, and its :class:`~verification.results.CaseResult`
comes back as data: the report, figures included, is drawn in verify's process, the
cases in their listed order whatever order they finish in. A case that raises is that
case's failure, as in a serial run; so is a case whose worker dies (out of memory, say):
the task is not retried on the local cluster. A kind that runs on Dask itself
(``USES_DASK``: the paper's sweeps) runs in verify's process and submits its work to the
same cluster.

Progress: a line when a case starts on a worker (naming the worker), the case's own
progress lines forwarded from the worker as they come (through Dask's event log, so the
lines of cases running together interleave), and its verdict when it ends.
"""

from __future__ import annotations

import argparse
import queue
import signal
import sys
import threading
import time
import uuid
from typing import Callable

# numpy, the solvers and Dask are imported inside the functions: ``verify --help`` answers
# without loading them.

__all__ = ["workers_count", "open_client", "close_client", "run_cases"]

#: seconds the probe of ``--scheduler`` waits for the scheduler's answer
TIMEOUT = 10.0


def workers_count(text: str) -> int:
    """``--workers N``: a whole number >= 1 (an ``argparse`` type: a bad value is a usage
    error naming the flag, exit 2)."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a whole number of worker processes >= 1, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1 worker process, got {n}")
    return n


def open_client(workers: int | None = None, scheduler: str | None = None):
    """A ``distributed.Client`` to ``scheduler`` (``tcp://HOST:PORT`` or a scheduler file
    ``*.json``, probed within :data:`TIMEOUT` seconds), else to a new local cluster of
    ``workers`` processes, one thread each, BLAS at one thread (Dask sets
    ``OPENBLAS_NUM_THREADS``, ``MKL_NUM_THREADS`` and ``OMP_NUM_THREADS`` to 1 in a
    worker it starts; a count set in verify's environment is kept), no memory limit (a
    serial run has none) and no retry of a task whose worker died: that case fails,
    saying so.

    Raises
    ------
    sweeps.spec.SweepError
        The scheduler file is missing or names no address, or no Dask scheduler answers
        (:func:`sweeps.cluster.connect`); the message starts with ``--scheduler``.
    """
    import dask
    import distributed  # noqa: F401 (its defaults in dask.config before the change below)
    from sweeps.cluster import connect

    if scheduler:
        return connect(scheduler, timeout=TIMEOUT)
    # one task at a time on a worker: a worker that dies takes no waiting task with it
    with dask.config.set({"distributed.scheduler.worker-saturation": 1.0}):
        return connect(workers=workers, memory_limit=0, preload=[__name__], scheduler_kwargs={"allowed_failures": 0})


def dask_setup(worker) -> None:
    """The preload of a local worker process (Dask calls it as the worker starts, and
    again when a worker is restarted): Ctrl-C in a terminal reaches the whole process
    group, and verify's process answers it by closing the cluster, so a worker ignores
    it instead of dying with a traceback of its own."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


def close_client(client) -> None:
    """Close ``client``, and its local cluster if it has one (never a remote scheduler)."""
    cluster = getattr(client, "cluster", None)
    try:
        client.close()
    finally:
        if cluster is not None:
            cluster.close()


def _payload(case: dict) -> bytes:
    """``case`` pickled for a worker; the modules of methods loaded from files by value."""
    import cloudpickle

    for method in case.get("_methods", {}).values():
        func = getattr(method.solve, "func", None)  # a guarded plugin's own function
        module = sys.modules.get(getattr(func, "__module__", None) or "")
        if module is not None and module.__name__.startswith("verify_method_"):  # methods._import_file
            cloudpickle.register_pickle_by_value(module)
    return cloudpickle.dumps(case)


def _on_worker(index: int, payload: bytes, quick: bool, topic: str):
    """One case on a worker (its :class:`CaseResult`): its start and progress lines sent to
    ``topic``."""
    import cloudpickle
    from distributed import get_worker

    from .runner import run_case

    worker = get_worker()
    worker.log_event(topic, ["start", index, worker.address])
    case = cloudpickle.loads(payload)
    return run_case(case, lambda line: worker.log_event(topic, ["line", index, str(line)]), quick)


def run_cases(cases: list[dict], client, quick: bool, progress: Callable[[str], None],
              done: Callable[[int, object], None]) -> list:
    """Run ``cases`` on ``client``'s cluster; return their results in the order of ``cases``.

    ``progress(line)`` gets the start and progress lines, ``done(index, result)`` each
    result as it arrives. Cases are submitted in their order, no more at a time than the
    cluster has threads (a worker that dies takes only its own case with it). Ctrl-C or
    SIGTERM (an exception in the calling thread) cancels the cases not finished and is
    raised again; the caller closes the client."""
    from .kinds import KINDS
    from .results import CaseResult
    from .runner import failed_result, run_case

    n, topic = len(cases), f"verify-progress-{uuid.uuid4().hex}"
    arrived: queue.Queue = queue.Queue()
    started: dict[int, float] = {}

    def event(ev):  # in the client's event loop
        kind, index, *rest = ev[1]
        if kind == "start":
            started[index] = time.perf_counter()
            progress(f"[{index + 1}/{n}] {cases[index]['name']}: {cases[index]['title']} (on {rest[0]})")
        else:
            progress(rest[0])

    def local(indices):  # the kinds that run on Dask themselves, one after another
        for i in indices:
            progress(f"[{i + 1}/{n}] {cases[i]['name']}: {cases[i]['title']} (here, on the cluster)")
            t0 = time.perf_counter()
            try:
                arrived.put((i, run_case(cases[i], progress, quick, client=client)))
            except BaseException as exc:  # a MemoryError: that case's failure
                arrived.put((i, failed_result(cases[i], f"{type(exc).__name__}: {exc}", time.perf_counter() - t0)))

    here = [i for i, c in enumerate(cases) if getattr(KINDS[c["kind"]], "USES_DASK", False)]
    waiting = [i for i in range(n) if i not in here]
    futures, running = {}, set()

    def submit() -> None:  # as many as the cluster has free threads (workers may join later)
        threads = sum(client.nthreads().values())
        if not threads and not futures:
            progress("verify: the scheduler has no worker yet; the cases wait for one")
        free = max(1, threads) - len(running)
        while waiting and free > 0:
            i, free = waiting.pop(0), free - 1
            future = client.submit(_on_worker, i, _payload(cases[i]), quick, topic, pure=False,
                                   key=f"verify-{cases[i]['name']}-{uuid.uuid4().hex[:8]}")
            futures[future] = i
            running.add(i)
            future.add_done_callback(lambda f: arrived.put((futures[f], f)))

    client.subscribe_topic(topic, event)
    try:
        submit()
        if here:
            threading.Thread(target=local, args=(here,), name="verify-local-cases", daemon=True).start()
        results, asked = {}, time.monotonic()
        while len(results) < n:
            try:
                i, item = arrived.get(timeout=0.2)  # a timeout: Ctrl-C and SIGTERM are seen at once
            except queue.Empty:
                if waiting and time.monotonic() - asked > 2.0:
                    submit()
                    asked = time.monotonic()
                continue
            running.discard(i)
            results[i] = item if isinstance(item, CaseResult) else _result(cases[i], item, started.get(i))
            done(i, results[i])
            submit()
        return [results[i] for i in range(n)]
    finally:
        try:
            client.cancel(list(futures), force=True)
            client.unsubscribe_topic(topic)
        except Exception:  # a client already closing
            pass


def _result(case: dict, future, t0: float | None):
    """The :class:`CaseResult` a finished future carries, or that case's failure."""
    from .runner import failed_result

    seconds = time.perf_counter() - t0 if t0 is not None else 0.0
    if future.status == "finished":
        try:
            return future.result()
        except Exception as exc:  # it could not be sent back (not picklable, a lost connection)
            return failed_result(case, f"its result did not come back from the worker: {type(exc).__name__}: {exc}",
                                 seconds)
    if future.status == "error":
        exc = future.exception()
        return failed_result(case, f"{type(exc).__name__} on the Dask worker: {exc}", seconds)
    return failed_result(case, f"its Dask task ended {future.status} (the scheduler or the worker went away)",
                         seconds)
