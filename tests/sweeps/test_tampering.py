"""Nothing an earlier run left is used unchecked: every damaged, edited or stale kernel
set, cached point and table row given to `sweep` is computed again with a line saying so,
or refused (exit 2) with the entry named; never served.

One pristine run (three loads on a coarse grid) is copied into each test, damaged there,
and run again; the table that comes out must hold the pristine numbers.
"""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

import bem
import sweeps.integrity
import sweeps.kernels
import sweeps.table

#: the cells a rerun may change (timings, and the checksum that covers them)
VOLATILE = {"seconds", "kernel_s", "solve_s", "energy_s", "checksum"}


def rows(table: Path) -> list[dict]:
    with open(table, newline="", encoding="utf-8") as fh:
        return [{k: v for k, v in r.items() if k not in VOLATILE} for r in csv.DictReader(fh)]


def summary(out: Path) -> dict:
    return json.loads((out / "summary.json").read_text())


@pytest.fixture(scope="module")
def pristine(sweep_command, load_sweep_file, tmp_path_factory):
    root = tmp_path_factory.mktemp("pristine")
    path = load_sweep_file()
    code, err = sweep_command(path, "--out", root / "out", "--cache", root / "cache", "--no-plots", "--quiet")
    assert code == 0, err
    return path, root


@pytest.fixture
def copy(pristine, tmp_path):
    """The pristine run's sweep file, and its output and cache folders copied here."""
    path, root = pristine
    shutil.copytree(root / "out", tmp_path / "out")
    shutil.copytree(root / "cache", tmp_path / "cache")
    return path, tmp_path / "out", tmp_path / "cache", rows(root / "out" / "results.csv")


def kernel_file(cache: Path) -> Path:
    [f] = (cache / "kernels").glob("*.npz")
    return f


def rewrite_tables(path: Path, change) -> None:
    with np.load(path) as data:
        arrays = {k: data[k] for k in data.files}
    arrays["ww"] = change(arrays["ww"])
    np.savez(path, **arrays)


def flip_a_byte(path: Path) -> None:
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0x10
    path.write_bytes(bytes(data))


