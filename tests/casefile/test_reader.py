"""The case-file schema and reader (casefile): one reader for bem, fem_reference and the
harness; every failure names the file, section and key; nothing passes silently."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

import casefile
from bem.cli import main as bem_main
from fem_reference.cli import main as fem_main

ROOT = Path(__file__).resolve().parents[2]
THICK = str(ROOT / "examples" / "paper-section10-thick.toml")
#: a cheap BEM grid (11 x 11 nodes, Nt = 100): an input that wrongly passes costs < 1 s
CHEAP = ["--set", "grid.spacing=1e-3", "--set", "grid.truncation=100", "--set", "grid.half_width=5e-3"]


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


BASE = """
[layer]
thickness = 5.0e-3
[material]
model = "elastic"
shear_modulus = 3.0e6
[indenter]
shape = "sphere"
radius = 0.02
[loading]
load = 100.0
[grid]
spacing = 1e-3
period = 0.2
truncation = 100
half_width = 5e-3
"""


# --- the schema is the one description --------------------------------------------------


def test_docs_schema_is_generated_from_the_schema():
    text = (ROOT / "docs" / "case-files.md").read_text()
    start, stop = text.index(casefile.docs.BEGIN), text.index(casefile.docs.END) + len(casefile.docs.END)
    assert text[start:stop] == casefile.schema_markdown(), "run `python -m casefile` to regenerate"


def test_documented_defaults_are_the_packages_defaults():
    """A default in the schema is the default of the dataclass the key lands in."""
    from bem import Friction, Layer, Loading
    from fem_reference import FemSettings

    landing = {"friction": Friction, "fem": FemSettings}
    for name, cls in landing.items():
        defaults = {f.name: f.default for f in dataclasses.fields(cls)}
        for key in casefile.schema.section(name).keys:
            assert defaults[key.name] == (key.default if key.default is not None else defaults[key.name]), key
            if key.default is None and key.name in defaults:
                assert defaults[key.name] is None or key.default_doc == "", key
    assert Loading(load=1.0).speed == casefile.schema.section("loading").key("speed").default
    layer_density = {f.name: f.default for f in dataclasses.fields(Layer)}["density"]
    assert layer_density == casefile.schema.section("layer").key("density").default


def test_every_example_and_case_validates():
    for path in sorted((ROOT / "examples").glob("*.toml")):
        casefile.read(path, tool="bem")
    from verification.runner import list_cases, load_case

    for path in list_cases():
        load_case(path)


# --- each failure mode of a case file, with its message --------------------------------


@pytest.mark.parametrize("main, prog", [(bem_main, "bem"), (fem_main, "fem-reference")])
@pytest.mark.parametrize("override, message", [
    ("layer.thicknes=5e-3",
     "[layer]: unknown key 'thicknes'; known keys: thickness, density; did you mean 'thickness'?"),
    ("frction.mu=0.2", "unknown section 'frction'"),
    ("loading.load=true", "[loading] load must be a number (N), got true (a boolean)"),
    ('loading.load="100"', "[loading] load must be a number (N), got '100' (a string)"),
    ("loading.load=abc", "[loading] load takes number, and 'abc' is not one"),
    ("layer.thickness=-0.005", "[layer] thickness must be > 0 m, got -0.005"),
    ("layer.thickness=nan", "[layer] thickness must be finite (m), got nan"),
    ("indenter.shape=cone", 'indenter] shape must be one of "sphere", "paraboloid", "cylinder", "heightmap", "line", got '
                            "'cone'"),
    ("loading.indentation=1e-4", "[loading] needs exactly one of load and indentation, got load, indentation"),
])
def test_both_tools_reject_the_same_input_the_same_way(main, prog, override, message, capsys):
    assert main(["solve", THICK, "--quiet", "--set", override]) == 2
    err = capsys.readouterr().err
    assert err.startswith((f"{prog}: error: {THICK} [", f"{prog}: error: {THICK}: ")) and message in err


def test_fem_reference_refuses_physics_it_cannot_solve(capsys):
    assert fem_main(["solve", THICK, "--quiet", "--set", "friction.mu=0.2"]) == 2
    assert "fem-reference solve cannot solve [friction]" in capsys.readouterr().err
    assert fem_main(["solve", THICK, "--quiet", "--set", "material.model=prony", "--set", "material.G_inf=1e6",
                     "--set", "material.G=[1e6]", "--set", "material.tau=[0.1]"]) == 2
    err = capsys.readouterr().err
    assert "[material]: unknown key 'shear_modulus' for model = \"prony\"" in err
    # the BEM's [grid] is the one section it ignores
    assert fem_main(["solve", THICK, "--quiet", "--set", "grid.spacing=1e-3", "--set", "fem.element_size=3e-4"]) == 0
    assert "contact radius" in capsys.readouterr().out


def test_the_shape_default_is_the_same_for_both(tmp_path):
    from bem.case import problem_from_config
    from fem_reference.case import problem_from_dict

    data = casefile.read(_write(tmp_path / "c.toml", BASE.replace('shape = "sphere"\n', "")))
    assert data["indenter"]["shape"] == "sphere"
    assert problem_from_dict(data).indenter.shape == "sphere"
    assert type(problem_from_config(data)[0].indenter).__name__ == "Sphere"


def test_harness_builds_the_fem_problem_through_fem_reference(tmp_path):
    """The harness no longer builds the FEM problem by hand: a viscoelastic material is
    refused by name instead of being read as elastic."""
    from fem_reference import InputError
    from verification.methods.fem import run as run_fem

    problem = {"layer": {"thickness": 5e-3}, "material": {"model": "three_parameter", "G0": 3e6, "tau": 0.25, "f": 1.0},
               "indenter": {"shape": "sphere", "radius": 0.02}, "loading": {"load": 100.0}}
    with pytest.raises(InputError, match='cannot solve \\[material\\] model = "three_parameter"'):
        run_fem(problem, {"model": "axisymmetric"}, 2e-4)


def test_paths_resolve_against_the_case_file(tmp_path, monkeypatch):
    """A material table and a height map beside the case file are found from any working
    folder; a missing file, a folder, an archive without h are errors naming the key."""
    from bem.case import problem_from_config

    folder = tmp_path / "cases"
    folder.mkdir()
    np.savetxt(folder / "curve.csv", [[1e-3, 3e6, 1e3], [1e3, 3.1e6, 2e5], [1e6, 6e6, 1e4]], delimiter=",")
    x = np.linspace(-0.01, 0.01, 41)
    h = (x[None, :] ** 2 + x[:, None] ** 2) / 0.04
    np.savez(folder / "h.npz", x=x, y=x, h=h)
    np.savez(folder / "no_h.npz", x=x, y=x)
    text = BASE.replace('model = "elastic"\nshear_modulus = 3.0e6', 'model = "table"\nfile = "curve.csv"')
    text = text.replace('shape = "sphere"\nradius = 0.02', 'shape = "heightmap"\nfile = "h.npz"')
    case = _write(folder / "case.toml", text)
    monkeypatch.chdir(tmp_path)
    data = casefile.read(case, tool="bem")
    assert data["material"]["file"] == str(folder / "curve.csv")
    problem, _ = problem_from_config(data)
    assert problem.indenter.h.shape == (41, 41)
    for override, message in [
        ('indenter.file="missing.npz"', "[indenter] file: file '" + str(tmp_path / "missing.npz") + "' not found"),
        (f'indenter.file="{folder}"', "is a folder, not a file"),
        (f'indenter.file="{folder / "no_h.npz"}"', "lacks the array(s) h"),
        (f'indenter.file="{folder / "curve.csv"}"', "is not an NPZ archive"),
    ]:
        with pytest.raises(casefile.CaseFileError, match=".*".join(map(_escape, message.split("'")))):
            problem_from_config(casefile.read(case, [override], tool="bem"))
    with pytest.raises(casefile.CaseFileError, match="\\[indenter\\] needs file"):
        casefile.validate({**data, "indenter": {"shape": "heightmap"}}, "bem")


def _escape(text: str) -> str:
    import re

    return re.escape(text)


def test_case_file_errors(tmp_path, capsys):
    assert bem_main(["solve", str(tmp_path), "--quiet"]) == 2
    assert "is a folder, not a file" in capsys.readouterr().err
    assert bem_main(["solve", str(tmp_path / "none.toml"), "--quiet"]) == 2
    assert "not found" in capsys.readouterr().err
    bad = _write(tmp_path / "bad.toml", "[layer\nthickness = 1")
    assert fem_main(["solve", str(bad), "--quiet"]) == 2
    assert "not a valid TOML file" in capsys.readouterr().err
    assert bem_main(["solve", THICK, "--quiet", "--set", "thickness=1"]) == 2
    assert "--set expects section.key=value" in capsys.readouterr().err


# --- output paths: checked before the solve; a failed write never loses the result --------


@pytest.mark.parametrize("main", [bem_main, fem_main])
def test_bad_output_paths_fail_before_solving(main, tmp_path, capsys):
    blocker = _write(tmp_path / "file", "")
    for option, path, message in [
        ("--plot", tmp_path / "x.txt", "the file must end in .png or .pdf or .svg"),
        ("--plot", blocker / "x.png", "is a file, not a folder"),
        ("--plot", tmp_path, "must end in"),
    ]:
        assert main(["solve", THICK, *CHEAP, option, str(path)]) == 2
        err = capsys.readouterr().err
        assert message in err and "compliance" not in err and "mesh" not in err  # no solve started
    option = "--fields" if main is bem_main else "--vtu"
    assert main(["solve", THICK, *CHEAP, option, str(tmp_path / "out.txt")]) == 2
    assert "the file must end in" in capsys.readouterr().err


def test_a_failed_write_keeps_the_printed_result(tmp_path, capsys, monkeypatch):
    import bem.plots

    def broken(*_):
        raise OSError("disk full")

    monkeypatch.setattr(bem.plots, "plot_normal_contact", broken)
    fields = tmp_path / "f.npz"
    code = bem_main(["solve", THICK, "--quiet", "--json", *CHEAP, "--plot", str(tmp_path / "p.png"),
                     "--fields", str(fields)])
    out = capsys.readouterr()
    assert code == 1
    assert json.loads(out.out)["load"] == pytest.approx(100.0)
    assert "the result above was computed, but --plot" in out.err and "disk full" in out.err
    assert fields.exists()  # the other output was written


def test_metrics_never_hold_nan(capsys):
    """--json is strict JSON (null, not NaN)."""
    assert bem_main(["solve", THICK, "--quiet", "--json", *CHEAP]) == 0
    json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"non-strict JSON constant {c}"))
