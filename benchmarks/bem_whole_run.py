"""Whole ``bem solve`` processes, as a user runs them: start-up, imports, the case file,
kernels, solve, energy figure and output, on the case timed against CONTACT.

The case: ``examples/elastic-paraboloid-creepage.toml`` (a rigid paraboloid rolling with
friction at the longitudinal creepage 0.01 on a thick elastic layer, 61 x 61 nodes at
0.2 mm), and the same at 0.1 mm (121 x 121) and 0.05 mm (241 x 241), the truncation
``Nt = L / 2a`` (``--spacing``). Each process runs ``bem solve CASE --set ... --json
--quiet``: with ``--no-error-estimate`` (the solve alone, what CONTACT computes) and as the
default (with the grid error's two coarse levels), alternated, ``--repeat`` times each
after one warm-up. The child gets the user's default environment: bytecode written and
reused (``PYTHONDONTWRITEBYTECODE`` removed) and no thread-count variables (``bem``
chooses one BLAS thread itself, :mod:`bem.threads`).

Printed per spacing (medians): the process's wall and CPU seconds (user + system, every
thread), the kernels, solve and energy figure as the process timed them, the rest of the
wall time (start-up, imports, reading the case, output), the default run's wall, the start-up
floor (``python -c "import numpy"``, the same alternation) and the answer (driving force
over ``mu P``, stick fraction). CONTACT's whole runs of the case are in BENCHMARKS.md,
"External references".

Run: ``python benchmarks/bem_whole_run.py [--spacing 0.2e-3 0.1e-3 0.05e-3] [--repeat 5]``;
``--markdown`` prints the summary table alone on stdout (the running report on stderr)
for ``benchmarks/collect.py``.
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

from _common import machine, markdown_mode, markdown_table, reporter

ROOT = Path(__file__).resolve().parents[1]
CASE = ROOT / "examples" / "elastic-paraboloid-creepage.toml"
PERIOD, MU, LOAD = 0.6, 0.2, 100.0  # the case file's period (m), mu and load (N)
BEM = [sys.executable, "-m", "bem.cli", "solve"]
FLOOR = [sys.executable, "-c", "import numpy"]
markdown = markdown_mode() if __name__ == "__main__" else False
say = reporter(markdown)


def user_environment() -> dict:
    """This process's environment as a user's shell would have it: bytecode cached, no
    thread counts set."""
    drop = {"PYTHONDONTWRITEBYTECODE", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"}
    return {k: v for k, v in os.environ.items() if k not in drop}


def timed_process(cmd: list) -> tuple[float, float, str]:
    """``cmd`` run to completion: (wall s, CPU s of the child, its stdout)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env=user_environment(), cwd=ROOT)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {done.returncode}:\n{done.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, done.stdout


def run(spacing: float, repeat: int) -> list:
    """One row of the summary: the medians at node spacing ``spacing`` (m)."""
    truncation = int(round(PERIOD / (2 * spacing)))
    sets = ["--set", f"grid.spacing={spacing!r}", "--set", f"grid.truncation={truncation}"]
    alone = BEM + [str(CASE), *sets, "--json", "--quiet", "--no-error-estimate"]
    default = BEM + [str(CASE), *sets, "--json", "--quiet"]
    for cmd in (alone, default, FLOOR):  # warm-up: bytecode written, files in the page cache
        timed_process(cmd)
    runs, defaults, floors = [], [], []
    for i in range(repeat):
        wall, cpu, out = timed_process(alone)
        runs.append((wall, cpu, json.loads(out)))
        defaults.append(timed_process(default)[0])
        floors.append(timed_process(FLOOR)[0])
        t = runs[-1][2]["timings_s"]
        say(f"{spacing * 1e3:g} mm, run {i + 1}: whole {wall:.3f} s (CPU {cpu:.3f} s), kernels {t['kernel_s']:.3f} s, "
            f"solve {t['solve_s']:.3f} s; default run {defaults[-1]:.3f} s; python + numpy {floors[-1]:.3f} s")
    med = statistics.median
    timing = {k: med(r[2]["timings_s"][k] for r in runs) for k in ("kernel_s", "solve_s", "energy_s")}
    wall = med(r[0] for r in runs)
    answer = runs[-1][2]
    nodes = int(round(2 * 6.0e-3 / spacing)) + 1
    return [f"{spacing * 1e3:g} mm, {nodes} x {nodes}, Nt = {truncation}", f"{wall:.2f}", f"{med(r[1] for r in runs):.2f}",
            f"{timing['kernel_s']:.3f}", f"{timing['solve_s']:.3f}", f"{timing['energy_s']:.4f}",
            f"{wall - sum(timing.values()):.2f}", f"{med(floors):.2f}", f"{med(defaults):.2f}",
            f"{answer['driving_force'] / (MU * LOAD):.4f}", f"{answer['stick_fraction']:.3f}"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, nargs="+", default=[0.2e-3, 0.1e-3, 0.05e-3],
                    help="node spacings (m); default 0.2, 0.1 and 0.05 mm")
    ap.add_argument("--repeat", type=int, default=5, help="runs of each command, alternated (default 5)")
    args = ap.parse_args()
    if args.repeat < 1 or any(not (0 < a <= 1e-3) for a in args.spacing):
        ap.error("--repeat must be >= 1 and every --spacing in (0, 1e-3] m")
    say(f"{machine()}; load average {os.getloadavg()[0]:.1f} at the start")
    rows = [run(a, args.repeat) for a in args.spacing]
    head = ["case", "whole run (s)", "whole run CPU (s)", "kernels (s)", "solve (s)", "energy figure (s)",
            "start-up, imports, input, output (s)", "python + numpy import (s)", "default run, with grid error (s)",
            "Fx / (mu P)", "stick fraction"]
    table = markdown_table(head, rows)
    print(table if markdown else "\nsummary (medians)\n" + table)


if __name__ == "__main__":
    main()
