"""``grid-error.csv``: a sweep over the node spacing refined by 2 gives, per combination of
its other axes, each figure at the finest spacing with its Richardson limit and error.

The reference is :func:`bem.convergence.richardson` applied here to the values
``results.csv`` holds, and its formulas (observed order ``p = log2(|d1| / |d2|)``, limit
``q3 + d2 / (2^p - 1)``) evaluated by hand on the rows it calls asymptotic. The case is
the section 11 friction example on coarse grids (a = 2, 1, 0.5 mm, Nt = 200, the least
that resolves 0.5 mm on L = 20 cm): six points solve in about a second.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import pytest

from bem.convergence import richardson
from sweeps.grid_error import FIGURES, spacing_axis
from sweeps.spec import read_sweep

ROOT = Path(__file__).resolve().parents[2]
FRICTION = ROOT / "examples" / "sweeps" / "base-friction.toml"
#: spacings (m) given out of order: the levels are sorted coarse to fine
SPACINGS = (0.5e-3, 2e-3, 1e-3)
LOADS = (20.0, 80.0)


def sweep_file(folder: Path, spacings, truncation: int = 200, name: str = "s.toml") -> Path:
    path = folder / name
    path.write_text(f'case = "{FRICTION}"\nset = ["grid.truncation={truncation}"]\n'
                    f'[[axis]]\nkey = "grid.spacing"\nvalues = [{", ".join(repr(a) for a in spacings)}]\n'
                    f'[[axis]]\nkey = "loading.load"\nvalues = [{", ".join(repr(p) for p in LOADS)}]\n')
    return path


def read(path: Path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def table_values(results: list[dict], load: str, figure: str, spacings) -> list[float]:
    """The figure at each spacing (coarse to fine) for this load, read from results.csv."""
    out = []
    for a in spacings:
        [row] = [r for r in results if r["loading.load"] == load and math.isclose(float(r["grid.spacing"]), a)]
        out.append(float(row[figure]))
    return out


@pytest.fixture(scope="module")
def three(sweep_command, tmp_path_factory):
    folder = tmp_path_factory.mktemp("three-spacings")
    code, err = sweep_command(sweep_file(folder, SPACINGS), "--out", folder / "out", "--no-cache", "--no-plots")
    assert code == 0, err
    return folder / "out", err


def test_rows_are_richardson_of_the_table(three):
    out, err = three
    results, rows = read(out / "results.csv"), read(out / "grid-error.csv")
    assert f"grid error {out / 'grid-error.csv'}" in err
    assert {r["loading.load"] for r in rows} == {repr(p) for p in LOADS}
    figures = {r["figure"] for r in rows}
    assert {"rolling_resistance", "rolling_resistance_energy", "rolling_resistance_friction", "friction_share",
            "stick_fraction", "driving_force"} <= figures <= set(FIGURES)
    assert len(rows) == len(LOADS) * len(figures)
    fine = sorted(SPACINGS, reverse=True)
    asymptotic = 0
    for r in rows:
        q = table_values(results, r["loading.load"], r["figure"], fine)
        c = richardson(q)
        assert r["spacings"] == ";".join(repr(a) for a in fine)
        assert [float(v) for v in r["values"].split(";")] == q
        assert float(r["finest"]) == q[-1]
        assert float(r["limit"]) == c.extrapolated and float(r["error"]) == c.error_finest
        assert r["order"] == ("" if math.isnan(c.order) else repr(c.order))
        assert r["estimate"] == ("richardson" if c.asymptotic else "not asymptotic: 3 x last change")
        if c.asymptotic:  # the formulas themselves
            asymptotic += 1
            d1, d2 = q[1] - q[0], q[2] - q[1]
            p = math.log2(abs(d1) / abs(d2))
            assert float(r["order"]) == pytest.approx(p, rel=1e-12)
            assert float(r["limit"]) == pytest.approx(q[2] + d2 / (2**p - 1), rel=1e-12)
        else:
            assert float(r["limit"]) == q[-1] and float(r["error"]) == pytest.approx(3 * abs(q[2] - q[1]), rel=1e-12)
    assert asymptotic >= 1  # both branches of the rule are exercised on this sweep


def test_two_spacings_assume_first_order(sweep_command, tmp_path):
    code, err = sweep_command(sweep_file(tmp_path, (1e-3, 0.5e-3)), "--out", tmp_path / "out", "--no-cache",
                              "--no-plots", "--quiet")
    assert code == 0, err
    results, rows = read(tmp_path / "out" / "results.csv"), read(tmp_path / "out" / "grid-error.csv")
    assert rows
    for r in rows:
        q1, q2 = table_values(results, r["loading.load"], r["figure"], (1e-3, 0.5e-3))
        assert r["estimate"] == "order 1 assumed (two spacings)" and float(r["order"]) == 1.0
        assert float(r["limit"]) == pytest.approx(2 * q2 - q1, rel=1e-12, abs=1e-300)
        assert float(r["error"]) == pytest.approx(abs(q2 - q1), rel=1e-12, abs=1e-300)


def test_a_failed_point_is_named(sweep_command, tmp_path):
    # Nt = 100 resolves 2 and 1 mm on L = 20 cm but not 0.5 mm (needs L / 2a = 200)
    code, err = sweep_command(sweep_file(tmp_path, SPACINGS, truncation=100), "--out", tmp_path / "out",
                              "--no-cache", "--no-plots", "--quiet")
    assert code == 1, err
    rows = read(tmp_path / "out" / "grid-error.csv")
    assert [r["loading.load"] for r in rows] == [repr(p) for p in LOADS]
    for r in rows:
        assert r["estimate"].startswith("failed at grid.spacing = 0.0005: ValueError: truncation_x")
        assert r["figure"] == r["limit"] == r["error"] == ""


def test_no_spacing_axis_writes_nothing(sweep_command, load_sweep_file, tmp_path):
    code, err = sweep_command(load_sweep_file(), "--out", tmp_path / "out", "--no-cache", "--no-plots")
    assert code == 0, err
    assert (tmp_path / "out" / "results.csv").exists()
    assert not (tmp_path / "out" / "grid-error.csv").exists()
    assert "grid error" not in err and "grid-error" not in err


def test_spacings_not_halving_are_not_extrapolated(tmp_path):
    key, why = spacing_axis(read_sweep(sweep_file(tmp_path, (1e-3, 0.75e-3, 0.5e-3))))
    assert key is None and "does not refine by 2" in why and "1.333" in why
    key, levels = spacing_axis(read_sweep(sweep_file(tmp_path, (0.25e-3, 1e-3, 0.5e-3))))
    assert key == "grid.spacing" and levels == (1e-3, 0.5e-3, 0.25e-3)
