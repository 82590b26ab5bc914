"""``[material] model = "dma"``: a case's material from DMA isotherms at a service
temperature, and the check of the rolling's frequency band against the data.

The isotherms of ``file`` are shifted to a master curve at ``reference_temperature``
(:func:`bem.dma.build_master_curve`, law ``shift_law`` fitted or with given constants);
the solve then uses, at the service ``temperature`` ``T`` (K):

- ``form = "prony"`` (default): the passive Prony series fitted once at ``T_ref``
  (:func:`bem.dma.fit_prony`), moved to ``T`` exactly, moduli times ``b_T`` and times
  ``tau_i`` times ``a_T`` (so ``G*(omega; T) = b_T G*_ref(a_T omega)`` holds to
  round-off). It is smooth where the isotherms scatter, satisfies the Kramers-Kronig
  relations, has ``G'' >= 0`` everywhere, and outside the data it tends to its own
  rubbery and glassy plateaus: the default a careful user wants;
- ``form = "table"``: the shifted points binned into a
  :class:`bem.materials.MasterCurveTable` (the data as measured, scatter included;
  beyond the data its terminal rules are not physics).

A rolling case loads the layer at ``omega = nu_x V`` (paper eq. 25). The modes that carry
the load are those the grid resolves: ``|nu_x|`` from the first non-zero mode
``2 pi / L_x`` up to the grid's Nyquist wavenumber ``pi / spacing_x`` (higher modes, up
to the truncation, only shape the uniform pressure within each node's patch; the modes
``nu_x = 0`` are felt at ``omega = 0``, and their share of a 3D solution vanishes as
``L_x`` grows). :func:`check_band` compares that band with the data's range at ``T``
(the reduced range divided by ``a_T``) and raises, when the band reaches more than
:data:`BAND_MARGIN` decades beyond it, unless ``extrapolate = true``.

Every error is a :class:`bem.dma.DMAError` (a ``ValueError``: ``bem solve`` exits 2)
whose message names the ``[material]`` key, the file and the value.
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass
from functools import lru_cache
from typing import Optional, Union

from ..materials import MasterCurveTable, Prony
from .errors import DMAError, DMAInputError, PronyFitError, ShiftError
from .master import MasterCurve, build_master_curve
from .prony_fit import PronyFit, fit_prony
from .reader import read_dma_csv
from .shift import WLF, Arrhenius

__all__ = ["CaseMaterial", "dma_material", "frequency_band", "check_band", "shifted_prony", "BAND_MARGIN"]

WHERE = '[material] model = "dma"'

#: How far (decades of frequency) the band may reach beyond the data before it is an
#: error: one bin of the table (0.1 decade), so that a service temperature equal to an
#: isotherm's, whose data are moved there by the law rather than by the isotherm's own
#: fitted shift, still covers that isotherm's range.
BAND_MARGIN = 0.1


@dataclass(frozen=True)
class CaseMaterial:
    """The material of a ``model = "dma"`` case and what the band check needs.

    Attributes
    ----------
    material : Prony or MasterCurveTable
        ``G*(omega)`` at ``temperature`` (Pa, omega in rad/s).
    temperature : float
        Service temperature ``T`` (K).
    log_aT, log_bT : float
        ``log10 a_T`` and ``log10 b_T`` at ``T`` (relative to ``T_ref``).
    omega_min, omega_max : float
        The data's frequency range at ``T`` (rad/s): the master curve's reduced range
        divided by ``a_T``.
    form : {"prony", "table"}
        Which form ``material`` is.
    extrapolate : bool
        Accept a frequency band outside the data (``[material] extrapolate``).
    source : str
        The DMA file.
    master : MasterCurve
        The master curve at ``T_ref``.
    fit : PronyFit or None
        The Prony fit at ``T_ref`` (``form = "prony"``).
    """

    material: Union[Prony, MasterCurveTable]
    temperature: float
    log_aT: float
    log_bT: float
    omega_min: float
    omega_max: float
    form: str
    extrapolate: bool
    source: str
    master: MasterCurve
    fit: Optional[PronyFit] = None


def _default(name: str):
    from casefile.schema import section

    return section("material").key(name, "dma").default


def _law(sec: dict):
    """The shift law: given constants as an object, or a name to fit."""
    name = sec.get("shift_law", _default("shift_law"))
    T_ref = sec["reference_temperature"]
    wlf_keys = [k for k in ("C1", "C2") if k in sec]
    if name == "wlf":
        if "activation_energy" in sec:
            raise DMAError(f"{WHERE}: activation_energy belongs to shift_law = \"arrhenius\", "
                           "got shift_law = \"wlf\"; give C1 and C2, or neither to fit them")
        if len(wlf_keys) == 1:
            missing = ({"C1", "C2"} - set(wlf_keys)).pop()
            raise DMAError(f"{WHERE}: {wlf_keys[0]} = {sec[wlf_keys[0]]!r} is given without {missing}; "
                           "give both WLF constants, or neither to fit them to the isotherms")
        return WLF(sec["C1"], sec["C2"], T_ref) if wlf_keys else "wlf"
    if wlf_keys:
        raise DMAError(f"{WHERE}: {', '.join(wlf_keys)} belong to shift_law = \"wlf\", got shift_law = "
                       f"\"{name}\"; give activation_energy (J/mol), or nothing to fit it")
    return Arrhenius(sec["activation_energy"], T_ref) if "activation_energy" in sec else "arrhenius"


def _file_key(path: pathlib.Path) -> tuple:
    stat = path.stat()
    return str(path.resolve()), stat.st_mtime_ns, stat.st_size


@lru_cache(maxsize=8)
def _master(file_key: tuple, T_ref: float, law, vertical: Optional[str]) -> MasterCurve:
    try:
        data = read_dma_csv(file_key[0])
    except DMAInputError as exc:
        raise DMAInputError(f"{WHERE}: {exc}") from None
    if vertical == "density" and any(s.density is None for s in data.isotherms):
        raise ShiftError(f"{WHERE}: vertical = \"density\" needs a density_kg_m3 column in {file_key[0]} "
                         "(the density at each row's temperature, kg/m^3)")
    try:
        return build_master_curve(data, T_ref, law, vertical=vertical)
    except ShiftError as exc:
        how = f"shift_law = \"{law}\" (fitted)" if isinstance(law, str) else f"the given law {law}"
        raise ShiftError(f"{WHERE}, {how}, reference_temperature = {T_ref!r} K: {exc}") from None


@lru_cache(maxsize=8)
def _fit(file_key: tuple, T_ref: float, law, vertical: Optional[str], terms_per_decade: float,
         tolerance: Optional[float]) -> PronyFit:
    master = _master(file_key, T_ref, law, vertical)
    try:
        return fit_prony(master.omega, master.storage, master.loss, terms_per_decade=terms_per_decade,
                         tolerance=tolerance)
    except PronyFitError as exc:
        raise PronyFitError(f"{WHERE}, file {file_key[0]}, fit_tolerance = {tolerance!r}, "
                            f"terms_per_decade = {terms_per_decade!r}: {exc}") from None


def shifted_prony(material: Prony, log_aT: float, log_bT: float = 0.0) -> Prony:
    """The series at another temperature: moduli (Pa) times ``b_T``, times (s) times ``a_T``.

    Exact for a Prony series: ``G*(omega; T) = b_T G*_ref(a_T omega)``.
    """
    a, b = 10.0 ** log_aT, 10.0 ** log_bT
    return Prony(material.G_inf * b, tuple(g * b for g in material.G), tuple(t * a for t in material.tau))


def dma_material(sec: dict, base_dir) -> CaseMaterial:
    """The material of a checked ``[material]`` table with ``model = "dma"``.

    Parameters
    ----------
    sec : dict
        The table (keys in ``docs/case-files.md``; temperatures in K).
    base_dir : path
        The folder that a relative ``file`` resolves against.

    Raises
    ------
    DMAError
        The file's bad rows (naming the file and line), a single isotherm where the law
        is fitted, a temperature at or below the WLF singularity, a Prony fit that
        misses ``fit_tolerance``, keys of another law or form.
    """
    path = pathlib.Path(base_dir) / sec["file"]
    if not path.is_file():
        raise DMAError(f"{WHERE}: file {str(path)!r} not found")
    T_ref = float(sec["reference_temperature"])
    T = float(sec.get("temperature", T_ref))
    form = sec.get("form", _default("form"))
    vertical = sec.get("vertical")
    if form == "table":
        stray = [k for k in ("terms_per_decade", "fit_tolerance") if k in sec]
        if stray:
            raise DMAError(f"{WHERE}: {', '.join(stray)} apply only to form = \"prony\", got form = \"table\"; "
                           "remove them")
    law = _law(sec)
    key = _file_key(path)
    master = _master(key, T_ref, law, vertical)
    try:
        log_a, log_b = float(master.log_shift(T)), float(master.log_vertical(T))
    except ShiftError as exc:
        raise ShiftError(f"{WHERE}: temperature = {T!r} K ({T - 273.15:.2f} degC): {exc}") from None
    if not (abs(log_a) < 250 and abs(log_b) < 250):  # 10^250 s: far beyond any physics, within floats
        raise ShiftError(f"{WHERE}: temperature = {T!r} K ({T - 273.15:.2f} degC) gives log10 a_T = {log_a:.4g}, "
                         f"log10 b_T = {log_b:.4g}: the shift law {master.law} is used too far from its data"
                         + (f"; a WLF law is singular at T_ref - C2 = {master.law.singular_temperature:.6g} K"
                            if isinstance(master.law, WLF) else ""))
    fit = None
    if form == "prony":
        fit = _fit(key, T_ref, law, vertical, float(sec.get("terms_per_decade", _default("terms_per_decade"))),
                   sec.get("fit_tolerance"))
        material = shifted_prony(fit.material, log_a, log_b)
    else:
        material = master.table(T)
    a = 10.0 ** log_a
    return CaseMaterial(material, T, log_a, log_b, float(master.omega[0]) / a, float(master.omega[-1]) / a,
                        form, bool(sec.get("extrapolate", False)), str(path), master, fit)


def frequency_band(speed: float, spacing_x: float, period_x: float) -> tuple[float, float]:
    """``(omega_low, omega_high)`` (rad/s) of the modes that carry the load: ``nu_x V``
    for ``|nu_x|`` from ``2 pi / L_x`` to ``pi / spacing_x`` (speed in m/s, lengths in m)."""
    return 2.0 * math.pi * speed / period_x, math.pi * speed / spacing_x


def check_band(cm: CaseMaterial, speed: float, spacing_x: float, period_x: float) -> tuple[float, float]:
    """Raise :class:`DMAError` if the case's frequency band leaves the data at ``cm.temperature``.

    The band may reach :data:`BAND_MARGIN` decades beyond the data. Returns the band
    ``(omega_low, omega_high)`` (rad/s; ``(0, 0)`` for ``speed = 0``, which needs the
    relaxed modulus ``G(0)``). With ``cm.extrapolate`` nothing is raised.
    """
    lo, hi = frequency_band(speed, spacing_x, period_x)
    below = math.inf if lo == 0 else math.log10(cm.omega_min / lo)
    above = math.log10(hi / cm.omega_max) if hi > 0 else -math.inf
    if cm.extrapolate or (below <= BAND_MARGIN and above <= BAND_MARGIN):
        return lo, hi
    T = cm.temperature
    if speed == 0:
        need = "a stationary contact (speed = 0) loads the layer at omega = 0 (the relaxed modulus G(0))"
    else:
        need = (f"this case loads the layer at omega = nu_x V from {lo:.3g} to {hi:.3g} rad/s (V = {speed:g} m/s, "
                f"|nu_x| from 2 pi / L_x = {2 * math.pi / period_x:.3g} to pi / spacing_x = "
                f"{math.pi / spacing_x:.3g} 1/m)")
    off = []
    if below > BAND_MARGIN:
        off.append("down to omega = 0, below them" if speed == 0 else f"{below:.2g} decades below them")
    if above > BAND_MARGIN:
        off.append(f"{above:.2g} decades above them")
    if cm.form == "prony":
        beyond = ("outside its data the fitted Prony series tends to its rubbery (G_inf) and glassy (G_inf + sum "
                  "G_i) plateaus: physical, but not measured")
    else:
        beyond = ("outside its data the table continues with constant G' and G'' proportional to omega "
                  "(below) or 1/omega (above): not physical (form = \"prony\" tends to its rubbery and glassy "
                  "plateaus instead)")
    raise DMAError(
        f"{WHERE}: {need}, but the data ({cm.source}) at temperature = {T:g} K ({T - 273.15:.2f} degC) "
        f"cover {cm.omega_min:.3g} to {cm.omega_max:.3g} rad/s: the band reaches {' and '.join(off)}; "
        f"{beyond}. Measure the missing range, change the temperature, the speed or the grid, or set "
        "[material] extrapolate = true to accept it"
    )
