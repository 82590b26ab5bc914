"""Case files at the edges: what no case file holds, each refused as a CaseFileError that
names the file and what is wrong, never a traceback."""

from __future__ import annotations

import pytest

import casefile
from casefile.reader import CaseFileError, parse_override

GOOD = """
[layer]
thickness = 0.01
[material]
model = "elastic"
shear_modulus = 1e6
[indenter]
shape = "sphere"
radius = 0.02
[loading]
load = 1.0
[grid]
spacing = 1e-3
period = 0.1
truncation = 64
"""


def _file(tmp_path, data, name="case.toml"):
    path = tmp_path / name
    (path.write_bytes if isinstance(data, bytes) else path.write_text)(data)
    return path


def test_a_good_file_reads(tmp_path):
    assert casefile.read(_file(tmp_path, GOOD), tool="bem")["grid"]["spacing"] == 1e-3


@pytest.mark.parametrize("text", ["x = " + "[" * 600 + "]" * 600, "x = " + "{a = " * 600 + "1" + "}" * 600])
def test_nesting_too_deep_to_read_is_refused(tmp_path, text):
    with pytest.raises(CaseFileError, match=r"case\.toml: its arrays or inline tables are nested too deeply"):
        casefile.read(_file(tmp_path, text))


def test_a_deep_table_header_is_an_unknown_key(tmp_path):
    text = GOOD + "[layer." + ".".join(["a"] * 5000) + "]\n"
    with pytest.raises(CaseFileError, match=r"\[layer\]: unknown key 'a'"):
        casefile.read(_file(tmp_path, text), tool="bem")


@pytest.mark.parametrize("data, byte", [(GOOD.replace("elastic", "\xe9lastic").encode("latin-1"), "0xe9"),
                                        (bytes(range(128, 256)), "0x80")])
def test_a_file_that_is_not_utf8_is_refused_naming_the_byte(tmp_path, data, byte):
    with pytest.raises(CaseFileError, match=rf"case\.toml: not a UTF-8 text file \(TOML is UTF-8; byte {byte} "):
        casefile.read(_file(tmp_path, data))


def test_a_long_dotted_override_is_refused_and_clipped():
    text = "a" + ".b" * 100_000 + "=1"
    with pytest.raises(CaseFileError) as info:
        parse_override(text)
    message = str(info.value)
    assert message.startswith("--set expects section.key=value (one dot in the name), got 'a.b.b")
    assert message.endswith(f"... ({len(text)} characters)") and len(message) < 200
