"""bem.frictional.model: Friction's validation messages whole, its limits and the defaults the
case-file schema documents, the errors' family, and FrictionalContact's derived fields
recomputed by hand.
"""

import math

import numpy as np
import pytest

from bem import Grid
from bem.contact import ContactError
from bem.frictional import Friction, FrictionNotConverged
from bem.frictional import Friction, LoadingUnreachable
from bem.frictional import LoadingUnreachable
from bem.grid import Grid


RNG = np.random.default_rng(7)
N, SX = RNG.uniform(0.1, 2.0, size=6), RNG.normal(size=6) * 0.3


def _contact_result(**over):
    from bem.frictional import FrictionalContact, FrictionRecord

    g = Grid(1.0e-3, 2.0e-3, 0.02, 0.04, 10, 10, 4, 3)
    N = np.array([[0.0, 1.0, 2.0, 0.0], [3.0, 0.0, 5.0, -1.0], [0.0, 0.5, 0.0, 0.0]])
    Sx = np.array([[0.0, 0.1, -0.2, 0.0], [0.3, 0.0, 0.4, 0.0], [0.0, -0.05, 0.0, 0.0]])
    Sy = np.array([[0.0, 0.2, 0.1, 0.0], [-0.1, 0.0, 0.2, 0.0], [0.0, 0.05, 0.0, 0.0]])
    wx = np.array([[0.0, 0.0, -2.0, 0.0], [1.5, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0]])
    wy = np.array([[0.0, 0.0, 1.0, 0.0], [-0.5, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]])
    stick = np.array([[0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 0]], bool)
    rec = FrictionRecord(3, ((5, 2, 0.5, 1.0), (5, 2, 1e-3, 1.1), (5, 2, 1e-9, 1.2)), "gmres", 42,
                         1e-11, 2e-12, 3e-8)
    fields = dict(grid=g, force=N, force_x=Sx, force_y=Sy, deflection=N * 1e-6, displacement_x=Sx * 1e-6,
                  displacement_y=Sy * 1e-6, gap=N * 0.0, slip_x=wx, slip_y=wy, stick=stick, indentation=1e-4,
                  load=11.5, omega=1.2, driving_force=0.7, driving_torque=0.014, rolling_resistance=0.9,
                  rolling_resistance_friction=0.25, rolling_resistance_viscous=0.65, speed=0.05, mu=0.3,
                  mode="towed", record=rec)
    fields.update(over)
    return FrictionalContact(**fields)


