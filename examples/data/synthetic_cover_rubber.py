"""Write ``dma-synthetic-cover-rubber.csv``: SYNTHETIC DMA frequency sweeps of an invented
conveyor-belt cover rubber. No specimen was measured; every number below is chosen.

    python examples/data/synthetic_cover_rubber.py     # rewrites the CSV beside this file

The material is a generalized Maxwell solid in shear, given at ``T_REF`` = 20 degC, and
thermorheologically simple under one WLF law (no vertical shift). The CSV holds what a
DMA would read off it: 21 isotherms from -60 to +40 degC in 5 K steps, each at 10
frequencies from 0.1 to 100 Hz (3 per decade), ``G'`` and ``G''`` exactly (no noise),
to 6 significant digits.

What was chosen, and within which ranges:

- WLF: the "universal" constants ``C1g = 17.44``, ``C2g = 51.6 K`` at the glass
  transition (Williams, Landel and Ferry, J. Am. Chem. Soc. 77 (1955) 3701-3707), with
  ``T_g = -65 degC``, between the glass transitions of natural rubber and of an emulsion
  SBR (about -70 and -50 degC; Ferry, Viscoelastic Properties of Polymers, 3rd ed.,
  Wiley 1980, ch. 11), the polymers of cover compounds. Moved to ``T_REF`` (``C1 = C1g
  C2g / (C2g + T_REF - T_g)``, ``C2 = C2g + T_REF - T_g``): ``C1 = 6.588``,
  ``C2 = 136.6 K``.
- The relaxed shear modulus ``G_inf`` = 1.2 MPa and the 1 Hz, 20 degC storage modulus
  of 2.0 MPa (``E' = 6.0 MPa``): a compound of Shore A hardness about 65-70 (a belt
  maker's test report specifies its cover rubber at 70 +- 5 Shore A:
  top-factories.com/products/7954071.html), whose Young's modulus by Gent's relation
  (Trans. IRI 34 (1958) 46-57) is 4.4-5.5 MPa.
- The glass transition: a relaxation spectrum falling as ``tau^-0.65`` from
  ``tau_g`` = 3e-11 s at 20 degC, 500 MPa in all (a glassy shear modulus of 0.5 GPa,
  the order of every amorphous polymer's); the loss tangent at 1 Hz peaks at -54 degC
  (1.1).
- The filler network's broad, weak relaxation in the rubbery region: 0.11 MPa per
  half decade of relaxation time at 1 s, falling as ``tau^-0.05``, cut off smoothly
  below 1e-9 s and above 3e3 s, which gives the loss tangent of
  0.08 at 20 degC and 1 Hz (a low-loss compound: chosen, not taken from a source).

Every branch modulus is positive, so the material is passive and satisfies the
Kramers-Kronig relations. Its figures are those of this invented material, not of any
real belt.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

T_REF = 20.0                           # degC
T_GLASS = -65.0                        # degC
C1 = 17.44 * 51.6 / (51.6 + T_REF - T_GLASS)
C2 = 51.6 + T_REF - T_GLASS            # K
G_INF = 1.2e6                          # Pa
TEMPERATURES = np.arange(-60.0, 40.0 + 1e-9, 5.0)      # degC
FREQUENCIES = 10.0 ** np.linspace(-1.0, 2.0, 10)       # Hz
CSV = Path(__file__).with_name("dma-synthetic-cover-rubber.csv")


def series() -> tuple[float, np.ndarray, np.ndarray]:
    """``(G_inf, G_i, tau_i)`` at ``T_REF`` (Pa, Pa, s): two branches per decade of
    relaxation time from 1e-13 to 1e4 s."""
    tau = 10.0 ** (np.arange(-26, 9) / 2.0)
    transition = (tau / 3e-11) ** -0.65 / (1.0 + (3e-11 / tau) ** 3)
    transition *= 500e6 / transition.sum()
    tail = 0.11e6 * tau ** -0.05 / (1.0 + (1e-9 / tau) ** 2) / (1.0 + (tau / 3e3) ** 2)
    return G_INF, transition + tail, tau


def log_aT(T_degC):
    """``log10 a_T`` of the WLF law at ``T_REF`` (temperature in degC)."""
    d = np.asarray(T_degC, dtype=float) - T_REF
    return -C1 * d / (C2 + d)


def modulus(omega, T_degC) -> np.ndarray:
    """``G*(omega; T)`` (Pa, complex) at angular frequency ``omega`` (rad/s)."""
    g_inf, g, tau = series()
    x = np.asarray(omega, dtype=float)[..., None] * tau * 10.0 ** log_aT(T_degC)
    return g_inf + np.sum(g * 1j * x / (1.0 + 1j * x), axis=-1)


def text() -> str:
    """The CSV file's text."""
    lines = [
        "# SYNTHETIC DMA data: an invented conveyor-belt cover rubber, not a measurement.",
        "# Written by synthetic_cover_rubber.py beside this file, whose docstring gives every",
        f"# chosen number and the ranges they were chosen within: a Prony series at {T_REF:g} degC",
        f"# under WLF (C1 = {C1:.4g}, C2 = {C2:.4g} K at {T_REF:g} degC), evaluated exactly (no noise).",
        "# Shear moduli G', G'' in MPa.",
        "isotherm,temperature_degC,frequency_hz,G_storage_MPa,G_loss_MPa",
    ]
    for k, T in enumerate(TEMPERATURES):
        G = modulus(2.0 * math.pi * FREQUENCIES, T) / 1e6
        lines += [f"{k},{T:g},{f:.6g},{g.real:.6g},{g.imag:.6g}" for f, g in zip(FREQUENCIES, G)]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    CSV.write_text(text(), encoding="utf-8")
    print(f"wrote {CSV}")
