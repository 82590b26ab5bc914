"""Analytic references for contact on elastic and viscoelastic bodies, as documented pure
functions of SI inputs (m, N or N/m, Pa, s) that return frozen result dataclasses.

One module per reference:

* :mod:`.hertz`: Hertz, a rigid sphere on an elastic half-space
  (:func:`hertz_contact`, :func:`hertz_contact_from_indentation`,
  :func:`effective_modulus_from_shear`) and a rigid cylinder in plane strain
  (:func:`hertz_line_contact`).
* :mod:`.bonded_layer`: the normal surface compliance of a layer bonded to a rigid base
  in Fourier space, the kernel ``L(kH)`` of Zehil and Gavin (2013), eq. 68
  (:func:`bonded_layer_kernel`, :func:`bonded_layer_kernel_complement`), the static
  incompressible compliance that checks the boundary-element kernel
  (:func:`layer_normal_compliance_static`) and its two asymptotes.
* :mod:`.jaffar_thick`: a sphere on a thick bonded layer, Jaffar (2008), the paper's
  eqs. 64-68 (:func:`jaffar_thick_layer_contact`, :func:`jaffar_b_coefficient`).
* :mod:`.jaffar_thin`: a sphere on a thin incompressible bonded layer, Jaffar (1997),
  eqs. 69-70 (:func:`jaffar_thin_layer_contact`).
* :mod:`.hunter`: Hunter (1961), a rigid cylinder rolling on a three-parameter
  viscoelastic half-space (:func:`hunter_rolling_contact`).

Pressures are compressive and positive (``p = -sigma_z``). The transcription slips of the
paper that these references expose are listed in each module and in
``docs/paper-notes.md``.
"""

from .bonded_layer import (
    bonded_layer_kernel,
    bonded_layer_kernel_complement,
    halfspace_normal_compliance_static,
    layer_normal_compliance_static,
    thin_layer_normal_compliance_static,
)
from .hertz import (
    HertzContact,
    HertzLineContact,
    effective_modulus_from_shear,
    hertz_contact,
    hertz_contact_from_indentation,
    hertz_line_contact,
)
from .hunter import HunterRollingContact, hunter_rolling_contact
from .jaffar_thick import ThickLayerContact, jaffar_b_coefficient, jaffar_thick_layer_contact
from .jaffar_thin import ThinLayerContact, jaffar_thin_layer_contact

__all__ = [
    "HertzContact",
    "ThickLayerContact",
    "ThinLayerContact",
    "effective_modulus_from_shear",
    "hertz_contact",
    "hertz_contact_from_indentation",
    "bonded_layer_kernel",
    "bonded_layer_kernel_complement",
    "jaffar_b_coefficient",
    "jaffar_thick_layer_contact",
    "jaffar_thin_layer_contact",
    "layer_normal_compliance_static",
    "halfspace_normal_compliance_static",
    "thin_layer_normal_compliance_static",
    "HertzLineContact",
    "hertz_line_contact",
    "HunterRollingContact",
    "hunter_rolling_contact",
]
