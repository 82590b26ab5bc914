"""Fast transforms against the paper's direct summation, 41 x 41 nodes, Nt = 500 (the
paper reports about 18 minutes for the full 3D matrix on an i7 M620).

Run: ``python benchmarks/bem_fast_vs_direct.py [--markdown]``.
"""

import time

import numpy as np
from _common import LAYER, machine, markdown_mode, markdown_table, reporter

from bem import Grid
from bem.spectral import BLOCKS, influence_kernels, influence_kernels_direct

markdown = markdown_mode()
say = reporter(markdown)
grid = Grid.centred((0.25e-3, 0.25e-3), (0.2, 0.2), (500, 500), (5e-3, 5e-3))
say(machine(), grid.shape)
rows = []
for label, blocks in (("normal block C_ww", ("ww",)), ("all nine blocks", tuple(BLOCKS))):
    t = time.perf_counter()
    fast = influence_kernels(grid, LAYER, 0.05, blocks)
    tf = time.perf_counter() - t
    t = time.perf_counter()
    direct = influence_kernels_direct(grid, LAYER, 0.05, blocks)
    td = time.perf_counter() - t
    err = max(np.abs(fast[b] - direct[b]).max() / np.abs(direct[b]).max() for b in blocks)
    say(f"{len(blocks)} block(s): fast {tf:.3f} s, direct {td:.2f} s, ratio {td / tf:.0f}, max rel diff {err:.1e}")
    rows.append([f"section 11 layer, 41 x 41 nodes, Nt = 500: {label}", f"{tf:.3f}", f"{td:.2f}",
                 f"{td / tf:.0f}", f"{err:.1e}"])
if markdown:
    print(markdown_table(["case", "fast (s)", "direct (s)", "direct / fast", "largest difference (of the largest entry)"],
                         rows))
