"""Synthetic DMA isotherms generated from a known Prony series and a known shift law."""

from __future__ import annotations

import numpy as np
import pytest

from bem.dma import DMAData
from bem.materials import Prony

# A broad relaxation spectrum (glassy ~1e9 Pa down to a rubbery 1e6 Pa plateau):
# G_i proportional to tau_i^-0.35, one term per decade from 1e-10 s to 1e4 s.
TAU = 10.0 ** np.arange(-10, 4.1, 1.0)
TRUE = Prony(1e6, tuple(2e8 * (TAU / 1e-10) ** -0.35), tuple(TAU))
OMEGA = 2 * np.pi * np.logspace(-1, 2, 13)  # 0.1-100 Hz, 4 points per decade


def isotherms(law, temperatures, material=TRUE, omega=OMEGA, log_b=None) -> DMAData:
    """Isotherms ``G*(omega; T) = b_T G*_ref(a_T omega)`` of ``material`` under ``law``."""
    log_b = np.zeros(len(temperatures)) if log_b is None else np.asarray(log_b)
    curves = []
    for T, lb in zip(temperatures, log_b):
        g = material.modulus(omega * 10.0 ** law.log_aT(T)) * 10.0 ** lb
        curves.append((omega, g.real, g.imag))
    return DMAData.from_arrays(temperatures, *zip(*curves))


isotherms.TRUE = TRUE
isotherms.OMEGA = OMEGA


@pytest.fixture
def synthetic():
    """``isotherms(law, temperatures, material=TRUE, omega=OMEGA, log_b=None)``, with
    the default material and frequencies as its ``TRUE`` and ``OMEGA`` attributes."""
    return isotherms



# --- case files with [material] model = "dma" ------------------------------------------
T_REF = 293.15  # K


def write_csv(path, data) -> None:
    """Write ``DMAData`` as a DMA CSV (K, rad/s, shear Pa)."""
    lines = ["temperature_K,omega_rad_s,G_storage_Pa,G_loss_Pa"]
    for s in data.isotherms:
        lines += [f"{float(s.temperature)!r},{float(w)!r},{float(gs)!r},{float(gl)!r}"
                  for w, gs, gl in zip(s.omega, s.storage, s.loss)]
    path.write_text("\n".join(lines) + "\n")


def toml(case: dict) -> str:
    """A case dict as TOML (sections of numbers, strings, booleans and lists of numbers)."""
    def value(v):
        if isinstance(v, bool):
            return str(v).lower()
        if isinstance(v, str):
            return f'"{v}"'
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(repr(float(x)) for x in v) + "]"
        return repr(float(v)) if isinstance(v, float) else repr(v)

    return "\n".join(f"[{name}]\n" + "\n".join(f"{k} = {value(v)}" for k, v in sec.items()) + "\n"
                     for name, sec in case.items())


def line_case(material: dict, speed: float = 0.01) -> dict:
    """A small line contact (plane strain) on a 5 mm layer without inertia, fixed grid:
    omega = nu_x V spans 2 pi V / 0.05 m to pi V / 5e-5 m (1.26-628 rad/s at 0.01 m/s)."""
    return {
        "layer": {"thickness": 5.0e-3},
        "material": material,
        "indenter": {"shape": "line", "radius": 0.02},
        "loading": {"speed": speed, "load": 150.0},
        "grid": {"spacing": 5.0e-5, "period": 0.05, "truncation": 500, "half_width": 3.0e-3},
    }


@pytest.fixture
def kit(tmp_path):
    """What the case tests share: ``kit.folder`` holds ``dma.csv``, 9 isotherms (-20 to
    60 degC, 0.1-100 Hz) of the Prony series above under ``kit.law`` = WLF(8.86, 101.6 K,
    20 degC); ``kit.material(**keys)`` is a ``[material] model = "dma"`` table on it at
    ``T_REF``; ``kit.case(material, speed)`` a line case; ``kit.write(case, name)`` writes
    a case file and returns its path; ``kit.toml``, ``kit.write_csv``, ``kit.T_REF``."""
    from types import SimpleNamespace

    from bem.dma import WLF

    law = WLF(8.86, 101.6, T_REF)
    write_csv(tmp_path / "dma.csv", isotherms(law, 273.15 + np.arange(-20.0, 61.0, 10.0)))

    def material(**keys):
        return {"model": "dma", "file": "dma.csv", "reference_temperature": T_REF, **keys}

    def write(case, name="case.toml"):
        path = tmp_path / name
        path.write_text(toml(case))
        return path

    return SimpleNamespace(folder=tmp_path, law=law, material=material, case=line_case, write=write, toml=toml,
                           write_csv=write_csv, T_REF=T_REF)
