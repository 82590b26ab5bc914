"""Property test of the case-file readers: a wrong type or an out-of-range value at any key
of the schema, a renamed key or a removed section, is an input error in every tool that
reads it (ValueError in bem, InputError in fem_reference, exit status 2 from the CLIs),
never another exception and never a result."""

from __future__ import annotations

import copy
import math
import string

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import casefile
from bem.case import friction_from_config, problem_from_config
from bem.cli import main as bem_main
from fem_reference import InputError
from fem_reference.case import problem_from_dict

VALID = {
    "layer": {"thickness": 5e-3, "density": 0.0},
    "loading": {"speed": 0.0, "load": 100.0},
    "grid": {"spacing": 1e-3, "period": 0.2, "truncation": 100, "half_width": 5e-3},
}
VARIANTS = {
    ("material", "elastic"): {"shear_modulus": 3e6},
    ("material", "three_parameter"): {"G0": 3e6, "tau": 0.25, "f": 1.0},
    ("material", "prony"): {"G_inf": 1e6, "G": [2e6], "tau": [0.1]},
    ("material", "table"): {"file": "curve.csv"},
    ("material", "dma"): {"file": "dma.csv", "reference_temperature": 293.15, "C1": 8.86, "C2": 101.6,
                          "extrapolate": True},
    ("indenter", "sphere"): {"radius": 0.02},
    ("indenter", "paraboloid"): {"radius": 0.02},
    ("indenter", "cylinder"): {"radius": 0.02, "length": 0.01},
    ("indenter", "heightmap"): {"file": "h.npz"},
}


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A folder with the files that path keys point at."""
    path = tmp_path_factory.mktemp("cases")
    np.savetxt(path / "curve.csv", [[1e-3, 3e6, 1e3], [1e3, 3.1e6, 2e5], [1e6, 6e6, 1e4]], delimiter=",")
    (path / "dma.csv").write_text("temperature_K,omega_rad_s,G_storage_Pa,G_loss_Pa\n"
                                  "293.15,1,3e6,1e5\n293.15,10,3.2e6,2e5\n293.15,100,3.6e6,3e5\n")
    x = np.linspace(-0.01, 0.01, 21)
    np.savez(path / "h.npz", x=x, y=x, h=(x[None, :] ** 2 + x[:, None] ** 2) / 0.04)
    (path / "a_folder").mkdir()
    return path


def _case(section: str | None = None, variant: str | None = None) -> dict:
    """A valid case; with ``section`` and ``variant``, that material model or indenter shape,
    with ``section = "friction"`` a frictional rolling case, with ``"fem"`` an [fem] section."""
    data = copy.deepcopy(VALID)
    data["material"] = {"model": "elastic", "shear_modulus": 3e6}
    data["indenter"] = {"shape": "sphere", "radius": 0.02}
    if (section, variant) in VARIANTS:
        selector = casefile.schema.section(section).selector
        data[section] = {selector: variant, **VARIANTS[section, variant]}
    if section == "friction":
        data["friction"] = {"mu": 0.2}
        data["loading"]["speed"] = 0.05
    if section == "fem":
        data["fem"] = {}
    return data


def _slots() -> list[tuple]:
    """Every (section, variant, key) of the schema."""
    out = []
    for spec in casefile.SCHEMA:
        out += [(spec.name, None, key) for key in spec.keys]
        out += [(spec.name, name, key) for name, v in spec.variants.items() for key in v.keys]
    return out


SLOTS = _slots()
NOT_FINITE = st.sampled_from([math.nan, math.inf, -math.inf])
NOT_A_NUMBER = st.one_of(st.booleans(), st.text(max_size=5), st.just([]), st.just({}), st.just([1.0, "a"]))


def wrong_values(key: casefile.Key) -> st.SearchStrategy:
    """Values that break ``key``'s type or rule."""
    if key.kind == "number":
        bad = [NOT_A_NUMBER, NOT_FINITE]
        if key.rule == ">0":
            bad.append(st.floats(max_value=0.0, allow_nan=False, allow_infinity=False))
        if key.rule == ">=0":
            bad.append(st.floats(max_value=-1e-300, allow_nan=False, allow_infinity=False))
        return st.one_of(*bad)
    if key.kind == "integer":
        bad = [NOT_A_NUMBER, st.floats(allow_nan=False, allow_infinity=False)]
        bad.append(st.integers(max_value=0 if key.rule == ">0" else -1))
        return st.one_of(*bad)
    if key.kind == "numbers":
        return st.one_of(st.just([]), st.floats(), st.booleans(), st.lists(st.text(max_size=3), min_size=1),
                         st.lists(st.floats(max_value=0.0), min_size=1), st.lists(NOT_FINITE, min_size=1))
    if key.kind == "path":
        return st.one_of(st.integers(), st.booleans(), st.just(""), st.just("missing.npz"), st.just("a_folder"))
    if key.kind == "bool":  # only true and false
        return st.one_of(st.integers(), st.floats(), st.text(max_size=5), st.just([]))
    wrong = st.text(max_size=8).filter(lambda s: s not in key.choices) if key.choices else st.nothing()
    return st.one_of(st.integers(), st.booleans(), st.floats(), st.just([]), wrong)


