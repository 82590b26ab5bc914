"""The `verify` command: it writes the report and exits 1 when a gate fails; a case given
by its path (`--case FILE.toml`), outside the cases folder, is read and its errors are
reported against that file before any solve; a missing path is a usage error naming it."""

from verification.cli import main as verify_main
from verification.runner import CASES_DIR


def test_verify_cli_writes_report_and_fails_on_a_failing_gate(tmp_path):
    out = tmp_path / "ok"
    assert verify_main(["--case", "table1", "--quick", "--out", str(out)]) == 0
    for name in ("summary.md", "report.md", "report.html", "metrics.json", "table1-table1.png"):
        assert (out / name).exists()
    strict = tmp_path / "cases"
    strict.mkdir()
    text = (CASES_DIR / "table1.toml").read_text().replace("tolerance = 1e-4", "tolerance = 1e-9")
    (strict / "table1.toml").write_text(text)
    assert verify_main(["--cases-dir", str(strict), "--quick", "--out", str(tmp_path / "bad")]) == 1
    assert "FAIL" in (tmp_path / "bad" / "summary.md").read_text()


def test_a_case_file_given_by_path_is_read(tmp_path, capsys):
    text = (CASES_DIR / "thick-layer.toml").read_text().replace('"bem", "fem"]', '"bme", "fem"]', 1)
    text = text.replace('name = "thick-layer"', 'name = "my-case"')
    path = tmp_path / "elsewhere" / "my-case.toml"
    path.parent.mkdir()
    path.write_text(text)
    assert verify_main(["--case", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "my-case.toml" in err and "unknown method 'bme'" in err, err
    assert not (tmp_path / "out" / "metrics.json").exists()


def test_a_missing_case_path_is_a_usage_error(tmp_path, capsys):
    missing = tmp_path / "nowhere.toml"
    assert verify_main(["--case", str(missing), "--out", str(tmp_path / "out")]) == 2
    assert "nowhere" in capsys.readouterr().err
