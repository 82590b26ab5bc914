"""The analytic references a case can name in ``[analytic] reference``, with the
quantities each provides (a gate on any other is refused before anything runs)."""

from __future__ import annotations

import math

from .. import analytic
from ..schema import CaseError, Field, check_table

__all__ = ["REFERENCES", "FIELDS", "check", "reference", "reference_value"]


def _hertz(P, R, H, G):  # the half-space: H plays no part
    return analytic.hertz_contact(P, R, analytic.effective_modulus_from_shear(G))


REFERENCES = {
    # name: (solution(P, R, H, G), the scalars it provides)
    "hertz": (_hertz, ("contact_radius", "indentation", "peak_pressure", "load")),
    "jaffar_thick": (analytic.jaffar_thick_layer_contact, ("contact_radius", "peak_pressure", "load")),
    "jaffar_thin": (analytic.jaffar_thin_layer_contact, ("contact_radius", "indentation", "peak_pressure", "load")),
}

FIELDS = {"reference": Field("string", True, choices=tuple(REFERENCES), doc="the analytic solution")}


def check(section: dict, problem: dict, where: str) -> None:
    """``[analytic]``: a known reference, for a problem it applies to (elastic, at rest,
    a sphere or paraboloid under a given load)."""
    check_table(section, FIELDS, where)
    if problem["material"]["model"] != "elastic" or problem["loading"].get("speed", 0.0) != 0:
        raise CaseError(f"{where}: {section['reference']!r} is a solution for an elastic layer at rest")
    if problem["indenter"].get("shape", "sphere") not in ("sphere", "paraboloid"):
        raise CaseError(f"{where}: {section['reference']!r} is a solution for a sphere or paraboloid")
    if "load" not in problem["loading"]:
        raise CaseError(f"{where}: {section['reference']!r} needs [problem] loading.load (load control)")


def reference(section: dict, problem: dict):
    """The analytic solution of ``[analytic]`` for ``[problem]``."""
    solution, _ = REFERENCES[section["reference"]]
    p = problem
    return solution(p["loading"]["load"], p["indenter"]["radius"], p["layer"]["thickness"],
                    p["material"]["shear_modulus"])


def reference_value(ref, quantity: str) -> float:
    """A scalar of an analytic solution (NaN when it has none; the schema refuses such gates)."""
    return float(getattr(ref, quantity, math.nan))
