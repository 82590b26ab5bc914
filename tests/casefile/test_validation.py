"""The validation engine (casefile.validation): every kind and rule with its message, and
the one error class and message style shared by case files, verification cases and sweep
files."""

from __future__ import annotations

import math

import pytest

import casefile
from casefile.validation import InputError, Key, check_table, check_value, did_you_mean


def test_every_input_error_is_one_class():
    from sweeps import SweepError
    from verification.schema import CaseError

    for error in (casefile.CaseFileError, CaseError, SweepError):
        assert issubclass(error, InputError) and issubclass(error, ValueError)
    assert casefile.InputError is InputError


@pytest.mark.parametrize("key, value, message", [
    (Key("P", "number", "N"), True, "t P must be a number (N), got true (a boolean)"),
    (Key("P", "number", "N"), "1", "t P must be a number (N), got '1' (a string)"),
    (Key("P", "number", "N"), math.inf, "t P must be finite (N), got inf"),
    (Key("P", "number", "N", rule=">0"), 0.0, "t P must be > 0 N, got 0.0"),
    (Key("rho", "number", "kg/m^3", rule=">=0"), -1.0, "t rho must be >= 0 kg/m^3, got -1.0"),
    (Key("n", "integer"), 2.0, "t n must be an integer, got 2.0"),
    (Key("n", "integer", rule=">=1"), 0, "t n must be an integer >= 1, got 0"),
    (Key("s", "string", choices=("sphere", "line")), "spere",
     "t s must be one of \"sphere\", \"line\", got 'spere'; did you mean 'sphere'?"),
    (Key("s", "string"), " ", "t s must be a non-empty string, got ' ' (a string)"),
    (Key("G", "numbers", "Pa", rule=">0"), [], "t G must be a non-empty list of numbers (Pa), got [] (a list)"),
    (Key("G", "numbers", "Pa", rule=">0"), [1.0, -2.0], "t G[1] must be > 0 Pa, got -2.0"),
    (Key("G", "numbers", "Pa"), [1.0, "a"], "t G[1] must be a number (Pa), got 'a' (a string)"),
    (Key("m", "strings", choices=("bem", "fem")), ["bem", "bme"],
     "t m[1] must be one of \"bem\", \"fem\", got 'bme'; did you mean 'bem'?"),
    (Key("v", "list"), 3, "t v must be a non-empty list, got 3"),
    (Key("q", "bool"), "yes", "t q must be true or false, got 'yes' (a string)"),
    (Key("o", "table"), [1], "t o must be a table, got [1] (a list)"),
    (Key("g", "tables"), [], "t g must be a non-empty array of tables ([[...]]), got [] (a list)"),
    (Key("c", "cells"), [[1, 2, 3]], "t c must be a list of [number, number] pairs, got [[1, 2, 3]] (a list)"),
    (Key("f", "path"), "", "t f must be a path, got '' (a string)"),
])
def test_each_kind_and_rule_refuses_with_the_key_the_rule_and_the_value(key, value, message):
    with pytest.raises(InputError) as err:
        check_value(f"t {key.name}", key, value)
    assert str(err.value) == message


@pytest.mark.parametrize("key, value", [
    (Key("P", "number", rule=">0"), 1), (Key("n", "integer", rule=">=1"), 1), (Key("q", "bool"), False),
    (Key("G", "numbers", rule=">=0"), [0.0, 2]), (Key("c", "cells"), [[1.0, 2]]), (Key("v", "list"), ["a", 1]),
    (Key("g", "tables"), [{}]), (Key("m", "strings", choices=("a",)), ["a", "a"]),
])
def test_each_kind_takes_its_values_unchanged(key, value):
    assert check_value("t", key, value) == value


def test_paths_resolve_against_the_given_folder(tmp_path):
    (tmp_path / "a.csv").write_text("1")
    (tmp_path / "sub").mkdir()
    assert check_value("t f", Key("f", "path"), "a.csv", tmp_path) == str(tmp_path / "a.csv")
    assert check_value("t f", Key("f", "paths"), ["a.csv"], tmp_path) == [str(tmp_path / "a.csv")]
    with pytest.raises(InputError, match=r"t f\[1\]: file '.*b.csv' not found \(paths in a file are relative"):
        check_value("t f", Key("f", "paths"), ["a.csv", "b.csv"], tmp_path)
    with pytest.raises(InputError, match="is a folder, not a file"):
        check_value("t f", Key("f", "path"), "sub", tmp_path)


