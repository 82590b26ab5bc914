"""Shared setup of the BEM benchmarks: the paper's section 11 layer and timing helpers."""

import platform
import resource
import time

from bem import Layer, ThreeParameterSolid

LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)


def machine() -> str:
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import os

    return f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}"


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def timed(fn, repeat=5):
    """(first call s, median of the following calls s, last result)."""
    t = time.perf_counter()
    out = fn()
    first = time.perf_counter() - t
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    times.sort()
    return first, times[len(times) // 2] if times else first, out
