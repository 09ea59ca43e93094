"""A ROS graph over three hosts: network namespaces joined by veth links to a bridge, the master (roscore) in the first,
the simulator in the second, the circle exercise in the third, each with its own ROS_IP, as a user spreads the
graph over machines. Needs root (CAP_NET_ADMIN) and iproute2; skipped with the reason where namespaces cannot be
made. Every address is inside namespaces this test creates and removes."""
import json
import os
import shutil
import subprocess
import textwrap

import pytest
from conftest import ros_missing
from ros_run.processes import Processes

SUBNET = "10.213.77"
PREFIX = "tso%d" % (os.getpid() % 100000)
HOSTS = {"master": SUBNET + ".1", "sim": SUBNET + ".2", "drive": SUBNET + ".3"}
MASTER_URI = "http://%s:11311" % HOSTS["master"]

# Runs in the master's namespace: /odom must arrive from the simulator host and the robot must move under the
# commands of the node on the third host; node URIs show which host each node runs on.
CHECK = textwrap.dedent(
    """
    import json, math, sys
    import rosgraph, rospy
    from nav_msgs.msg import Odometry
    rospy.init_node("three_hosts_check")
    first = rospy.wait_for_message("/odom", Odometry, timeout=60).pose.pose.position
    moved = 0.0
    deadline = rospy.get_time() + 60
    while moved < 0.3 and rospy.get_time() < deadline:
        now = rospy.wait_for_message("/odom", Odometry, timeout=30).pose.pose.position
        moved = math.hypot(now.x - first.x, now.y - first.y)
    master = rosgraph.Master("/three_hosts_check")
    print(json.dumps({"moved": moved, "gazebo": master.lookupNode("/gazebo"), "circle": master.lookupNode("/circle")}))
    """
)


def _ip(*args):
    subprocess.run(["ip"] + list(args), check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)


def _can_make_namespaces():
    if shutil.which("ip") is None:
        return "iproute2 (ip) is not installed"
    if os.geteuid() != 0:
        return "network namespaces need root"
    probe = PREFIX + "probe"
    try:
        _ip("netns", "add", probe)
    except subprocess.CalledProcessError as error:
        return "cannot create a network namespace: %s" % error.stderr.decode().strip()
    _ip("netns", "del", probe)
    return None


@pytest.fixture
def three_hosts():
    """Namespaces <prefix>master/sim/drive, each with eth0 on a bridge in <prefix>hub; removed afterwards."""
    reason = _can_make_namespaces()
    if reason:
        pytest.skip(reason)
    hub = PREFIX + "hub"
    made = []
    try:
        _ip("netns", "add", hub)
        made.append(hub)
        _ip("-n", hub, "link", "add", "br0", "type", "bridge")
        _ip("-n", hub, "link", "set", "br0", "up")
        for index, (host, address) in enumerate(HOSTS.items()):
            namespace = PREFIX + host
            _ip("netns", "add", namespace)
            made.append(namespace)
            port = "p%d" % index
            _ip("link", "add", "%s%s" % (PREFIX, port), "type", "veth", "peer", "name", "%s%se" % (PREFIX, port))
            _ip("link", "set", "%s%s" % (PREFIX, port), "netns", hub)
            _ip("link", "set", "%s%se" % (PREFIX, port), "netns", namespace)
            _ip("-n", hub, "link", "set", "%s%s" % (PREFIX, port), "master", "br0", "up")
            _ip("-n", namespace, "link", "set", "%s%se" % (PREFIX, port), "name", "eth0")
            _ip("-n", namespace, "addr", "add", address + "/24", "dev", "eth0")
            _ip("-n", namespace, "link", "set", "eth0", "up")
            _ip("-n", namespace, "link", "set", "lo", "up")
        yield {host: PREFIX + host for host in HOSTS}
    finally:
        for namespace in reversed(made):
            subprocess.run(["ip", "netns", "del", namespace], stderr=subprocess.DEVNULL)


def host_command(namespaces, host, command):
    """``command`` run in ``host``'s namespace, and its environment: ROS_IP of that host, the master on the first."""
    env = dict(os.environ, ROS_IP=HOSTS[host], ROS_MASTER_URI=MASTER_URI)
    env.pop("ROS_HOSTNAME", None)  # ROS_HOSTNAME would win over ROS_IP
    return ["ip", "netns", "exec", namespaces[host]] + command, env


def test_master_simulator_and_driver_on_three_hosts(three_hosts, tmp_path):
    reason = ros_missing()
    if reason:
        pytest.skip(reason)
    # Each host's processes in a tagged process group of their own (scripts/lib/ros_run/processes.py), output to
    # <host>.log in tmp_path; all stopped on leaving, whatever roslaunch started included.
    with Processes(str(tmp_path)) as processes:
        for host, command in (
            ("master", ["roscore", "-p", "11311"]),
            ("sim", ["roslaunch", "--wait", "turtle_sim_ode", "turtlebot_world.launch"]),
            ("drive", ["rosrun", "my_first_rospkg", "circle", "_laps:=0.5"]),
        ):
            processes.start(*host_command(three_hosts, host, command), host + ".log")
        command, env = host_command(three_hosts, "master", ["/usr/bin/python3", "-c", CHECK])
        try:
            check = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=150)
            status, out, err = check.returncode, check.stdout, check.stderr
        except subprocess.TimeoutExpired as expired:  # run() has killed it
            status, out, err = "timed out", expired.stdout or b"", expired.stderr or b""
        detail = "check stderr:\n%s\nsim log tail:\n%s" % (
            err.decode()[-2000:],
            (tmp_path / "sim.log").read_text()[-2000:],
        )
        assert status == 0, detail
        result = json.loads(out.decode().strip().splitlines()[-1])
        assert result["moved"] >= 0.3, result
        assert HOSTS["sim"] in result["gazebo"], result
        assert HOSTS["drive"] in result["circle"], result
