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
wall time (start-up, imports, reading the case, output), and of that rest three floors
timed in processes of their own in the same alternation: Python's start (``python -c
pass``), numpy's import on top, and our modules' import on top of that (the ``bem`` and
``casefile`` modules the run loaded; the collector paused and one BLAS thread, as ``bem``
has them), with the time Python spent building their dataclasses (timed inside
``dataclasses``'s class builder, where this Python has the one of 3.11-3.13); then the
default run's wall and the answer (driving force over ``mu P``, stick fraction).
CONTACT's whole runs of the case: ``benchmarks/contact_reference.py``.

Run: ``python benchmarks/bem_whole_run.py [--spacing 0.2e-3 0.1e-3 0.05e-3] [--repeat 5]``;
``--markdown`` prints the summary table alone on stdout (the running report on stderr)
for ``benchmarks/collect.py``.
"""

import argparse
import json
import os
import statistics
import sys
from pathlib import Path

from _common import PARABOLOID as CASE, machine, markdown_mode, markdown_table, paraboloid_grid, reporter, run_child

ROOT = Path(__file__).resolve().parents[1]
BEM = [sys.executable, "-m", "bem.cli", "solve"]
START = [sys.executable, "-c", "pass"]
#: numpy loaded as ``bem`` loads it: one BLAS thread from the start (:mod:`bem.threads`)
ONE_THREAD = 'import os; os.environ.update(OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")\n'
NUMPY = [sys.executable, "-c", ONE_THREAD + "import gc; gc.disable(); import numpy"]
#: a child that imports numpy then ``sys.argv[1:]`` and prints the seconds spent in the
#: dataclass builder (``nan`` where this Python has no ``dataclasses._process_class``)
IMPORTS = """import gc; gc.disable()
import dataclasses, importlib, sys, time
spent, build = [0.0], getattr(dataclasses, "_process_class", None)
if build:
    def timed(*args, **kwargs):
        t = time.perf_counter()
        try:
            return build(*args, **kwargs)
        finally:
            spent[0] += time.perf_counter() - t
    dataclasses._process_class = timed
import numpy
for name in sys.argv[1:]:
    importlib.import_module(name)
print(spent[0] if build else float("nan"))
"""
#: a child that runs ``bem solve`` in-process on ``sys.argv[1:]`` and prints the ``bem``
#: and ``casefile`` modules it loaded
LOADED = """import contextlib, io, sys
from bem.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    main(sys.argv[1:])
print(" ".join(sorted(m for m in sys.modules if m.split(".")[0] in ("bem", "casefile"))))
"""
markdown = markdown_mode() if __name__ == "__main__" else False
say = reporter(markdown)


def user_environment() -> dict:
    """This process's environment as a user's shell would have it: bytecode cached, no
    thread counts set."""
    drop = {"PYTHONDONTWRITEBYTECODE", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"}
    return {k: v for k, v in os.environ.items() if k not in drop}


def timed_process(cmd: list) -> tuple[float, float, str]:
    """``cmd`` run to completion in the user's environment: (wall s, CPU s, its stdout)."""
    wall, cpu, _, out = run_child(cmd, user_environment(), ROOT)
    return wall, cpu, out


def run(spacing: float, repeat: int) -> list:
    """One row of the summary: the medians at node spacing ``spacing`` (m)."""
    sets = paraboloid_grid(spacing)
    alone = BEM + [str(CASE), *sets, "--json", "--quiet", "--no-error-estimate"]
    default = BEM + [str(CASE), *sets, "--json", "--quiet"]
    modules = timed_process([sys.executable, "-c", LOADED, "solve", str(CASE), *sets, "--quiet",
                             "--no-error-estimate"])[2].split()
    imports = [sys.executable, "-c", ONE_THREAD + IMPORTS, *modules]
    for cmd in (alone, default, START, NUMPY, imports):  # warm-up: bytecode written, files in the page cache
        timed_process(cmd)
    runs, defaults, starts, numpys, ours, classes = [], [], [], [], [], []
    for i in range(repeat):
        wall, cpu, out = timed_process(alone)
        runs.append((wall, cpu, json.loads(out)))
        defaults.append(timed_process(default)[0])
        starts.append(timed_process(START)[0])
        numpys.append(timed_process(NUMPY)[0])
        wall_ours, _, spent = timed_process(imports)
        ours.append(wall_ours)
        classes.append(float(spent))
        t = runs[-1][2]["timings_s"]
        say(f"{spacing * 1e3:g} mm, run {i + 1}: whole {wall:.3f} s (CPU {cpu:.3f} s), kernels {t['kernel_s']:.3f} s, "
            f"solve {t['solve_s']:.3f} s; default run {defaults[-1]:.3f} s; python {starts[-1]:.3f} s, + numpy "
            f"{numpys[-1]:.3f} s, + our {len(modules)} modules {ours[-1]:.3f} s (dataclasses {classes[-1]:.3f} s)")
    med = statistics.median
    timing = {k: med(r[2]["timings_s"][k] for r in runs) for k in ("kernel_s", "solve_s", "energy_s")}
    wall = med(r[0] for r in runs)
    answer = runs[-1][2]
    (nodes, _), (truncation, _) = answer["grid"]["nodes"], answer["grid"]["truncation"]
    return [f"{spacing * 1e3:g} mm, {nodes} x {nodes}, Nt = {truncation}", f"{wall:.3f}",
            f"{med(r[1] for r in runs):.3f}",
            f"{timing['kernel_s']:.3f}", f"{timing['solve_s']:.3f}", f"{timing['energy_s']:.4f}",
            f"{wall - sum(timing.values()):.3f}", f"{med(starts):.3f}", f"{med(numpys) - med(starts):.3f}",
            f"{med(ours) - med(numpys):.3f} ({med(classes):.3f})", f"{med(defaults):.2f}",
            f"{answer['driving_force'] / (answer['mu'] * answer['load']):.4f}", f"{answer['stick_fraction']:.3f}"]


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
            "start-up, imports, input, output (s)", "of it: Python's start (s)", "numpy's import (s)",
            "our modules' import (s) (building their dataclasses)", "default run, with grid error (s)",
            "Fx / (mu P)", "stick fraction"]
    table = markdown_table(head, rows)
    print(table if markdown else "\nsummary (medians)\n" + table)


if __name__ == "__main__":
    main()
