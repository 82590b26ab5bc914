"""``python -m casefile [FILE.md]``: rewrite the generated schema in FILE.md
(default docs/case-files.md), or print it with ``-``."""

import sys

from . import schema_markdown, update_markdown

target = sys.argv[1] if len(sys.argv) > 1 else "docs/case-files.md"
if target == "-":
    print(schema_markdown())
else:
    print(f"{target}: {'updated' if update_markdown(target) else 'already up to date'}")
