"""Case files: the one schema of the TOML files that ``bem solve``, ``fem-reference
solve`` and the verification harness read.

It reads the file, applies ``--set section.key=value`` overrides, rejects unknown keys and
wrong types (naming the file, the section and the key), resolves relative paths against
the case file's folder, and hands each tool a checked dict. Its validation engine
(:mod:`casefile.validation`: :class:`Key`, :func:`check_table`, :class:`InputError`) also
checks the verification cases and the sweep files, so every input error of the project
reads the same way and is an :class:`InputError`. It holds no physics and no
numerics: ``bem`` and ``fem_reference`` each translate the dict into their own problem
objects, so the two methods stay independent. SI units throughout.

    import casefile
    data = casefile.read("examples/paper-section11-frictionless.toml", ["loading.load=100"], tool="bem")

The schema, key by key, is in ``docs/case-files.md`` (generated from :data:`SCHEMA`).
"""

from .docs import schema_markdown, update_markdown
from .reader import CaseFileError, apply_overrides, check_output, parse_override, read, validate
from .schema import SCHEMA, TOOLS, Section, Variant
from .validation import InputError, Key, check_table, check_value, did_you_mean

__all__ = [
    "read", "validate", "apply_overrides", "parse_override", "check_output", "InputError", "CaseFileError",
    "SCHEMA", "TOOLS", "Key", "Section", "Variant", "check_table", "check_value", "did_you_mean",
    "schema_markdown", "update_markdown",
]
