"""Small verification cases the harness's command-line tests share."""

# A thick elastic layer under a paraboloid, one coarse BEM grid: about a second to solve.
THICK_LAYER_CASE = """
name = "hs"
title = "A thick layer: Hertz holds"
kind = "stationary"
[problem]
layer = { thickness = 0.03 }
material = { model = "elastic", shear_modulus = 3.0e6 }
indenter = { shape = "paraboloid", radius = 0.02 }
loading = { load = 10.0 }
[bem]
spacings = [0.2e-3]
half_width = 2.9e-3
[analytic]
reference = "hertz"
[[gates]]
quantity = "contact_radius"
methods = ["bem"]
against = "analytic"
tolerance = 0.01
reason = "the coarse grid: 0.4 % measured"
"""


def assert_refused(kind: str, case: dict, edits, path="case.toml") -> None:
    """Each ``(edit, message)`` of ``edits``: ``edit`` applied to a copy of ``case`` makes
    the kind's check raise :class:`verification.schema.CaseError` matching ``message``."""
    import copy

    import pytest

    from verification.kinds import KINDS
    from verification.schema import CaseError

    for edit, message in edits:
        bad = copy.deepcopy(case)
        edit(bad)
        with pytest.raises(CaseError, match=message):
            KINDS[kind].check(bad, path, {})


def default_sigint() -> None:
    """``preexec_fn`` of a child that is to answer Ctrl-C as in a terminal: a shell starts
    background jobs (a CI script's, say) with SIGINT ignored, and Python keeps an ignored
    SIGINT (no KeyboardInterrupt); the child gets the default disposition back."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
