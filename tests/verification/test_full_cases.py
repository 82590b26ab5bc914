"""`verify --full`: a case with ``full = true`` (finer levels, more memory and time) runs
only under --full or when named with --case; the default run leaves it out."""

import json

from verification.cli import main as verify_main
from verification.runner import CASES_DIR, list_cases, load_case


def test_a_full_case_runs_only_with_full(tmp_path, capsys):
    cases = tmp_path / "cases"
    cases.mkdir()
    text = (CASES_DIR / "table1.toml").read_text()
    (cases / "table1.toml").write_text(text.replace('quick = true', 'quick = true\nfull = true', 1))
    assert verify_main(["--cases-dir", str(cases), "--quick", "--out", str(tmp_path / "default")]) == 2
    assert "no case" in capsys.readouterr().err
    assert verify_main(["--cases-dir", str(cases), "--quick", "--full", "--out", str(tmp_path / "full")]) == 0
    metrics = json.loads((tmp_path / "full" / "metrics.json").read_text())
    assert [c["name"] for c in metrics["cases"]] == ["table1"]


def test_the_full_sphere_case_is_the_default_one_a_level_finer():
    default = load_case(CASES_DIR / "rolling-sphere-3d.toml")
    full = load_case(CASES_DIR / "rolling-sphere-3d-full.toml")
    assert full.get("full") and not default.get("full")
    assert full["fem"]["element_sizes"][:-1] == default["fem"]["element_sizes"]
    assert full["problem"] == default["problem"]
    assert "rolling-sphere-3d-full" in {p.stem for p in list_cases()}
