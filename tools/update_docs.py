"""make docs: regenerate the generated parts of the documentation.

- docs/configuration.md: the key tables, from allocator_pkg.configuration.schema;
- docs/closed_loop.md: the scenario file's keys (allocator_pkg.simulation.scenario_keys);
- docs/dp_capability.md: the particulars file's keys, the site file's and the Level 3 criteria
  (allocator_pkg.dp.inputs.particulars, .site, allocator_pkg.dp.level3.case);
- docs/faults.md: the fault matrix of every shipped vehicle (allocator_pkg.capability.fault_matrix).

Each generated table sits between its ``<!-- BEGIN GENERATED: <name> -->`` and ``<!-- END
GENERATED -->`` markers (the prose around them is kept). Tests fail when these files and the
code disagree.
"""

import sys
from collections.abc import Callable
from pathlib import Path

from allocator_pkg.capability.fault_matrix import markdown
from allocator_pkg.configuration.file_keys import markdown_table
from allocator_pkg.configuration.schema import markdown_reference
from allocator_pkg.dp.inputs.particulars import PARTICULARS_KEYS
from allocator_pkg.dp.inputs.site import SITE_KEYS
from allocator_pkg.dp.level3.case import CRITERIA_KEYS
from allocator_pkg.simulation.scenario_keys import SCENARIO_KEYS

END = "<!-- END GENERATED -->\n"
ROOT = Path(__file__).resolve().parents[1]
FAULTS = ROOT / "docs" / "faults.md"
GENERATED: dict[Path, dict[str, Callable[[], str]]] = {
    ROOT / "docs" / "configuration.md": {"make docs": markdown_reference},
    ROOT / "docs" / "closed_loop.md": {"scenario keys": lambda: markdown_table(SCENARIO_KEYS)},
    ROOT / "docs" / "dp_capability.md": {"particulars keys": lambda: markdown_table(PARTICULARS_KEYS),
                                         "site keys": lambda: markdown_table(SITE_KEYS),
                                         "level 3 criteria": lambda: markdown_table(CRITERIA_KEYS)},
}
"""Per document, the generator of each of its generated sections by the name in its markers."""


def vehicle_files() -> list[Path]:
    return sorted(p for p in (ROOT / "config").glob("*.yaml") if p.stem != "default")


def render(text: str, name: str, content: str) -> str:
    """``text`` with the section ``name`` replaced by ``content``."""
    begin = f"<!-- BEGIN GENERATED: {name} -->\n"
    head, found, rest = text.partition(begin)
    if not found:
        raise ValueError(f"no marker {begin.strip()}")
    _, _, tail = rest.partition(END)
    return head + begin + content + END + tail


def main() -> int:
    for doc, sections in GENERATED.items():
        text = doc.read_text()
        for name, generate in sections.items():
            text = render(text, name, generate())
        doc.write_text(text)
        print(f"updated {doc}")
    FAULTS.write_text(markdown(vehicle_files()))
    print(f"updated {FAULTS}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
