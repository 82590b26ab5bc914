"""Sweep files: expansion into points, and every bad input refused before anything runs."""

from __future__ import annotations

import socket
import time
from pathlib import Path

import numpy as np
import pytest

from sweeps import SweepError, expand, read_sweep
from sweeps.cli import main

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "examples" / "sweeps" / "base-frictionless.toml"
FRICTION = ROOT / "examples" / "sweeps" / "base-friction.toml"


def write(tmp_path: Path, body: str, case: Path = BASE, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(f'case = "{case}"\n{body}')
    return path


def test_product_of_a_list_and_a_log_range(tmp_path):
    path = write(tmp_path, """
[[axis]]
key = "loading.load"
values = [10.0, 150.0]
[[axis]]
key = "loading.speed"
start = 1e-3
stop = 1.0
num = 4
scale = "log"
""")
    points = expand(read_sweep(path))
    assert len(points) == 8
    speeds = sorted({p.values["loading.speed"] for p in points})
    np.testing.assert_allclose(speeds, [1e-3, 1e-2, 1e-1, 1.0], rtol=1e-12)
    p = points[5]  # product, last axis fastest: load 150, speed 1e-2
    assert p.values == {"loading.load": 150.0, "loading.speed": speeds[1]}
    assert p.config["loading"]["load"] == 150.0 and p.config["loading"]["speed"] == speeds[1]
    assert p.config["layer"]["thickness"] == 5e-3  # the rest is the base case
    assert len({q.point_id for q in points}) == 8


def test_zip_cases_and_integer_ranges(tmp_path):
    path = tmp_path / "z.toml"
    path.write_text(f"""
case = ["{BASE}", "{FRICTION}"]
combine = "zip"
set = ["grid.spacing=1e-3"]
[[axis]]
key = "loading.load"
values = [10.0, 20.0, 30.0]
[[axis]]
key = "grid.truncation"
start = 100
stop = 120
num = 3
""")
    sweep = read_sweep(path)
    points = expand(sweep)
    assert [a.key for a in sweep.axes] == ["case", "loading.load", "grid.truncation"]
    assert len(points) == 6  # the case axis multiplies the zipped ones
    assert [p.config["grid"]["truncation"] for p in points[:3]] == [100, 110, 120]
    assert all(isinstance(p.config["grid"]["truncation"], int) for p in points)
    assert [p.values["case"] for p in points] == ["base-frictionless"] * 3 + ["base-friction"] * 3
    assert [p.friction for p in points] == [False] * 3 + [True] * 3
    assert points[0].config["grid"]["spacing"] == 1e-3


@pytest.mark.parametrize("axis, message", [
    ('key = "loading.weight"\nvalues = [1.0]', "[loading] has no key 'weight'"),
    ('key = "loadng.load"\nvalues = [1.0]', "known section"),
    ('key = "load"\nvalues = [1.0]', "must be section.key"),
    ('key = "loading.load"\nvalues = []', "values must be a non-empty list"),
    ('key = "loading.load"\nstart = 1.0\nstop = 2.0\nnum = 0', "num must be an integer >= 1"),
    ('key = "loading.load"\nstart = "ten"\nstop = 2.0\nnum = 3', "start must be a number, got 'ten' (a string)"),
    ('key = "loading.load"\nvalues = [10.0, "heavy"]', "values[1] must be a number (N), got 'heavy' (a string)"),
    ('key = "loading.speed"\nstart = 0.0\nstop = 1.0\nnum = 3\nscale = "log"', "a log range needs start > 0"),
    ('key = "loading.load"\nstart = 1.0\nstop = 2.0', "missing num"),
    ('key = "loading.load"\nvalues = [1.0]\nstart = 1.0', "either values"),
    ('key = "indenter.shape"\nstart = 1.0\nstop = 2.0\nnum = 2', "a range needs a numeric key"),
])
def test_bad_axes_are_clear_errors(tmp_path, axis, message):
    path = write(tmp_path, f"[[axis]]\n{axis}\n")
    with pytest.raises(SweepError) as err:
        read_sweep(path)
    assert message in str(err.value)


def test_a_point_that_breaks_the_schema_is_named(tmp_path):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nvalues = [10.0, -5.0]\n')
    with pytest.raises(SweepError, match=r"point 1 \(loading.load = -5.0\).*load must be > 0 N, got -5.0"):
        expand(read_sweep(path))


def test_zip_of_unequal_axes(tmp_path):
    path = write(tmp_path, 'combine = "zip"\n[[axis]]\nkey = "loading.load"\nvalues = [1.0, 2.0]\n'
                           '[[axis]]\nkey = "loading.speed"\nvalues = [0.1]\n')
    with pytest.raises(SweepError, match="equal length, got loading.load: 2, loading.speed: 1"):
        read_sweep(path)


def test_cli_refuses_bad_input_before_running(tmp_path, capsys):
    path = write(tmp_path, '[[axis]]\nkey = "loading.weight"\nvalues = [1.0]\n')
    out = tmp_path / "out"
    assert main([str(path), "--out", str(out)]) == 2
    assert "sweep: error:" in capsys.readouterr().err
    assert not out.exists()


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_a_scheduler_that_does_not_answer(tmp_path, capsys):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nvalues = [10.0]\n')
    out = tmp_path / "out"
    address = f"tcp://127.0.0.1:{_closed_port()}"
    t0 = time.perf_counter()
    assert main([str(path), "--out", str(out), "--scheduler", address, "--timeout", "1", "--no-cache"]) == 2
    assert time.perf_counter() - t0 < 20
    err = capsys.readouterr().err
    assert f"--scheduler {address}: no Dask scheduler answers at {address} within 1 s" in err
    assert not (out / "results.csv").exists()


def test_every_shipped_sweep_file_checks(capsys):
    files = sorted((ROOT / "examples" / "sweeps").glob("*.toml"))
    sweeps = [f for f in files if not f.name.startswith("base-")]
    assert len(sweeps) >= 10
    for f in sweeps:
        assert main([str(f), "--check"]) == 0, f
    out = capsys.readouterr().out
    assert "sweep fig7a-load-H5: 30 points over case (2), loading.load (15), combined as product; 1 kernel set(s)" in out
    assert "sweep fig10a-speed-H1: 52 points over loading.load (4), loading.speed (13), combined as product; " \
           "13 kernel set(s)" in out