def _translate(data: dict, folder) -> list:
    """What each tool that reads the case makes of it: a list of results (no solve)."""
    data = casefile.validate(data, folder=folder)  # resolves the paths against the folder
    made = []
    try:
        made += [problem_from_config(data), friction_from_config(data)]
    except casefile.CaseFileError as exc:
        if "cannot solve" not in str(exc) and "does not read" not in str(exc):
            raise
    try:
        made.append(problem_from_dict(data))
    except InputError as exc:
        if "cannot solve" not in str(exc) and "does not read" not in str(exc) and "speed must be 0" not in str(exc):
            raise
    return made


def _expect_input_error(data: dict, folder) -> None:
    try:
        made = _translate(data, folder)
    except (ValueError, InputError):
        return
    pytest.fail(f"accepted {data}: {made}")


def test_the_valid_cases_are_accepted(folder):
    """The base cases themselves pass, so the property below tests the mutation."""
    for section, variant, _ in SLOTS:
        assert _translate(_case(section, variant), folder)


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(slot=st.sampled_from(SLOTS), data=st.data())
def test_a_wrong_value_at_any_key_is_an_input_error(folder, slot, data):
    section, variant, key = slot
    case = _case(section, variant)
    value = data.draw(wrong_values(key), label=f"[{section}] {key.name}")
    case.setdefault(section, {})[key.name] = value
    _expect_input_error(case, folder)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(slot=st.sampled_from(SLOTS), data=st.data())
def test_a_renamed_key_or_a_removed_section_is_an_input_error(folder, slot, data):
    section, variant, key = slot
    case = _case(section, variant)
    if data.draw(st.booleans(), label="remove a required section"):
        required = [s.name for s in casefile.SCHEMA if s.required_by]
        del case[data.draw(st.sampled_from(required), label="section")]
    else:
        table = case.setdefault(section, {})
        value = table.pop(key.name, key.default if key.default is not None else 1.0)
        at = data.draw(st.integers(0, len(key.name)), label="at")
        typo = key.name[:at] + data.draw(st.sampled_from(string.ascii_lowercase + "_"), label="char") + key.name[at:]
        spec = casefile.schema.section(section)
        assume(spec.key(typo, variant) is None)
        table[typo] = value
    _expect_input_error(case, folder)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(slot=st.sampled_from([s for s in SLOTS if s[1] is None and s[0] in ("layer", "loading", "grid")]),
       data=st.data())
def test_the_cli_exits_2_with_the_key_named(slot, data, capsys):
    """Through ``bem solve --set``: exit status 2 and a message naming the key, no traceback."""
    import json
    from pathlib import Path

    section, _, key = slot
    value = data.draw(wrong_values(key).filter(lambda v: not isinstance(v, dict)), label="value")
    text = json.dumps(value).replace("NaN", "nan").replace("Infinity", "inf")
    case = Path(__file__).resolve().parents[2] / "examples" / "paper-section10-thick.toml"
    code = bem_main(["solve", str(case), "--quiet", "--set", f"{section}.{key.name}={text}"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.startswith("bem: error:") and (key.name in err or "--set" in err), err
