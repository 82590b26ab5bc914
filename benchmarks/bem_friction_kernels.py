"""The nine influence kernels of frictional rolling (issue 11): time and peak memory, and
with ``--old REV`` the same kernels by the ``bem.spectral`` of git revision ``REV`` (paired,
in one process) and their largest difference relative to each block's largest entry.

Cases as in ``bem_friction_rolling.py``: the issue's CONTACT case by ``--spacing`` (no
inertia: half-space split, :func:`bem.spectral.influence_kernels`) and the section 11
layer (with inertia: batched sums) by ``--nodes`` (0: the example's 41 x 41).

Run (from ``benchmarks/``, ``OPENBLAS_NUM_THREADS=1``, one case a command for its own peak
RSS): ``../.venv/bin/python bem_friction_kernels.py --spacing 0.1e-3 [--old 20a7340]`` or
``--nodes 513``.
"""

import argparse
import os
import time

import numpy as np

from _common import machine, peak_rss_mb
from bem_friction_rolling import contact_case, old_module, section11_case

from bem.spectral import BLOCKS, influence_kernels


def measure(label: str, problem, old_rev: str | None) -> None:
    g, layer, V = problem.grid, problem.layer, problem.loading.speed
    t0, c0 = time.perf_counter(), time.process_time()
    new = influence_kernels(g, layer, V, BLOCKS)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"{label}: {g.nodes_x} x {g.nodes_y} nodes, Nt = {g.truncation_x}: kernels {wall:.2f} s (CPU {cpu:.2f} s), "
          f"peak RSS {peak_rss_mb():.0f} MB", flush=True)
    if old_rev:
        spectral = old_module(old_rev, "spectral")
        t0, c0 = time.perf_counter(), time.process_time()
        old = spectral.influence_kernels(g, layer, V, BLOCKS)
        owall, ocpu = time.perf_counter() - t0, time.process_time() - c0
        diff = max(float(np.abs(new[b] - old[b]).max() / np.abs(old[b]).max()) for b in BLOCKS)
        print(f"  {old_rev}: {owall:.2f} s (CPU {ocpu:.2f} s) -> {wall:.2f} s (CPU {cpu:.2f} s): "
              f"{owall / wall:.1f}x wall, {ocpu / cpu:.1f}x CPU; largest difference {diff:.1e} of the block",
              flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, nargs="*", default=[])
    ap.add_argument("--nodes", type=int, nargs="*", default=[])
    ap.add_argument("--old", metavar="REV")
    args = ap.parse_args()
    print(machine(), "| load average", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    for a in args.spacing:
        measure(f"issue 11 case, spacing {a * 1e3:g} mm", contact_case(a)[0], args.old)
    for n in args.nodes:
        measure("section 11", section11_case(n or None)[0], args.old)
