"""The roller-3d kind: a rolling roller, methods compared as in rolling-3d plus the contact
length and the peak on y = 0, and the BEM's mid-plane against the plane-strain line
contact. A plugin that moves the BEM's answer by known amounts must be measured off by
exactly those amounts; the mid-plane error must fall with the roller's length."""

import json
from pathlib import Path

import pytest

from verification.cli import main as verify_main

CASE = """
name = "roller"
title = "A roller rolling on the section-11 layer, coarse"
kind = "roller-3d"
[problem]
layer = { thickness = 5.0e-3, density = 0.0 }
material = { model = "three_parameter", G0 = 3.0e6, tau = 0.25, f = 1.0 }
indenter = { shape = "cylinder", radius = 0.02, length = 8.0e-3, edge_radius = 2.0e-3 }
loading = { speed = 5.0e-3, load = 8.0 }
[bem]
spacings = [4.0e-4, 2.0e-4]
period = 0.1
half_width = 4.5e-3
[methods.moved]
entry = "PLUGIN:solve"
sizes = [4.0e-4, 2.0e-4]
period = 0.1
half_width = 4.5e-3
[midplane]
lengths = [0.01, 0.03]
spacing = 1.0e-4
period = 0.1
half_width = 3.0e-3
[[gates]]
quantity = "midplane_pressure_rms_interior"
methods = ["bem"]
against = "plane_strain"
tolerance = 2e-3
reason = "measured"
"""

GATES = """
[[gates]]
quantity = "QUANTITY"
methods = ["moved"]
against = "bem"
tolerance = 1.0
reason = "measured only"
"""

# The BEM moved by known amounts: the leading edge ahead by 1% of the contact length, the
# pressure on y = 0 up by 2% of its peak.
PLUGIN = '''
import copy
from verification.methods import bem

def solve(problem, level):
    run = bem.solve(problem, level)
    s = dict(run.scalars)
    s["leading_edge"] += 0.01 * (s["leading_edge"] - s["trailing_edge"])
    out = copy.copy(run)
    out.method, out.scalars = "moved", s
    out.pressure = run.pressure + 0.02 * run.pressure.max()
    return out
'''


def _write(tmp_path: Path, quantities: list[str]) -> Path:
    plugin = tmp_path / "moved.py"
    plugin.write_text(PLUGIN)
    text = CASE.replace("PLUGIN", str(plugin))
    for q in quantities:
        text += GATES.replace("QUANTITY", q)
    folder = tmp_path / "cases"
    folder.mkdir()
    (folder / "roller.toml").write_text(text)
    return folder


def test_moved_roller_and_the_mid_plane(tmp_path):
    """contact_length off by the 1% the leading edge moved, the peak on y = 0 by 2%; the
    mid-plane's RMS at L = 30 mm below 1e-3 and a third of the one at L = 10 mm (measured
    6.6e-4 and 3.5e-3 at a = 0.1 mm, period 0.1 m), which is reported beside it."""
    folder = _write(tmp_path, ["contact_length", "peak_pressure_midplane"])
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(folder), "--out", str(out)]) == 0
    case = json.loads((out / "metrics.json").read_text())["cases"][0]
    g = {(x["method"], x["quantity"]): x for x in case["gates"]}
    assert g[("moved", "contact_length")]["error"] == pytest.approx(0.01, rel=1e-9)
    assert g[("moved", "peak_pressure_midplane")]["error"] == pytest.approx(0.02, rel=1e-9)
    gated = g[("bem", "midplane_pressure_rms_interior")]
    short = g[("bem", "midplane_pressure_rms_interior[L=10mm]")]
    assert gated["verdict"] == "PASS" and gated["error"] < 1e-3
    assert short["verdict"] == "REPORTED" and short["error"] > 3 * gated["error"]
    assert "roller-midplane.png" in {p.name for p in out.iterdir()}


@pytest.mark.parametrize("edit, message", [
    (('shape = "cylinder", radius = 0.02, length = 8.0e-3, edge_radius = 2.0e-3', 'shape = "sphere", radius = 0.02'),
     'needs shape = "cylinder"'),
    (('lengths = [0.01, 0.03]', 'lengths = [0.03, 0.01]'), "lengths must increase"),
    (('methods = ["bem"]\nagainst = "plane_strain"', 'methods = ["moved"]\nagainst = "plane_strain"'),
     "the mid-plane gate takes"),
    (('[midplane]\nlengths = [0.01, 0.03]\nspacing = 1.0e-4\nperiod = 0.1\nhalf_width = 3.0e-3\n', ''),
     "needs a [midplane] section"),
    (('spacing = 1.0e-4\nperiod = 0.1\nhalf_width = 3.0e-3', 'spacing = 1.0e-4\nperiod = 0.1\nhalfwidth = 3.0e-3'),
     "did you mean"),
    (('edge_radius = 2.0e-3', 'edge_radius = 5.0e-3'),
     "[problem] indenter: edge_radius must be <= length / 2 = 0.004 m (the two end roundings meet at mid-length), "
     "got 0.005"),
])
def test_bad_roller_cases_are_refused_before_anything_is_solved(tmp_path, capsys, edit, message):
    folder = _write(tmp_path, [])
    path = folder / "roller.toml"
    text = path.read_text()
    assert edit[0] in text
    path.write_text(text.replace(edit[0], edit[1], 1))
    assert verify_main(["--cases-dir", str(folder), "--out", str(tmp_path / "out")]) == 2
    assert message in capsys.readouterr().err
