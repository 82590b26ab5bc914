"""``bem solve`` with a [friction] section: JSON keys, figure, fields and errors."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from bem.cli import main

CASE = str(Path(__file__).resolve().parents[3] / "examples" / "paper-section11-friction.toml")
CHEAP = ["--set", "grid.spacing=1e-3", "--set", "grid.truncation=500"]


def test_cli_friction_json_plot_and_fields(tmp_path, capsys):
    png, npz = tmp_path / "out" / "friction.png", tmp_path / "fields.npz"
    code = main(["solve", CASE, "--json", *CHEAP, "--plot", str(png), "--fields", str(npz)])
    captured = capsys.readouterr()
    assert code == 0
    out = json.loads(captured.out)
    for key in ("rolling_resistance", "rolling_resistance_friction", "rolling_resistance_viscous",
                "rolling_resistance_energy", "omega", "driving_force", "driving_torque", "stick_fraction"):
        assert isinstance(out[key], float) and math.isfinite(out[key]), key
    assert out["driving_torque"] == pytest.approx(out["driving_force"] * 0.02, rel=1e-12)  # T = Q R
    assert 0 < out["stick_fraction"] < 1 and out["mode"] == "pushed_at_top" and out["mu"] == 0.2
    assert out["solver"]["coulomb_residual"] < 1e-6
    assert "friction 1:" in captured.err and "energy:" in captured.err
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000
    fields = np.load(npz)
    assert fields["stick"].dtype == bool and fields["force_x"].shape == fields["force"].shape
    assert abs(fields["force_x"].sum() + np.sum(fields["force"] * fields["x"][None, :]) / 0.02
               - out["driving_force"]) < 1e-9  # Q = sum N x / R + sum S_x
    # the frictional part recomputed from the fields: the slip power sum |S| |w| over V
    S, w = np.hypot(fields["force_x"], fields["force_y"]), np.hypot(fields["slip_x"], fields["slip_y"])
    assert np.sum(S * w) / 0.05 == pytest.approx(out["rolling_resistance_friction"], rel=1e-9)
    # the total from the fields' Q and the reported Omega (eq. 4, pushed at the top: T = Q R),
    # and so the viscous part R_r - R_r^F from the fields alone (not as total = friction +
    # viscous, which the code's definition of the viscous part makes true whatever the fields)
    Q = fields["force_x"].sum() + np.sum(fields["force"] * fields["x"][None, :]) / 0.02
    total = Q * (1 + 0.02 * out["omega"] / 0.05)
    assert out["rolling_resistance"] == pytest.approx(total, rel=1e-9)
    assert out["rolling_resistance_viscous"] == pytest.approx(total - np.sum(S * w) / 0.05, rel=1e-9)
    slip = ~fields["stick"] & fields["contact"]
    assert slip.any() and np.all(w[fields["stick"]] == 0)
    # Coulomb on the slip nodes, S = mu N along the slip, from the returned fields
    np.testing.assert_allclose(S[slip], 0.2 * fields["force"][slip], rtol=1e-6)
    cross = fields["force_x"] * fields["slip_y"] - fields["force_y"] * fields["slip_x"]
    assert np.abs(cross[slip]).max() < 1e-6 * np.max(S[slip] * w[slip])


def test_cli_friction_bad_input(capsys):
    assert main(["solve", CASE, "--quiet", *CHEAP, "--set", "friction.mu=-0.1"]) == 2
    assert "mu must be >= 0, got -0.1" in capsys.readouterr().err
    assert main(["solve", CASE, "--quiet", *CHEAP, "--set", "friction.mu=1e-3"]) == 1  # solved, unreachable
    assert "LoadingUnreachable" in capsys.readouterr().err


def test_frictional_figures_come_with_their_grid_error_unless_declined(capsys):
    """With [friction] the grid error is estimated by default (the frictional figures
    converge at first order): three levels a = 2, 1, 0.5 mm; --no-error-estimate skips it;
    a grid whose coarse levels cannot hold the contact still gives its result, exit 0,
    and says why the estimate is missing."""
    roomy = ["--set", "grid.spacing=0.5e-3", "--set", "grid.half_width=8e-3", "--set", "grid.truncation=400"]
    assert main(["solve", CASE, "--json", "--quiet", *roomy]) == 0
    estimate = json.loads(capsys.readouterr().out)["grid_error"]
    assert estimate["spacings"] == pytest.approx([2e-3, 1e-3, 0.5e-3])
    friction = estimate["figures"]["rolling_resistance_friction"]
    assert len(friction["values"]) == 3 and friction["error"] > 0
    assert main(["solve", CASE, "--json", "--quiet", "--no-error-estimate", *roomy]) == 0
    assert "grid_error" not in json.loads(capsys.readouterr().out)
    assert main(["solve", CASE, *CHEAP]) == 0  # 1 mm: the 4 mm level is 3 x 3 nodes
    out = capsys.readouterr().out
    assert "rolling resistance" in out and "grid error: not estimated" in out and "ContactAtEdge" in out
