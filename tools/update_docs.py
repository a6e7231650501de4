"""Regenerate the key tables of docs/configuration.md from allocator_pkg.schema (make docs).

The tables sit between the BEGIN/END markers; the prose around them is kept. A test fails
when the file and the schema disagree.
"""

import sys
from pathlib import Path

from allocator_pkg.schema import markdown_reference

BEGIN = "<!-- BEGIN GENERATED: make docs -->\n"
END = "<!-- END GENERATED -->\n"
DOC = Path(__file__).resolve().parents[1] / "docs" / "configuration.md"


def render(text: str) -> str:
    head, _, rest = text.partition(BEGIN)
    _, _, tail = rest.partition(END)
    return head + BEGIN + markdown_reference() + END + tail


def main() -> int:
    DOC.write_text(render(DOC.read_text()))
    print(f"updated {DOC}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
