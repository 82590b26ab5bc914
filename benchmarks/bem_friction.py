"""Frictional rolling of the paper's viscoelastic sphere (section 11 with Coulomb friction):
time, iterations and memory.

1. The section 11 example with ``mu = 0.2``, pushed at the top (a = 0.25 mm, Nt = 2000,
   41 x 41 nodes): the nine compliance kernels + the frictional solve, the first call and
   the median of warm calls; the energy figure (P_visc + P_fric) / V is timed apart (an
   independent check, not needed for R_r).
2. Large frictional contacts: the same problem on ``--nodes`` x ``--nodes`` nodes
   (half-width 5.2 mm, a = 10.4 mm / (nodes - 1), Nt = L / (2 a) rounded up, as
   ``bem_large_grid.py``; default 257, i.e. a = 40.6 um), solved by the matrix-free GMRES
   path (the dense path above ``Friction.dense_limit`` unknowns is not used): time,
   active-set and GMRES iterations and peak RSS (resource.getrusage). ``--dense`` forces
   the dense solver instead (81 x 81 took 229 s and 2.9 GB that way).

Run: ``python benchmarks/bem_friction.py [--nodes 257 ...] [--skip-section11] [--dense]
[--markdown]``; ``--nodes`` with no value skips the large grids. With ``--markdown`` the
results table (one row per case) alone goes to stdout, the running report to stderr.
"""

import argparse
import math
import time

from _common import LAYER, machine, markdown_mode, markdown_table, peak_rss_mb, reporter, timed

from bem import Grid, Loading, Problem, Sphere
from bem.frictional import Friction, solve_friction

markdown = markdown_mode()
say = reporter(markdown)
ROWS: list = []
HEADERS = ["case", "contact nodes", "kernels (s)", "solve (s)", "kernels + solve, first call (s)",
           "kernels + solve, median (s)", "active-set iterations", "GMRES iterations", "R_r (N)", "peak RSS (MB)"]


def section11(repeat: int) -> None:
    grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
    problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
    first, median, (res, t) = timed(lambda: solve_friction(problem, Friction(0.2), energy=False), repeat=repeat)
    r = res.record
    n = int(res.contact.sum())
    say(f"section 11 with friction, {grid.nodes_x} x {grid.nodes_y} nodes, Nt = 2000:")
    say(f"  R_r = {res.rolling_resistance:.5f} N (friction {res.rolling_resistance_friction:.5f} N, "
        f"Omega {res.omega:.5f} rad/s, stick {res.stick_fraction:.3f}, "
        f"{r.iterations} active-set iterations, {n} contact nodes)")
    say(f"  kernels {t['kernel_s']:.2f} s + solve {t['solve_s']:.2f} s (last run)")
    say(f"  kernels + solve: first call {first:.2f} s, median of {repeat} warm calls {median:.2f} s")
    t0 = time.perf_counter()
    res_e, te = solve_friction(problem, Friction(0.2))
    say(f"  with the energy figure ({res_e.rolling_resistance_energy:.5f} N): "
        f"{time.perf_counter() - t0:.2f} s, of which energy {te['energy_s']:.2f} s")
    ROWS.append([f"viscoelastic sphere (section 11), mu = 0.2, {grid.nodes_x} x {grid.nodes_y}, Nt = 2000", n,
                 f"{t['kernel_s']:.2f}", f"{t['solve_s']:.2f}", f"{first:.2f}", f"{median:.2f}", r.iterations,
                 r.linear_iterations, f"{res.rolling_resistance:.5f}", f"{peak_rss_mb():.0f}"])


def large(nodes: int, dense: bool) -> None:
    half = 5.2e-3
    a = 2 * half / (nodes - 1)
    nt = math.ceil(0.2 / (2 * a) - 1e-9)
    grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (half, half))
    problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
    friction = Friction(0.2, dense_limit=10**9 if dense else Friction(0.2).dense_limit)
    rss0 = peak_rss_mb()
    t0 = time.perf_counter()
    res, t = solve_friction(problem, friction, energy=False, progress=lambda s: say("  " + s))
    total = time.perf_counter() - t0
    n = int(res.contact.sum())
    r = res.record
    say(f"frictional rolling on {grid.nodes_x} x {grid.nodes_y} nodes (a = {a * 1e6:.1f} um, Nt = {nt}), "
        f"{n} contact nodes ({3 * n + 2} unknowns)")
    say(f"  R_r = {res.rolling_resistance:.5f} N (friction {res.rolling_resistance_friction:.5f} N, "
        f"Omega {res.omega:.6f} rad/s, stick {res.stick_fraction:.3f})")
    say(f"  {r.iterations} active-set iterations, {r.linear_solver} {r.linear_iterations} iterations; "
        f"residuals: gap {r.gap_residual:.1e}, stick {r.stick_residual:.1e}, Coulomb {r.coulomb_residual:.1e}")
    say(f"  kernels {t['kernel_s']:.1f} s + solve {t['solve_s']:.1f} s = {total:.1f} s; "
        f"peak RSS {peak_rss_mb():.0f} MB (before: {rss0:.0f} MB)")
    ROWS.append([f"viscoelastic sphere (section 11), mu = 0.2, {grid.nodes_x} x {grid.nodes_y}, Nt = {nt}"
                 + (", dense LU" if dense else ""), n, f"{t['kernel_s']:.1f}", f"{t['solve_s']:.1f}", f"{total:.1f}",
                 "-", r.iterations, r.linear_iterations, f"{res.rolling_resistance:.5f}", f"{peak_rss_mb():.0f}"])


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nodes", type=int, nargs="*", default=[257])
    ap.add_argument("--dense", action="store_true")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--skip-section11", action="store_true")
    args = ap.parse_args()
    say(machine())
    if not args.skip_section11:
        section11(args.repeat)
    for nodes in args.nodes:
        large(nodes, args.dense)
    if markdown:
        print(markdown_table(HEADERS, ROWS))
