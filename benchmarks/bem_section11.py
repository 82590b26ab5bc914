"""Section 11 example without friction (a = 0.25 mm, Nt = 2000, 41 x 41 nodes): time of the
compliance kernel and of the contact solve.

Run: ``python benchmarks/bem_section11.py [--markdown]``.
"""

from _common import LAYER, machine, markdown_mode, markdown_table, reporter, timed

from bem import Grid, Loading, Problem, Sphere, solve

markdown = markdown_mode()
say = reporter(markdown)
grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
first, median, res = timed(lambda: solve(problem, energy=False), repeat=7)
t = res.record.times
say(machine())
say(f"R_r = {res.rolling_resistance:.5f} N (Table 1: 3.0257 N)")
say(f"kernel {t['kernel_s']:.3f} s + solve {t['solve_s']:.3f} s (last run)")
say(f"kernel + solve: first call {first:.3f} s, median of 7 warm calls {median:.3f} s")
if markdown:
    print(markdown_table(
        ["case", "kernel (s)", "solve (s)", "kernel + solve, first call (s)", "kernel + solve, median of 7 (s)",
         "R_r (N)", "Table 1 (N)"],
        [["section 11, frictionless, 41 x 41 nodes, Nt = 2000", f"{t['kernel_s']:.3f}", f"{t['solve_s']:.3f}",
          f"{first:.3f}", f"{median:.3f}", f"{res.rolling_resistance:.5f}", "3.0257"]]))
