"""Verification cases are checked whole before anything is solved: every typo below ends
in exit 2 with a message naming the file, the gate and the field."""

import copy
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from verification.cli import main as verify_main
from verification.methods import bem as bem_method
from verification.runner import CASES_DIR, CaseError, list_cases, load_case

THICK = (CASES_DIR / "thick-layer.toml").read_text()


@pytest.fixture
def no_solve(monkeypatch):
    """Any solve is a test failure: the checks must come first."""
    def boom(*args, **kwargs):
        raise AssertionError("a solve started before the input was checked")

    monkeypatch.setattr(bem_method, "solve", boom)
    monkeypatch.setattr(bem_method, "run", boom)
    import verification.methods.fem as fem_method

    monkeypatch.setattr(fem_method, "solve", boom)
    monkeypatch.setattr(fem_method, "run", boom)


def _verify(tmp_path, text, capsys, name="thick-layer", *extra):
    folder = tmp_path / "cases"
    folder.mkdir(exist_ok=True)
    (folder / f"{name}.toml").write_text(text)
    code = verify_main(["--cases-dir", str(folder), "--out", str(tmp_path / "out"), *extra])
    return code, capsys.readouterr().err


TYPOS = [
    # (what, replace, by, the message must contain)
    ("method typo", 'methods = ["bem"]\nagainst = "fem"\nlevels', 'methods = ["bme"]\nagainst = "fem"\nlevels',
     "gates[1] (contact_radius) methods: unknown method 'bme'; known: bem, fem; did you mean 'bem'?"),
    ("level typo", 'levels = ["finest", "extrapolated"]', 'levels = ["finset", "extrapolated"]',
     "gates[1] levels[0] must be one of \"finest\", \"extrapolated\", got 'finset'; did you mean 'finest'?"),
    ("quantity typo", 'quantity = "indentation"', 'quantity = "indentaton"',
     "gates[2] (indentaton): unknown quantity 'indentaton'"),
    ("against typo", 'against = "fem"\nlevels', 'against = "fme"\nlevels',
     "gates[1] (contact_radius) against: unknown reference 'fme'; known: analytic, bem, fem; did you mean 'fem'?"),
    ("reference typo", 'reference = "jaffar_thick"', 'reference = "jafar_thick"',
     "[analytic] reference must be one of \"hertz\", \"jaffar_thick\", \"jaffar_thin\", got 'jafar_thick'"),
    ("unknown gate key", "tolerance = 0.01\nreason", "tolerence = 0.01\nreason",
     "gates[0]: unknown key 'tolerence'"),
    ("gate without reason", 'reason = "Jaffar', 'reasons = "Jaffar', "gates[0]: unknown key 'reasons'"),
    ("negative tolerance", "tolerance = 0.01\nreason", "tolerance = -0.01\nreason", "tolerance must be > 0"),
    ("unknown section", "[analytic]", "[analytc]", "unknown key or section 'analytc'"),
    ("unknown kind", 'kind = "stationary"', 'kind = "stationnary"', "kind: unknown kind 'stationnary'"),
    ("quick as a string", "quick = true", 'quick = "yes"', "quick must be true or false"),
    ("problem typo", "shear_modulus = 3.0e6", "shear_modulus = -3.0e6", "[problem]"),
    ("bem section typo", "half_width = 5.4e-3", "halfwidth = 5.4e-3", "[bem]: unknown key 'halfwidth'"),
    ("fem section typo", 'model = "axisymmetric"', 'model = "axisymetric"', "[fem]"),
    ("extrapolated from too few levels", "spacings = [0.4e-3, 0.2e-3, 0.1e-3]", "spacings = [0.2e-3, 0.1e-3]",
     "'extrapolated' needs three levels of 'bem', the case gives 2"),
    ("name not the file's", 'name = "thick-layer"', 'name = "thick"', "must be the file's name"),
    ("not TOML", "[bem]", "[bem", "not a valid TOML file"),
]


@pytest.mark.parametrize("what, old, new, message", TYPOS, ids=[t[0] for t in TYPOS])
def test_each_typo_is_an_input_error_before_any_solve(what, old, new, message, tmp_path, capsys, no_solve):
    assert old in THICK, what
    code, err = _verify(tmp_path, THICK.replace(old, new, 1), capsys)
    assert code == 2, err
    assert message in err and "thick-layer.toml" in err, err
    assert not (tmp_path / "out").exists()


def test_a_case_without_gates_is_an_error(tmp_path, capsys, no_solve):
    text = THICK[: THICK.index("[[gates]]")]
    code, err = _verify(tmp_path, text, capsys)
    assert code == 2 and "needs gates: at least one [[gates]] table" in err
    code, err = _verify(tmp_path, "gates = []\n" + text, capsys)
    assert code == 2 and "gates must be a non-empty array of tables" in err


def test_a_gate_on_a_quantity_the_reference_lacks_is_an_error(tmp_path, capsys, no_solve):
    text = THICK.replace('methods = ["bem", "fem"]\nagainst = "analytic"',
                         'methods = ["bem", "fem"]\nagainst = "analytic"\nquantity = "x"', 1)
    text = text.replace('quantity = "contact_radius"\nmethods = ["bem", "fem"]', 'methods = ["bem", "fem"]', 1)
    text = text.replace('quantity = "x"', 'quantity = "indentation"')
    code, err = _verify(tmp_path, text, capsys)
    assert code == 2 and "the 'jaffar_thick' solution gives no 'indentation'" in err, err


