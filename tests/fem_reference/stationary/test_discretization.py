"""The stationary model's resolved sizes: a candidate zone wider than the sphere or not
inside the domain is refused by name, and the uniform refinements divide the element
size."""

import pytest

from fem_reference import (ContactProblem, ElasticMaterial, FemSettings, Indenter, InputError,
                           Layer, Loading)
from fem_reference.stationary.discretization import resolve


def test_discretization_checks_the_zone():
    base = dict(layer=Layer(5e-3), material=ElasticMaterial(3e6),
                indenter=Indenter("sphere", 0.02), loading=Loading(load=100.0))
    with pytest.raises(InputError, match="fem.contact_zone must be < indenter.radius"):
        resolve(ContactProblem(**base, fem=FemSettings(contact_zone=0.03)))
    with pytest.raises(InputError, match="fem.domain_radius must exceed"):
        resolve(ContactProblem(**base, fem=FemSettings(contact_zone=0.01, domain_radius=0.01)))
    disc = resolve(ContactProblem(**base, fem=FemSettings(element_size=2e-4, refine=2)))
    assert disc.element_size == pytest.approx(5e-5) and disc.mesh_size == 2e-4
