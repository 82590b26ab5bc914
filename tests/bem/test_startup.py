"""What a small ``bem solve`` loads: only the modules it uses. scipy.fft's import (0.135 s,
:mod:`bem.fft`) is about half of a small run; the kernels' lattice sums and a line contact's
chirp-z sums do without it. zipfile (with shutil, bz2, lzma), json and
concurrent.futures (with logging) took 5.4, 1.4 and 3.7 ms of every start when loaded
for a height map's errors, ``--json`` and threads a one-core run never starts, and
argparse's own formatter imports shutil (2.8 ms; :class:`bem.cli._Formatter`)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CASE = EXAMPLES / "elastic-paraboloid-creepage.toml"
UNUSED = ("scipy.fft", "scipy.ndimage", "scipy.special", "scipy.sparse", "shutil", "zipfile", "json",
          "concurrent.futures", "logging", "threadpoolctl")


def test_a_small_frictional_solve_on_one_core_loads_no_module_it_does_not_use():
    code = ("import sys\n"
            "from bem.cli import main\n"
            f"assert main(['solve', {str(CASE)!r}, '--quiet', "
            "'--no-error-estimate', '--set', 'grid.spacing=0.4e-3', '--set', 'grid.truncation=750']) == 0\n"
            f"print(sorted(m for m in {UNUSED!r} if m in sys.modules))\n")
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.splitlines()[-1] == "[]"


def test_a_line_contact_loads_no_scipy():
    """A plane-strain solve (examples/rolling-line-2d.toml, 201 nodes): its kernels' and
    dissipation's chirp-z sums run on one thread in numpy.fft, so the process imports
    neither scipy.fft nor, through it, scipy.special (0.14 s together; the whole run takes
    0.12 s)."""
    code = ("import sys\n"
            "from bem.cli import main\n"
            f"assert main(['solve', {str(EXAMPLES / 'rolling-line-2d.toml')!r}, '--quiet']) == 0\n"
            f"print(sorted(m for m in {UNUSED!r} if m in sys.modules))\n")
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.splitlines()[-1] == "[]"


def test_lattice_kernels_above_128_nodes_a_side_load_no_scipy_fft():
    """The kernels of a grid of more than 128 nodes a side whose period is a whole number
    of node pairs (``L = 2 Q a``: the DCT-I / DST-I sums of :mod:`bem.mode_sums`) run in
    numpy.fft: a one-core process does not import scipy.fft for them (0.135 s)."""
    code = ("import sys\n"
            "from bem import Elastic, Grid, Layer, Loading, Paraboloid, Problem\n"
            "from bem.mode_sums import lattice_half\n"
            "from bem.problem import compute_kernels\n"
            "from bem.spectral import BLOCKS\n"
            "grid = Grid.centred((1e-4, 1e-4), (0.06, 0.06), (300, 300), (6.4e-3, 6.4e-3))\n"
            "assert grid.shape == (129, 129) and lattice_half(1e-4 / 0.06, 301, 129) == 300\n"
            "problem = Problem(Layer(0.02, Elastic(3e6), 0.0), Paraboloid(0.02), grid, Loading(1.0, load=10.0))\n"
            "compute_kernels(problem, BLOCKS)\n"
            f"print(sorted(m for m in {UNUSED!r} if m in sys.modules))\n")
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout
    assert out.splitlines()[-1] == "[]"


def test_a_default_run_below_the_threaded_transforms_loads_no_scipy():
    """Section 11 frictionless at 161 x 161 nodes (embedding 324 x 324, 105 000 points, below
    :data:`bem.operator.IMPORT_PAYS_FROM`) run as a user starts it, every core available: its
    transforms stay on one thread in numpy.fft, and scipy.fft's import (0.135 s, as long as
    the solve) is not paid. On a one-core machine this holds trivially."""
    code = ("import sys\n"
            "from bem.cli import main\n"
            f"assert main(['solve', {str(EXAMPLES / 'paper-section11-frictionless.toml')!r}, '--quiet', "
            "'--set', 'grid.spacing=6.25e-5', '--set', 'grid.truncation=4000']) == 0\n"
            "print(sorted(m for m in ('scipy.fft', 'scipy.special') if m in sys.modules))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PATH": "/usr/bin:/bin"}).stdout
    assert out.splitlines()[-1] == "[]"


def test_the_help_formatter_takes_the_terminal_width_from_columns(monkeypatch):
    from bem.cli import _Formatter

    monkeypatch.setenv("COLUMNS", "100")
    assert _Formatter("bem")._width == 98
    assert _Formatter("bem", width=60)._width == 60
    monkeypatch.setenv("COLUMNS", "wide")  # not a number: the terminal's width, or 80 without one
    monkeypatch.setattr("os.get_terminal_size", lambda fd: os.terminal_size((120, 40)))
    assert _Formatter("bem")._width == 118

    def no_terminal(fd):
        raise OSError("not a terminal")

    monkeypatch.setattr("os.get_terminal_size", no_terminal)
    assert _Formatter("bem")._width == 78


def test_the_command_collects_no_garbage_while_it_loads_and_does_during_the_solve():
    """``bem solve`` as its own process (``command``) pauses the cyclic collector while
    numpy and the solver's modules load (their objects live to the end) and freezes them;
    the solve, whose active-set iterations leave cycles, runs with the collector on. In
    process, ``main`` leaves the collector alone."""
    code = ("import gc, sys\n"
            "import bem.cli, bem.driver\n"
            "seen = []\n"
            "solve = bem.driver.solve\n"
            "def watched(*a, **k):\n"
            "    seen.append((gc.isenabled(), gc.get_freeze_count() > 0))\n"
            "    return solve(*a, **k)\n"
            "bem.driver.solve = watched\n"
            "argv = ['solve', sys.argv[1], '--quiet', '--no-error-estimate', '--set', 'grid.spacing=0.4e-3',"
            " '--set', 'grid.truncation=750']\n"
            "assert bem.cli.main(argv) == 0 and seen == [(True, False)], seen\n"
            "bem.cli._pause_collection()\n"
            "assert not gc.isenabled()\n"
            "assert bem.cli.main(argv) == 0 and seen[1] == (True, True), seen\n"
            "print('ok')\n")
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", code, str(CASE)], capture_output=True, text=True, env=env)
    assert out.stdout.splitlines()[-1] == "ok", out.stderr


def _glibc() -> bool:
    try:
        return (os.confstr("CS_GNU_LIBC_VERSION") or "").startswith("glibc")
    except (AttributeError, ValueError, OSError):
        return False


@pytest.mark.skipif(not _glibc(), reason="the allocator settings are glibc's")
def test_the_command_keeps_freed_memory_on_small_grids_only():
    """glibc's default gives a solve's arrays of a few hundred KiB to a few MiB back to the
    system and faults their pages in again at the next (:func:`bem.cli._keep_freed_memory`):
    two 1 MiB arrays made and freed 20 times, 10 240 pages written, fault about that many;
    with the command's settings almost none. Only the command sets them (not ``main`` in
    someone's process), only for grids up to ``KEEP_FREED_UPTO`` nodes, and never over a
    user's own ``MALLOC_*`` variables."""
    code = ("import resource, numpy as np\n"
            "import bem.cli as c\n"
            "def faults():\n"
            "    start = resource.getrusage(resource.RUSAGE_SELF).ru_minflt\n"
            "    for _ in range(20):\n"
            "        a, b = np.ones(1 << 17), np.ones(1 << 17)\n"
            "        del a, b\n"
            "    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - start\n"
            "faults()\n"
            "assert not c._keep_freed_memory(100)\n"
            "c._own_process = True\n"
            "assert not c._keep_freed_memory(c.KEEP_FREED_UPTO + 1)\n"
            "default = faults()\n"
            "assert c._keep_freed_memory(c.KEEP_FREED_UPTO)\n"
            "print(default, faults())\n")
    env = {"PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    default, kept = map(int, out.stdout.split())
    assert default > 5000 and kept < 1000, (default, kept)
    users = subprocess.run([sys.executable, "-c", "import bem.cli as c\nc._own_process = True\n"
                            "print(c._keep_freed_memory(100))"], capture_output=True, text=True,
                           env={**env, "MALLOC_TOP_PAD_": "1048576"})
    assert users.stdout.split() == ["False"], users.stderr
