"""The report's pages read at a glance: the verdict and a linked contents at the top, one
unit per quantity (the Runs tables': mm, MPa, N), comparisons without a gate shown apart
as information, gate rows naming their parameters, no ``nan`` where a word says it."""

import math
import re

import numpy as np

from verification.formatting import parameters, scalars_line, unit
from verification.kinds import Context, stationary
from verification.metrics import Convergence
from verification.report import write_report
from verification.results import CaseResult, Gate, Run


def _gate(case="demo", quantity="contact_radius", **kw):
    spec = dict(case=case, quantity=quantity, method="bem", against="fem", level="finest", value=2.5e-3,
                reference=2.4e-3, error=0.004, tolerance=0.005, reason="because")
    return Gate(**{**spec, **kw})


def _sweep_result() -> CaseResult:
    r = CaseResult("sweep", "A made-up sweep", "why", "sweep")
    r.gates = [
        _gate("sweep[H=0.5mm]"),
        _gate("sweep[H=2mm]", quantity="peak_pressure", value=1.5e6, reference=1.4e6, error=0.07),
        _gate("sweep[H=2mm]", quantity="pressure_max_edge", value=0.02, reference=0.0, error=0.02,
              tolerance=0.01, report_only=True, reason="shown only"),
        _gate("sweep[H=2mm]", quantity="indentation", value=math.nan, error=math.nan, reason="no result"),
    ]
    return r


def _write(tmp_path, results):
    out = tmp_path / "out"
    write_report(results, out)
    return (out / "report.md").read_text(), (out / "report.html").read_text(), (out / "summary.md").read_text()


def _md_rows(md: str, title: str) -> list[list[str]]:
    """The body rows of the markdown table under the bold ``title``."""
    block = md.split(f"**{title}**", 1)[1].split("\n\n", 2)[1]
    return [[c.strip() for c in line.strip("|").split("|")] for line in block.splitlines()[2:]]


def test_values_are_shown_in_the_units_of_the_runs_tables(tmp_path):
    md, _, _ = _write(tmp_path, [_sweep_result()])
    rows = _md_rows(md, "Gates")
    radius, pressure = rows[0], rows[1]
    assert radius[5:8] == ["2.5", "2.4", "mm"]  # m -> mm
    assert pressure[5:8] == ["1.5", "1.4", "MPa"]  # Pa -> MPa
    assert unit("rolling_resistance", "rolling-2d") == ("N/m", 1.0)  # plane strain: per unit length
    assert unit("rolling_resistance[a=1mm,Nt=500]", "table1") == ("N", 1.0)
    assert unit("pressure_rms_interior", "stationary")[0] == "of peak"
    assert unit("midplane_pressure_rms_interior[L=40mm]", "roller-3d")[0] == "of peak"


def test_gate_rows_name_their_parameters(tmp_path):
    md, html, _ = _write(tmp_path, [_sweep_result()])
    rows = _md_rows(md, "Gates")
    assert rows[0][1] == "contact_radius (H = 0.5 mm)" and rows[1][1] == "peak_pressure (H = 2 mm)"
    assert parameters("table1", "table1", "rolling_resistance[a=0.25mm,Nt=2000]") == "a = 0.25 mm, Nt = 2000"
    assert parameters("demo", "demo", "contact_radius") == ""


def test_reported_rows_are_information_without_a_tolerance(tmp_path):
    md, html, _ = _write(tmp_path, [_sweep_result()])
    gated = _md_rows(md, "Gates")
    assert [row[0] for row in gated] == ["PASS", "FAIL", "FAIL"]
    reported = _md_rows(md, "Reported without a gate")
    assert len(reported) == 1 and reported[0][0] == "pressure_max_edge (H = 2 mm)"
    assert "1.0e-02" not in " ".join(reported[0])  # the tolerance it exceeds is not shown
    table = html.split("Reported without a gate", 1)[1].split("</table>", 1)[0]
    assert "class='info'" in table and "class='fail'" not in table and "PASS" not in table


def test_the_top_says_the_verdict_and_links_every_case(tmp_path):
    good = CaseResult("good", "Passes", "why", "stationary")
    good.gates = [_gate("good")]
    _, html, summary = _write(tmp_path, [good, _sweep_result()])
    head = html.split("<body>", 1)[1][:400]
    assert "class='verdict bad'" in head and "FAIL" in head  # the sweep fails: red at the top
    for name in ("good", "sweep"):
        assert f"<a href='#{name}'>{name}</a>" in html and f"id='{name}'" in html
    targets = set(re.findall(r"href='#([^']+)'", html))
    assert targets <= set(re.findall(r"id='([^']+)'", html))  # every link of the page lands
    assert "| good | PASS |" in summary  # summary.md (a CI job summary) stays plain


def test_no_nan_in_the_pages(tmp_path):
    r = _sweep_result()
    r.runs["bem"] = [Run("bem", 1e-4, {"contact_radius": 1e-3, "indentation": math.nan}, np.zeros(3), np.ones(3))]
    r.kind = "stationary"
    r.convergence[("bem", "contact_radius")] = Convergence((1.0, 1.1, 1.2), math.nan, 1.2, math.nan, False)
    md, html, summary = _write(tmp_path, [r])
    for text in (md, html, summary):
        assert not re.search(r"\bnan\b", text, re.I)
    assert "no order (the levels do not converge monotonically): finest kept" in md


class _Method:
    def levels(self, case):
        from verification.results import Level

        return [Level(0, 1e-4, {})]

    def solve(self, problem, level):
        return Run("toy", level.size, {"contact_radius": 2.5e-3, "indentation": 1e-4, "peak_pressure": 1.2e6,
                                       "rolling_resistance": -8e-17}, np.zeros(2), np.ones(2))


def test_progress_lines_print_what_the_case_is_about():
    lines = []
    ctx = Context(progress=lines.append, methods={"toy": _Method()})
    for speed in (0.0, 0.05):
        case = {"name": "demo", "problem": {"loading": {"speed": speed}}, "gates": []}
        stationary.solve_methods(case, CaseResult("demo", "", "", "stationary"), ctx, names=["toy"])
    still, rolling = lines
    assert "r_c = 2.5 mm, d = 0.1 mm, p_max = 1.2 MPa" in still and "R_r" not in still
    assert "R_r = -8e-17 N" in rolling
    assert scalars_line({"load": 10.0}, ["load", "indentation"]) == "P = 10 N"
