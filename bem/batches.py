"""Rows of Fourier modes in batches on two threads: what the kernel sums share.

The kernels (:mod:`bem.spectral`) are sums over ``m`` of row sums over ``n``: each batch
of rows is evaluated and summed on its own, so only the batch's symbols are held, and two
threads share the batches (NumPy's transforms and matrix products release the GIL).
"""

from __future__ import annotations

import functools

import numpy as np

from .threads import cores

__all__ = ["CHUNK", "ROWS", "in_batches"]

CHUNK = 256  # rows of m per batch of complex symbols
#: rows of m per batch where a batch's arrays should stay in cache: the Gaussians' row sums
#: and the exact symbols of the modes that see the base (:mod:`bem.spectral`). At 256 rows
#: the first C_ww of section 11 at 41 x 41 took 63 ms against 47, the nine kernels of
#: section 10.2's thin layer (every mode sees the base) 0.30 s against 0.18
ROWS = 64


@functools.cache
def _keep_heap() -> None:
    """GNU libc's ``malloc`` gives a freed block above its ``mmap`` threshold (128 kB at
    first) back to the system, and raises that threshold, and twice it the heap's trim
    threshold, when such a block (up to 32 MB) is freed. Until then every batch's arrays
    are fresh pages: the first kernels of a process at 257 x 257 nodes took 113 000 page
    faults (0.46 s, 0.23 s the next time); with one 31 MB block freed first (allocated, not
    written) 11 000 (0.26 s). What the first kernels' last arrays do anyway, done at the
    start; elsewhere a ``malloc`` and ``free``."""
    np.empty(31 << 20, dtype=np.uint8)


def in_batches(rows: int, work, chunk: int = CHUNK) -> None:
    """``work(start)`` for every batch of ``chunk`` rows (``start = 0, chunk, ...`` below
    ``rows``), on two threads, or on the caller's alone where the process may use one core
    (:func:`bem.threads.cores`) or there is one batch."""
    _keep_heap()
    starts = range(0, rows, chunk)
    if cores() == 1 or len(starts) == 1:
        for start in starts:
            work(start)
        return
    from concurrent.futures import ThreadPoolExecutor  # 4 ms of a start-up, with logging

    with ThreadPoolExecutor(max_workers=2) as pool:
        list(pool.map(work, starts))
