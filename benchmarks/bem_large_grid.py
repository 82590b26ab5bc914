"""A large steady rolling contact: the section 11 example on N x N nodes (default 1025),
L = 0.2 m, Nt = L / (2 a). Time and peak memory."""

import sys
import time

from _common import LAYER, machine, peak_rss_mb

from bem import Grid, Loading, Problem, Sphere, solve_frictionless

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1025
half = 5.2e-3
a = 2 * half / (n - 1)
nt = int(0.2 / (2 * a)) + 1
grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (half, half))
print(machine(), grid.shape, f"a = {a * 1e6:.2f} um, Nt = {nt}", flush=True)
t = time.perf_counter()
res, timing = solve_frictionless(Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0)), progress=print)
print(f"R_r = {res.rolling_resistance:.5f} N, contact nodes {int(res.contact.sum())}, {res.record.linear_solver} "
      f"{res.record.linear_iterations} iterations, {res.record.iterations} active-set iterations")
print(f"kernel {timing['kernel_s']:.1f} s, solve {timing['solve_s']:.1f} s, total {time.perf_counter() - t:.1f} s, "
      f"peak RSS {peak_rss_mb():.0f} MB")
