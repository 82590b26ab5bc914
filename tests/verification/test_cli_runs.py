"""`verify` on the default cases: the quick suite (what `verify --quick` runs) passes every
gate, and so does each case it leaves out (slow: the rolling and sweep cases take
minutes); the default suite holds the stationary, sweep, Table 1 and limit cases."""

import json
import tomllib

import pytest

from verification.cli import main
from verification.runner import CASES_DIR, list_cases, load_case

SLOW_CASES = [p.stem for p in list_cases() if not tomllib.loads(p.read_text()).get("quick", False)]


def test_quick_suite_passes(tmp_path):
    assert main(["--quick", "--out", str(tmp_path)]) == 0
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["passed"] and len(metrics["cases"]) >= 4
    assert all(g["passed"] for c in metrics["cases"] for g in c["gates"])


@pytest.mark.slow
@pytest.mark.parametrize("name", SLOW_CASES)
def test_case_outside_the_quick_suite_passes(name, tmp_path):
    assert main(["--case", name, "--out", str(tmp_path)]) == 0
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    gates = [g for c in metrics["cases"] for g in c["gates"] if g["verdict"] != "REPORTED"]
    assert gates and all(g["passed"] for g in gates)


def test_the_slow_list_is_not_empty():
    assert {"thin-layer", "thickness-sweep", "rolling-layer-2d", "rolling-inertia-2d"} <= set(SLOW_CASES)


def test_default_suite_holds_the_stationary_sweep_table1_and_limit_cases():
    names = {p.stem for p in list_cases()}
    assert {"halfspace-hertz", "thick-layer", "thin-layer", "thickness-sweep", "table1", "rolling-limits"} <= names
    sweep = load_case(CASES_DIR / "thickness-sweep.toml")
    assert len(sweep["sweep"]["thicknesses"]) >= 5
