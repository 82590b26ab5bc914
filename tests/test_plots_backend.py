"""Library plotting leaves the caller's matplotlib backend alone.

``matplotlib.use("Agg")`` (or pyplot) inside a library switches a notebook user's
backend; the figures are bare :class:`matplotlib.figure.Figure` objects saved with
``Figure.savefig``. Checked by running every plotting function under a non-Agg backend,
and by reading the source of every package the distribution ships.
"""

from __future__ import annotations

import ast
import importlib.util
import tomllib
from pathlib import Path

import matplotlib
import pytest

import bem
from bem.plots import plot_frictional_contact, plot_normal_contact

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
ROOT = Path(__file__).resolve().parents[1]
# The top-level packages pyproject.toml ships (``casefile*`` -> ``casefile``).
PACKAGES = tuple(pattern.rstrip("*") for pattern in tomllib.loads(
    (ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["setuptools"]["packages"]["find"]["include"])


@pytest.fixture
def svg_backend():
    """Select the (non-Agg) svg backend for the test, restore the previous one after."""
    before = matplotlib.get_backend()
    matplotlib.use("svg", force=True)
    try:
        yield "svg"
    finally:
        matplotlib.use(before, force=True)


def _assert_png(path: Path) -> None:
    data = Path(path).read_bytes()
    assert data[:8] == PNG_SIGNATURE, f"{path} is not a PNG"
    assert len(data) > 5_000, f"{path} is suspiciously small ({len(data)} bytes)"


def _no_open_pyplot_figures() -> bool:
    """No figure left in pyplot's registry (pyplot imported only if something else did)."""
    import sys

    plt = sys.modules.get("matplotlib.pyplot")
    return plt is None or plt.get_fignums() == []


@pytest.fixture(scope="module")
def bem_problem():
    layer = bem.Layer(5e-3, bem.ThreeParameterSolid(G0=3.0e6, tau=0.25, f=1.0), 1000.0)
    grid = bem.Grid.centred((0.5e-3, 0.5e-3), (0.2, 0.2), (200, 200), (4e-3, 4e-3))
    return bem.Problem(layer, bem.Sphere(0.02), grid, bem.Loading(0.1, load=30.0))


def test_bem_plots_keep_backend(svg_backend, bem_problem, tmp_path):
    result = bem.solve(bem_problem)
    out = plot_normal_contact(result, tmp_path / "sub" / "normal.png")
    assert matplotlib.get_backend() == svg_backend
    assert out == tmp_path / "sub" / "normal.png"
    _assert_png(out)

    frictional = bem.solve(bem_problem, bem.Friction(0.2), energy=False)
    out = plot_frictional_contact(frictional, tmp_path / "friction.png")
    assert matplotlib.get_backend() == svg_backend
    _assert_png(out)
    assert _no_open_pyplot_figures()


def test_fem_plot_keeps_backend(svg_backend, tmp_path):
    from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, Layer,
                               Loading, solve)
    from fem_reference.output import plot_result

    result = solve(ContactProblem(Layer(5e-3), ElasticMaterial(3.0e6), Indenter("sphere", 0.02),
                                  Loading(load=100.0), FemSettings(element_size=2e-4)))
    plot_result(result, tmp_path / "fem.png")
    assert matplotlib.get_backend() == svg_backend
    _assert_png(tmp_path / "fem.png")
    assert _no_open_pyplot_figures()


def _package_sources():
    for name in PACKAGES:
        spec = importlib.util.find_spec(name)  # locates the package without importing it
        assert spec is not None and spec.submodule_search_locations, name
        for folder in spec.submodule_search_locations:
            yield from sorted(Path(folder).rglob("*.py"))


def _backend_offences(source: str, filename: str = "<source>") -> list[str]:
    """``matplotlib.use(...)`` calls and pyplot imports in one module's source."""
    tree = ast.parse(source, filename=filename)
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [f"line {node.lineno}: import {a.name}" for a in node.names
                      if a.name == "matplotlib.pyplot" or a.name == "pylab"]
        elif isinstance(node, ast.ImportFrom):
            if node.module in ("matplotlib.pyplot", "pylab") or (
                    node.module == "matplotlib" and any(a.name == "pyplot" for a in node.names)):
                found.append(f"line {node.lineno}: from {node.module} import ...")
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in ("use", "switch_backend"):
            owner = node.func.value
            if isinstance(owner, ast.Name) and owner.id in ("matplotlib", "mpl", "plt"):
                found.append(f"line {node.lineno}: {owner.id}.{node.func.attr}(...)")
    return found


def test_no_backend_switch_or_pyplot_in_library_code():
    assert {"bem", "fem_reference", "verification", "sweeps", "casefile"} <= set(PACKAGES)
    sources = list(_package_sources())
    assert len(sources) > 20
    offences = {str(p): bad for p in sources
                if (bad := _backend_offences(p.read_text(encoding="utf-8"), str(p)))}
    assert offences == {}


def test_offence_finder_catches_the_patterns():
    import textwrap

    code = textwrap.dedent("""
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib import pyplot
        # matplotlib.use("Agg") in a comment is fine
        \"\"\"so is ``matplotlib.use`` in a docstring\"\"\"
    """)
    assert len(_backend_offences(code)) == 3
