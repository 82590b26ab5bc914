"""The BEM runs its BLAS on one thread unless the user set a thread count
(:mod:`bem.threads`), observed from inside a solve through its progress callback."""

import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from bem import Elastic, Grid, Layer, Loading, Paraboloid, Problem, solve
from bem.threads import THREAD_VARIABLES, cores


def _blas_threads() -> set[int]:
    return {lib["num_threads"] for lib in threadpool_info() if lib["user_api"] == "blas"}


def _threads_during_solve() -> set[int]:
    seen: set[int] = set()
    grid = Grid.centred((0.5e-3, 0.5e-3), (0.05, 0.05), (100, 100), (3e-3, 3e-3))
    problem = Problem(Layer(0.01, Elastic(3e6), 0.0), Paraboloid(0.02), grid, Loading(0.0, load=20.0))
    solve(problem, progress=lambda line: seen.update(_blas_threads()))
    return seen


@pytest.fixture
def two_blas_threads(monkeypatch):
    for name in THREAD_VARIABLES:
        monkeypatch.delenv(name, raising=False)
    if not _blas_threads():
        pytest.skip("no BLAS library that threadpoolctl can see")
    with threadpool_limits(limits=2, user_api="blas"):
        yield


def test_a_solve_runs_its_blas_on_one_thread_and_restores_the_count(two_blas_threads):
    assert _threads_during_solve() == {1}
    assert _blas_threads() == {2}


@pytest.mark.parametrize("variable", THREAD_VARIABLES)
def test_a_thread_count_the_user_set_is_kept(two_blas_threads, monkeypatch, variable):
    monkeypatch.setenv(variable, "2")
    assert _threads_during_solve() == {2}


def test_the_grid_error_solves_run_their_blas_on_one_thread(two_blas_threads):
    """``bem solve``'s default grid error solves the coarse levels outside the driver
    (:func:`bem.frictional.grid_error.estimate_grid_error`): they too run on one thread."""
    from bem.frictional import Friction
    from bem.frictional.grid_error import estimate_grid_error

    seen: set[int] = set()
    grid = Grid.centred((0.2e-3, 0.2e-3), (0.05, 0.05), (125, 125), (4e-3, 4e-3))
    problem = Problem(Layer(0.01, Elastic(3e6), 0.0), Paraboloid(0.02), grid, Loading(1.0, load=5.0))
    friction = Friction(0.2, "omega", omega=0.99 / 0.02)
    fine = solve(problem, friction)
    estimate_grid_error(problem, friction, fine=fine, progress=lambda line: seen.update(_blas_threads()))
    assert seen == {1}
    assert _blas_threads() == {2}


def test_the_cores_a_process_may_use(monkeypatch):
    """:func:`bem.threads.cores`: the CPU affinity, at most ``OMP_NUM_THREADS`` when it is a
    positive integer (ignored otherwise); a process pinned to one core runs one thread of
    its own (the transforms of a large grid on one worker)."""
    from bem.operator import fft_workers

    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    monkeypatch.setattr("os.sched_getaffinity", lambda pid: {0, 1, 2, 3})
    assert cores() == 4
    for value, expected in (("2", 2), ("8", 4), ("0", 4), ("two", 4), (" 1 ", 1)):
        monkeypatch.setenv("OMP_NUM_THREADS", value)
        assert cores() == expected, value
    monkeypatch.delenv("OMP_NUM_THREADS")
    monkeypatch.setattr("os.sched_getaffinity", lambda pid: {3})
    assert cores() == 1 and fft_workers((1000, 1000)) == 1


def _blas_threads_in_a_command_process(**env) -> set[int]:
    """The BLAS thread counts of a fresh process that starts as the ``bem`` command does
    (:func:`bem.threads.one_blas_thread_from_start`, then numpy), under ``env`` on top of
    this one's without the thread variables."""
    import json
    import os
    import subprocess
    import sys

    code = ("from bem.threads import one_blas_thread_from_start\n"
            "one_blas_thread_from_start()\n"
            "import json, numpy\n"
            "from threadpoolctl import threadpool_info\n"
            "print(json.dumps(sorted({l['num_threads'] for l in threadpool_info() if l['user_api'] == 'blas'})))\n")
    clean = {k: v for k, v in os.environ.items() if k not in THREAD_VARIABLES}
    done = subprocess.run([sys.executable, "-c", code], env={**clean, **env}, capture_output=True, text=True,
                          timeout=60, check=True)
    return set(json.loads(done.stdout))


def test_the_command_loads_its_blas_with_one_thread_unless_the_user_chose(two_blas_threads):
    """The ``bem`` command sets the count before numpy loads: OpenBLAS then starts no
    threads of its own (they spun while numpy loaded); a count the user set is kept."""
    assert _blas_threads_in_a_command_process() == {1}
    assert _blas_threads_in_a_command_process(OPENBLAS_NUM_THREADS="2") == {2}
