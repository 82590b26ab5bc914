"""The nine influence kernels of frictional rolling: time and peak memory, and with
``--old REV`` the same kernels by the ``bem.spectral`` of git revision ``REV`` (paired, in
one process) and their largest difference relative to each block's largest entry.

Cases as in ``bem_friction_rolling.py``: the elastic paraboloid on a thick layer by
``--spacing`` (no inertia: half-space split, :func:`bem.spectral.influence_kernels`) and the
section 11 viscoelastic layer (with inertia: batched sums) by ``--nodes`` (0: the example's
41 x 41).

Run (``OPENBLAS_NUM_THREADS=1``, one case a command for its own peak RSS):
``python benchmarks/bem_friction_kernels.py --spacing 0.1e-3 [--old REV]`` or ``--nodes
513``; ``--markdown`` prints the results table (one row per case) alone on stdout, the
running report on stderr.
"""

import argparse
import os
import time

import numpy as np

from _common import machine, markdown_mode, markdown_table, peak_rss_mb, reporter
from bem_friction_rolling import contact_case, old_module, section11_case

from bem.spectral import BLOCKS, influence_kernels

markdown = markdown_mode()
say = reporter(markdown)
ROWS: list = []


def measure(label: str, problem, old_rev: str | None) -> None:
    g, layer, V = problem.grid, problem.layer, problem.loading.speed
    t0, c0 = time.perf_counter(), time.process_time()
    new = influence_kernels(g, layer, V, BLOCKS)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    say(f"{label}: {g.nodes_x} x {g.nodes_y} nodes, Nt = {g.truncation_x}: kernels {wall:.2f} s (CPU {cpu:.2f} s), "
        f"peak RSS {peak_rss_mb():.0f} MB")
    ROWS.append([f"{label}, {g.nodes_x} x {g.nodes_y}", g.truncation_x, f"{wall:.2f}", f"{cpu:.2f}",
                 f"{peak_rss_mb():.0f}"])
    if old_rev:
        spectral = old_module(old_rev, "spectral")
        t0, c0 = time.perf_counter(), time.process_time()
        old = spectral.influence_kernels(g, layer, V, BLOCKS)
        owall, ocpu = time.perf_counter() - t0, time.process_time() - c0
        diff = max(float(np.abs(new[b] - old[b]).max() / np.abs(old[b]).max()) for b in BLOCKS)
        say(f"  {old_rev}: {owall:.2f} s (CPU {ocpu:.2f} s) -> {wall:.2f} s (CPU {cpu:.2f} s): "
            f"{owall / wall:.1f}x wall, {ocpu / cpu:.1f}x CPU; largest difference {diff:.1e} of the block")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, nargs="*", default=[])
    ap.add_argument("--nodes", type=int, nargs="*", default=[])
    ap.add_argument("--old", metavar="REV")
    args = ap.parse_args()
    say(machine(), "| load average", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    for a in args.spacing:
        measure(f"elastic paraboloid, thick elastic layer, spacing {a * 1e3:g} mm", contact_case(a)[0], args.old)
    for n in args.nodes:
        measure("viscoelastic sphere (section 11)", section11_case(n or None)[0], args.old)
    if markdown:
        print(markdown_table(["case", "Nt", "kernels (s)", "kernels CPU (s)", "peak RSS (MB)"], ROWS))
