"""What a small ``bem solve`` loads: only the modules it uses. scipy.fft's import is about a
third of a small run (:mod:`bem.fft`); zipfile (with shutil, bz2, lzma), json and
concurrent.futures (with logging) took 5.4, 1.4 and 3.7 ms of every start when loaded
for a height map's errors, ``--json`` and threads a one-core run never starts, and
argparse's own formatter imports shutil (2.8 ms; :class:`bem.cli._Formatter`)."""

import os
import subprocess
import sys
from pathlib import Path

CASE = Path(__file__).resolve().parents[2] / "examples" / "elastic-paraboloid-creepage.toml"
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
