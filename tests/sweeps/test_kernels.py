"""Kernel reuse, measured: one compliance per layer, material, speed and grid; the kernel
tables of a wider region serve a narrower one exactly; the on-disk cache."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import bem.problem
from bem.case import problem_from_config
from bem.problem import compute_kernels
from bem.spectral import BLOCKS
from sweeps import expand, fit_kernels, kernel_key, read_sweep, run_sweep

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "examples" / "sweeps" / "base-frictionless.toml"
FRICTION = ROOT / "examples" / "sweeps" / "base-friction.toml"
COARSE = '["grid.spacing=1e-3", "grid.truncation=100"]'


@pytest.fixture(scope="module")
def client():
    from distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0")
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()


def load_sweep(tmp_path: Path, case: str, loads: int = 10) -> Path:
    path = tmp_path / "loads.toml"
    path.write_text(f'case = {case}\nset = {COARSE}\n[[axis]]\nkey = "loading.load"\n'
                    f'start = 15.0\nstop = 150.0\nnum = {loads}\n')
    return path



def _count_kernel_sets(monkeypatch) -> list:
    """The ``blocks`` of every kernel set formed from now on (with or without power tables)."""
    calls = []
    for name in ("influence_kernels", "kernels_with_power"):
        real = getattr(bem.problem, name)
        monkeypatch.setattr(bem.problem, name, lambda *a, _real=real, **k: calls.append(k.get("blocks")) or _real(*a, **k))
    return calls

def test_a_wider_regions_tables_serve_a_narrower_one(tmp_path):
    points = expand(read_sweep(load_sweep(tmp_path, f'"{FRICTION}"', 2)))
    small, _ = problem_from_config(points[0].config)
    wide = replace(small, grid=replace(small.grid, nodes_x=small.grid.nodes_x + 8, nodes_y=small.grid.nodes_y + 4))
    direct, _ = compute_kernels(small, tuple(BLOCKS))
    cut = fit_kernels(compute_kernels(wide, tuple(BLOCKS))[0], small.grid)
    for b in BLOCKS:
        assert cut[b].shape == direct[b].shape
        np.testing.assert_allclose(cut[b], direct[b], rtol=0, atol=1e-12 * np.abs(direct[b]).max())
    with pytest.raises(ValueError, match="cannot serve a grid"):
        fit_kernels(direct, wide.grid)


def test_kernel_key_holds_what_the_compliance_depends_on(tmp_path):
    path = tmp_path / "k.toml"
    path.write_text(f'case = ["{BASE}", "{FRICTION}"]\n[[axis]]\nkey = "loading.load"\nvalues = [20.0, 150.0]\n')
    points = expand(read_sweep(path))
    keys = {kernel_key(p.config, problem_from_config(p.config)[0]) for p in points}
    assert len(keys) == 1  # load and friction do not enter
    for override in ("loading.speed=0.1", "layer.thickness=6e-3", "grid.truncation=600", "material.tau=0.3",
                     "layer.density=0.0"):
        path.write_text(f'case = "{BASE}"\nset = ["{override}"]\n[[axis]]\nkey = "loading.load"\nvalues = [20.0]\n')
        [p] = expand(read_sweep(path))
        assert kernel_key(p.config, problem_from_config(p.config)[0]) not in keys, override


def test_a_ten_load_sweep_forms_one_kernel(tmp_path, client, monkeypatch):
    """Counted where kernels are formed (bem.problem.influence_kernels, in this process's
    threaded workers), not taken from the sweep's own report."""
    calls = _count_kernel_sets(monkeypatch)
    sweep = read_sweep(load_sweep(tmp_path, f'"{BASE}"'))
    report = run_sweep(sweep, tmp_path / "out", client=client, cache=tmp_path / "cache", stream=None)
    assert report.computed == 10 and report.failed == 0
    assert len(calls) == 1 and report.kernels_formed == 1 and report.groups == 1
    nodes = sorted({int(r["nodes_x"]) for r in report.rows})
    assert len(nodes) > 2  # the region grows with the load: the set is cut for each point
    assert all(float(r["kernel_s"]) == 0.0 for r in report.rows)
    # the same points solved one by one, each forming its own kernel: the same numbers
    for r, p in zip(report.rows[::3], expand(sweep)[::3]):
        problem, auto = problem_from_config(p.config)
        alone = bem.solve(problem, grow=auto)
        assert alone.record.times["kernel_s"] > 0
        assert float(r["rolling_resistance"]) == pytest.approx(alone.rolling_resistance, rel=1e-12)

    # a rerun in a new folder takes the kernel set from the disk cache (points too)
    calls.clear()
    again = run_sweep(sweep, tmp_path / "out2", client=client, cache=tmp_path / "cache", stream=None)
    assert again.resumed == 10 and again.computed == 0 and calls == []
    for f in (tmp_path / "cache" / "points").glob("*.json"):
        f.unlink()
    third = run_sweep(sweep, tmp_path / "out3", client=client, cache=tmp_path / "cache", stream=None)
    assert third.computed == 10 and third.kernels_from_cache == 1 and third.kernels_formed == 0 and calls == []
    cols = ("rolling_resistance", "rolling_resistance_energy", "contact_radius")
    assert [[r[c] for c in cols] for r in third.rows] == [[r[c] for c in cols] for r in report.rows]


def test_friction_and_frictionless_points_share_nine_blocks(tmp_path, client, monkeypatch):
    calls = _count_kernel_sets(monkeypatch)
    sweep = read_sweep(load_sweep(tmp_path, f'["{BASE}", "{FRICTION}"]', 2))
    report = run_sweep(sweep, tmp_path / "out", client=client, cache=None, stream=None)
    assert report.failed == 0 and report.computed == 4
    assert len(calls) == 1 and set(calls[0]) == set(BLOCKS)
    rows = {(r["case"], float(r["loading.load"])): r for r in report.rows}
    fr = rows[("base-friction", 150.0)]
    # the friction share is the friction's part of the dissipated power
    assert float(fr["friction_share"]) == pytest.approx(
        float(fr["rolling_resistance_friction"]) / float(fr["rolling_resistance_energy"]), rel=1e-12)
    # without friction the two figures of R_r agree to the exact sphere's O(r^2/R^2) (bem.frictional)
    no = rows[("base-frictionless", 150.0)]
    r2 = (float(no["contact_radius"]) / 0.02) ** 2
    assert abs(float(no["rolling_resistance_energy"]) / float(no["rolling_resistance"]) - 1) < 2 * r2
