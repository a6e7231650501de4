"""make docs: regenerate the generated parts of the documentation.

- docs/configuration.md: the key tables, from allocator_pkg.configuration.schema, between the BEGIN/END
  markers (the prose around them is kept);
- docs/faults.md: the fault matrix of every shipped vehicle (allocator_pkg.capability.fault_matrix).

Tests fail when these files and the code disagree.
"""

import sys
from pathlib import Path

from allocator_pkg.capability.fault_matrix import markdown
from allocator_pkg.configuration.schema import markdown_reference

BEGIN = "<!-- BEGIN GENERATED: make docs -->\n"
END = "<!-- END GENERATED -->\n"
ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "configuration.md"
FAULTS = ROOT / "docs" / "faults.md"


def vehicle_files() -> list[Path]:
    return sorted(p for p in (ROOT / "config").glob("*.yaml") if p.stem != "default")


def render(text: str) -> str:
    head, _, rest = text.partition(BEGIN)
    _, _, tail = rest.partition(END)
    return head + BEGIN + markdown_reference() + END + tail


def main() -> int:
    DOC.write_text(render(DOC.read_text()))
    FAULTS.write_text(markdown(vehicle_files()))
    print(f"updated {DOC} and {FAULTS}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
