"""``bem solve`` where the user meets it: interrupted (SIGINT, SIGTERM: exit 130 and no
file), read through a closed pipe (a quiet end), and each input that once ended in a
traceback or a silent answer, now an error naming it (exit 2)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bem.cli import main

ROOT = Path(__file__).resolve().parents[1]
SMALL = """
[layer]
thickness = 0.01
[material]
model = "elastic"
shear_modulus = 1e6
[indenter]
shape = "sphere"
radius = 0.02
[loading]
load = 1.0
[grid]
spacing = 1e-3
period = 0.1
truncation = 64
"""
#: a rolling case whose run lasts most of a second after its first progress line (the
#: paper's section 11 grid: the active set and the energy figure, 0.05 s, then the plot's
#: matplotlib import and drawing, 0.8 s, before anything is written)
LONG = ROOT / "examples" / "paper-section11-frictionless.toml"


@pytest.fixture
def small(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    return path


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_solve_exits_130_and_writes_nothing(tmp_path, sig):
    fields, plot = tmp_path / "f.npz", tmp_path / "p.png"
    proc = subprocess.Popen([sys.executable, "-m", "bem.cli", "solve", str(LONG), "--fields", str(fields),
                             "--plot", str(plot)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    first = proc.stderr.readline()  # the solve has started: its first progress line
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=120)
    assert first and proc.returncode == 130, (first, err)
    assert f"bem: interrupted ({signal.Signals(sig).name}): nothing written" in err
    assert out == "" and sorted(os.listdir(tmp_path)) == []


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_fem_solve_exits_130_and_writes_nothing(tmp_path, sig):
    vtu, plot = tmp_path / "f.vtu", tmp_path / "p.png"
    proc = subprocess.Popen([sys.executable, "-m", "fem_reference.cli", "solve",
                             str(ROOT / "examples" / "paper-section10-thick.toml"), "--set", "fem.refine=2",
                             "--vtu", str(vtu),
                             "--plot", str(plot)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})
    first = proc.stderr.readline()  # the solve has started: its first progress line
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=120)
    assert first and proc.returncode == 130, (first, err)
    assert f"fem-reference: interrupted ({signal.Signals(sig).name}): nothing written" in err
    assert out == "" and sorted(os.listdir(tmp_path)) == []


def test_a_closed_stdout_ends_quietly(small):
    done = subprocess.run(f"{sys.executable} -m bem.cli solve {small} --json --quiet | head -c 10",
                          shell=True, capture_output=True, text=True, timeout=120)
    assert done.stdout == '{\n  "rolli' and done.stderr == ""


def test_outputs_are_written_whole(small, tmp_path, capsys):
    assert main(["solve", str(small), "--quiet", "--fields", str(tmp_path / "f.npz")]) == 0
    assert sorted(os.listdir(tmp_path)) == ["f.npz", "small.toml"]
    assert np.load(tmp_path / "f.npz")["force"].shape == (7, 7)


@pytest.mark.parametrize("override, message", [
    ("grid.truncation=100000000", r"the kernel tables of this grid \(truncation = 100000000 x 100000000, 7 x 7 "
                                  r"nodes\) need at least 1.5\d+e\+03 GiB, more than this machine's"),
    ("grid.truncation=100000000000000000000", r"need at least 1.5\d+e\+15 GiB"),
    ("layer.thickness=1e300", r"thickness must be <= 1e\+100 m"),
    ("indenter.radius=1e300", r"nodes_x = \d+ at spacing_x = 0.001 m spans"),
    ("loading.load=1e-300", r"loading.load = 1e-300 N is lost to rounding at the scale of this problem"),
    ("grid.spacing_x=1e-3", r"\[grid\] gives both spacing and spacing_x: spacing sets the x and y values"),
    ("grid.truncation_y=64", r"\[grid\] gives both truncation and truncation_y"),
    ("grid.period_x=0.2", r"\[grid\] gives both period and period_x"),
])
def test_bad_values_end_in_an_error_naming_them(small, capsys, override, message):
    assert main(["solve", str(small), "--quiet", "--set", override]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bem: error: ") and "Traceback" not in err
    assert __import__("re").search(message, err), err


def test_a_friction_radius_other_than_the_indenters_is_refused(small, capsys):
    args = ["solve", str(small), "--quiet", "--set", "loading.speed=0.01", "--set", "friction.mu=0.5",
            "--set", "grid.half_width=3e-3"]
    assert main(args + ["--set", "friction.radius=1.0"]) == 2
    assert "[friction] radius = 1.0 m differs from [indenter] radius = 0.02 m" in capsys.readouterr().err


@pytest.mark.parametrize("arrays, message", [
    (None, "holds one array, not an NPZ archive"),
    (dict(x=np.array([]), y=np.array([]), h=np.zeros((0, 0))), "x must be strictly increasing with >= 2 values"),
    (dict(x=np.array([-1e-2, 1e-2]), y=np.array([-1e-2, 1e-2]), h=np.eye(2, dtype=bool)),
     "h must hold real numbers (m), got an array of dtype bool"),
])
def test_bad_height_maps_end_in_an_error(small, tmp_path, capsys, arrays, message):
    if arrays is None:
        file = tmp_path / "map.npy"
        np.save(file, np.zeros((3, 3)))
    else:
        file = tmp_path / "map.npz"
        np.savez(file, **arrays)
    text = small.read_text().replace('shape = "sphere"', 'shape = "heightmap"').replace("radius = 0.02",
                                                                                        f'file = "{file.name}"')
    small.write_text(text + "half_width = 5e-3\n")
    assert main(["solve", str(small), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err, err
