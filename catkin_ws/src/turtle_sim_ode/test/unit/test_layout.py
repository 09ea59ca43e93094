"""The package's layout holds: layers import one way, no module cycles, ROS only in turtle_sim_ode.ros, short
modules (Python, C and tests alike), and one parse of a spawned model's text."""
from __future__ import annotations

import ast
from pathlib import Path
from typing import Dict, Set

import pytest
from conftest import PACKAGE_ROOT, TURTLEBOT_URDF

from turtle_sim_ode.models import text as model_text
from turtle_sim_ode.models.urdf import parse_urdf
from turtle_sim_ode.world.simulation import Simulation

SOURCE = PACKAGE_ROOT / "src" / "turtle_sim_ode"
# Each layer may import from itself and from the layers before it; analysis (helpers for demos and tests) imports
# none of them, and any may use it.
HELPERS = "analysis"
LAYERS = ("physics", "models", "control", "sensors", "world", "ros")
ROS_MODULES = ("rospy", "genpy", "rosgraph", "rospkg", "tf2_ros", "dynamic_reconfigure")
MAX_MODULE_LINES = 500


def module_name(path: Path) -> str:
    parts = path.relative_to(SOURCE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path: Path) -> Set[str]:
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module:
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
        elif isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
    return found


MODULES: Dict[str, Set[str]] = {module_name(path): imports_of(path) for path in sorted(SOURCE.rglob("*.py"))}


def own_imports(module: str) -> Set[str]:
    return {name for name in MODULES[module] if name in MODULES and name != module}


def layer_of(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 2 else ""


@pytest.mark.parametrize("module", sorted(MODULES))
def test_layers_import_one_way(module: str) -> None:
    layer = layer_of(module)
    for imported in own_imports(module):
        other = layer_of(imported)
        if not other or other == layer or other == HELPERS:
            continue
        assert layer in LAYERS and other in LAYERS, f"{module} imports {imported}"
        assert LAYERS.index(other) < LAYERS.index(layer), f"{module} ({layer}) imports {imported} ({other})"


def test_no_import_cycles() -> None:
    visiting: Set[str] = set()
    done: Set[str] = set()

    def visit(module: str, path: tuple) -> None:
        if module in done:
            return
        assert module not in visiting, "import cycle: " + " -> ".join(path + (module,))
        visiting.add(module)
        for imported in own_imports(module):
            visit(imported, path + (module,))
        visiting.discard(module)
        done.add(module)

    for module in MODULES:
        visit(module, ())


@pytest.mark.parametrize("module", sorted(MODULES))
def test_only_the_ros_layer_imports_ros(module: str) -> None:
    ros_imports = {
        name
        for name in MODULES[module]
        if name.split(".")[0] in ROS_MODULES or name.split(".")[0].endswith("_msgs") or ".msg" in name
    }
    assert layer_of(module) == "ros" or not ros_imports, f"{module} imports {sorted(ros_imports)}"


# The Python package, the C libraries loaded through ctypes (src/*.c, their headers) and the tests.
SHORT_FILES = sorted(SOURCE.rglob("*.py")) + sorted((PACKAGE_ROOT / "src").glob("*.[ch]"))
SHORT_FILES += sorted((PACKAGE_ROOT / "include").rglob("*.h"))
SHORT_FILES += sorted((PACKAGE_ROOT / "test").rglob("*.py"))


@pytest.mark.parametrize("path", SHORT_FILES, ids=lambda path: str(path.relative_to(PACKAGE_ROOT)))
def test_modules_are_short(path: Path) -> None:
    assert len(path.read_text().splitlines()) <= MAX_MODULE_LINES


def test_a_spawned_model_is_parsed_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """The spawn service parses the text (outside the world lock) and spawns the parsed model with its sensors and
    plugins: the XML parser runs once."""
    parses = []
    parse = model_text.SafeET.fromstring

    def counting(text, *args, **kwargs):  # type: ignore[no-untyped-def]
        parses.append(len(text))
        return parse(text, *args, **kwargs)

    monkeypatch.setattr(model_text.SafeET, "fromstring", counting)
    sim = Simulation()
    robot = parse_urdf(TURTLEBOT_URDF)
    sim.spawn_model("mobile_base", robot)
    assert parses == [len(TURTLEBOT_URDF)]
    assert sim.plugins["mobile_base"].drives and sim.robots["mobile_base"]
