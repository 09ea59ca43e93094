"""Gazebo classic's world API (the /gazebo/* services of gazebo_ros), ROS-free: entity states and joint
configurations here, over the names of world.entities, the properties of world.properties and the loads of
world.loads.

Poses are a position and a ROS quaternion (x, y, z, w); everything is in SI units and plain Python types.
Properties are dicts keyed by the gazebo_msgs field names. Every logical failure raises WorldError, with a message
fit for a service's status_message, before anything in the world changes.
"""
from __future__ import annotations

from typing import Dict, Sequence, Tuple

from turtle_sim_ode.models.transforms import Transform, Vec3, compose, inverse, quat_rotate
from turtle_sim_ode.models.urdf import MAX_LENGTH
from turtle_sim_ode.physics import ode_constants as oc
from turtle_sim_ode.world.entities import SCOPE, Frame
from turtle_sim_ode.world.kinematics import add, conjugate, set_configuration, set_rigid_twist, sub
from turtle_sim_ode.world.loads import LoadControl
from turtle_sim_ode.world.properties import PropertyControl
from turtle_sim_ode.world.records import QuatXYZW
from turtle_sim_ode.world.values import MAX_SPEED, WorldError, finite, orientation, vec3

# position, orientation (x, y, z, w), linear velocity, angular velocity
EntityState = Tuple[Vec3, QuatXYZW, Vec3, Vec3]


