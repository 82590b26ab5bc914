"""Frictional rolling benchmarks (issue 5).

1. The paper's section 11 with Coulomb friction (mu = 0.2, pushed at the top, a = 0.25 mm,
   Nt = 2000, 41 x 41 nodes): the nine compliance kernels + the frictional solve, the
   first call and the median of warm calls; the energy figure (P_visc + P_fric) / V is
   timed apart (it is an independent check, not needed for R_r).
2. The largest frictional grid of the dense active-set solver in a few minutes: the same
   problem on finer grids (``--spacing`` in m, default 0.15 mm: 67 x 67 nodes), its time
   and peak RSS (resource.getrusage).

Run: ``.venv/bin/python benchmarks/bem_friction.py [--spacing 1.5e-4] [--skip-section11]``.
"""

import argparse
import time

from _common import LAYER, machine, peak_rss_mb, timed

from bem import Grid, Loading, Problem, Sphere
from bem.friction import Friction
from bem.rolling import solve_friction


def section11(repeat: int) -> None:
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
    problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
    first, median, (res, t) = timed(lambda: solve_friction(problem, Friction(0.2), energy=False), repeat=repeat)
    print(f"section 11 with friction, {grid.nodes_x} x {grid.nodes_y} nodes, Nt = 2000:")
    print(f"  R_r = {res.rolling_resistance:.5f} N (friction {res.rolling_resistance_friction:.5f} N, "
          f"Omega {res.omega:.5f} rad/s, stick {res.stick_fraction:.3f}, "
          f"{res.record.iterations} active-set iterations, {int(res.contact.sum())} contact nodes)")
    print(f"  kernels {t['kernel_s']:.2f} s + solve {t['solve_s']:.2f} s (last run)")
    print(f"  kernels + solve: first call {first:.2f} s, median of {repeat} warm calls {median:.2f} s")
    t0 = time.perf_counter()
    res, t = solve_friction(problem, Friction(0.2))
    print(f"  with the energy figure ({res.rolling_resistance_energy:.5f} N): "
          f"{time.perf_counter() - t0:.2f} s, of which energy {t['energy_s']:.2f} s")


def largest(spacing: float) -> None:
    half = 5e-3
    nt = max(2000, int(round(0.2 / (2 * spacing) * 1.25)))
    grid = Grid.centred((spacing, spacing), (0.2, 0.2), (nt, nt), (half, half))
    problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
    rss0 = peak_rss_mb()
    t0 = time.perf_counter()
    res, t = solve_friction(problem, Friction(0.2), energy=False)
    total = time.perf_counter() - t0
    n = int(res.contact.sum())
    print(f"largest dense frictional grid: {grid.nodes_x} x {grid.nodes_y} nodes (a = {spacing * 1e3:.3g} mm, "
          f"Nt = {nt}), {n} contact nodes ({3 * n + 2} unknowns)")
    print(f"  R_r = {res.rolling_resistance:.5f} N (friction {res.rolling_resistance_friction:.5f} N, "
          f"stick {res.stick_fraction:.3f}, {res.record.iterations} iterations)")
    print(f"  kernels {t['kernel_s']:.1f} s + solve {t['solve_s']:.1f} s = {total:.1f} s; "
          f"peak RSS {peak_rss_mb():.0f} MB (before: {rss0:.0f} MB)")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spacing", type=float, default=1.5e-4)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--skip-section11", action="store_true")
    args = ap.parse_args()
    print(machine())
    if not args.skip_section11:
        section11(args.repeat)
    largest(args.spacing)
