"""The cluster path for real (a ``dask scheduler`` and a ``dask worker`` started as
processes on localhost), and a sweep killed half-way that a rerun finishes."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sweeps import read_sweep, run_sweep
from sweeps.cli import main
from sweeps.paper import read_table
from tests.sweeps.dask_processes import dask_cluster  # noqa: F401 (a fixture)

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "examples" / "sweeps" / "base-frictionless.toml"
FRICTION = ROOT / "examples" / "sweeps" / "base-friction.toml"
TIMING = {"seconds", "kernel_s", "solve_s", "energy_s", "checksum"}  # the checksum covers the timings


def sweep_file(tmp_path: Path, loads: int) -> Path:
    path = tmp_path / "small.toml"
    path.write_text(f'case = ["{BASE}", "{FRICTION}"]\nset = ["grid.spacing=1e-3", "grid.truncation=100"]\n'
                    f'[[axis]]\nkey = "loading.load"\nstart = 20.0\nstop = 150.0\nnum = {loads}\n')
    return path


def without_timings(rows):
    return [{k: v for k, v in r.items() if k not in TIMING} for r in rows]


def assert_same_numbers(rows, other, rel=1e-9):
    """Equal cells, numbers to ``rel`` (the killed run's workers were processes with
    single-threaded BLAS, the rerun's are threads: sums may round differently)."""
    assert len(rows) == len(other)
    for r, o in zip(without_timings(rows), without_timings(other)):
        assert r.keys() == o.keys()
        for k in r:
            try:
                assert float(r[k]) == pytest.approx(float(o[k]), rel=rel, abs=1e-300), (r["index"], k)
            except ValueError:
                assert r[k] == o[k], (r["index"], k)


def test_a_sweep_on_a_running_cluster_gives_the_local_table(tmp_path, dask_cluster, capsys):
    path = sweep_file(tmp_path, 3)
    assert main([str(path), "--scheduler", dask_cluster, "--out", str(tmp_path / "remote"), "--no-cache",
                 "--no-plots", "--quiet"]) == 0
    summary = json.loads((tmp_path / "remote" / "summary.json").read_text())
    assert summary["scheduler"] == dask_cluster and summary["workers"] == 1 and summary["kernels_formed"] == 1
    assert main([str(path), "--workers", "1", "--out", str(tmp_path / "local"), "--no-cache", "--no-plots",
                 "--quiet"]) == 0
    remote, local = (read_table(tmp_path / f / "results.csv") for f in ("remote", "local"))
    assert len(remote) == 6 and all(r["status"] == "ok" for r in remote)
    assert without_timings(remote) == without_timings(local)


def test_a_killed_sweep_resumes_with_only_the_rest(tmp_path):
    from distributed import Client, LocalCluster

    path = sweep_file(tmp_path, 8)
    out = tmp_path / "out"
    table = out / "results.csv"
    proc = subprocess.Popen([str(Path(sys.executable).with_name("sweep")), str(path), "--workers", "1", "--out",
                             str(out), "--no-cache", "--no-plots", "--quiet"], start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and proc.poll() is None:
            if table.exists() and len(table.read_text().splitlines()) >= 1 + 5:
                break
            time.sleep(0.01)
        assert proc.poll() is None, "the sweep ended before it could be killed half-way"
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the sweep, its local cluster and its worker
        proc.wait()
    kept = read_table(table)
    assert 5 <= len(kept) < 16 and all(r["status"] == "ok" for r in kept)
    sweep = read_sweep(path)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        again = run_sweep(sweep, out, client=client, cache=None, stream=None)
        fresh = run_sweep(sweep, tmp_path / "fresh", client=client, cache=None, stream=None)
    assert again.resumed == len(kept) and again.computed == 16 - len(kept)
    assert_same_numbers(again.rows, fresh.rows)
    by_index = {r["index"]: r for r in again.rows}
    assert all(by_index[r["index"]] == r for r in kept)  # the finished rows are kept as they were
