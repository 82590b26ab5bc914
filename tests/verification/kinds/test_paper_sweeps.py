"""The ``paper-sweeps`` kind: its gates, from sweep tables drawn from the paper's own laws
(the sweeps themselves are replaced, so nothing is solved), and bad cases refused."""

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from sweeps.paper import TABLE2, TABLE3, paper_fit
from tests.verification.small_cases import assert_refused
from verification.runner import load_case, run_case

CASE = Path(__file__).resolve().parents[3] / "verification" / "cases" / "paper-sweeps.toml"
HS = np.array([1, 2, 3, 5, 7, 10, 15, 30]) * 1e-3


def _share(H):
    """A share that falls from 10 % at 1 mm to 1 % at 5 mm and stays there (m -> -)."""
    return 0.01 + 0.09 * np.clip((5e-3 - H) / 4e-3, 0, 1) ** 2


def _rows(key):
    ok = {"status": "ok"}
    if key == "loads":
        return [{**ok, "layer.thickness": repr(H), "loading.load": repr(float(P)), "friction_share": "0.009",
                 "rolling_resistance_energy": repr(float(paper_fit(TABLE2, H, (10, 150))(P)))}
                for H in TABLE2 for P in np.linspace(10, 150, 5)]
    if key == "thickness":
        return [{**ok, "layer.thickness": repr(float(H)), "loading.load": repr(P),
                 "friction_share": repr(float(_share(H))),
                 "rolling_resistance_energy": repr(float(paper_fit(TABLE3, P, (1e-3, 30e-3))(H)))}
                for P in TABLE3 for H in HS]
    return [{**ok, "layer.thickness": "0.001", "loading.speed": repr(float(v)),
             "rolling_resistance_energy": repr(float(2 - (np.log10(v) + 1.6) ** 2))} for v in np.geomspace(1e-3, 1, 7)]


def test_share_rise_is_gated_from_the_thickness_sweep(monkeypatch):
    import sweeps.engine

    monkeypatch.setattr(sweeps.engine, "run_sweep",
                        lambda sweep, out, client=None, stream=None, **kw: SimpleNamespace(rows=_rows(Path(out).name)))
    result = run_case(load_case(CASE), progress=lambda m: None, client=object())
    gates = {g.quantity: g for g in result.gates}
    for P in TABLE3:
        gate = gates[f"share_rise[P={P:g}N]"]
        assert gate.value == pytest.approx(0.1, rel=1e-12) and gate.error == gate.value  # 1 % over 10 %
        assert gate.passed and not gate.report_only
    assert all(gates[f"table3[P={P:g}N]"].error < 1e-5 for P in TABLE3)


def test_bad_cases_are_refused():
    assert_refused("paper-sweeps", load_case(CASE), [
        (lambda c: c["gates"][-1].update(quantity="share_raise"), "unknown quantity 'share_raise'.*share_rise"),
        (lambda c: c["sweeps"].update(thickness="no-such-sweep.toml"), r"\[sweeps\] thickness: no sweep file"),
    ], path=CASE)
