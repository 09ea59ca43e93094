"""What the rostests that call the simulator's /gazebo services share: the services and their gazebo_msgs types,
proxies for them, the test models, and poses."""
import os

import rospy
from gazebo_msgs import srv as gz
from geometry_msgs.msg import Point, Pose, Quaternion
from std_srvs.srv import Empty

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "models")

# gazebo_ros's service names under /gazebo/ and their types.
GAZEBO_SERVICES = {
    "spawn_urdf_model": gz.SpawnModel,
    "spawn_sdf_model": gz.SpawnModel,
    "delete_model": gz.DeleteModel,
    "get_model_state": gz.GetModelState,
    "set_model_state": gz.SetModelState,
    "get_model_properties": gz.GetModelProperties,
    "get_world_properties": gz.GetWorldProperties,
    "get_link_state": gz.GetLinkState,
    "set_link_state": gz.SetLinkState,
    "get_link_properties": gz.GetLinkProperties,
    "set_link_properties": gz.SetLinkProperties,
    "get_joint_properties": gz.GetJointProperties,
    "set_joint_properties": gz.SetJointProperties,
    "get_physics_properties": gz.GetPhysicsProperties,
    "set_physics_properties": gz.SetPhysicsProperties,
    "set_model_configuration": gz.SetModelConfiguration,
    "apply_body_wrench": gz.ApplyBodyWrench,
    "clear_body_wrenches": gz.BodyRequest,
    "apply_joint_effort": gz.ApplyJointEffort,
    "clear_joint_forces": gz.JointRequest,
    "delete_light": gz.DeleteLight,
    "get_light_properties": gz.GetLightProperties,
    "set_light_properties": gz.SetLightProperties,
    "pause_physics": Empty,
    "unpause_physics": Empty,
    "reset_world": Empty,
    "reset_simulation": Empty,
}


def connect_gazebo_services(target, timeout=60):
    """Wait for every /gazebo service and set a proxy for each on ``target`` (a test class), named as the service."""
    for name, srv_type in GAZEBO_SERVICES.items():
        rospy.wait_for_service("/gazebo/" + name, timeout=timeout)
        setattr(target, name, staticmethod(rospy.ServiceProxy("/gazebo/" + name, srv_type)))


def model_text(name):
    with open(os.path.join(MODELS, name)) as model_file:
        return model_file.read()


def pose(x=0.0, y=0.0, z=0.0, qx=0.0, qy=0.0, qz=0.0, qw=1.0):
    return Pose(Point(x, y, z), Quaternion(qx, qy, qz, qw))
