"""bem.frictional.loading: each loading mode's equilibrium row against its definition, and
the reachability check at its limit.
"""

import numpy as np
import pytest

from bem.frictional import LoadingUnreachable
from bem.frictional.loading import check_reachable, constraint


RNG = np.random.default_rng(7)
ARM, ELL = RNG.normal(size=6) * 0.1, RNG.normal(size=6) * 1e-3
N, SX = RNG.uniform(0.1, 2.0, size=6), RNG.normal(size=6) * 0.3
R = 0.02


@pytest.mark.parametrize("mode, row", [
    # pushed at the top: Q R + sum l S_x = 0 with the horizontal force Q = sum N arm + sum S_x
    ("pushed_at_top", lambda: (N @ ARM + SX.sum()) * R + ELL @ SX),
    # towed at the axle: no torque, T = -sum l S_x = 0
    ("towed", lambda: ELL @ SX),
    # driven by a torque: no horizontal force, Q = sum N arm + sum S_x = 0
    ("torque", lambda: N @ ARM + SX.sum()),
])
def test_each_mode_row_is_its_equilibrium(mode, row):
    cN, cx = constraint(mode, ARM, ELL, R)
    assert cN.shape == cx.shape == ARM.shape
    assert cN @ N + cx @ SX == pytest.approx(row(), rel=1e-14, abs=1e-18)


def test_omega_mode_has_no_row():
    assert constraint("omega", ARM, ELL, R) is None


def test_reachability_at_its_limit():
    """Full slip can give mu sum |c_x| N0 against the |c_N . N0| the mode needs: equal is
    enough, a hair less raises with the numbers; towed and omega are always reachable."""
    N0 = np.array([1.0, 2.0, 3.0])
    cons = (np.array([0.5, 0.25, 0.0]), np.array([1.0, -1.0, 2.0]))  # need 1.0, sum |c_x| N0 = 9
    check_reachable("torque", 1.0 / 9.0, cons, N0)  # can = need exactly
    with pytest.raises(LoadingUnreachable, match=(
            r"^mode 'torque' needs tangential forces beyond the friction limit: mu = 0\.11 can give a "
            r"moment/force of 0\.99, the rolling resistance asks for 1 \(in units of N\); raise mu or use "
            r"mode 'towed' or 'omega'$")):
        check_reachable("torque", 0.11, cons, N0)
    with pytest.raises(LoadingUnreachable, match=r"asks for 1 \(in units of N m\); raise mu"):
        check_reachable("pushed_at_top", 0.11, (-cons[0], cons[1]), N0)  # |need| whatever its sign
    check_reachable("towed", 0.0, cons, N0)
    check_reachable("omega", 0.0, None, N0)
