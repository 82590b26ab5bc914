"""``--help`` of the four commands answers at once (it loads neither numpy nor the solvers)
and says the options' defaults and the exit codes."""

import subprocess
import sys

import pytest

COMMANDS = {"bem.cli": ["solve", "--help"], "fem_reference.cli": ["solve", "--help"],
            "verification.cli": ["--help"], "sweeps.cli": ["--help"]}

PROBE = """
import contextlib, io, sys, importlib
module = importlib.import_module(sys.argv[1])
out = io.StringIO()
with contextlib.redirect_stdout(out):
    try:
        module.main(sys.argv[2:])
    except SystemExit as exc:
        assert exc.code == 0, exc.code
heavy = sorted(m for m in ("numpy", "scipy", "matplotlib", "dask", "skfem") if m in sys.modules)
print(heavy)
print(out.getvalue())
"""


@pytest.mark.parametrize("module", COMMANDS)
def test_help_loads_no_numerical_library_and_says_defaults_and_exit_codes(module):
    done = subprocess.run([sys.executable, "-c", PROBE, module, *COMMANDS[module]], capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    loaded, text = done.stdout.split("\n", 1)
    assert loaded == "[]", f"{module} --help imports {loaded}"
    flat = " ".join(text.split())
    assert "exit" in flat.lower() and "2 bad input" in flat, text  # the exit codes, bad input among them
    assert "default" in flat, text


def test_verify_default_cases_folder_is_the_runners():
    from verification import cli, runner

    assert cli.CASES_DIR == runner.CASES_DIR
