"""The nine influence kernels of frictional rolling, with their power tables where the
layer dissipates (what :func:`bem.problem.compute_kernels` computes for a frictional solve):
time and peak memory of the first computation (what a solve pays, with the process's first
trigonometric tables), and with ``--old REV`` the same tables by the ``bem.spectral`` of git
revision ``REV`` (paired, in one process, alternating new and old ``--repeat`` times: the
first pair and the fastest of each) and their largest difference relative to each table's
largest entry.

Cases as in ``bem_friction_rolling.py``: the elastic paraboloid on a thick layer by
``--spacing`` (no inertia, at rest: half-space split, kernels alone) and the section 11
viscoelastic layer (a little inertia, ``rho V^2 / G = 8e-7``: the deep modes' series,
kernels and power tables) by ``--nodes`` (0: the example's 41 x 41, ``N_t = 2000``).

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

from bem.energy import dissipates
from bem.spectral import BLOCKS

markdown = markdown_mode()
say = reporter(markdown)
ROWS: list = []


def tables(spectral, g, layer, V) -> dict:
    """The nine kernels and, where the layer dissipates, their power tables (``"P" + block``)."""
    if not dissipates(g, layer, V):
        return spectral.influence_kernels(g, layer, V, BLOCKS)
    out, power = spectral.kernels_with_power(g, layer, V, BLOCKS)
    return {**out, **{"P" + b: t for b, t in power.items()}}


def timed(spectral, g, layer, V) -> tuple[dict, float, float]:
    t0, c0 = time.perf_counter(), time.process_time()
    out = tables(spectral, g, layer, V)
    return out, time.perf_counter() - t0, time.process_time() - c0


def measure(label: str, problem, old_rev: str | None, repeat: int) -> None:
    import bem.spectral

    g, layer, V = problem.grid, problem.layer, problem.loading.speed
    old = old_module(old_rev, "spectral") if old_rev else None
    runs = []
    for _ in range(max(1, repeat)):
        new, wall, cpu = timed(bem.spectral, g, layer, V)
        runs.append((wall, cpu, *(timed(old, g, layer, V)[1:] if old else ())))
    wall, cpu = runs[0][:2]
    what = "kernels and power tables" if len(new) > len(BLOCKS) else "kernels"
    say(f"{label}: {g.nodes_x} x {g.nodes_y} nodes, Nt = {g.truncation_x}: {what} {wall:.2f} s (CPU {cpu:.2f} s), "
        f"peak RSS {peak_rss_mb():.0f} MB")
    ROWS.append([f"{label}, {g.nodes_x} x {g.nodes_y}", g.truncation_x, len(new), f"{wall:.2f}", f"{cpu:.2f}",
                 f"{peak_rss_mb():.0f}"])
    if old:
        ref = tables(old, g, layer, V)
        diff = {b: float(np.abs(new[b] - ref[b]).max() / np.abs(ref[b]).max()) for b in ref}
        worst = max(diff, key=diff.get)
        for name, pick in (("first", runs[0]), (f"best of {len(runs)}", [min(r[i] for r in runs) for i in range(4)])):
            say(f"  {name}: {old_rev} {pick[2]:.2f} s (CPU {pick[3]:.2f} s) -> {pick[0]:.2f} s (CPU {pick[1]:.2f} s): "
                f"{pick[2] / pick[0]:.1f}x wall, {pick[3] / pick[1]:.1f}x CPU")
        say(f"  largest difference {diff[worst]:.1e} of the table ({worst})")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, nargs="*", default=[])
    ap.add_argument("--nodes", type=int, nargs="*", default=[])
    ap.add_argument("--old", metavar="REV")
    ap.add_argument("--repeat", type=int, default=1, help="runs a case, paired with --old (default 1)")
    args = ap.parse_args()
    say(machine(), "| load average", " ".join(f"{x:.2f}" for x in os.getloadavg()))
    for a in args.spacing:
        measure(f"elastic paraboloid, thick elastic layer, spacing {a * 1e3:g} mm", contact_case(a)[0], args.old, args.repeat)
    for n in args.nodes:
        measure("viscoelastic sphere (section 11)", section11_case(n or None)[0], args.old, args.repeat)
    if markdown:
        print(markdown_table(["case", "Nt", "tables", "kernels (s)", "kernels CPU (s)", "peak RSS (MB)"], ROWS))
