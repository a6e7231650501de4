"""The package's modules import each other without a cycle and only downward, folder by folder:
every import counts, at module level, inside functions and under TYPE_CHECKING alike."""

import ast
from pathlib import Path

from conftest import ROOT

PACKAGE = ROOT / "allocator_pkg"


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def imports(path: Path, modules: set[str]) -> set[str]:
    """The package modules a file imports (a package counts as its __init__; ``from p import m``
    of a submodule m counts as importing m only)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            submodules = {f"{target}.{alias.name}" for alias in node.names} & modules
            found.update(submodules)
            if len(submodules) < len(node.names):       # a name defined in the module itself
                found.add(target)
    return {module for module in found if module in modules and module != name}


def graph() -> dict[str, set[str]]:
    files = sorted(PACKAGE.rglob("*.py"))
    modules = {module_name(path) for path in files}
    return {module_name(path): imports(path, modules) for path in files}


def cycle(edges: dict[str, set[str]]) -> list[str]:
    """One import cycle, as the modules along it, or []."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(module: str) -> list[str]:
        state[module] = 1
        stack.append(module)
        for target in sorted(edges[module]):
            if state.get(target) == 1:
                return [*stack[stack.index(target):], target]
            if target not in state:
                found = visit(target)
                if found:
                    return found
        stack.pop()
        state[module] = 2
        return []

    for module in sorted(edges):
        if module not in state:
            found = visit(module)
            if found:
                return found
    return []


def test_no_import_cycle_in_the_package():
    found = cycle(graph())
    assert not found, "import cycle: " + " -> ".join(found)


def test_the_cycle_finder_finds_cycles():
    assert cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert cycle({"a": {"b"}, "b": set(), "c": {"a", "b"}}) == []


def test_the_configuration_types_import_nothing_of_the_package_but_angles():
    assert graph()["allocator_pkg.vehicle.config"] == {"allocator_pkg.vehicle.angles"}


LAYERS = ("vehicle", "effectiveness", "configuration", "solvers", "methods", "allocation", "capability", "hull",
          "simulation", "dp", "ros", "cli", "testing")
"""The package's folders, lowest first: a module imports only from its own folder or one below."""


def layer(module: str) -> int | None:
    """The rank of a module's folder in LAYERS (None: the package itself, above every layer)."""
    parts = module.split(".")
    return LAYERS.index(parts[1]) if len(parts) > 1 else None


def upward(edges: dict[str, set[str]]) -> list[tuple[str, str]]:
    """Every import from a module to one in a higher layer."""
    return sorted((module, target) for module, targets in edges.items() for target in targets
                  if layer(module) is not None and (layer(target) is None or layer(target) > layer(module)))


def test_every_module_sits_in_a_layer_folder():
    assert {module.split(".")[1] for module in graph() if module.count(".")} == set(LAYERS)
    assert [path.name for path in PACKAGE.glob("*.py")] == ["__init__.py"]


def test_no_module_imports_from_a_higher_layer():
    found = upward(graph())
    assert not found, "upward imports: " + ", ".join(f"{a} -> {b}" for a, b in found)


def test_the_layer_check_finds_an_upward_import():
    edges = {"allocator_pkg.methods.qp": {"allocator_pkg.vehicle.config"},
             "allocator_pkg.vehicle.config": {"allocator_pkg.ros.node"},
             "allocator_pkg.ros.node": {"allocator_pkg"}}
    assert upward(edges) == [("allocator_pkg.ros.node", "allocator_pkg"),
                             ("allocator_pkg.vehicle.config", "allocator_pkg.ros.node")]


def outside_imports(path: Path) -> set[str]:
    """The top-level names of every module a file imports from outside the package."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and not node.level:
            found.add(node.module.split(".")[0])
    return found - {"allocator_pkg"}


def is_report(module: str) -> bool:
    """A module of a ``report`` folder: the only place a plot is drawn."""
    return "report" in module.split(".")[1:-1]


def test_the_maths_never_imports_rclpy_and_the_nodes_never_a_command_line_or_a_plot():
    for path in sorted(PACKAGE.rglob("*.py")):
        module, names = module_name(path), outside_imports(path)
        rank = layer(module)
        if rank is not None and rank < LAYERS.index("ros"):
            assert not {name for name in names if name.startswith("rcl") or name.endswith("_msgs")}, module
        if rank is not None and rank < LAYERS.index("cli"):
            assert "argparse" not in names, module
        if not is_report(module):
            assert "matplotlib" not in names, module


def test_nothing_in_ros_imports_a_report_module():
    edges = graph()
    found = sorted((module, target) for module, targets in edges.items() if module.split(".")[1:2] == ["ros"]
                   for target in targets if is_report(target))
    assert not found, found


def test_no_two_modules_of_the_package_share_a_name():
    names = [path.stem for path in PACKAGE.rglob("*.py") if path.name != "__init__.py"]
    assert sorted({name for name in names if names.count(name) > 1}) == []


def test_the_tests_mirror_the_package():
    """A test module in a folder under test/ is named after a module of the same package folder,
    or tests that folder as a whole (the node, its inputs, the properties of every method)."""
    for path in sorted((ROOT / "test").rglob("test_*.py")):
        folder = path.parent.relative_to(ROOT / "test")
        if folder.parts:
            assert (PACKAGE / folder).is_dir(), path
