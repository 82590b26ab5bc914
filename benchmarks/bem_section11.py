"""Section 11 example without friction (a = 0.25 mm, Nt = 2000, 41 x 41 nodes): time of the
compliance kernel and of the contact solve."""

from _common import LAYER, machine, timed

from bem import Grid, Loading, Problem, Sphere, solve_frictionless

grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (2000, 2000), (5e-3, 5e-3))
problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
first, median, (res, t) = timed(lambda: solve_frictionless(problem), repeat=7)
print(machine())
print(f"R_r = {res.rolling_resistance:.5f} N (Table 1: 3.0257 N)")
print(f"kernel {t['kernel_s']:.3f} s + solve {t['solve_s']:.3f} s (last run)")
print(f"kernel + solve: first call {first:.3f} s, median of 7 warm calls {median:.3f} s")
