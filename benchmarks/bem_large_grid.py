"""A large steady rolling contact: the section 11 example on N x N nodes (default 257 and
1025, each in its own process for its peak memory), L = 0.2 m, Nt = L / (2 a). Time and
peak memory.

Run: ``python benchmarks/bem_large_grid.py [N ...] [--markdown]``.
"""

import json
import subprocess
import sys
import time

from _common import LAYER, machine, markdown_mode, markdown_table, peak_rss_mb, reporter

from bem import Grid, Loading, Problem, Sphere, solve


def one(n: int) -> dict:
    """Solve on n x n nodes in this process; the figures as a dict."""
    half = 5.2e-3
    a = 2 * half / (n - 1)
    nt = int(0.2 / (2 * a)) + 1
    grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (half, half))
    print(machine(), grid.shape, f"a = {a * 1e6:.2f} um, Nt = {nt}", file=sys.stderr, flush=True)
    t = time.perf_counter()
    res = solve(Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0)),
                progress=lambda s: print(s, file=sys.stderr, flush=True), energy=False)
    timing = res.record.times
    return dict(n=n, a_um=a * 1e6, nt=nt, contact=int(res.contact.sum()), rr=res.rolling_resistance,
                solver=res.record.linear_solver, linear=res.record.linear_iterations, active=res.record.iterations,
                kernel=timing["kernel_s"], solve=timing["solve_s"], total=time.perf_counter() - t,
                rss=peak_rss_mb())


if __name__ == "__main__":
    markdown = markdown_mode()
    say = reporter(markdown)
    if sys.argv[1:2] == ["--one"]:
        print(json.dumps(one(int(sys.argv[2]))))
        sys.exit()
    rows = []
    for n in [int(v) for v in sys.argv[1:]] or [257, 1025]:
        out = subprocess.run([sys.executable, __file__, "--one", str(n)], stdout=subprocess.PIPE, text=True, check=True)
        r = json.loads(out.stdout.strip().splitlines()[-1])
        say(f"{n} x {n}: R_r = {r['rr']:.5f} N, contact nodes {r['contact']}, {r['solver']} {r['linear']} iterations, "
            f"{r['active']} active-set iterations; kernel {r['kernel']:.1f} s, solve {r['solve']:.1f} s, "
            f"total {r['total']:.1f} s, peak RSS {r['rss']:.0f} MB")
        rows.append([f"section 11, frictionless, {n} x {n} nodes (a = {r['a_um']:.1f} um, Nt = {r['nt']})",
                     r["contact"], f"{r['kernel']:.1f}", f"{r['solve']:.1f}", f"{r['active']} / {r['linear']}",
                     f"{r['rss']:.0f}", f"{r['rr']:.5f}"])
    if markdown:
        print(markdown_table(["case", "contact nodes", "kernel (s)", "solve (s)", "active-set / GMRES iterations",
                              "peak RSS (MB)", "R_r (N)"], rows))
