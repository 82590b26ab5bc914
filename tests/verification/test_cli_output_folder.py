"""``verify --out`` never deletes what verify did not write: a folder of someone's files
survives every spelling of ``--out``, the working and the cases folder are never the
report's, and a previous report is replaced only when it carries the marker file."""

from pathlib import Path

import pytest

from verification.cli import main as verify_main
from tests.verification.small_cases import THICK_LAYER_CASE as CASE
from verification.out_folder import MARKER


THESIS = {"thesis.tex": "\\chapter{Contact}\n", "figures/fig1.pdf": "%PDF-1.4\n", ".git/HEAD": "ref: main\n"}


@pytest.fixture
def cases(tmp_path):
    folder = tmp_path / "cases"
    folder.mkdir()
    (folder / "hs.toml").write_text(CASE)
    return folder


@pytest.fixture
def thesis(tmp_path):
    folder = tmp_path / "thesis"
    for name, text in THESIS.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    return folder


def _intact(folder: Path) -> bool:
    return all((folder / name).read_text() == text for name, text in THESIS.items())


def _verify(cases, *args) -> int:
    return verify_main(["--cases-dir", str(cases), *map(str, args)])


def test_a_folder_of_the_users_files_survives_every_spelling_of_out(tmp_path, cases, thesis, monkeypatch, capsys):
    (tmp_path / "link").symlink_to(thesis)
    monkeypatch.chdir(tmp_path)
    spellings = ["thesis", "thesis/", str(thesis), str(thesis) + "/", "./cases/../thesis", "link", "link/"]
    for out in spellings:
        assert _verify(cases, "--out", out) == 2, out
        err = capsys.readouterr().err
        assert "is not a report verify wrote" in err and "--overwrite" in err, out
        assert "[1/1]" not in err  # refused before anything was solved
        assert _intact(thesis), out
    monkeypatch.chdir(thesis)
    for out in (".", "./", str(thesis), "figures/.."):
        assert _verify(cases, "--out", out, "--overwrite") == 2, out
        assert "is the working folder" in capsys.readouterr().err
        assert _intact(thesis), out
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cases", "link", "thesis"]


def test_out_is_never_the_cases_folder_or_a_folder_holding_it_or_the_working_folder(tmp_path, cases, monkeypatch,
                                                                                  capsys):
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    for out, says in ((cases, "is the folder of the cases"), (tmp_path, "holds the working folder"),
                      ("..", "holds the working folder"), (tmp_path.parent, "holds the working folder")):
        assert _verify(cases, "--out", out, "--overwrite") == 2, out
        err = capsys.readouterr().err
        assert says in err and "--out verification-report" in err, out
    assert (cases / "hs.toml").read_text() == CASE
    # a case file named by path protects its folder too
    elsewhere = tmp_path / "mine"
    elsewhere.mkdir()
    (elsewhere / "hs.toml").write_text(CASE)
    assert verify_main(["--case", str(elsewhere / "hs.toml"), "--out", str(elsewhere), "--overwrite"]) == 2
    assert "is the folder of the cases" in capsys.readouterr().err
    assert (elsewhere / "hs.toml").read_text() == CASE


def test_a_previous_report_is_replaced_only_when_it_carries_the_marker(tmp_path, cases, capsys):
    out = tmp_path / "report"
    assert _verify(cases, "--out", out) == 0
    assert (out / MARKER).read_text().startswith("verify report format 1\n")
    (out / "notes.txt").write_text("scribbled into the report")
    assert _verify(cases, "--out", out) == 0  # a report: replaced whole
    assert not (out / "notes.txt").exists() and (out / MARKER).is_file()
    assert not [p for p in tmp_path.iterdir() if p.name not in ("cases", "report")]  # nothing left beside
    (out / MARKER).unlink()  # now it is the user's folder
    capsys.readouterr()
    assert _verify(cases, "--out", out) == 2
    assert "it looks like a report of a verify that wrote no marker" in capsys.readouterr().err
    assert (out / "metrics.json").is_file()


def test_a_report_reached_through_a_symlink_is_replaced_where_it_is(tmp_path, cases):
    real = tmp_path / "reports" / "today"
    assert _verify(cases, "--out", real) == 0
    link = tmp_path / "latest"
    link.symlink_to(real)
    assert _verify(cases, "--out", link) == 0
    assert link.is_symlink() and (link / MARKER).is_file() and (real / "report.md").is_file()
    assert sorted(p.name for p in (tmp_path / "reports").iterdir()) == ["today"]


def test_overwrite_puts_the_report_there_and_keeps_the_users_files_beside(tmp_path, cases, thesis, capsys):
    assert _verify(cases, "--out", thesis, "--overwrite") == 0
    assert (thesis / MARKER).is_file() and (thesis / "report.md").is_file()
    kept = [p for p in tmp_path.iterdir() if p.name.startswith("thesis.kept-")]
    assert len(kept) == 1 and _intact(kept[0])
    assert f"they are kept in {kept[0]}" in capsys.readouterr().err


def test_an_empty_folder_takes_the_report(tmp_path, cases):
    out = tmp_path / "empty"
    out.mkdir()
    assert _verify(cases, "--out", out) == 0
    assert (out / MARKER).is_file()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cases", "empty"]


def test_junit_inside_the_report_folder_is_refused(tmp_path, cases, capsys):
    out = tmp_path / "report"
    out.mkdir()
    assert _verify(cases, "--out", out, "--junit", out / "junit.xml") == 2
    assert "which the report replaces" in capsys.readouterr().err
    assert not any(out.iterdir())


def test_junit_replaces_only_a_junit_file_verify_wrote(tmp_path, cases, capsys):
    mine = tmp_path / "results.xml"
    mine.write_text("<?xml version='1.0'?>\n<thesis>mine</thesis>\n")
    assert _verify(cases, "--out", tmp_path / "report", "--junit", mine) == 2
    assert "is not a JUnit file verify wrote" in capsys.readouterr().err
    assert mine.read_text().endswith("<thesis>mine</thesis>\n")
    ours = tmp_path / "gates.xml"
    assert _verify(cases, "--out", tmp_path / "report", "--junit", ours) == 0
    assert _verify(cases, "--out", tmp_path / "report", "--junit", ours) == 0  # its own file: replaced
    assert '<testsuites name="verify"' in ours.read_text()
