"""The quick verification suite (what `verify --quick` runs) passes every gate."""

import json

from verification.cli import main


def test_quick_suite_passes(tmp_path):
    assert main(["--quick", "--out", str(tmp_path)]) == 0
    metrics = json.loads((tmp_path / "metrics.json").read_text())
    assert metrics["passed"] and len(metrics["cases"]) >= 4
    assert all(g["passed"] for c in metrics["cases"] for g in c["gates"])
