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
