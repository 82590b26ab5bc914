"""The whole of the paper's Table 1 (35 cells): values, errors and total time.

Run: ``python benchmarks/table1.py [--markdown]`` (the table: one row per grid spacing).
"""

import csv
import time
from pathlib import Path

from _common import LAYER, machine, markdown_mode, markdown_table, reporter

from bem import Grid, Loading, Problem, Sphere, solve

markdown = markdown_mode()
say = reporter(markdown)
table = Path(__file__).resolve().parents[1] / "verification" / "data" / "zehil_gavin_2013_table1.csv"
rows = list(csv.reader(line for line in table.open() if not line.startswith("#")))
nts = [int(v) for v in rows[0][1:]]
say(machine())
say("a (mm) | " + " | ".join(f"Nt={n}" for n in nts))
start, worst, summary = time.perf_counter(), 0.0, []
for row in rows[1:]:
    a = float(row[0]) * 1e-3
    cells, row_worst, row_start = [], 0.0, time.perf_counter()
    for nt, value in zip(nts, row[1:]):
        if not value:
            cells.append("N/A")
            continue
        grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (5e-3, 5e-3))
        rr = solve(Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0)), energy=False).rolling_resistance
        row_worst = max(row_worst, abs(rr - float(value)))
        cells.append(f"{rr:.5f} ({rr - float(value):+.1e})")
    worst = max(worst, row_worst)
    say(f"{row[0]} | " + " | ".join(cells))
    summary.append([f"section 11, frictionless, a = {row[0]} mm", sum(c != "N/A" for c in cells),
                    f"{row_worst:.1e}", f"{time.perf_counter() - row_start:.1f}"])
total = time.perf_counter() - start
say(f"largest |error| {worst:.2e} N; whole table {total:.1f} s")
if markdown:
    summary.append(["**the whole table**", sum(int(r[1]) for r in summary), f"{worst:.1e}", f"{total:.1f}"])
    print(markdown_table(["grid spacing", "cells (Nt = " + ", ".join(map(str, nts)) + ")",
                          "largest R_r error vs the paper (N)", "time (s)"], summary))
