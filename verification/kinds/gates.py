"""The checks every comparing kind makes of its gates and of the methods they use, before
anything is solved: the gate's keys, its quantity, its methods and reference, its levels,
and each used method's section and number of levels."""

from __future__ import annotations

from ..schema import LEVELS, CaseError, close

__all__ = ["used_methods", "check_gate", "check_methods"]


def used_methods(case: dict, pseudo: tuple[str, ...]) -> list[str]:
    """The methods the gates name (as methods or as references), in order of first use,
    without the ``pseudo`` references (``analytic``, ``dissipation``, ...)."""
    names = []
    for gate in case["gates"]:
        for m in gate.get("methods", []) + [gate.get("against", "")]:
            if m and m not in pseudo and m not in names:
                names.append(m)
    return names


def check_gate(gate: dict, where: str, quantities: tuple[str, ...], methods: dict, pseudo: tuple[str, ...],
               levels: tuple[str, ...] | None = LEVELS, kind: str = "") -> None:
    """One gate: ``methods`` and ``against`` given; a known quantity; known methods; a
    reference among ``pseudo`` and the methods, not one of the gate's own methods;
    ``levels`` among those allowed (``None``: the kind takes no levels); no ``limit``."""
    for key in ("methods", "against"):
        if key not in gate:
            raise CaseError(f"{where}: '{key}' is required")
    if "limit" in gate:
        raise CaseError(f"{where}: 'limit' belongs to rolling-limits cases")
    if levels is None and "levels" in gate:
        raise CaseError(f"{where}: 'levels' does not apply to a {kind} case (the finest level is gated)")
    q = gate["quantity"]
    if q not in quantities:
        raise CaseError(f"{where}: unknown quantity {q!r}; known: {', '.join(quantities)}{close(q, quantities)}")
    for m in gate["methods"]:
        if m not in methods:
            raise CaseError(f"{where} methods: unknown method {m!r}; known: {', '.join(methods)}{close(m, methods)}")
    against = gate["against"]
    known = [*pseudo, *methods]
    if against not in known:
        raise CaseError(f"{where} against: unknown reference {against!r}; known: {', '.join(known)}{close(against, known)}")
    if against in gate["methods"]:
        raise CaseError(f"{where}: method {against!r} compared against itself")
    for level in gate.get("levels", []) if levels else []:
        if level not in levels:
            raise CaseError(f"{where} levels: {level!r} is not one of {', '.join(levels)}{close(level, levels)}")


def check_methods(case: dict, path, names: list[str], methods: dict) -> None:
    """Each used method: its case section exists and passes the method's own check; it
    has at least one level, and three where a gate asks for ``extrapolated``."""
    for name in names:
        method = methods[name]
        if method.check is not None:
            if not method.settings(case):
                raise CaseError(f"{path}: the gates use {name!r} but the case has no [{method.section}] with its levels")
            method.check(method.settings(case), case["problem"], f"{path} [{method.section}]")
        n = len(method.levels(case))
        if n == 0:
            raise CaseError(f"{path}: method {name!r} has no level for case {case['name']!r} ({method.origin})")
        for i, gate in enumerate(case["gates"]):
            uses = name in gate["methods"] or name == gate["against"]
            if uses and "extrapolated" in gate.get("levels", []) and n < 3:
                raise CaseError(f"{path} gates[{i}] ({gate['quantity']}): 'extrapolated' needs three levels "
                                f"of {name!r}, the case gives {n}")