class WorldControl(PropertyControl, LoadControl):
    """Gazebo's world services over ``models``; mixed into Simulation, which owns the models
    and calls ``apply_loads`` before each physics step while ``loads`` is not empty."""

    # --- states -----------------------------------------------------------------------------
    @staticmethod
    def _relative(pose: Transform, linear: Vec3, angular: Vec3, frame: Frame) -> EntityState:
        """As gazebo_ros: pose in the frame; velocities minus the frame's, in the frame's axes."""
        if frame is not None:
            frame_pose, frame_linear, frame_angular = frame
            back = conjugate(frame_pose[1])
            pose = compose(inverse(frame_pose), pose)
            linear = quat_rotate(back, sub(linear, frame_linear))
            angular = quat_rotate(back, sub(angular, frame_angular))
        position, (w, x, y, z) = pose
        return position, (x, y, z, w), linear, angular

    def _absolute(
        self,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float],
        angular: Sequence[float],
        reference_frame: str,
        moving_frame: bool = True,
    ) -> Tuple[Transform, Vec3, Vec3]:
        """Validated world pose and twist from ones relative to ``reference_frame`` (the
        inverse of ``_relative``); the position must be within MAX_LENGTH of the world origin.
        ``moving_frame`` False: the twist is only turned into world axes, the frame's own velocity
        is not added (gazebo_ros's setModelState)."""
        pose: Transform = (vec3(position, "position", MAX_LENGTH), orientation(quaternion, "orientation"))
        velocity = vec3(linear, "linear velocity", MAX_SPEED)
        spin = vec3(angular, "angular velocity", MAX_SPEED)
        frame = self._frame(reference_frame)
        if frame is not None:
            frame_pose, frame_linear, frame_angular = frame
            pose = compose(frame_pose, pose)
            velocity = quat_rotate(frame_pose[1], velocity)
            spin = quat_rotate(frame_pose[1], spin)
            if moving_frame:
                velocity, spin = add(velocity, frame_linear), add(spin, frame_angular)
            vec3(pose[0], f"position relative to the world (from '{reference_frame}')", MAX_LENGTH)
        return pose, velocity, spin

    def get_model_state(self, name: str, reference_frame: str = "") -> EntityState:
        """The model frame's pose and the velocity of its canonical (root) link's origin."""
        model = self._model(name)
        frame = self._frame(reference_frame)
        linear, angular = model.link_twist(model.root_link)
        return self._relative(model.model_transform(), linear, angular, frame)

    def set_model_state(
        self,
        name: str,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float] = (0.0, 0.0, 0.0),
        angular: Sequence[float] = (0.0, 0.0, 0.0),
        reference_frame: str = "",
    ) -> None:
        """Teleport the model frame; every body then moves with the model as one rigid body
        (``linear`` is its root link origin's velocity). Joints keep their positions; a static
        model ignores the twist. Relative to a model or link, the pose is in that frame and the
        twist in its axes, without the frame's own velocity (gazebo_ros_api_plugin.cpp,
        setModelState: a model stepped relative to itself comes to rest at each step)."""
        model = self._model(name)
        pose, linear, angular = self._absolute(position, quaternion, linear, angular, reference_frame, False)
        model.set_transform(pose)
        set_rigid_twist(model.bodies, model.link_transform(model.root_link)[0], linear, angular)

    def get_link_state(self, name: str, reference_frame: str = "") -> EntityState:
        """The link frame's pose and its origin's velocity."""
        model, link = self._link(name)
        frame = self._frame(reference_frame)
        linear, angular = model.link_twist(link)
        return self._relative(model.link_transform(link), linear, angular, frame)

    def set_link_state(
        self,
        name: str,
        position: Sequence[float],
        quaternion: Sequence[float],
        linear: Sequence[float] = (0.0, 0.0, 0.0),
        angular: Sequence[float] = (0.0, 0.0, 0.0),
        reference_frame: str = "",
    ) -> None:
        """Move the body carrying the link (with every link fixed to it) so the link is at
        this pose and its origin at this velocity; joints pull the other bodies after it."""
        model, link, body = self._link_body(name)
        pose, linear, angular = self._absolute(position, quaternion, linear, angular, reference_frame)
        position, quaternion = compose(pose, inverse(model.links[link].offset))
        body.setPosition(position)
        body.setQuaternion(quaternion)
        set_rigid_twist([body], pose[0], linear, angular)

    def to_world(
        self, reference_frame: str, position: Sequence[float], quaternion: Sequence[float]
    ) -> Tuple[Vec3, QuatXYZW]:
        """A pose given in ``reference_frame`` (as SpawnModel's initial_pose) in the world."""
        (world_position, (w, x, y, z)), _, _ = self._absolute(
            position, quaternion, (0, 0, 0), (0, 0, 0), reference_frame
        )
        return world_position, (x, y, z, w)

    # --- joints ---------------------------------------------------------------------------
    def set_model_configuration(self, model_name: str, joint_names: Sequence[str], positions: Sequence[float]) -> None:
        """Put the named joints (plain or "model::joint") at these positions by moving the
        bodies below them; the root body stays, the model comes to rest, other joints keep
        their positions. Drive odometry does not count the wheels' jump."""
        model = self._model(model_name)
        if len(joint_names) != len(positions):
            raise WorldError(
                f"joint_names and positions have different lengths " f"({len(joint_names)} and {len(positions)})"
            )
        targets: Dict[str, float] = {}
        for name, position in zip(joint_names, positions):
            joint = name[len(model_name) + len(SCOPE) :] if name.startswith(model_name + SCOPE) else name
            if joint not in model.joints:
                raise WorldError(f"model '{model_name}' has no joint '{name}'")
            targets[joint] = finite(position, f"position of joint '{name}'", MAX_LENGTH)
            handle = model.joints[joint].joint
            if model.joints[joint].type != "continuous":
                low, high = handle.getParam(oc.PARAM_LO_STOP), handle.getParam(oc.PARAM_HI_STOP)
                if not low <= targets[joint] <= high:
                    raise WorldError(
                        f"position {position:g} of joint '{name}' is outside its limits [{low:g}, {high:g}]"
                    )
        if not targets:
            return
        set_configuration(model, targets)
        now = self.physics.sim_time
        for robot in self.robots.values():
            if robot.model is model and any(wheel.name in targets for wheel in robot.wheels):
                robot.wheels_moved(now)
