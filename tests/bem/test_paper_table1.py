"""The paper's Table 1: frictionless rolling resistance of the section 11 example for
node spacings 0.15-1 mm and truncation orders 500-3000, every printed cell within 1e-4 N
(the table prints 4 decimals, so rounding alone allows 5e-5 N)."""

import csv
from pathlib import Path

import pytest

from bem import Grid, Layer, Loading, Problem, Sphere, ThreeParameterSolid, solve

TABLE = Path(__file__).resolve().parents[2] / "verification" / "data" / "zehil_gavin_2013_table1.csv"
LAYER = Layer(5e-3, ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), density=1000.0)


def cells():
    rows = list(csv.reader(line for line in TABLE.open() if not line.startswith("#")))
    truncations = [int(v) for v in rows[0][1:]]
    for row in rows[1:]:
        for nt, value in zip(truncations, row[1:]):
            if value:
                yield float(row[0]) * 1e-3, nt, float(value)


CELLS = list(cells())
FAST = {(1.0e-3, 500), (1.0e-3, 3000), (0.5e-3, 1000), (0.25e-3, 2000)}


def rolling_resistance(a, nt):
    grid = Grid.centred((a, a), (0.2, 0.2), (nt, nt), (5e-3, 5e-3))
    problem = Problem(LAYER, Sphere(0.02), grid, Loading(0.05, load=150.0))
    return solve(problem, energy=False).rolling_resistance


@pytest.mark.parametrize(
    "a, nt, published",
    [pytest.param(*c, marks=() if c[:2] in FAST else pytest.mark.slow, id=f"a={c[0]*1e3:g}mm-Nt={c[1]}") for c in CELLS],
)
def test_table1_cell(a, nt, published):
    assert abs(rolling_resistance(a, nt) - published) < 1e-4


def test_table_has_35_cells():
    assert len(CELLS) == 35
