"""The Dask client of a sweep (and of ``verify --workers``/``--scheduler``): a local
cluster, or an existing scheduler reached within a timeout whatever goes wrong.

Before a ``distributed.Client`` is made for ``--scheduler``, the address is probed: a
scheduler file must exist and name an address; the address must accept a connection,
complete Dask's handshake and answer an ``identity`` request as a ``Scheduler``, all
within ``timeout`` seconds (one deadline for the whole exchange, so a server that accepts
and says nothing, or sends bytes that are not Dask's, is an error naming the address, not
a hang).
"""

from __future__ import annotations

import asyncio
import json
import logging
import os
import threading
from pathlib import Path

from .spec import SweepError

__all__ = ["connect", "scheduler_address", "probe"]

_HINT = "start one with `dask scheduler` and `dask worker ADDRESS`, or leave out --scheduler"
#: Dask sets ``MALLOC_TRIM_THRESHOLD_`` in the worker processes it starts (to hand freed
#: memory back sooner); glibc then fixes its mmap threshold at 128 kB, so every array
#: above that is a fresh mmap, zeroed page by page. Measured on 2 loaded cores: the
#: ``rolling-limits`` verification case 6.1-6.8 s in such a process against 1.7-2.7 s
#: without the variable. A local cluster's workers are started without it (a value the
#: user's own environment sets is kept).
_WORKER_ENVIRON = {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}


def scheduler_address(scheduler: str) -> str:
    """The address of ``scheduler``: itself, or the ``address`` of a scheduler file ``*.json``.

    Raises
    ------
    SweepError
        A scheduler file that is missing, unreadable or names no address.
    """
    if not scheduler.endswith(".json"):
        return scheduler
    path = Path(scheduler)
    if not path.is_file():
        raise SweepError(f"--scheduler {scheduler}: no such scheduler file; {_HINT}")
    try:
        address = json.loads(path.read_text(encoding="utf-8")).get("address")
    except (OSError, ValueError, AttributeError) as exc:
        raise SweepError(f"--scheduler {scheduler}: not a Dask scheduler file ({type(exc).__name__}: {exc})") from None
    if not isinstance(address, str) or not address:
        raise SweepError(f"--scheduler {scheduler}: the scheduler file names no address (\"address\": {address!r})")
    return address


async def _identity(address: str, timeout: float) -> dict:
    from distributed.comm import connect as dask_connect

    comm = await dask_connect(address, timeout=timeout)
    try:
        await comm.write({"op": "identity"})
        return await comm.read()
    finally:
        comm.abort()


def probe(address: str, timeout: float, label: str | None = None) -> None:
    """Check that a Dask scheduler answers at ``address`` within ``timeout`` seconds.

    Raises
    ------
    SweepError
        Nothing listens, the connection or handshake does not finish in time, or the
        server answers with something that is not a Dask scheduler's identity.
    """
    label = label or address
    box = {}

    def ask():  # in a thread of its own: the caller may already run an event loop (a notebook)
        try:
            box["answer"] = asyncio.run(asyncio.wait_for(_identity(address, timeout), timeout))
        except BaseException as exc:  # handed to the caller
            box["error"] = exc

    thread = threading.Thread(target=ask, name="sweep-scheduler-probe", daemon=True)
    thread.start()
    thread.join(timeout + 5.0)  # wait_for ends it at the timeout; the margin is for a slow machine
    try:
        if thread.is_alive():
            raise TimeoutError
        if "error" in box:
            raise box["error"]
        answer = box["answer"]
    except (asyncio.TimeoutError, TimeoutError):
        raise SweepError(f"--scheduler {label}: no Dask scheduler answers at {address} within {timeout:g} s; "
                         f"{_HINT}") from None
    except Exception as exc:  # refused, unresolvable, or bytes that are not Dask's (of any error type)
        raise SweepError(f"--scheduler {label}: no Dask scheduler answers at {address} within {timeout:g} s "
                         f"({type(exc).__name__}: {str(exc)[:200]}); {_HINT}") from None
    if not isinstance(answer, dict) or answer.get("type") != "Scheduler":
        kind = answer.get("type") if isinstance(answer, dict) else type(answer).__name__
        raise SweepError(f"--scheduler {label}: the server at {address} answers, but is not a Dask scheduler "
                         f"(it says it is {kind!r})")


def connect(scheduler: str | None = None, workers: int | None = None, processes: bool = True,
            timeout: float = 10.0, **cluster_options):
    """A ``distributed.Client``: to ``scheduler`` (``tcp://host:port`` or a scheduler file
    ``*.json``), else to a new local cluster of ``workers`` (default: the machine's cores)
    single-threaded workers (processes, or threads with ``processes=False``).

    ``cluster_options``: more keywords of the local cluster (``distributed.LocalCluster``,
    for example ``memory_limit`` in bytes, 0 for none); not used with ``scheduler``.

    Raises
    ------
    SweepError
        The scheduler file is missing or names no address, or no Dask scheduler answers
        at the address within ``timeout`` seconds (:func:`probe`).
    """
    import dask
    from distributed import Client, LocalCluster

    if scheduler:
        if not timeout > 0:
            raise SweepError(f"--timeout must be > 0 s, got {timeout!r}")
        address = scheduler_address(scheduler)
        probe(address, timeout, scheduler)
        try:
            return Client(address, timeout=f"{timeout}s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise SweepError(f"--scheduler {scheduler}: no Dask scheduler answers at {address} within {timeout:g} s "
                             f"({type(exc).__name__}: {exc}); {_HINT}") from None
    n = workers or os.cpu_count() or 1
    with dask.config.set(_WORKER_ENVIRON):
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=processes, dashboard_address=":0",
                               silence_logs=logging.ERROR, **cluster_options)
    return Client(cluster)