KERNEL_DAMAGE = {
    "float16": (lambda f: rewrite_tables(f, lambda t: t.astype(np.float16)), "does not match its checksum"),
    "doubled": (lambda f: rewrite_tables(f, lambda t: 2 * t), "does not match its checksum"),
    "truncated": (lambda f: f.write_bytes(f.read_bytes()[: f.stat().st_size // 2]), "cannot be read"),
    "empty": (lambda f: f.write_bytes(b""), "cannot be read"),
    "bit-flipped": (flip_a_byte, ""),
    "a folder": (lambda f: (f.unlink(), f.mkdir()), "is not a file"),
}


def test_an_untouched_cache_serves_its_kernels_and_points(copy, sweep_command, tmp_path):
    path, out, cache, before = copy
    code, err = sweep_command(path, "--out", tmp_path / "second", "--cache", cache, "--no-plots")
    assert code == 0 and "again" not in err, err
    assert summary(tmp_path / "second")["resumed"] == 3
    shutil.rmtree(cache / "points")
    code, err = sweep_command(path, "--out", tmp_path / "third", "--cache", cache, "--no-plots", "--quiet")
    s = summary(tmp_path / "third")
    assert code == 0 and s["kernels_from_cache"] == 1 and s["kernels_formed"] == 0 and s["computed"] == 3
    assert rows(tmp_path / "third" / "results.csv") == before


@pytest.mark.parametrize("damage", KERNEL_DAMAGE)
def test_a_damaged_kernel_set_is_formed_again(copy, sweep_command, tmp_path, damage):
    path, out, cache, before = copy
    shutil.rmtree(cache / "points")  # the points must be solved, with the cached kernels
    spoil, reason = KERNEL_DAMAGE[damage]
    f = kernel_file(cache)
    spoil(f)
    code, err = sweep_command(path, "--out", tmp_path / "new", "--cache", cache, "--no-plots", "--quiet")
    assert code == 0, err
    assert f"kernel set {f.stem}: {f}" in err and reason in err and "; formed again" in err
    s = summary(tmp_path / "new")
    assert s["kernels_formed"] == 1 and s["kernels_from_cache"] == 0 and s["computed"] == 3
    assert rows(tmp_path / "new" / "results.csv") == before
    if damage == "a folder":  # left as it is (never removed), and said so
        assert f.is_dir() and f"kernel set {f.stem} not cached (IsADirectoryError" in err
    else:  # the set formed again replaced the damaged one
        code, err = sweep_command(path, "--out", tmp_path / "third", "--cache", cache, "--no-plots", "--quiet")
        assert code == 0 and summary(tmp_path / "third")["resumed"] == 3


def test_kernels_of_another_version_of_the_code_are_formed_again(copy, sweep_command, tmp_path, monkeypatch):
    path, out, cache, before = copy
    old = sweeps.integrity.code_version()
    monkeypatch.setattr(sweeps.integrity, "code_version", lambda: "0.1.0+000000000000")
    monkeypatch.setattr(sweeps.kernels, "code_version", sweeps.integrity.code_version)
    monkeypatch.setattr(sweeps.table, "code_version", sweeps.integrity.code_version)
    code, err = sweep_command(path, "--out", out, "--cache", cache, "--no-plots", "--quiet")
    assert code == 0, err
    assert f"computed by another version of the code ({old}, now 0.1.0+000000000000)" in err
    assert f"was formed by another version of the code ({old})" in err
    s = summary(out)
    assert s["computed"] == 3 and s["resumed"] == 0 and s["kernels_formed"] == 1
    assert [{**r, "code": old} for r in rows(out / "results.csv")] == before


def test_the_code_version_follows_the_bytes_of_the_numerical_modules(tmp_path, monkeypatch):
    files = []
    for name in ("driver.py", "problem.py"):
        f = tmp_path / "bem" / name
        f.parent.mkdir(exist_ok=True)
        f.write_text(f"# {name}\nX = 1.0\n")
        files.append(f)
    monkeypatch.setattr(sweeps.integrity, "_code_files", lambda: files)
    version = sweeps.integrity.code_version.__wrapped__
    first = version()
    assert version() == first and first.startswith("0.1.0+")
    files[1].write_text("# problem.py\nX = 1.0000001\n")
    assert version() != first
    monkeypatch.undo()
    real = {f"{p.parent.name}/{p.name}" for p in sweeps.integrity._code_files()}
    assert {"bem/driver.py", "frictional/solve.py", "bem/problem.py", "sweeps/point.py"} <= real
    assert not {"bem/cli.py", "bem/plots.py"} & real


def point_file(cache: Path, point_id: str) -> Path:
    return cache / "points" / f"{point_id}.json"


def edit_value(f: Path) -> None:
    data = json.loads(f.read_text())
    data["row"]["rolling_resistance"] = 999.0
    f.write_text(json.dumps(data))


POINT_DAMAGE = {
    "an edited value": (edit_value, "does not match its checksum (edited or damaged)"),
    "status ok alone": (lambda f: f.write_text('{"status": "ok"}'), "is not a cached point of this form"),
    "a list": (lambda f: f.write_text("[1, 2, 3]"), "holds a JSON list, not a cached point"),
    "a string": (lambda f: f.write_text('"ok"'), "holds a JSON str, not a cached point"),
    "truncated": (lambda f: f.write_text(f.read_text()[:40]), "cannot be read (JSONDecodeError"),
    "binary": (lambda f: f.write_bytes(b"\x00\xff\xfe" * 9), "cannot be read"),
    "a folder": (lambda f: (f.unlink(), f.mkdir()), "cannot be read (IsADirectoryError"),
}


@pytest.mark.parametrize("damage", POINT_DAMAGE)
def test_a_damaged_cached_point_is_computed_again(copy, sweep_command, tmp_path, damage):
    path, out, cache, before = copy
    spoil, reason = POINT_DAMAGE[damage]
    f = point_file(cache, before[1]["point_id"])
    spoil(f)
    code, err = sweep_command(path, "--out", tmp_path / "new", "--cache", cache, "--no-plots", "--quiet")
    assert code == 0, err
    assert f"point 1: cached point {f} {reason}" in err and "; computed again" in err
    s = summary(tmp_path / "new")
    assert s["computed"] == 1 and s["resumed"] == 2
    assert rows(tmp_path / "new" / "results.csv") == before
    if damage == "a folder":
        assert f.is_dir() and "point 1 not cached (IsADirectoryError" in err


def edit_cell(table: Path, line: int, column: str, value: str) -> None:
    text = table.read_text().splitlines(keepends=True)
    header = next(csv.reader([text[0]]))
    cells = next(csv.reader([text[line - 1]]))
    cells[header.index(column)] = value
    text[line - 1] = ",".join(cells) + "\n"
    table.write_text("".join(text))


TABLE_DAMAGE = {
    "an edited value": (lambda t: edit_cell(t, 3, "rolling_resistance", "999.0"),
                        "line 3 (point 1): its cells do not match its checksum (edited or damaged)"),
    "an edited load": (lambda t: edit_cell(t, 4, "loading.load", "151.0"),
                       "line 4 (point 2): its cells do not match its checksum"),
    "binary bytes appended": (lambda t: t.write_bytes(t.read_bytes() + b"\x89PNG\r\n\x1a\n\x00\xff\xfe"),
                              "line 5: not UTF-8 text"),
    "a row given twice": (lambda t: t.write_text(t.read_text() + t.read_text().splitlines(keepends=True)[1]),
                          "line 5 (point 0): point 0 is given twice"),
    "a garbled header": (lambda t: t.write_bytes(b"\xff\xfe" + t.read_bytes()), "line 1: not UTF-8 text (the header)"),
}


@pytest.mark.parametrize("damage", TABLE_DAMAGE)
def test_a_damaged_table_is_rebuilt_from_the_point_cache(copy, sweep_command, damage):
    path, out, cache, before = copy
    spoil, reason = TABLE_DAMAGE[damage]
    spoil(out / "results.csv")
    code, err = sweep_command(path, "--out", out, "--cache", cache, "--no-plots", "--quiet")
    assert code == 0, err
    assert f"{out / 'results.csv'} is damaged ({reason}" in err and "rebuilt from its" in err
    assert rows(out / "results.csv") == before


@pytest.mark.parametrize("damage", TABLE_DAMAGE)
def test_a_damaged_table_without_a_cache_is_refused(copy, sweep_command, damage):
    path, out, cache, before = copy
    spoil, reason = TABLE_DAMAGE[damage]
    table = out / "results.csv"
    spoil(table)
    damaged = table.read_bytes()
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet")
    assert code == 2
    assert f"sweep: error: {table} is damaged: {reason}" in err and "--overwrite" in err
    assert table.read_bytes() == damaged  # refused: left as it was
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet", "--overwrite")
    assert code == 0 and rows(table) == before


def test_a_row_cut_short_by_an_interrupted_run_is_computed_again(copy, sweep_command):
    path, out, cache, before = copy
    table = out / "results.csv"
    table.write_text(table.read_text()[:-30])  # the last row loses its end and its newline
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet")
    assert code == 0, err
    assert "computed again: line 4: cut short (an interrupted run)" in err
    assert summary(out)["computed"] == 1 and rows(table) == before


def test_a_folder_in_place_of_the_table_is_refused(copy, sweep_command):
    path, out, cache, before = copy
    (out / "results.csv").unlink()
    (out / "results.csv").mkdir()
    for extra in ((), ("--overwrite",)):
        code, err = sweep_command(path, "--out", out, "--cache", cache, "--no-plots", "--quiet", *extra)
        assert code == 2 and f"{out / 'results.csv'}: is a folder, not the sweep's file" in err
    assert (out / "results.csv").is_dir()


def test_another_sweep_into_the_same_folder_is_refused(copy, sweep_command, load_sweep_file):
    path, out, cache, before = copy
    speeds = load_sweep_file([0.02, 0.05], axis="loading.speed", file="speeds.toml")
    renamed = load_sweep_file(name="other", file="other.toml")
    for other, says in ((speeds, "this is 'speeds' over loading.speed"),
                        (renamed, "this is 'other' over loading.load")):
        code, err = sweep_command(other, "--out", out, "--cache", cache, "--no-plots", "--quiet")
        assert code == 2, err
        assert f"{out} holds the sweep 's' over loading.load; {says}: not replaced" in err and "--overwrite" in err
        assert rows(out / "results.csv") == before
    (out / "sweep.json").unlink()  # the table's header still tells whose it is
    code, err = sweep_command(speeds, "--out", out, "--cache", cache, "--no-plots", "--quiet")
    assert code == 2 and "is the table of a sweep over loading.load; this sweep's axes are loading.speed" in err
    code, err = sweep_command(speeds, "--out", out, "--cache", cache, "--no-plots", "--quiet", "--overwrite")
    assert code == 0, err
    assert "--overwrite" in err and [r["loading.speed"] for r in rows(out / "results.csv")] == ["0.02", "0.05"]


def test_a_resumed_sweep_computes_its_failed_points_again(sweep_command, load_sweep_file, tmp_path, monkeypatch):
    path = load_sweep_file(file="failing.toml")
    out = tmp_path / "out"
    real = bem.solve

    def failing(problem, *args, **kwargs):
        if problem.loading.load == 80.0:
            raise RuntimeError("a solver failure made for this test")
        return real(problem, *args, **kwargs)

    monkeypatch.setattr(bem, "solve", failing)
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet")
    assert code == 1 and [r["status"] for r in rows(out / "results.csv")] == ["ok", "failed", "ok"]
    monkeypatch.setattr(bem, "solve", real)
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet", "--keep-failed")
    assert code == 1 and summary(out)["computed"] == 0 and summary(out)["failed"] == 1
    code, err = sweep_command(path, "--out", out, "--no-cache", "--no-plots", "--quiet")
    assert code == 0, err
    assert "1 point(s) that failed in the earlier run computed again (points 1)" in err
    s = summary(out)
    assert s["computed"] == 1 and s["resumed"] == 2 and s["failed"] == 0
    assert [r["status"] for r in rows(out / "results.csv")] == ["ok"] * 3


def test_an_edited_input_file_makes_a_new_point(tmp_path):
    """A point's identity holds the content of the files its case names (a master curve),
    so a cached point of the old file is never served for the new one."""
    from sweeps import expand, read_sweep

    curve = tmp_path / "curve.csv"
    curve.write_text("omega,G',G''\n0.1,3.0e6,1.0e5\n1.0,3.5e6,5.0e5\n10.0,5.0e6,1.0e6\n100.0,6.0e6,2.0e5\n")
    base = tmp_path / "base.toml"
    text = (Path(__file__).resolve().parents[2] / "examples" / "sweeps" / "base-frictionless.toml").read_text()
    material = text.index("[material]")
    base.write_text(text[:material] + f'[material]\nmodel = "table"\nfile = "{curve}"\n\n'
                    + text[text.index("[indenter]"):])
    path = tmp_path / "s.toml"
    path.write_text(f'case = "{base}"\n[[axis]]\nkey = "loading.load"\nvalues = [20.0]\n')
    first = expand(read_sweep(path))[0].point_id
    assert expand(read_sweep(path))[0].point_id == first
    curve.write_text(curve.read_text().replace("5.0e5", "5.1e5"))
    assert expand(read_sweep(path))[0].point_id != first


def test_a_cache_that_is_not_a_folder_is_refused(sweep_command, load_sweep_file, tmp_path):
    path = load_sweep_file(file="cache-file.toml")
    (tmp_path / "cache").write_text("not a folder")
    code, err = sweep_command(path, "--out", tmp_path / "out", "--cache", tmp_path / "cache", "--no-plots", "--quiet")
    assert code == 2 and f"--cache {tmp_path / 'cache'}: cannot be used as the cache folder" in err, err
    assert not (tmp_path / "out").exists()
