"""The report is written whole or not at all: strict JSON, nothing stale, the previous
report intact when a run is interrupted while solving or while writing; JUnit and drift."""

import json
import math
import os
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from verification import report as report_module
from verification.report import drift, load_baseline, write_report
from tests.verification.small_cases import default_sigint
from verification.results import CaseResult, Gate, Run

ROOT = Path(__file__).resolve().parents[2]


def _result(name="demo", error=0.001, nan=False):
    r = CaseResult(name, "A made-up case", "why", "stationary")
    r.runs["bem"] = [Run("bem", 1e-4, {"contact_radius": 1e-3, "indentation": math.nan}, np.zeros(3), np.ones(3))]
    r.gates = [
        Gate(case=name, quantity="contact_radius", method="bem", against="fem", level="finest", value=1.0,
             reference=1.0, error=error, tolerance=0.005, reason="because"),
        Gate(case=name, quantity="indentation", method="bem", against="fem", level="finest", value=math.nan,
             reference=1.0, error=math.nan if nan else 0.0, tolerance=0.005, reason="because"),
        Gate(case=name, quantity="pressure_max_edge", method="bem", against="fem", level="finest", value=0.2,
             reference=0.0, error=0.2, tolerance=math.inf, reason="shown", report_only=True),
    ]
    return r


def _strict_load(path: Path):
    def refuse(token):
        raise ValueError(f"non-standard JSON token {token}")
    return json.loads(path.read_text(), parse_constant=refuse)


def test_metrics_are_strict_json_with_null_for_nan(tmp_path):
    write_report([_result(nan=True)], tmp_path / "out")
    metrics = _strict_load(tmp_path / "out" / "metrics.json")
    gates = metrics["cases"][0]["gates"]
    assert gates[1]["error"] is None and gates[1]["verdict"] == "FAIL"
    assert gates[2]["tolerance"] is None  # infinity is not JSON either
    assert metrics["cases"][0]["runs"]["bem"][0]["indentation"] is None
    assert metrics["passed"] is False


def test_a_new_report_leaves_nothing_of_the_old_one(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "old-case-profiles.png").write_bytes(b"old")
    write_report([_result()], out)
    assert not (out / "old-case-profiles.png").exists()
    assert {p.name for p in out.iterdir()} >= {"summary.md", "report.md", "report.html", "metrics.json"}
    assert not list(tmp_path.glob(".out.*"))  # no staging or old folder left beside it


def test_interrupted_while_writing_the_previous_report_is_intact(tmp_path, monkeypatch):
    out = tmp_path / "out"
    write_report([_result(error=0.001)], out)  # a passing report
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    real = report_module._write_all

    def half_then_interrupt(results, folder, drifts):
        real(results, folder, drifts)
        (folder / "report.md").write_text("half")
        raise KeyboardInterrupt

    monkeypatch.setattr(report_module, "_write_all", half_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        write_report([_result(error=0.5)], out)  # a failing one, interrupted
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    assert not list(tmp_path.glob(".out.*"))


def test_a_staging_folder_of_a_killed_run_is_removed(tmp_path):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = tmp_path / f".out.partial-{dead.pid}"
    stale.mkdir()
    (stale / "metrics.json").write_text("{}")
    write_report([_result()], tmp_path / "out")
    assert not stale.exists()


def test_junit_has_one_test_case_per_gate(tmp_path):
    junit = tmp_path / "gates.xml"
    write_report([_result(error=0.5), _result("other")], tmp_path / "out", junit=junit)
    root = ET.parse(junit).getroot()
    cases = root.findall(".//testcase")
    assert len(cases) == 6
    assert len(root.findall(".//failure")) == 1 and len(root.findall(".//skipped")) == 2
    failed = [c for c in cases if c.find("failure") is not None][0]
    assert failed.get("classname") == "verify.demo" and "contact_radius vs fem" in failed.get("name")


def test_drift_flags_moves_larger_than_the_fraction_of_the_tolerance(tmp_path):
    write_report([_result(error=0.001)], tmp_path / "base")
    baseline = load_baseline(tmp_path / "base" / "metrics.json")
    assert drift([_result(error=0.0015)], baseline, 0.25) == []  # moved 0.1 of the tolerance
    flags = drift([_result(error=0.003)], baseline, 0.25)  # 0.4 of the tolerance, still passing
    assert [f.key for f in flags] == ["demo: bem contact_radius vs fem (finest)"]
    assert "0.40 of the tolerance (worse)" in flags[0].note
    write_report([_result(error=0.003)], tmp_path / "now", drifts=flags)
    summary = (tmp_path / "now" / "summary.md").read_text()
    assert "Drift since the baseline" in summary and "PASS" in summary


def test_summary_names_the_worst_gate_of_each_case(tmp_path):
    write_report([_result(error=0.004), _result("bad", error=0.02)], tmp_path / "out")
    lines = (tmp_path / "out" / "summary.md").read_text().splitlines()
    assert lines[2].startswith("**FAIL: 1 of 2 cases")
    demo = next(x for x in lines if x.startswith("| demo |"))
    bad = next(x for x in lines if x.startswith("| bad |"))
    assert "| PASS | 2/2 | bem contact_radius vs fem (finest) | 0.80 |" in demo
    assert "| FAIL | 1/2 |" in bad and "| 4.00 |" in bad
    assert len(lines) < 25  # one screen


def _run_verify(args, cwd):
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    return subprocess.Popen([sys.executable, "-m", "verification.cli", *args], cwd=cwd, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=default_sigint)


@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 130), (signal.SIGKILL, -9)])
def test_a_run_killed_while_solving_leaves_the_previous_report(tmp_path, sig, code):
    out = tmp_path / "out"
    write_report([_result()], out)
    before = {p.name: p.read_bytes() for p in out.iterdir()}
    proc = _run_verify(["--case", "table1", "--out", str(out)], ROOT)  # the full table: minutes
    deadline = time.time() + 120
    seen = ""
    while "Nt =" not in seen and time.time() < deadline:  # wait until it is solving
        seen += proc.stderr.readline()
    proc.send_signal(sig)
    assert proc.wait(timeout=60) == code
    if sig != signal.SIGKILL:
        assert "the report in" in proc.stderr.read()
    assert {p.name: p.read_bytes() for p in out.iterdir()} == before
    if sig != signal.SIGKILL:
        assert not list(tmp_path.glob(".out.*"))


def test_a_figure_that_cannot_be_drawn_does_not_lose_the_verdicts(tmp_path, monkeypatch, capsys):
    from verification.kinds import stationary

    def broken(result, folder):
        raise ValueError("no such format")

    monkeypatch.setattr(stationary, "figures", broken)
    write_report([_result()], tmp_path / "out")
    text = (tmp_path / "out" / "report.md").read_text()
    assert "could not be drawn: ValueError: no such format" in text and "| contact_radius | bem |" in text
    assert json.loads((tmp_path / "out" / "metrics.json").read_text())["passed"] is True
    assert "warning: demo" in capsys.readouterr().err
