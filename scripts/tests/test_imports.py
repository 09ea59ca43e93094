"""scripts/ has no import circle: no module of scripts/lib (nor a script or a test) imports, however indirectly, one
that imports it back, counting imports inside functions too (bench_camera and camera_peers once did so)."""
from __future__ import annotations

import ast
import os
from typing import Dict, List, Optional, Set

SCRIPTS = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
LIB = os.path.join(SCRIPTS, "lib")


def module_names() -> Dict[str, str]:
    """Every Python module of scripts/ by the name it is imported as (scripts/lib and scripts/tests are on the path
    of the scripts and the tests), with its file."""
    found = {}
    for folder in (SCRIPTS, os.path.join(SCRIPTS, "tests")):
        for name in os.listdir(folder):
            if name.endswith(".py"):
                found[name[:-3]] = os.path.join(folder, name)
    for root, _, files in os.walk(LIB):
        package = os.path.relpath(root, LIB).replace(os.sep, ".")
        for name in files:
            if name.endswith(".py"):
                stem = package if name == "__init__.py" else f"{package}.{name[:-3]}"
                found[stem[2:] if stem.startswith("..") else stem.lstrip(".")] = os.path.join(root, name)
    return found


def imports_of(path: str, known: Set[str]) -> Set[str]:
    """The modules of ``known`` that the file at ``path`` imports, anywhere in it."""
    found = set()
    for node in ast.walk(ast.parse(open(path).read())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            found.add(node.module)
            found.update(f"{node.module}.{alias.name}" for alias in node.names)
    return {name for name in found if name in known}


def find_circle(graph: Dict[str, Set[str]]) -> Optional[List[str]]:
    """One import circle of ``graph`` (module -> modules it imports), as the modules along it, or None."""
    done: Set[str] = set()

    def visit(module: str, path: List[str]) -> Optional[List[str]]:
        if module in path:
            return path[path.index(module) :] + [module]
        if module in done:
            return None
        for imported in sorted(graph.get(module, ())):
            circle = visit(imported, path + [module])
            if circle:
                return circle
        done.add(module)
        return None

    for module in sorted(graph):
        circle = visit(module, [])
        if circle:
            return circle
    return None


def test_the_circle_finder_finds_a_circle_through_a_function_level_import() -> None:
    graph = {"bench_camera": {"camera_peers"}, "camera_peers": {"bench_camera", "peer_venv"}, "peer_venv": set()}
    assert find_circle(graph) == ["bench_camera", "camera_peers", "bench_camera"]
    assert find_circle({"a": {"b"}, "b": {"c"}, "c": set()}) is None


def test_scripts_have_no_import_circle() -> None:
    modules = module_names()
    assert "bench.camera" in modules and "ros_run.processes" in modules and "bench_sim" in modules
    graph = {name: imports_of(path, set(modules)) - {name} for name, path in modules.items()}
    assert "bench.camera" in graph["bench.camera_peers"], "the module names no longer match the imports"
    circle = find_circle(graph)
    assert circle is None, "import circle: " + " -> ".join(circle)
