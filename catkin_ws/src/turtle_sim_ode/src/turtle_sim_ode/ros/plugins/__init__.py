"""The ROS side of the plugins a model carries: one adapter module per plugin (or family) that owns its topics, made
from the config its ROS-free module read (world.plugins, sensors.plugins). ``ADAPTERS`` maps a config's type to its
module's ``interfaces(context, config)``; adding a plugin is a module and a line here.

Each publisher keeps its own schedule in sim time; SimulatorNode calls publish_due() after every step. A model's
plugins of a kind in ``GROUPED`` are made together, so that many of them share one schedule and one reading."""
from __future__ import annotations

from typing import Callable, Dict, List, Optional, Tuple

from turtle_sim_ode.ros.periodic import Advertising, ModelContext, Periodic, TopicCheck
from turtle_sim_ode.ros.plugins import (
    block_laser,
    bumper,
    camera,
    diff_drive,
    elevator,
    f3d,
    force,
    ft_sensor,
    hector_gps,
    hector_imu,
    imu,
    joint_state_publisher,
    kobuki,
    laser,
    odometry_source,
    p3d,
    planar_move,
    range_finder,
    ros_control,
    skid_steer_drive,
    vacuum_gripper,
    tricycle_drive,
    velodyne,
)
from turtle_sim_ode.ros.settings import SimulatorSettings
from turtle_sim_ode.ros.wire import PackedPublisher, release
from turtle_sim_ode.sensors.plugins.block_laser import BlockLaserConfig
from turtle_sim_ode.sensors.plugins.bumper import ContactConfig
from turtle_sim_ode.sensors.plugins.camera import CameraConfig
from turtle_sim_ode.sensors.plugins.imu import ImuConfig
from turtle_sim_ode.sensors.plugins.laser import LaserConfig
from turtle_sim_ode.sensors.plugins.multicamera import MultiCameraConfig
from turtle_sim_ode.sensors.plugins.range_finder import RangeConfig
from turtle_sim_ode.sensors.plugins.velodyne import VelodyneConfig
from turtle_sim_ode.world.plugins import DriveConfig, GroundTruthConfig, JointStatesConfig
from turtle_sim_ode.world.plugins.elevator import ElevatorConfig
from turtle_sim_ode.world.plugins.f3d import F3dConfig
from turtle_sim_ode.world.plugins.force import ForceConfig
from turtle_sim_ode.world.plugins.ft_sensor import FtSensorConfig
from turtle_sim_ode.world.plugins.hector_gps import HectorGpsConfig
from turtle_sim_ode.world.plugins.hector_imu import HectorImuConfig
from turtle_sim_ode.world.plugins.kobuki import KobukiConfig
from turtle_sim_ode.world.plugins.odometry_source import OdometrySourceConfig
from turtle_sim_ode.world.plugins.planar_move import PlanarMoveConfig
from turtle_sim_ode.world.plugins.ros_control import RosControlPluginConfig
from turtle_sim_ode.world.plugins.skid_steer_drive import SkidSteerConfig
from turtle_sim_ode.world.plugins.vacuum_gripper import VacuumGripperConfig
from turtle_sim_ode.world.plugins.tricycle_drive import TricycleConfig
from turtle_sim_ode.world.simulation import Simulation

Adapter = Callable[[ModelContext, object], List[Periodic]]
ADAPTERS: Dict[type, Adapter] = {
    KobukiConfig: kobuki.interfaces,
    DriveConfig: diff_drive.interfaces,
    SkidSteerConfig: skid_steer_drive.interfaces,
    PlanarMoveConfig: planar_move.interfaces,
    TricycleConfig: tricycle_drive.interfaces,
    GroundTruthConfig: p3d.interfaces,
    OdometrySourceConfig: odometry_source.interfaces,
    JointStatesConfig: joint_state_publisher.interfaces,
    LaserConfig: laser.interfaces,
    ContactConfig: bumper.interfaces,
    CameraConfig: camera.interfaces,
    MultiCameraConfig: camera.multicamera_interfaces,
    VelodyneConfig: velodyne.interfaces,
    RangeConfig: range_finder.interfaces,
    BlockLaserConfig: block_laser.interfaces,
    HectorImuConfig: hector_imu.interfaces,
    HectorGpsConfig: hector_gps.interfaces,
    ForceConfig: force.interfaces,
    F3dConfig: f3d.interfaces,
    FtSensorConfig: ft_sensor.interfaces,
    VacuumGripperConfig: vacuum_gripper.interfaces,
    RosControlPluginConfig: ros_control.interfaces,
    ElevatorConfig: elevator.interfaces,
}


# Plugin kinds whose ROS side is made for all of a model's plugins of the kind at once (contexts, configs).
GROUPED: Dict[type, Callable[[List[ModelContext], List[object]], List[Periodic]]] = {
    ImuConfig: imu.grouped_interfaces,  # type: ignore[dict-item]
}


def plugin_namespace(spawn_namespace: str, config: object) -> str:
    """A plugin's robot namespace: its own <robotNamespace> wherever the element exists (empty: the root), else the
    spawn request's robot_namespace, as gazebo_ros's GazeboRosApiPlugin::walkChildAddRobotNamespace adds that only
    to plugins without the element."""
    own = getattr(config, "robot_namespace", None)
    return spawn_namespace if own is None else own


def model_interfaces(
    name: str,
    sim: Simulation,
    settings: SimulatorSettings,
    tf_broadcaster: PackedPublisher,
    namespace: str,
    check_topic: Optional[TopicCheck] = None,
    pace_from_now: Callable[[], None] = lambda: None,
) -> List[Periodic]:
    """Every ROS publisher and subscriber the plugins of model `name` ask for (call under the world lock), each
    topic first shown to ``check_topic``, ``pace_from_now`` as ModelContext has it. All or nothing: if one fails,
    those opened so far are closed again."""
    interfaces: List[Periodic] = []
    Advertising.check, Advertising.opened = check_topic, []
    plugins = sim.plugins.get(name)
    try:
        grouped: Dict[type, Tuple[List[ModelContext], List[object]]] = {}
        for config in plugins.configs if plugins is not None else []:
            own_namespace = plugin_namespace(namespace, config)
            context = ModelContext(name, sim, settings, tf_broadcaster, own_namespace, pace_from_now)
            if type(config) in GROUPED:
                contexts, configs = grouped.setdefault(type(config), ([], []))
                contexts.append(context)
                configs.append(config)
            else:
                interfaces += ADAPTERS[type(config)](context, config)
        for kind, (contexts, configs) in grouped.items():
            interfaces += GROUPED[kind](contexts, configs)
    except BaseException:
        for interface in interfaces:
            interface.close()
        for handle in Advertising.opened:  # those of an interface that failed half-way
            release(handle)
        raise
    finally:
        Advertising.check, Advertising.opened = None, []
    return interfaces
