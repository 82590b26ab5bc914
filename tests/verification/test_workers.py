"""`verify --workers N` and `verify --scheduler ADDRESS`: the cases side by side on Dask
give the serial run's metrics.json (timings aside), its figures and its order of cases; a
worker that dies fails its case, not the run; SIGTERM or Ctrl-C ends the run and its local
cluster; bad flags are usage errors naming the flag."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import psutil
import pytest

from tests.sweeps.dask_processes import dask_cluster  # noqa: F401 (a fixture)
from tests.verification.small_cases import THICK_LAYER_CASE, default_sigint
from verification.cli import main as verify_main

#: two of the cheapest cases of --quick, of two kinds (stationary BEM and FEM; rolling limits)
CASES = ("halfspace-hertz", "rolling-limits")
VERIFY = Path(sys.executable).with_name("verify")

#: a method from a .py file (it must travel to the workers by value): Hertz's contact on a
#: half-space (E* = 4G), every helper in the file
PLUGIN = '''
import numpy as np
from verification.results import Run

def radius(G, P, R):
    return (3 * P * R / (16 * G)) ** (1 / 3)

def solve(problem, level):
    G, P = problem["material"]["shear_modulus"], problem["loading"]["load"]
    R = problem["indenter"]["radius"]
    a = radius(G, P, R)
    r = np.linspace(0.0, 1.5 * a, 31)
    p0 = 3 * P / (2 * np.pi * a**2)
    return Run("hertz", level.size, {"contact_radius": a, "indentation": a * a / R, "peak_pressure": p0,
                                     "load": P}, r, p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0, None)))
'''


def without_timings(doc):
    """metrics.json without its timings: every ``seconds`` (of a case and of a run)."""
    if isinstance(doc, dict):
        return {k: without_timings(v) for k, v in doc.items() if k != "seconds"}
    if isinstance(doc, list):
        return [without_timings(v) for v in doc]
    return doc


def metrics(folder: Path) -> dict:
    return without_timings(json.loads((folder / "metrics.json").read_text()))


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    """The two cases run one after another in this process, with the Hertz plugin, BLAS
    on one thread as in a worker: the FEM's sparse factorization sums in another order on
    two threads, and the last digits of its figures (and the convergence orders of figures
    converged to rounding) then differ between any two runs that do not share a thread
    count."""
    from threadpoolctl import threadpool_limits

    root = tmp_path_factory.mktemp("serial")
    (root / "hertz_plugin.py").write_text(PLUGIN)
    args = [a for c in CASES for a in ("--case", c)] + ["--method", f"hertz={root / 'hertz_plugin.py'}:solve"]
    with threadpool_limits(limits=1, user_api="blas"):
        assert verify_main([*args, "--quick", "--out", str(root / "report")]) == 1  # Hertz misses the layer's d
    return args, root / "report"


def test_two_workers_give_the_serial_report(serial, tmp_path, capsys):
    """Equal numbers, bit for bit, with BLAS on one thread in the serial run as in each
    worker; the same cases and gates in the same order; the same figures."""
    args, serial_out = serial
    capsys.readouterr()
    assert verify_main([*args, "--quick", "--workers", "2", "--out", str(tmp_path / "par")]) == 1
    err = capsys.readouterr().err
    assert metrics(tmp_path / "par") == metrics(serial_out)
    assert [c["name"] for c in metrics(tmp_path / "par")["cases"]] == list(CASES)
    figures = sorted(p.name for p in serial_out.glob("*.png"))
    assert figures and sorted(p.name for p in (tmp_path / "par").glob("*.png")) == figures
    for i, name in enumerate(CASES, 1):  # its start, a forwarded line of its own, its verdict
        assert f"[{i}/2] {name}: " in err and "(on tcp://" in err, err
        assert f"  {name}: V = " in err or f"  {name}: bem h = " in err, err
        assert f"  {name}: PASS" in err or f"  {name}: FAIL" in err, err


def test_a_scheduler_of_its_own_gives_the_serial_case(serial, tmp_path, dask_cluster):  # noqa: F811
    """`dask scheduler` and `dask worker` as processes; verify reaches them through the
    scheduler file."""
    args, serial_out = serial
    info = tmp_path / "scheduler.json"
    one = ["--case", CASES[0], *args[-2:]]  # halfspace-hertz and the plugin
    assert verify_main([*one, "--quick", "--scheduler", str(info), "--out", str(tmp_path / "remote")]) == 1
    (case,) = metrics(tmp_path / "remote")["cases"]
    assert case == metrics(serial_out)["cases"][0]


def _write_cases(folder: Path, plugin: Path) -> None:
    folder.mkdir()
    (folder / "hs.toml").write_text(THICK_LAYER_CASE)
    dies = THICK_LAYER_CASE.replace('name = "hs"', 'name = "dies"').replace('["bem"]', '["exits"]')
    (folder / "dies.toml").write_text(dies + f'[methods.exits]\nentry = "{plugin}:solve"\n')


def test_a_worker_that_dies_fails_its_case_and_the_run_goes_on(tmp_path, capsys):
    plugin = tmp_path / "exits.py"
    plugin.write_text("import os\n\ndef solve(problem, level):\n    os._exit(3)\n")
    _write_cases(tmp_path / "cases", plugin)
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(tmp_path / "cases"), "--workers", "1", "--out", str(out)]) == 1
    doc = json.loads((out / "metrics.json").read_text())
    dies, hs = doc["cases"]
    assert (dies["name"], dies["passed"], hs["name"], hs["passed"]) == ("dies", False, "hs", True)
    (gate,) = dies["gates"]
    assert gate["quantity"] == "run" and "KilledWorker" in gate["reason"], gate["reason"]


@pytest.mark.parametrize("group", [False, True], ids=["SIGTERM to verify", "Ctrl-C to the process group"])
def test_an_interrupt_ends_the_run_and_its_local_cluster(group, tmp_path):
    cases = tmp_path / "cases"
    cases.mkdir()
    slow = THICK_LAYER_CASE.replace("spacings = [0.2e-3]", "spacings = [0.2e-3, 0.1e-3, 0.05e-3, 0.025e-3]")
    (cases / "hs.toml").write_text(slow)
    out = tmp_path / "out"
    proc = subprocess.Popen([str(VERIFY), "--cases-dir", str(cases), "--workers", "1", "--out", str(out)],
                            stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=default_sigint)
    try:
        family = psutil.Process(proc.pid)
        for line in proc.stderr:  # the case has started on the worker
            if "(on tcp://" in line:
                break
        workers = family.children(recursive=True)
        assert workers, "no worker process"
        if group:  # what a terminal does: the workers get it too, and ignore it
            os.killpg(proc.pid, signal.SIGINT)
        else:
            proc.send_signal(signal.SIGTERM)
        assert proc.wait(timeout=60) == 130
        err = proc.stderr.read()
        assert "interrupted after 0 of 1 cases" in err and "Traceback" not in err, err
        gone, alive = psutil.wait_procs(workers, timeout=10)
        assert not alive, alive
        assert not out.exists()
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def _environment():
    import os

    return {k: os.environ.get(k) for k in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS",
                                           "MALLOC_TRIM_THRESHOLD_")}


def test_a_local_worker_runs_blas_on_one_thread_and_allocates_as_a_process_does(monkeypatch):
    """One BLAS thread; and not Dask's MALLOC_TRIM_THRESHOLD_, which fixes glibc's mmap
    threshold (the rolling-limits case took 6.1-6.8 s in a process with it, 1.7-2.7 s
    without)."""
    from verification.parallel import close_client, open_client

    for name in _environment():
        monkeypatch.delenv(name, raising=False)
    client = open_client(workers=1)
    try:
        (env,) = client.run(_environment).values()
    finally:
        close_client(client)
    assert env == {"OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "OMP_NUM_THREADS": "1",
                   "MALLOC_TRIM_THRESHOLD_": None}


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize("flags, said", [
    (["--workers", "0"], "argument --workers: must be >= 1"),
    (["--workers", "-2"], "argument --workers: must be >= 1"),
    (["--workers", "two"], "argument --workers: must be a whole number"),
    (["--workers", "1.5"], "argument --workers: must be a whole number"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:8786"], "not allowed with argument --workers"),
])
def test_bad_workers_flags_are_usage_errors(flags, said, tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        verify_main(["--case", "halfspace-hertz", *flags, "--out", str(tmp_path / "out")])
    assert exc.value.code == 2
    assert said in capsys.readouterr().err


@pytest.mark.parametrize("where, said", [
    ("tcp://127.0.0.1:{port}", "no Dask scheduler answers at tcp://127.0.0.1:"),
    ("{tmp}/none.json", "no such scheduler file"),
])
def test_an_unreachable_scheduler_is_a_usage_error(where, said, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("verification.parallel.TIMEOUT", 1.0)  # Dask retries a refused connection until then
    scheduler = where.format(port=_closed_port(), tmp=tmp_path)
    t0 = time.perf_counter()
    code = verify_main(["--case", "halfspace-hertz", "--scheduler", scheduler, "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and f"verify: error: --scheduler {scheduler}: " in err and said in err, err
    assert not (tmp_path / "out").exists() and time.perf_counter() - t0 < 10
