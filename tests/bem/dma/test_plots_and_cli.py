"""Figures are bare matplotlib Figures (no pyplot state) and ``python -m bem.dma`` runs
the whole workflow on the shipped example data."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from bem.dma import WLF, build_master_curve, fit_prony
from bem.dma.__main__ import main
from bem.dma.plots import plot_isotherms, plot_master_curve, plot_shift_factors
from bem.case import material_from_config
from bem.materials import MasterCurveTable, Prony

REPO = Path(__file__).resolve().parents[3]
EXAMPLE = REPO / "examples" / "data" / "dma-pyvisco-freq-raw.csv"
PNG = b"\x89PNG\r\n\x1a\n"


def _no_pyplot_figures() -> bool:
    plt = sys.modules.get("matplotlib.pyplot")
    return plt is None or plt.get_fignums() == []


def test_each_plot_returns_a_figure_that_saves_as_png(synthetic, tmp_path):
    law = WLF(8.86, 101.6, 293.15)
    data = synthetic(law, 273.15 + np.arange(0.0, 41.0, 10.0))
    master = build_master_curve(data, law=law, vertical="density", density=1000.0)
    fit = fit_prony(master.omega, master.storage, master.loss)
    figures = [plot_isotherms(data, "isotherms"), plot_master_curve(master, fit, "master"),
               plot_shift_factors(master, "shifts")]
    assert len(figures[2].axes) == 2  # log a_T and log b_T
    assert len(plot_shift_factors(build_master_curve(data, law=law)).axes) == 1
    assert len(plot_master_curve(master).axes) == 3  # two panels and the colour bar
    for k, fig in enumerate(figures):
        assert isinstance(fig, Figure)
        path = tmp_path / f"{k}.png"
        fig.savefig(path, dpi=50)
        assert path.read_bytes()[:8] == PNG
    assert _no_pyplot_figures()


def test_module_command_writes_figures_and_a_table_a_case_can_read(tmp_path, capsys):
    table = tmp_path / "table.csv"
    assert main([str(EXAMPLE), "--t-ref", "20", "--terms-per-decade", "1", "--out", str(tmp_path),
                 "--table", str(table),
                 "--service-temperature", "40", "--print-material"]) == 0
    out = capsys.readouterr().out
    assert "21 isotherms" in out and "Prony fit:" in out
    block = out[out.index("[material]"):out.index("wrote")]
    material = material_from_config(tomllib.loads(block)["material"], tmp_path)
    assert isinstance(material, Prony) and material.G_inf > 0
    for name in ("isotherms.png", "master-curve.png", "shift-factors.png"):
        assert (tmp_path / name).read_bytes()[:8] == PNG
    read = MasterCurveTable.from_csv(table)  # the format of [material] model = "table"
    assert min(read.loss) >= 0 and len(read.omega) > 100


def test_module_command_reports_bad_input_and_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("temperature_degC,frequency_hz,G_storage_Pa\n20,1,1\n")
    assert main([str(bad), "--t-ref", "20", "--out", str(tmp_path)]) == 2
    assert "missing column G_loss_<unit> or E_loss_<unit>" in capsys.readouterr().err


def test_example_data_shift_monotonically_and_fit_passively():
    from bem.dma import read_dma_csv

    master = build_master_curve(read_dma_csv(EXAMPLE), 273.15 + 20, "wlf")
    assert np.all(np.diff(master.log_aT) < 0)  # hotter isotherms relax faster
    fit = master.fit_prony(terms_per_decade=1)
    assert np.all(fit.material.modulus(np.logspace(-20, 20, 401)).imag >= 0)
    assert fit.rms_error_storage < 0.1  # G' superposes well; the cold isotherms' G'' does not


def test_bem_dma_is_the_module_command(tmp_path, capsys):
    from bem.cli import main as bem_main

    bad = tmp_path / "bad.csv"
    bad.write_text("temperature_degC,frequency_hz,G_storage_Pa\n20,1,1\n")
    assert bem_main(["dma", str(bad), "--t-ref", "20", "--out", str(tmp_path)]) == 2
    assert "missing column G_loss_<unit>" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exit_:
        bem_main(["dma", "--help"])
    assert exit_.value.code == 0 and "usage: bem dma" in capsys.readouterr().out


def test_bem_dma_help_loads_no_numerical_library():
    import subprocess

    probe = ("import contextlib, io, sys\nfrom bem.cli import main\nout = io.StringIO()\n"
             "with contextlib.redirect_stdout(out):\n    try:\n        main(['dma', '--help'])\n"
             "    except SystemExit as exc:\n        assert exc.code == 0\n"
             "print(sorted(m for m in ('numpy', 'scipy', 'matplotlib') if m in sys.modules))\n"
             "print(out.getvalue())\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    loaded, text = done.stdout.split("\n", 1)
    assert loaded == "[]" and "usage: bem dma" in text and "2 bad input" in " ".join(text.split())
