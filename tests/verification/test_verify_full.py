"""Every verification case that `verify --quick` leaves out passes its gates (slow: the
rolling and sweep cases take minutes)."""

import json
import tomllib

import pytest

from verification.cli import main
from verification.runner import list_cases

SLOW_CASES = [p.stem for p in list_cases() if not tomllib.loads(p.read_text()).get("quick", False)]


@pytest.mark.slow
@pytest.mark.parametrize("name", SLOW_CASES)
def test_case_outside_the_quick_suite_passes(name, tmp_path):
    assert main(["--case", name, "--out", str(tmp_path)]) == 0
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    gates = [g for c in metrics["cases"] for g in c["gates"] if g["verdict"] != "REPORTED"]
    assert gates and all(g["passed"] for g in gates)


def test_the_slow_list_is_not_empty():
    assert {"thin-layer", "thickness-sweep", "rolling-layer-2d", "rolling-inertia-2d"} <= set(SLOW_CASES)
