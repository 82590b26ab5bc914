"""Shared setup of the benchmarks: the paper's section 11 layer, timing helpers and the
Markdown table each script prints with ``--markdown`` (read by ``benchmarks/collect.py``)."""

import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

#: CONTACT's case: a rigid paraboloid rolling with friction at a creepage on a thick
#: elastic layer (61 x 61 nodes at its own 0.2 mm)
PARABOLOID = Path(__file__).resolve().parents[1] / "examples" / "elastic-paraboloid-creepage.toml"


def __getattr__(name: str):
    """``LAYER``, the paper's section 11 layer, built on first use: a script that times other
    processes alone (``contact_reference.py``) then never loads numpy, and the peak memory
    it reads of its children (at least the parent's own at the fork) stays below theirs."""
    if name != "LAYER":
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    from bem import Layer, ThreeParameterSolid

    layer = globals()["LAYER"] = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)
    return layer


def machine() -> str:
    """The CPU model, core count and Python version, for the first line of a report."""
    cpu = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}"


def peak_rss_mb() -> float:
    """Peak resident memory of this process so far (MB)."""
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


def paraboloid_grid(spacing: float) -> list:
    """``--set`` arguments that put :data:`PARABOLOID` on nodes ``spacing`` (m) apart with
    the truncation ``Nt = L / 2a`` (``L`` the case file's period)."""
    period = tomllib.loads(PARABOLOID.read_text())["grid"]["period"]
    return ["--set", f"grid.spacing={spacing!r}", "--set", f"grid.truncation={round(period / (2 * spacing))}"]


def run_child(cmd: list, env: dict, cwd: Path, cpu: int | None = None) -> tuple[float, float, float, str]:
    """``cmd`` run to its end (on CPU ``cpu`` alone when given): its wall and CPU seconds
    (user + system, every thread), its peak resident memory (MiB; it reads at least the
    parent's own at the fork) and its standard output. Raises SystemExit with its
    standard error when it fails."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        pin = (lambda: os.sched_setaffinity(0, {cpu})) if cpu is not None else None
        t = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=cwd, env=env, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                preexec_fn=pin)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - t
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        if proc.returncode != 0:
            raise SystemExit(f"{' '.join(map(str, cmd))} exited {proc.returncode}:\n{err.read().decode()[-3000:]}")
        return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, out.read().decode()


def markdown_mode() -> bool:
    """True when ``--markdown`` is on the command line (and removed from it): the script
    then prints its results table alone on stdout and its running report on stderr."""
    if "--markdown" in sys.argv:
        sys.argv.remove("--markdown")
        return True
    return False


def reporter(markdown: bool):
    """``print`` for the running report: to stderr in Markdown mode, else to stdout."""
    def say(*args, **kwargs):
        kwargs.setdefault("flush", True)
        print(*args, **kwargs, file=sys.stderr if markdown else sys.stdout)
    return say


def markdown_table(headers, rows) -> str:
    """A Markdown table: ``headers`` (units in the heads) and one row per case."""
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)
