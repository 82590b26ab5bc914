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

import importlib

# Names are imported on first use (PEP 562), so that ``sweep --help`` answers without
# loading numpy, scipy, Dask and the BEM.
_EXPORTS = {
    "engine": ("RunReport", "connect", "run_sweep"),
    "fits": ("Fit", "fit_law", "fit_power", "fit_two_exponential"),
    "kernels": ("KernelCache", "fit_kernels", "kernel_key"),
    "point": ("solve_point",),
    "report": ("curves", "write_report"),
    "integrity": ("code_version",),
    "spec": ("MAX_POINTS", "Axis", "Point", "Sweep", "SweepError", "count", "expand", "read_sweep"),
    "table": ("RESULTS",),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}


def __getattr__(name: str):
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
        globals()[name] = value
        return value
    try:  # a submodule, as ``sweeps.paper`` after ``import sweeps``
        return importlib.import_module(f".{name}", __name__)
    except ModuleNotFoundError as exc:
        if exc.name != f"{__name__}.{name}":
            raise
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "Axis", "Fit", "KernelCache", "MAX_POINTS", "Point", "RESULTS", "RunReport", "Sweep", "SweepError",
    "code_version", "connect", "count", "curves", "expand", "fit_kernels", "fit_law", "fit_power",
    "fit_two_exponential", "kernel_key", "read_sweep", "run_sweep", "solve_point", "write_report",
]
