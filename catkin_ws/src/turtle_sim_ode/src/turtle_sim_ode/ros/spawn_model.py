"""`rosrun turtle_sim_ode spawn_model`: gazebo_ros's spawn_model, with its flags, against /gazebo services."""
from __future__ import annotations

import argparse
import math
import sys
from typing import List, Optional

import rospy
from gazebo_msgs.srv import DeleteModel, GetWorldProperties, SetModelConfiguration, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from std_srvs.srv import Empty


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> Quaternion:
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return Quaternion(
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    )


def parse_args(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="spawn_model", description="Spawn a model into the simulator " "(gazebo_ros spawn_model compatible)."
    )
    kind = parser.add_mutually_exclusive_group(required=True)
    kind.add_argument("-urdf", action="store_true", help="the model is URDF")
    kind.add_argument("-sdf", action="store_true", help="the model is SDF")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("-file", metavar="FILE", help="read the model from this file")
    source.add_argument("-param", metavar="PARAM", help="read the model from this ROS parameter")
    source.add_argument("-stdin", action="store_true", help="read the model from standard input")
    source.add_argument("-database", metavar="NAME", help="not supported: there is no model database")
    parser.add_argument("-model", required=True, metavar="NAME", help="name of the model to spawn")
    parser.add_argument("-reference_frame", default="", help="initial pose is relative to this model or link")
    parser.add_argument("-gazebo_namespace", default="/gazebo", help="namespace of the simulator's services")
    parser.add_argument("-robot_namespace", default=rospy.get_namespace(), help="namespace of the model's plugins")
    parser.add_argument("-unpause", action="store_true", help="unpause physics after spawning")
    parser.add_argument("-wait", metavar="MODEL", help="wait for this model to exist before spawning")
    parser.add_argument("-timeout", type=float, default=30.0, help="seconds to wait for the services (default 30)")
    for axis, help_text in (
        ("x", "m"),
        ("y", "m"),
        ("z", "m"),
        ("R", "roll, rad"),
        ("P", "pitch, rad"),
        ("Y", "yaw, rad"),
    ):
        parser.add_argument("-" + axis, type=float, default=0.0, help="initial pose: %s" % help_text)
    parser.add_argument(
        "-J",
        nargs=2,
        action="append",
        default=[],
        metavar=("JOINT", "POSITION"),
        help="initial joint position (repeatable)",
    )
    parser.add_argument(
        "-package_to_model",
        action="store_true",
        help="accepted; package:// mesh names are read from the ROS package path as they are",
    )
    parser.add_argument("-b", dest="bond", action="store_true", help="delete the model when this node exits")
    args = parser.parse_args(argv)
    for joint, position in args.J:
        try:
            float(position)
        except ValueError:
            parser.error("-J %s: position '%s' is not a number" % (joint, position))
    if args.database:
        parser.error("-database: there is no model database here; use -file or -param")
    return args


def read_model(args: argparse.Namespace) -> Optional[str]:
    if args.file:
        try:
            with open(args.file) as model_file:
                return model_file.read()
        except OSError as error:
            rospy.logfatal("cannot read -file %s: %s", args.file, error)
            return None
    if args.param:
        text = rospy.get_param(args.param, None)
        if not isinstance(text, str):
            rospy.logfatal("parameter %s holds no model text", rospy.resolve_name(args.param))
            return None
        return text
    return sys.stdin.read()


def main(argv: List[str]) -> int:
    rospy.init_node("spawn_model", anonymous=True)
    args = parse_args(argv)
    model_xml = read_model(args)
    if model_xml is None:
        return 1
    service = args.gazebo_namespace.rstrip("/") + "/"
    try:
        rospy.wait_for_service(service + "spawn_urdf_model", timeout=args.timeout)
    except rospy.ROSException:
        rospy.logfatal("no simulator: %sspawn_urdf_model did not come up within %g s", service, args.timeout)
        return 1
    if args.wait:
        world = rospy.ServiceProxy(service + "get_world_properties", GetWorldProperties)
        rospy.loginfo("waiting for model [%s]", args.wait)
        while not rospy.is_shutdown() and args.wait not in world().model_names:
            rospy.sleep(0.1)  # no event announces a spawn: poll the world
    pose = Pose(Point(args.x, args.y, args.z), quaternion_from_rpy(args.R, args.P, args.Y))
    spawn = rospy.ServiceProxy(service + ("spawn_urdf_model" if args.urdf else "spawn_sdf_model"), SpawnModel)
    spawned = []
    if args.bond:
        # Registered before spawning: a shutdown right after the spawn must still delete the model.
        delete = rospy.ServiceProxy(service + "delete_model", DeleteModel)
        rospy.on_shutdown(lambda: spawned and delete(args.model))
    result = spawn(args.model, model_xml, args.robot_namespace, pose, args.reference_frame)
    if not result.success:
        rospy.logfatal("spawn failed: %s", result.status_message)
        return 1
    spawned.append(args.model)
    rospy.loginfo(result.status_message)
    if args.J:
        configure = rospy.ServiceProxy(service + "set_model_configuration", SetModelConfiguration)
        configured = configure(args.model, "", [j for j, _ in args.J], [float(p) for _, p in args.J])
        if not configured.success:
            rospy.logerr("setting joint positions failed: %s", configured.status_message)
    if args.unpause:
        rospy.ServiceProxy(service + "unpause_physics", Empty)()
    if args.bond:
        rospy.spin()
    return 0
