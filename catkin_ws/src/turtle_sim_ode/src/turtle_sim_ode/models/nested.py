"""SDF nested models, flattened as Gazebo flattens them: the links and joints of a <model> inside a <model> become
the outer model's, named with Gazebo's scope ``inner::link`` (deeper ones ``a::b::link``), the links posed in the
outer model's frame; the nested model's plugins go with them. One model is spawned, whose link and joint names are
the scoped names Gazebo gives (``outer::inner::link`` in gazebo_msgs' link names)."""
from __future__ import annotations

from xml.etree.ElementTree import Element, SubElement

from turtle_sim_ode.models.transforms import Transform, compose, pose_transform, rpy_of
from turtle_sim_ode.models.text import ModelError, read_number
from turtle_sim_ode.models.description import Pose
from turtle_sim_ode.models.urdf import _offset

# Deeper nesting than any description needs; a deeper one is refused.
MAX_NESTING = 16


def read_pose(element: Element, what: str) -> Pose:
    """The <pose> child: "x y z roll pitch yaw" relative to the default frame."""
    pose = element.find("pose")
    if pose is None:
        return Pose()
    for attribute in ("relative_to", "frame"):
        if pose.get(attribute):
            raise ModelError(
                f"{what} <pose {attribute}='{pose.get(attribute)}'>: only poses " f"in the default frame are supported"
            )
    parts = (pose.text or "").split()
    if not parts:
        return Pose()
    if len(parts) != 6:
        raise ModelError(f"{what} <pose>: expected 6 numbers, got {pose.text!r}")
    values = [read_number(p, f"{what} <pose>") for p in parts]
    return Pose(_offset((values[0], values[1], values[2]), f"{what} <pose> x y z"), (values[3], values[4], values[5]))


def _set_pose(element: Element, transform: Transform) -> None:
    pose = element.find("pose")
    if pose is None:
        pose = SubElement(element, "pose")
    pose.text = " ".join(repr(float(v)) for v in tuple(transform[0]) + rpy_of(transform[1]))


def flatten_nested_models(model: Element, what: str, depth: int = 0) -> None:
    """Move every nested <model>'s links, joints and plugins into ``model`` (in place), scoped and re-posed;
    ModelError for a nested model without a name, with an <include>, with an axis in its model frame
    (``use_parent_model_frame``), or nested deeper than MAX_NESTING."""
    for nested in model.findall("model"):
        name = nested.get("name")
        if not name:
            raise ModelError(f"{what}: a nested <model> needs a name")
        where = f"{what} nested model '{name}'"
        if depth >= MAX_NESTING:
            raise ModelError(f"{where}: models nested deeper than {MAX_NESTING}")
        if nested.find("include") is not None:
            raise ModelError(f"{where}: an <include> inside a model is not supported")
        flatten_nested_models(nested, where, depth + 1)
        placement = pose_transform(read_pose(nested, where))
        for link in nested.findall("link"):
            link_name = link.get("name") or ""
            _set_pose(link, compose(placement, pose_transform(read_pose(link, f"{where} link '{link_name}'"))))
            link.set("name", f"{name}::{link_name}")
            model.append(link)
        for joint in nested.findall("joint"):
            for axis in ("axis", "axis2"):
                flag = joint.find(f"{axis}/use_parent_model_frame")
                if flag is not None and (flag.text or "").strip().lower() in ("1", "true"):
                    raise ModelError(f"{where} joint '{joint.get('name')}': use_parent_model_frame is not supported")
            joint.set("name", f"{name}::{joint.get('name') or ''}")
            for tag in ("parent", "child"):
                reference = joint.find(tag)
                if reference is not None and reference.text and reference.text.strip() != "world":
                    reference.text = f"{name}::{reference.text.strip()}"
            model.append(joint)
        for plugin in nested.findall("plugin"):
            model.append(plugin)
        model.remove(nested)
