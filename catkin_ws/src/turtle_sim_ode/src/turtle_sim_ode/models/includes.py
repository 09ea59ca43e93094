"""A world's <include>s resolved as Gazebo resolves them: ``model://NAME`` is the folder NAME on the model path
(GAZEBO_MODEL_PATH and the gazebo_model_path exports of the ROS packages), whose model.config names the model's SDF
file (the one of the highest <sdf version> this simulator reads); the <include>'s <name>, <pose> and <static>
override the model's own. Files are read through models.resources (only under the package and model paths).

An <include> inside an included model is not supported (sdf refuses it), but include chains are followed first, to a
depth limit, so that a self-include or a cycle is refused as such and supporting nested includes later cannot loop."""
from __future__ import annotations

from dataclasses import replace
from typing import List, Optional, Sequence, Set, Tuple

from turtle_sim_ode.models.lights import SUN, Light, parse_light
from turtle_sim_ode.models.resources import ResourcePaths
from turtle_sim_ode.models.sdf import parse_included_model
from turtle_sim_ode.models.sdf_parts import NEWEST_VERSION
from turtle_sim_ode.models.sdf_world import Include, World, WorldModel
from turtle_sim_ode.models.text import ModelError, parse_xml
from turtle_sim_ode.models.description import Pose


def _version(text: Optional[str]) -> Tuple[int, ...]:
    try:
        return tuple(int(part) for part in (text or "0").split("."))
    except ValueError:
        return (0,)


def model_file(paths: ResourcePaths, name: str) -> Tuple[str, str]:
    """(folder, SDF text) of Gazebo model ``name``; ModelError naming it where it cannot be found or read."""
    folder = paths.model_folder(name)
    if folder is None:
        raise ModelError(f"cannot resolve model://{name}: no such model on the model path {paths.model_paths}")
    _, config = paths.read("model.config", base=folder)
    root = parse_xml(config.decode("utf-8", "replace"), f"model://{name}/model.config")
    candidates = [
        (_version(element.get("version")), (element.text or "").strip())
        for element in root.findall("sdf")
        if (element.text or "").strip() and _version(element.get("version")) <= NEWEST_VERSION
    ]
    if not candidates:
        raise ModelError(f"model://{name}/model.config names no <sdf> file of version <= 1.7")
    _, sdf_name = max(candidates)
    _, text = paths.read(sdf_name, base=folder)
    return folder, text.decode("utf-8", "replace")


# How deep includes may nest, and how many model files one world's chains may visit: far beyond Gazebo worlds' use.
MAX_INCLUDE_DEPTH = 8
MAX_INCLUDED_FILES = 64


def _nested_model_includes(text: str, name: str) -> List[str]:
    """The model:// names a model file's own <include>s name."""
    root = parse_xml(text, f"model://{name}")
    uris = [(include.findtext("uri") or "").strip() for include in root.iter("include")]
    return [uri[len("model://") :].strip("/") for uri in uris if uri.startswith("model://")]


def check_include_chain(
    paths: ResourcePaths, name: str, chain: Sequence[str] = (), visited: Optional[Set[str]] = None
) -> None:
    """Follow model ``name``'s nested model:// includes; ModelError naming the chain at a cycle (a model that
    includes itself, directly or not), beyond MAX_INCLUDE_DEPTH, or beyond MAX_INCLUDED_FILES files."""
    chain = list(chain) + [name]
    shown = " -> ".join(f"model://{entry}" for entry in chain)
    if name in chain[:-1]:
        raise ModelError(f"include cycle: {shown}")
    if len(chain) > MAX_INCLUDE_DEPTH:
        raise ModelError(f"includes nested deeper than {MAX_INCLUDE_DEPTH}: {shown}")
    visited = set() if visited is None else visited
    visited.add(" ".join(chain))
    if len(visited) > MAX_INCLUDED_FILES:
        raise ModelError(f"includes reach more than {MAX_INCLUDED_FILES} model files: {shown}")
    _, text = model_file(paths, name)
    for nested in _nested_model_includes(text, name):
        check_include_chain(paths, nested, chain, visited)


# model://ground_plane when no model folder of that name is on the model path: the model Gazebo's model database
# serves (gazebo_models ground_plane/model.sdf): static, one link "link", a 100 m x 100 m plane facing up whose
# collision has friction mu 100, mu2 50, drawn in Gazebo/Grey.
BUILT_IN_GROUND_PLANE = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="ground_plane">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        <surface><friction><ode><mu>100</mu><mu2>50</mu2></ode></friction></surface>
      </collision>
      <visual name="visual">
        <cast_shadows>false</cast_shadows>
        <geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry>
        <material><script><uri>file://media/materials/scripts/gazebo.material</uri><name>Gazebo/Grey</name></script></material>
      </visual>
    </link>
  </model>
</sdf>
"""
GROUND_PLANE = "ground_plane"


def resolve_includes(world: World, paths: Optional[ResourcePaths]) -> Tuple[List[WorldModel], List[Include]]:
    """The world's model:// includes as models to spawn, and the includes left unresolved (other URI schemes, or
    any but the built-in ground plane without ``paths``); ModelError naming the include where one cannot be read or
    parsed, or where two models get one name. A ground_plane folder on the model path wins over the built-in one."""
    names: Set[str] = {model.name for model in world.models}
    models: List[WorldModel] = []
    left: List[Include] = []
    for include in world.includes:
        name = include.uri[len("model://") :].strip("/")
        built_in = name == GROUND_PLANE and (paths is None or paths.model_folder(name) is None)
        if not include.uri.startswith("model://") or (paths is None and not built_in):
            left.append(include)
            continue
        try:
            if built_in:
                folder, text = None, BUILT_IN_GROUND_PLANE
            else:
                assert paths is not None  # an unresolvable include was left above
                check_include_chain(paths, name)
                folder, text = model_file(paths, name)
            model, own_pose = parse_included_model(text, include.name, include.static)
        except ModelError as error:
            raise ModelError(f"<include> {include.uri}: {error}") from None
        if model.name in names:
            raise ModelError(f"<include> {include.uri}: two models are named '{model.name}'")
        names.add(model.name)
        pose = include.pose if include.pose != Pose() else own_pose
        models.append(WorldModel(model.name, pose, model, folder, include.index))
    return models, left


def sun_lights(world: World, paths: ResourcePaths) -> List[Light]:
    """The world's lights with model://sun as the model path has it (the first <light> of its SDF file, under the
    include's name) where a sun model is on the path; else with the built-in sun (gazebo_models' values)."""
    if not world.sun or paths.model_folder("sun") is None:
        return list(world.lights)
    _, text = model_file(paths, "sun")
    element = parse_xml(text, "model://sun").find("light")
    if element is None:
        raise ModelError("model://sun: its SDF file has no <light>")
    found = parse_light(element)
    return [
        replace(found, name=light.name) if replace(light, name=SUN.name) == SUN else light for light in world.lights
    ]
