"""Every analytic reference refuses bad input with a message that names the argument, the
value, the unit and the rule; its results are frozen."""

import pytest

from verification import analytic as an

G = 3.0e6  # Pa, paper sec. 10


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: an.hertz_contact(100.0, -1, 4 * G), "radius must be > 0 m, got -1"),
        (lambda: an.hertz_contact(0.0, 0.02, 4 * G), "load must be > 0 N, got 0.0"),
        (lambda: an.hertz_contact(1.0, 0.02, -5.0), "effective_modulus must be > 0 Pa, got -5.0"),
        (lambda: an.hertz_contact_from_indentation(-1e-4, 0.02, 4 * G), "indentation must be > 0 m, got -0.0001"),
        (lambda: an.effective_modulus_from_shear(G, 0.7), r"poisson_ratio must be in \(-1, 0.5\], got 0.7"),
        (lambda: an.jaffar_thick_layer_contact(1.0, 0.02, -0.005, G), "thickness must be > 0 m, got -0.005"),
        (lambda: an.jaffar_thick_layer_contact(1.0, 0.02, 0.005, 0), "shear_modulus must be > 0 Pa, got 0"),
        (lambda: an.jaffar_thin_layer_contact(1.0, 1.0, 1e-4, G, 0.3), "poisson_ratio must be 0.5"),
        (lambda: an.layer_normal_compliance_static([1.0, -2.0], 0.005, G), "wavenumber must be >= 0 rad/m"),
        (lambda: an.hertz_contact(float("nan"), 0.02, 4 * G), "load must be finite, got nan"),
        (lambda: an.jaffar_b_coefficient(-1), "m must be an integer >= 0, got -1"),
    ],
)
def test_invalid_inputs_are_named_with_their_value_unit_and_rule(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_non_numbers_and_booleans_are_refused():
    with pytest.raises(TypeError, match="radius must be a real number in m"):
        an.hertz_contact(1.0, "2 cm", 4 * G)
    with pytest.raises(TypeError, match="load"):
        an.hertz_contact(True, 0.02, 4 * G)


def test_results_are_frozen():
    c = an.hertz_contact(1.0, 0.02, 4 * G)
    with pytest.raises(AttributeError):
        c.load = 2.0
