"""The dissipation of normal forces alone takes a fast path (only C_ww, from the outer-grid
normal compliance, whose half-space modes use an expansion); it must equal the general
path (all nine entries of the closed-form compliance) on any forces, layer and speed.
The general path is forced by a tangential force of 1e-300 N, which adds nothing.
Measured: equal to 2e-16 relative; tolerance 1e-12 (the expansion's stated 1e-12).
Both paths, and the power tables, weigh the end modes as the kernels do: on ALIASED,
2 N_t a / L is odd along x and y and the modes |m| = N_tx, |n| = N_ty count 1/2."""

import numpy as np
import pytest

from bem.energy import viscous_dissipation
from bem.grid import Grid
from bem.layer import Layer
from bem.materials import Prony, ThreeParameterSolid

GRID = Grid(0.7e-3, 0.9e-3, 0.02, 0.025, 40, 30, 7, 6)
ALIASED = Grid(0.5e-3, 0.8e-3, 0.02, 0.024, 60, 15, 7, 6)  # 2 N_t a / L = 3 along x, 1 along y
GRIDS = pytest.mark.parametrize("grid", [GRID, ALIASED], ids=["plain", "aliased-ends"])


@pytest.mark.parametrize("thickness, density, speed", [
    (5e-3, 0.0, 0.05),        # the loss peak region
    (5e-3, 1000.0, 20.0),     # strong inertia (0.6 of the shear-wave speed)
    (0.2, 0.0, 0.5),          # a thick layer: most modes take the half-space expansion
    (2e-4, 0.0, 1e-3),        # a thin one
])
@GRIDS
def test_normal_forces_take_the_fast_path_to_the_same_power(thickness, density, speed, grid):
    rng = np.random.default_rng(7)
    material = Prony(1e6, (2e6, 5e5), (0.01, 0.3)) if density else ThreeParameterSolid(3e6, 0.25, 1.0)
    layer = Layer(thickness, material, density)
    Fz = -rng.random(grid.shape)  # compressive
    zero = np.zeros(grid.shape)
    tiny = zero.copy()
    tiny[3, 4] = 1e-300
    fast = viscous_dissipation(grid, layer, speed, Fz, zero, zero)
    general = viscous_dissipation(grid, layer, speed, Fz, tiny, zero)
    assert fast > 0
    assert fast == pytest.approx(general, rel=1e-12)


@pytest.mark.parametrize("density, matmul_nodes", [
    (0.0, 128),     # no inertia: half-space modes split off, n- and m-sums by matrix products
    (1000.0, 128),  # inertia: every mode's symbol streamed
    (0.0, 4),       # the same two by chirp-z transforms (grids above matmul_nodes a side)
    (1000.0, 4),
])
@GRIDS
def test_power_tables_give_the_mode_sum_dissipation(monkeypatch, density, matmul_nodes, grid):
    """The power tables (one more transform of the kernels' symbols) and FFTs of the forces
    give the mode sum of viscous_dissipation: the same truncated sum regrouped, so equal to
    rounding. Measured: 6e-15 relative at most; tolerance 1e-12. The kernels computed
    alongside are those of influence_kernels, bit for bit."""
    from bem import spectral
    from bem.energy import dissipation_from_tables
    monkeypatch.setattr(spectral, "_MATMUL_NODES", matmul_nodes)
    rng = np.random.default_rng(11)
    layer = Layer(5e-3, ThreeParameterSolid(3e6, 0.25, 1.0), density)
    blocks = tuple(spectral.BLOCKS)
    kernels, tables = spectral.kernels_with_power(grid, layer, 0.05, blocks)
    alone = spectral.influence_kernels(grid, layer, 0.05, blocks)
    assert all(np.array_equal(kernels[b], alone[b]) for b in blocks)
    F = [rng.standard_normal(grid.shape) for _ in range(3)]
    zero = np.zeros(grid.shape)
    for forces in (F, [F[0], zero, zero], [zero, F[1], zero]):
        exact = viscous_dissipation(grid, layer, 0.05, *forces)
        assert exact != 0
        assert dissipation_from_tables(tables, 0.05, *forces) == pytest.approx(exact, rel=1e-12)
    with pytest.raises(ValueError, match="power table wu"):
        dissipation_from_tables({"ww": tables["ww"]}, 0.05, *F)
