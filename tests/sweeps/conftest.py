"""Fixtures of the sweep tests: the `sweep` command run in this process on a threaded
Dask cluster (starting a process cluster per command would cost seconds each)."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "examples" / "sweeps" / "base-frictionless.toml"
#: a coarse grid (a = 1 mm, Nt = 100): a point solves in tens of milliseconds
COARSE = '["grid.spacing=1e-3", "grid.truncation=100"]'


@pytest.fixture(scope="module")
def threaded_cluster():
    from distributed import LocalCluster

    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0")
    yield cluster
    cluster.close()


@pytest.fixture(scope="module")
def sweep_command(threaded_cluster):
    """``run(*args) -> (exit status, stderr)``: ``sweep ARGS`` with the local cluster
    replaced by a client of the module's threaded cluster."""
    import contextlib
    import io

    from distributed import Client

    import sweeps.engine
    from sweeps.cli import main

    def run(*args):
        err = io.StringIO()
        with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stderr(err):
            mp.setattr(sweeps.engine, "connect", lambda *a, **k: Client(threaded_cluster.scheduler_address))
            code = main([str(a) for a in args])
        return code, err.getvalue()

    return run


@pytest.fixture(scope="module")
def load_sweep_file(tmp_path_factory):
    """``make(loads, name=None, axis="loading.load") -> path``: a frictionless sweep file on
    the coarse grid."""
    folder = tmp_path_factory.mktemp("sweep-files")

    def make(values=(20.0, 80.0, 150.0), name=None, axis="loading.load", file="s.toml"):
        path = folder / file
        head = f'name = "{name}"\n' if name is not None else ""
        path.write_text(f'{head}case = "{BASE}"\nset = {COARSE}\n[[axis]]\nkey = "{axis}"\n'
                        f'values = [{", ".join(repr(float(v)) for v in values)}]\n')
        return path

    return make