def test_all_errors_of_all_cases_are_reported_together(tmp_path, capsys, no_solve):
    folder = tmp_path / "cases"
    folder.mkdir()
    (folder / "a.toml").write_text(THICK.replace('name = "thick-layer"', 'name = "a"').replace('"bem", "fem"]', '"bme", "fem"]', 1))
    (folder / "b.toml").write_text(THICK.replace('name = "thick-layer"', 'name = "b"').replace("[bem]", "[bem", 1))
    code = verify_main(["--cases-dir", str(folder), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2 and "a.toml" in err and "b.toml" in err


def test_usage_errors_name_what_is_missing(tmp_path, capsys, no_solve):
    assert verify_main(["--cases-dir", str(tmp_path / "nowhere")]) == 2
    assert "cases folder" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    assert verify_main(["--cases-dir", str(tmp_path / "empty")]) == 2
    assert "holds no case file" in capsys.readouterr().err
    assert verify_main(["--case", "thik-layer", "--out", str(tmp_path / "o")]) == 2
    assert "did you mean 'thick-layer'?" in capsys.readouterr().err
    (tmp_path / "file").write_text("x")
    assert verify_main(["--case", "table1", "--out", str(tmp_path / "file")]) == 2
    assert "is a file, not a folder" in capsys.readouterr().err
    assert verify_main(["--case", "table1", "--out", str(tmp_path / "file" / "sub")]) == 2
    assert verify_main(["--case", "table1", "--junit", str(tmp_path / "j.txt"), "--out", str(tmp_path / "o")]) == 2
    assert "must end in .xml" in capsys.readouterr().err
    assert verify_main(["--case", "table1", "--baseline", str(tmp_path / "file"), "--out", str(tmp_path / "o")]) == 2
    assert "not a metrics.json" in capsys.readouterr().err
    assert verify_main(["--case", "table1", "--method", "x=nosuchmodule:solve", "--out", str(tmp_path / "o")]) == 2
    assert "cannot import 'nosuchmodule'" in capsys.readouterr().err


def test_every_shipped_case_loads():
    for path in list_cases():
        case = load_case(path)
        assert case["gates"]


# --- random mutations of every shipped case -----------------------------------------

CASES = {p.stem: tomllib.loads(p.read_text()) for p in list_cases()}


def _leaves(node, path=()):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(node, list) and node and all(isinstance(v, dict) for v in node):
        for i, v in enumerate(node):
            yield from _leaves(v, path + (i,))
    else:
        yield path, node


def _keys(node, path=()):
    if isinstance(node, dict):
        for k, v in node.items():
            yield path + (k,)
            yield from _keys(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            if isinstance(v, dict):
                yield from _keys(v, path + (i,))


def _wrong_type(value):
    """Values of a type the key cannot take (bool is never a number here)."""
    if isinstance(value, bool):
        return ["yes", 1, [True]]
    if isinstance(value, (int, float)):
        return ["1.0", True, [value], {"v": value}]
    if isinstance(value, str):
        return [1, True, [value], {"v": value}]
    if isinstance(value, list):
        return ["list", 3, {"v": 1}]
    return ["table", 3, [1]]


def _at(node, path):
    for p in path:
        node = node[p]
    return node


def _dump(data) -> str:
    """TOML of nested dicts, lists, strings, numbers and bools (enough for the cases)."""
    def val(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            return repr(v)
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return "{" + ", ".join(f"{k!r} = {val(x)}".replace("'", '"') for k, x in v.items()) + "}"
    return "\n".join(f'"{k}" = {val(v)}' for k, v in data.items()) + "\n"


@st.composite
def mutations(draw):
    name = draw(st.sampled_from(sorted(CASES)))
    case = copy.deepcopy(CASES[name])
    how = draw(st.sampled_from(["rename", "retype", "remove"]))
    if how == "rename":
        path = draw(st.sampled_from(list(_keys(case))))
        parent = _at(case, path[:-1])
        suffix = draw(st.sampled_from(["_", "s", "x", "2"]))
        new = str(path[-1]) + suffix
        parent[new] = parent.pop(path[-1])
    elif how == "retype":
        path, value = draw(st.sampled_from(list(_leaves(case))))
        _at(case, path[:-1])[path[-1]] = draw(st.sampled_from(_wrong_type(value)))
    else:
        required = ["problem", "gates", "kind", "name", "title", "bem", "fem", "analytic", "sweep", "table1",
                    "limits", "speeds", "sweeps"]
        required = [s for s in required if s in case]
        section = draw(st.sampled_from(required))
        del case[section]
    return name, how, case


@settings(max_examples=150, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(mutations())
def test_a_mutated_case_is_an_input_error_never_a_pass_nor_a_traceback(tmp_path_factory, mutation):
    name, how, case = mutation
    folder = tmp_path_factory.mktemp("mut")
    path = folder / f"{name}.toml"
    path.write_text(_dump(case))
    with pytest.raises(CaseError):
        load_case(path)
