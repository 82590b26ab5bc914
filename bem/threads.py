"""One BLAS thread for the BEM's work, unless the user chose a thread count.

The BEM's BLAS calls are many and small (the line preconditioner's Toeplitz solves, the
dense LU of coarse grids and short contact sets, the kernels' mode sums in blocks): a
multithreaded BLAS spends more on waking and synchronising its threads than it gains,
and on a machine whose cores are busy its spinning threads compete with the work.
Measured on 2 cores (other work running): ``bem solve`` of the elastic paraboloid with
friction at 0.1 mm (121 x 121 nodes) takes 1.9 s wall with one thread against 3.1 s with
OpenBLAS's default two, the process computing the nine kernels at 0.1 mm 2.1 s against
6.2 s (medians of paired runs). The limit is set at run time with threadpoolctl, which reaches the BLAS
libraries already loaded (numpy's and scipy's); environment variables act only before a
library loads. A user who sets ``OPENBLAS_NUM_THREADS``, ``MKL_NUM_THREADS`` or
``OMP_NUM_THREADS`` keeps the count they chose.

The BEM's own threads (the kernels' two batch threads, the transforms of large grids, the
frictional solver's second thread) number at most :func:`cores`: the cores the process
may run on (its CPU affinity: a job pinned to one core, or a container's share), and no
more than ``OMP_NUM_THREADS`` when it is set, the usual way to give a job its threads.
"""

from __future__ import annotations

import functools
import os
import sys
from contextlib import nullcontext

__all__ = ["THREAD_VARIABLES", "blas_threads_chosen", "one_blas_thread", "one_blas_thread_from_start",
           "with_one_blas_thread", "cores"]

#: environment variables by which a user chooses the BLAS thread count themselves
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS")


def blas_threads_chosen() -> bool:
    """Whether the environment sets a BLAS thread count (any of :data:`THREAD_VARIABLES`)."""
    return any(os.environ.get(name, "").strip() for name in THREAD_VARIABLES)


def one_blas_thread():
    """A context in which the loaded BLAS libraries run one thread (restored on exit), or
    changes nothing when the user chose a count (:func:`blas_threads_chosen`)."""
    if blas_threads_chosen():
        return nullcontext()
    from threadpoolctl import threadpool_limits
    return threadpool_limits(limits=1, user_api="blas")


def one_blas_thread_from_start() -> None:
    """For a process of its own (the ``bem`` command): one BLAS thread from the BLAS
    libraries' first load, set by the variables they read then (``OPENBLAS_NUM_THREADS``,
    ``MKL_NUM_THREADS``), unless the user chose a count (:func:`blas_threads_chosen`) or
    numpy is already loaded. :func:`one_blas_thread` reaches the same limit at run time,
    but OpenBLAS has by then started a thread per core, which spins while numpy loads:
    ``bem solve`` of the elastic paraboloid with friction at 0.2 mm (61 x 61 nodes) took
    0.10 s more CPU and 0.01 s more wall on 2 cores that way (paired runs)."""
    if blas_threads_chosen() or "numpy" in sys.modules:
        return
    for name in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[name] = "1"


def with_one_blas_thread(function):
    """``function`` run inside :func:`one_blas_thread`."""
    @functools.wraps(function)
    def limited(*args, **kwargs):
        with one_blas_thread():
            return function(*args, **kwargs)
    return limited


def cores() -> int:
    """How many threads the BEM may run at once (>= 1): the cores of the process's CPU
    affinity (``os.sched_getaffinity``; ``os.cpu_count()`` where the system has none), at
    most ``OMP_NUM_THREADS`` when that is a positive integer."""
    try:
        n = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        n = os.cpu_count() or 1
    limit = os.environ.get("OMP_NUM_THREADS", "").strip()
    if limit.isdigit() and int(limit) > 0:
        n = min(n, int(limit))
    return max(1, n)
