"""gazebo_ros_ft_sensor (``libgazebo_ros_ft_sensor.so``, gazebo_plugins/src/gazebo_ros_ft_sensor.cpp): the wrench a
joint carries, in its child link's frame. Its tags (GazeboRosFT::Load: <jointName> and <topicName> required,
<updateRate> 0 = every step, <gaussianNoise> 0) and its per-step work (UpdateChild: the body2 force and torque of
Joint::GetForceTorque(0), each of the six values with its own gaussian noise).

ODEJoint::GetForceTorque (gazebo/physics/ode/ODEJoint.cc) takes body2 from the feedback of ODE's body 1, the child
(ODEJoint::Attach joins child then parent, as models.builder does): the constraint force f1 and torque t1 on the
child's centre of mass, in the world. It moves the torque to the joint (for a URDF joint the child link's origin:
t1 + f1 × (joint − centre of mass)), turns both into the child link's frame and negates them: what the child pulls
on the joint with. A payload hanging at rest reads its weight, pointing down: (0, 0, −m g) in an upright link.
Not done: GetForceTorque also takes off the effort applied through the joint (Joint::SetForce); here efforts are not
recorded, so a driven joint reads the effort too.

A URDF fixed joint has no ODE joint here: its links are merged into one body, as Gazebo lumps fixed joints by
default, where the plugin then finds no joint ("jointName: ... does not exist") and publishes nothing. So here too:
``sensor_joint`` gives None (the ROS side warns and publishes nothing); a name that is no joint at all is a
ModelError."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Optional, Tuple

from turtle_sim_ode.models.built import BuiltModel, JointHandle
from turtle_sim_ode.models.transforms import Vec3, quat_rotate
from turtle_sim_ode.models.text import ModelError, robot_namespace_tag
from turtle_sim_ode.models.description import GazeboPlugin
from turtle_sim_ode.world.kinematics import add, conjugate, cross, sub
from turtle_sim_ode.world.plugins.tags import number, text

FT_SENSOR = "libgazebo_ros_ft_sensor.so"
MODEL_PLUGINS = (FT_SENSOR,)


@dataclass(frozen=True)
class FtSensorConfig:
    joint: str
    topic: str
    update_rate: float = 0.0
    gaussian_noise: float = 0.0
    robot_namespace: Optional[str] = None  # None: no <robotNamespace>


def read(model_name: str, plugin: GazeboPlugin, overrides: Mapping[str, object]) -> FtSensorConfig:
    joint, topic = text(plugin, "jointName", ""), text(plugin, "topicName", "")
    if not joint or not topic:
        raise ModelError(f"{plugin.filename} needs <jointName> and <topicName>")
    return FtSensorConfig(
        joint,
        topic,
        number(plugin, "updateRate", 0.0),
        number(plugin, "gaussianNoise", 0.0),
        robot_namespace_tag(plugin.params),
    )


def sensor_joint(model: BuiltModel, name: str) -> Optional[JointHandle]:
    """The joint ``name`` of ``model`` as an ODE joint; None for a fixed (merged) or floating joint; ModelError if the
    model has no joint of that name."""
    if name in model.joints:
        return model.joints[name]
    if name in model.robot.joints:
        return None
    raise ModelError(f"model '{model.name}' has no joint '{name}' for {FT_SENSOR}")


class JointWrench:
    """The wrench a joint carries, as GazeboRosFT reads it: in the child link's frame, about the joint."""

    def __init__(self, model: BuiltModel, handle: JointHandle) -> None:
        self._model = model
        self._joint = handle.joint
        self._body = handle.joint.getBody(0)  # the child's (body 1 in ODE's numbering)
        self.child = model.robot.joints[handle.name].child
        self._joint.setFeedback(True)

    def wrench(self) -> Tuple[Vec3, Vec3]:
        """(force, torque) of the last step."""
        f1, t1, _, _ = self._joint.getFeedback()
        origin, orientation = self._model.link_transform(self.child)
        moment = add(t1, cross(f1, sub(origin, self._body.getPosition())))
        to_link = conjugate(orientation)
        force = quat_rotate(to_link, (-f1[0], -f1[1], -f1[2]))
        return force, quat_rotate(to_link, (-moment[0], -moment[1], -moment[2]))
