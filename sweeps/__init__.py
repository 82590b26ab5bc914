"""Parametric studies of BEM cases on Dask (the paper's sections 11.4-11.7).

A sweep file (TOML, ``docs/sweeps.md``) names a base case and the axes that vary it;
:func:`read_sweep` checks it, :func:`expand` makes its points, :func:`run_sweep` runs them
on ``dask.distributed`` (a local cluster, or an existing one), forming one kernel set per
layer, material, speed and grid (:mod:`sweeps.kernels`), and writes the tidy table;
:func:`write_report` draws the plots and fits the laws (:mod:`sweeps.fits`).
:mod:`sweeps.paper` holds the paper's Tables 2-3 and the checks a verification case
makes on the sweeps' results. SI units throughout.

    from sweeps import read_sweep, run_sweep, write_report
    sweep = read_sweep("examples/sweeps/fig7a-load-H5.toml")
    report = run_sweep(sweep, "out/sweeps/fig7a", cache="out/sweeps/kernel-cache")
    write_report(sweep, report.rows, "out/sweeps/fig7a")
"""

from .engine import RunReport, connect, run_sweep
from .fits import Fit, fit_law, fit_power, fit_two_exponential
from .kernels import KernelCache, fit_kernels, kernel_key
from .point import solve_point
from .report import curves, write_report
from .spec import Axis, Point, Sweep, SweepError, expand, read_sweep
from .table import RESULTS

__all__ = [
    "Axis", "Fit", "KernelCache", "Point", "RESULTS", "RunReport", "Sweep", "SweepError", "connect", "curves",
    "expand", "fit_kernels", "fit_law", "fit_power", "fit_two_exponential", "kernel_key", "read_sweep",
    "run_sweep", "solve_point", "write_report",
]