def test_a_table_names_unknown_missing_and_exclusive_keys():
    keys = (Key("load", "number", "N", "normal load P"), Key("indentation", "number", "m"),
            Key("speed", "number", "m/s", "speed V", required=True))
    assert check_table("c.toml [loading]", {"load": 1.0, "speed": 0.0}, keys, one_of=(("load", "indentation"),))
    with pytest.raises(InputError) as err:
        check_table("c.toml [loading]", {"lod": 1.0}, keys, context=" here")
    assert str(err.value) == ("c.toml [loading]: unknown key 'lod' here; known keys: load, indentation, speed; "
                              "did you mean 'load'?")
    with pytest.raises(InputError, match=r"^c.toml \[loading\] needs speed \(m/s\): speed V$"):
        check_table("c.toml [loading]", {"load": 1.0}, keys)
    with pytest.raises(InputError, match="needs exactly one of load and indentation, got neither"):
        check_table("c.toml [loading]", {"speed": 0.0}, keys, one_of=(("load", "indentation"),))
    assert check_table("t", {"other": 1, "speed": 1.0}, keys, open_=True) == {"other": 1, "speed": 1.0}
    with pytest.raises(InputError, match="^t must be a table, got 3$"):
        check_table("t", 3, keys)


def test_the_caller_names_the_error_class():
    class Mine(InputError):
        pass

    with pytest.raises(Mine):
        check_table("t", {"x": 1}, (), error=Mine)


def test_a_declaration_with_an_unknown_kind_or_rule_is_refused():
    with pytest.raises(ValueError, match="kind must be one of"):
        Key("x", "float")
    with pytest.raises(ValueError, match="rule must be one of"):
        Key("x", "number", rule="<0")


def test_did_you_mean_only_for_a_near_miss():
    assert did_you_mean("thicknes", ["thickness", "density"]) == "; did you mean 'thickness'?"
    assert did_you_mean("zzz", ["thickness", "density"]) == ""


def test_the_three_file_types_say_the_same_mistake_the_same_way(tmp_path):
    """A boolean where a number belongs, and a misspelt key, in a case file, a verification
    case table and a sweep file: one message form."""
    from sweeps import SweepError, read_sweep
    from verification.schema import GATE, CaseError, check_table as check_case_table

    case = {"layer": {"thickness": True}}
    with pytest.raises(casefile.CaseFileError, match=r"^c.toml \[layer\] thickness must be a number \(m\), "
                                                     r"got true \(a boolean\)$"):
        casefile.validate(case, source="c.toml")
    gate = {"quantity": "load", "tolerance": True, "reason": "r"}
    with pytest.raises(CaseError, match=r"^v.toml gates\[0\] tolerance must be a number, got true \(a boolean\)$"):
        check_case_table(gate, GATE, "v.toml gates[0]")
    base = tmp_path / "base.toml"
    base.write_text("")
    sweep = tmp_path / "s.toml"
    sweep.write_text(f'case = "{base.name}"\n[[axis]]\nkey = "loading.load"\nstart = true\nstop = 2.0\nnum = 2\n')
    with pytest.raises(SweepError, match=r"s.toml \[\[axis\]\] #1 \(loading.load\) start must be a number, "
                                         r"got true \(a boolean\)$"):
        read_sweep(sweep)
    for error, run in [
        (casefile.CaseFileError, lambda: casefile.validate({"layer": {"thicknes": 1.0}}, source="c.toml")),
        (CaseError, lambda: check_case_table({"toleranse": 1.0}, GATE, "v.toml gates[0]")),
    ]:
        with pytest.raises(error, match=r"(\[layer\]|gates\[0\]): unknown key '(thicknes|toleranse)'; known keys: "
                                        r".*; did you mean '(thickness|tolerance)'\?$"):
            run()
    sweep.write_text(f'case = "{base.name}"\naxes = []\n')
    with pytest.raises(SweepError, match=r"s.toml: unknown key 'axes'; known keys: name, case, set, combine, axis, "
                                         r"output, fit; did you mean 'axis'\?$"):
        read_sweep(sweep)
