"""The whole of the paper's Table 1 (35 cells): values, errors and total time."""

import csv
import time
from pathlib import Path

from _common import LAYER, machine

from bem import Grid, Loading, Problem, Sphere, solve_frictionless

table = Path(__file__).resolve().parents[1] / "verification" / "data" / "zehil_gavin_2013_table1.csv"
rows = list(csv.reader(line for line in table.open() if not line.startswith("#")))
nts = [int(v) for v in rows[0][1:]]
print(machine())
print("a (mm) | " + " | ".join(f"Nt={n}" for n in nts))
start, worst = time.perf_counter(), 0.0
for row in rows[1:]:
    a = float(row[0]) * 1e-3
    cells = []
    for nt, value in zip(nts, row[1:]):
        if not value:
            cells.append("N/A")
            continue
        grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (5e-3, 5e-3))
        rr = solve_frictionless(Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0)))[0].rolling_resistance
        worst = max(worst, abs(rr - float(value)))
        cells.append(f"{rr:.5f} ({rr - float(value):+.1e})")
    print(f"{row[0]} | " + " | ".join(cells), flush=True)
print(f"largest |error| {worst:.2e} N; whole table {time.perf_counter() - start:.1f} s")
