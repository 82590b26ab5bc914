"""The rolling-3d kind: a rolling sphere, every method on its levels, compared on the line
y = 0, by Richardson and by each method's energy balance. A plugin that moves the BEM's
answer by known amounts must be measured off by exactly those amounts."""

import json
from pathlib import Path

import pytest

from verification.cli import main as verify_main
from verification.runner import load_case

CASE = """
name = "roll3d"
title = "A sphere rolling on the section-11 layer, coarse"
kind = "rolling-3d"
[problem]
layer = { thickness = 5.0e-3, density = 1000.0 }
material = { model = "three_parameter", G0 = 3.0e6, tau = 0.25, f = 1.0 }
indenter = { shape = "sphere", radius = 0.02 }
loading = { speed = 0.05, load = 150.0 }
[bem]
spacings = [1.0e-3, 5.0e-4, 2.5e-4]
period = 0.2
half_width = 5.0e-3
[methods.moved]
entry = "PLUGIN:solve"
sizes = [1.0e-3, 5.0e-4, 2.5e-4]
period = 0.2
half_width = 5.0e-3
[[gates]]
quantity = "rolling_resistance"
methods = ["bem"]
against = "dissipation"
tolerance = 2e-3
reason = "energy balance; 6.4e-4 measured at a = 0.25 mm"
"""

GATES = """
[[gates]]
quantity = "QUANTITY"
methods = ["moved"]
against = "bem"
LEVELS
tolerance = 1.0
reason = "measured only"
"""

# The BEM moved by known amounts: R_r x 1.01, the leading edge ahead by 1% of the contact
# length, the pressure on y = 0 up by 2% of its peak.
PLUGIN = '''
import copy
import numpy as np
from verification.methods import bem

def solve(problem, level):
    run = bem.solve(problem, level)
    s = dict(run.scalars)
    s["rolling_resistance"] *= 1.01
    s["leading_edge"] += 0.01 * (s["leading_edge"] - s["trailing_edge"])
    out = copy.copy(run)
    out.method, out.scalars = "moved", s
    out.pressure = run.pressure + 0.02 * run.pressure.max()
    return out
'''


def _write(tmp_path: Path, gates: list[tuple[str, str]]) -> Path:
    plugin = tmp_path / "moved.py"
    plugin.write_text(PLUGIN)
    text = CASE.replace("PLUGIN", str(plugin))
    for q, levels in gates:
        text += GATES.replace("QUANTITY", q).replace("LEVELS", levels)
    folder = tmp_path / "cases"
    folder.mkdir()
    (folder / "roll3d.toml").write_text(text)
    return folder


def test_a_moved_method_is_measured_off_by_what_it_was_moved(tmp_path):
    folder = _write(tmp_path, [("rolling_resistance", ""), ("rolling_resistance", 'levels = ["extrapolated"]'),
                               ("leading_edge", ""), ("trailing_edge", ""), ("pressure_rms_interior", "")])
    out = tmp_path / "out"
    assert verify_main(["--cases-dir", str(folder), "--out", str(out)]) == 0
    case = json.loads((out / "metrics.json").read_text())["cases"][0]
    g = {(x["method"], x["quantity"], x["against"], x["level"]): x for x in case["gates"]}
    assert g[("moved", "rolling_resistance", "bem", "finest")]["error"] == pytest.approx(0.01, rel=1e-9)
    # Richardson is linear in the values: a 1% scale survives extrapolation exactly
    assert g[("moved", "rolling_resistance", "bem", "extrapolated")]["error"] == pytest.approx(0.01, rel=1e-6)
    assert g[("moved", "leading_edge", "bem", "finest")]["error"] == pytest.approx(0.01, rel=1e-9)
    assert g[("moved", "trailing_edge", "bem", "finest")]["error"] == 0.0
    # the RMS of a uniform 2%-of-peak shift over the interior of y = 0 is 2%
    assert g[("moved", "pressure_rms_interior", "bem", "finest")]["error"] == pytest.approx(0.02, rel=1e-9)
    energy = g[("bem", "rolling_resistance", "dissipation", "finest")]
    assert energy["passed"] and energy["error"] < 1e-3
    names = sorted(p.name for p in out.iterdir())
    for figure in ("roll3d-pressure.png", "roll3d-convergence.png", "roll3d-pressure-map.png"):
        assert figure in names


@pytest.mark.parametrize("edit, message", [
    (('speed = 0.05', 'speed = 0.0'), "needs speed > 0"),
    (('shape = "sphere"', 'shape = "line"'), "rolling-2d"),
    (('quantity = "rolling_resistance"\nmethods = ["bem"]\nagainst = "dissipation"',
      'quantity = "indentation"\nmethods = ["bem"]\nagainst = "dissipation"'), "energy balance checks rolling_resistance"),
    (('quantity = "rolling_resistance"', 'quantity = "rolling_resistence"'), "did you mean"),
    (('against = "dissipation"', 'against = "dissipation"\nlevels = ["extrapolated"]\n'), None),
    (('spacings = [1.0e-3, 5.0e-4, 2.5e-4]\nperiod', 'spacings = [5.0e-4, 2.5e-4]\nperiod'),
     "'extrapolated' needs three levels"),
])
def test_bad_cases_are_refused_before_anything_is_solved(tmp_path, capsys, edit, message):
    folder = _write(tmp_path, [])
    path = folder / "roll3d.toml"
    text = path.read_text()
    assert edit[0] in text
    text = text.replace(edit[0], edit[1], 1)
    if message == "'extrapolated' needs three levels":
        text = text.replace('against = "dissipation"', 'against = "dissipation"\nlevels = ["extrapolated"]')
    path.write_text(text)
    if message is None:  # extrapolated with three levels is accepted
        load_case(path)
        return
    assert verify_main(["--cases-dir", str(folder), "--out", str(tmp_path / "out")]) == 2
    assert message in capsys.readouterr().err
