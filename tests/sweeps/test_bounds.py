"""Bounded resources and confined outputs: a sweep too large to build is refused from its
axes' lengths alone, a scheduler that is not there (or not Dask) is an error within the
timeout whatever the failure, and a sweep's name cannot lead its files out of the output
folder."""

from __future__ import annotations

import json
import socket
import threading
import time
from pathlib import Path

import pytest

from sweeps import MAX_POINTS
from sweeps.cli import main

ROOT = Path(__file__).resolve().parents[2]
BASE = ROOT / "examples" / "sweeps" / "base-frictionless.toml"


def write(tmp_path: Path, body: str, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(f'case = "{BASE}"\n{body}')
    return path


def timed(args, capsys) -> tuple[int, str, float]:
    t0 = time.perf_counter()
    code = main([str(a) for a in args])
    return code, capsys.readouterr().err, time.perf_counter() - t0


@pytest.mark.parametrize("axes, count", [
    ('[[axis]]\nkey = "loading.load"\nstart = 1.0\nstop = 2.0\nnum = 1000000\n', "num = 1000000 values"),
    ('[[axis]]\nkey = "loading.load"\nstart = 1.0\nstop = 2.0\nnum = 1000000000000\n', "num = 1000000000000 values"),
    ('[[axis]]\nkey = "loading.load"\nstart = 1.0\nstop = 200.0\nnum = 200\n'
     '[[axis]]\nkey = "loading.speed"\nstart = 0.01\nstop = 0.1\nnum = 200\n',
     "40000 points (loading.load (200) x loading.speed (200), combined as product)"),
    ('[[axis]]\nkey = "loading.load"\nvalues = [' + ", ".join(f"{1 + i}.0" for i in range(MAX_POINTS + 1)) + "]\n",
     f"(loading.load): {MAX_POINTS + 1} values"),
])
def test_a_sweep_too_large_is_refused_before_its_points_are_built(tmp_path, capsys, axes, count):
    path = write(tmp_path, axes)
    for extra in (["--check"], ["--out", str(tmp_path / "out"), "--no-cache"]):
        code, err, seconds = timed([path, *extra], capsys)
        assert code == 2 and count in err and f"at most {MAX_POINTS} points" in err, err
        assert seconds < 10  # measured 0.1-0.5 s on a loaded machine: nothing is built
    assert not (tmp_path / "out").exists()


def test_the_limit_itself_is_allowed(tmp_path, capsys):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nstart = 1.0\nstop = 2.0\nnum = 100\n'
                           '[[axis]]\nkey = "loading.speed"\nstart = 0.01\nstop = 0.1\nnum = 100\n')
    from sweeps import count, read_sweep

    assert count(read_sweep(path)) == MAX_POINTS


@pytest.mark.parametrize("name", ["/tmp/escape", "../escape", "a/../../escape", "..", "C:escape", "a\nb"])
def test_a_name_that_leaves_the_output_folder_is_refused(tmp_path, capsys, name, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = write(tmp_path, f'name = {json.dumps(name)}\n[[axis]]\nkey = "loading.load"\nvalues = [10.0]\n')
    code, err, _ = timed([path, "--no-cache"], capsys)
    assert code == 2 and f"name = {name!r} must be a relative name inside the output folder" in err, err
    assert not (tmp_path / "out").exists() and not Path("/tmp/escape").exists()


class Server:
    """A TCP server on localhost that accepts and then says nothing, or sends ``reply``."""

    def __init__(self, reply: bytes = b""):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.address = f"tcp://127.0.0.1:{self.sock.getsockname()[1]}"
        self.reply, self.conns = reply, []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(conn)
            if self.reply:
                try:
                    conn.sendall(self.reply)
                except OSError:
                    pass

    def close(self):
        for c in self.conns:
            c.close()
        self.sock.close()


@pytest.mark.parametrize("reply, says", [
    (b"", "no Dask scheduler answers at {address} within 1 s;"),
    (b"HTTP/1.1 200 OK\r\nContent-Length: 5\r\n\r\nhello", "no Dask scheduler answers at {address} within 1 s ("),
    (b"\x01" + b"\x00" * 7 + b"\xff" * 8 + b"garbage" * 50, "no Dask scheduler answers at {address} within 1 s"),
])
def test_a_server_that_is_not_dask_is_an_error_within_the_timeout(tmp_path, capsys, reply, says):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nvalues = [10.0]\n')
    server = Server(reply)
    try:
        code, err, seconds = timed([path, "--out", tmp_path / "out", "--no-cache", "--scheduler", server.address,
                                    "--timeout", "1"], capsys)
    finally:
        server.close()
    assert code == 2 and says.format(address=server.address) in err, err
    assert seconds < 8  # the 1 s deadline holds (measured about 1.0 s silent, under 0.5 s with garbage)
    assert not (tmp_path / "out" / "results.csv").exists()


@pytest.mark.parametrize("content, says", [
    (None, "no such scheduler file"),
    ("not json", "not a Dask scheduler file (JSONDecodeError"),
    ('{"id": "x"}', "the scheduler file names no address"),
])
def test_a_bad_scheduler_file_is_an_error_at_once(tmp_path, capsys, content, says):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nvalues = [10.0]\n')
    info = tmp_path / "scheduler.json"
    if content is not None:
        info.write_text(content)
    code, err, seconds = timed([path, "--out", tmp_path / "out", "--no-cache", "--scheduler", info,
                                "--timeout", "1"], capsys)
    assert code == 2 and f"--scheduler {info}: {says}" in err, err
    assert seconds < 8


def test_a_scheduler_file_naming_a_silent_server(tmp_path, capsys):
    path = write(tmp_path, '[[axis]]\nkey = "loading.load"\nvalues = [10.0]\n')
    server = Server()
    info = tmp_path / "scheduler.json"
    info.write_text(json.dumps({"address": server.address}))
    try:
        code, err, seconds = timed([path, "--out", tmp_path / "out", "--no-cache", "--scheduler", info,
                                    "--timeout", "1"], capsys)
    finally:
        server.close()
    assert code == 2 and f"--scheduler {info}: no Dask scheduler answers at {server.address} within 1 s" in err
    assert seconds < 8