@pytest.mark.parametrize("kwargs, message", [
    ({"mu": -0.1}, "mu must be >= 0, got -0.1"),
    ({"mu": 0.2, "mode": "pulled"}, "mode must be one of"),
    ({"mu": 0.2, "mode": "omega"}, "omega (rad/s) must be given"),
    ({"mu": 0.2, "omega": 1.0}, "omega (rad/s) must be given"),
    ({"mu": 0.2, "radius": -1.0}, "radius must be > 0 m"),
])
def test_bad_friction_input_is_refused(kwargs, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Friction(**kwargs)


@pytest.mark.parametrize("kwargs, message", [
    ({"mu": -0.1}, "mu must be >= 0, got -0.1"),
    ({"mu": math.nan}, "mu must be >= 0, got nan"),
    ({"mu": math.inf}, "mu must be >= 0, got inf"),
    ({"mu": "0.2"}, "mu must be >= 0, got '0.2' (a str, not a real number)"),
    ({"mu": 0.2, "mode": "pulled"}, "mode must be one of pushed_at_top, towed, torque, omega, got 'pulled'"),
    ({"mu": 0.2, "mode": "omega"},
     "omega (rad/s) must be given with mode = 'omega' and only then, got mode = 'omega', omega = None"),
    ({"mu": 0.2, "omega": 1.0},
     "omega (rad/s) must be given with mode = 'omega' and only then, got mode = 'pushed_at_top', omega = 1.0"),
    ({"mu": 0.2, "mode": "omega", "omega": math.inf}, "omega must be finite (rad/s), got inf"),
    ({"mu": 0.2, "mode": "omega", "omega": math.nan}, "omega must be finite (rad/s), got nan"),
    ({"mu": 0.2, "radius": -1.0}, "radius must be > 0 m, got -1.0"),
    ({"mu": 0.2, "radius": 0.0}, "radius must be > 0 m, got 0.0"),
    ({"mu": 0.2, "radius": math.inf}, "radius must be > 0 m, got inf"),
    ({"mu": 0.2, "radius": math.nan}, "radius must be > 0 m, got nan"),
    ({"mu": 0.2, "max_iter": 0}, "max_iter must be an integer > 0, got 0"),
    ({"mu": 0.2, "max_iter": 2.0}, "max_iter must be an integer > 0, got 2.0"),
    ({"mu": 0.2, "direction_tol": 0.0}, "direction_tol must be > 0, got 0.0"),
    ({"mu": 0.2, "direction_tol": math.nan}, "direction_tol must be > 0, got nan"),
    ({"mu": 0.2, "dense_limit": -1}, "dense_limit must be an integer >= 0, got -1"),
    ({"mu": 0.2, "dense_limit": 10.0}, "dense_limit must be an integer >= 0, got 10.0"),
    ({"mu": 0.2, "set_tol": -1e-9}, "set_tol must be >= 0, got -1e-09"),
    ({"mu": 0.2, "set_tol": math.nan}, "set_tol must be >= 0, got nan"),
])
def test_friction_validation_messages_whole(kwargs, message):
    with pytest.raises(ValueError) as info:
        Friction(**kwargs)
    assert str(info.value) == message


def test_friction_limits_accepted_and_defaults_as_documented():
    """The limits themselves are accepted (mu = 0, omega = 0, max_iter = 1, dense_limit = 0,
    set_tol = 0, a tiny radius and direction_tol); the defaults are the case-file schema's."""
    from casefile.schema import section

    Friction(0, "omega", omega=0.0, radius=1e-12, max_iter=1, direction_tol=1e-300, dense_limit=0, set_tol=0.0)
    Friction(0.0, "omega", omega=-3.0)
    f = Friction(0.2)
    keys = {k.name: k.default for k in section("friction").keys}
    for name in ("mode", "max_iter", "direction_tol", "set_tol", "dense_limit"):
        assert getattr(f, name) == keys[name], name
    assert f.omega is None and f.radius is None


def test_friction_errors_are_contact_errors():
    from bem.contact import ContactError, ContactNotConverged
    from bem.frictional import LoadingUnreachable

    assert issubclass(FrictionNotConverged, ContactNotConverged)
    assert issubclass(LoadingUnreachable, ContactError) and not issubclass(LoadingUnreachable, ContactNotConverged)


def test_frictional_contact_derived_fields_by_hand():
    from bem.contact import SHARED_SCALARS

    r = _contact_result()
    assert r.record.residual == 3e-8
    assert type(r).__dataclass_fields__["rolling_resistance_energy"].default is not None
    assert math.isnan(r.rolling_resistance_energy)
    contact = r.force > 0
    np.testing.assert_array_equal(r.contact, contact)
    np.testing.assert_array_equal(r.slip, contact & ~r.stick)
    assert r.slip.sum() == 3
    area = 1e-3 * 2e-3
    np.testing.assert_allclose(r.pressure, r.force / area, rtol=1e-15)
    np.testing.assert_allclose(r.traction_x, r.force_x / area, rtol=1e-15)
    np.testing.assert_allclose(r.traction_y, r.force_y / area, rtol=1e-15)
    assert r.stick_fraction == 2 / 5
    assert r.contact_area == pytest.approx(5 * area, rel=1e-15)
    assert r.contact_radius == pytest.approx(math.sqrt(5 * area / math.pi), rel=1e-15)
    assert r.peak_pressure == pytest.approx(5.0 / area, rel=1e-15) and isinstance(r.peak_pressure, float)
    x = (np.arange(4) - 1.5) * 1e-3
    assert r.pressure_centroid_x == pytest.approx(float((r.force * x).sum() / r.force.sum()), rel=1e-14)
    # S . w over the contact: (-0.2)(-2) + 0.1 * 1 + 0.3 * 1.5 + (-0.1)(-0.5) + (-0.05)(-1) + 0.05 * 1
    assert r.friction_power == pytest.approx(0.4 + 0.1 + 0.45 + 0.05 + 0.05 + 0.05, rel=1e-14)
    empty = _contact_result(force=np.zeros((3, 4)))
    assert math.isnan(empty.stick_fraction)
    s = r.summary()
    for name in SHARED_SCALARS:
        assert s[name] == getattr(r, name) or (math.isnan(s[name]) and math.isnan(getattr(r, name))), name
    for name in ("rolling_resistance_friction", "rolling_resistance_viscous", "omega", "driving_force",
                 "driving_torque", "stick_fraction", "mu", "mode", "speed"):
        assert s[name] == getattr(r, name), name
    assert math.isnan(s["rolling_resistance_energy"])
    assert s["grid"] == {"nodes": [4, 3], "spacing": [1e-3, 2e-3], "period": [0.02, 0.04], "truncation": [10, 10]}
    assert s["solver"] == {"iterations": 3, "residual": 3e-8,
                           "history": [[5, 2, 0.5, 1.0], [5, 2, 1e-3, 1.1], [5, 2, 1e-9, 1.2]],
                           "gap_residual": 1e-11, "stick_residual": 2e-12, "coulomb_residual": 3e-8,
                           "linear_solver": "gmres", "linear_iterations": 42}
    assert _contact_result(rolling_resistance_energy=1.5).summary()["rolling_resistance_energy"] == 1.5
    rec = r.record
    assert type(rec)(1, (), "dense", 0, 0.3, 0.2, 0.1).residual == 0.3
    assert type(rec)(1, (), "dense", 0, 0.1, 0.3, 0.2).residual == 0.3


@pytest.mark.parametrize("field, value", [("mu", True), ("mu", "0.2"), ("radius", np.bool_(True)),
                                          ("direction_tol", "1e-7"), ("set_tol", False)])
def test_friction_refuses_what_is_not_a_real_number_naming_the_field(field, value):
    with pytest.raises(TypeError, match=f"^{field} must be .*not a real number"):
        Friction(**{"mu": 0.2, field: value})


@pytest.mark.parametrize("field", ["max_iter", "dense_limit"])
def test_friction_refuses_a_boolean_count(field):
    with pytest.raises(TypeError, match=f"^{field} must be an integer"):
        Friction(0.2, **{field: True})


def test_friction_takes_numpy_scalars_as_python_numbers():
    f = Friction(np.float32(0.25), "omega", omega=np.float64(2.5), radius=np.float32(0.02),
                 max_iter=np.int64(7), dense_limit=np.int32(0))
    assert (f.mu, f.omega, f.max_iter, f.dense_limit) == (0.25, 2.5, 7, 0)
    assert all(type(v) is float for v in (f.mu, f.omega, f.radius)) and type(f.max_iter) is int
