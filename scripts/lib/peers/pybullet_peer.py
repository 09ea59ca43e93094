#!/usr/bin/env python3
"""The PyBullet side of scripts/bench_sim.py, run by the Python of the benchmark's venv (PyBullet cannot be imported
by /usr/bin/python3): the TurtleBot URDF in PyBullet with velocity motors on the wheels, stepped at a fixed dt.

Writes JSON to --out: best steps/s, the base's (x, y) track driving a circle (the caller fits the radius), the collision
shapes PyBullet made, and notes on where the model had to be adapted. stdout is not used: PyBullet prints to it.
"""
import argparse
import json
import os
import tempfile
import time
import xml.etree.ElementTree as ElementTree
from typing import Dict, List, Tuple

GRAVITY = -9.81
SOLVER_ITERATIONS = 50  # as our quickStep
SETTLE_STEPS = 500
SAMPLE_PERIOD_S = 0.01
SAMPLES_FROM_S = 1.0  # leave out the start (the robot accelerates onto the circle)
# PyBullet gives a link without <inertial> 1 kg and unit inertia; ODE (like Gazebo) merges it into its parent.
NEGLIGIBLE_INERTIAL = (
    '<inertial><mass value="1e-4"/><inertia ixx="1e-8" ixy="0" ixz="0" iyy="1e-8" iyz="0" izz="1e-8"/></inertial>'
)


def read_robot(urdf_text: str) -> Tuple[Dict[str, str], Dict[str, float], List[str]]:
    """(kobuki drive plugin parameters, mu1 of each link's <gazebo> surface, links without <inertial>)."""
    root = ElementTree.fromstring(urdf_text)
    drive: Dict[str, str] = {}
    for plugin in root.iter("plugin"):
        if plugin.get("filename", "").endswith("kobuki.so"):
            drive = {child.tag: (child.text or "").strip() for child in plugin}
    friction = {
        gazebo.get("reference", ""): float(gazebo.findtext("mu1", "1"))
        for gazebo in root.findall("gazebo")
        if gazebo.get("reference") and gazebo.find("mu1") is not None
    }
    massless = [link.get("name", "") for link in root.findall("link") if link.find("inertial") is None]
    return drive, friction, massless


def with_negligible_inertials(urdf_text: str, links: List[str]) -> str:
    root = ElementTree.fromstring(urdf_text)
    for link in root.findall("link"):
        if link.get("name") in links:
            link.append(ElementTree.fromstring(NEGLIGIBLE_INERTIAL))
    return ElementTree.tostring(root, encoding="unicode")


class TurtleBotWorld:
    """A ground plane and the TurtleBot in a fresh PyBullet world, wheels driven by velocity motors."""

    def __init__(self, pybullet, urdf_path: str, time_step: float, friction: Dict[str, float]) -> None:
        self.p = pybullet
        p = pybullet
        p.resetSimulation()
        p.setGravity(0, 0, GRAVITY)
        p.setTimeStep(time_step)
        p.setPhysicsEngineParameter(numSolverIterations=SOLVER_ITERATIONS)
        ground = p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE))
        # Bullet multiplies the two frictions: 1 on the ground gives the wheel's own mu, as ODE's min() with ours.
        p.changeDynamics(ground, -1, lateralFriction=1.0)
        # Implicit cylinders: by default PyBullet turns URDF cylinders into convex meshes.
        flags = p.URDF_USE_INERTIA_FROM_FILE | p.URDF_USE_IMPLICIT_CYLINDER
        self.robot = p.loadURDF(urdf_path, [0, 0, 0], flags=flags)
        self.link_index = {p.getBodyInfo(self.robot)[0].decode(): -1}
        self.joint_index = {}
        for index in range(p.getNumJoints(self.robot)):
            info = p.getJointInfo(self.robot, index)
            self.joint_index[info[1].decode()] = index
            self.link_index[info[12].decode()] = index
        for link, mu in friction.items():
            p.changeDynamics(self.robot, self.link_index[link], lateralFriction=mu)

    def drive(self, joints: Tuple[str, str], speeds: Tuple[float, float], torque: float) -> None:
        for joint, speed in zip(joints, speeds):
            self.p.setJointMotorControl2(
                self.robot, self.joint_index[joint], self.p.VELOCITY_CONTROL, targetVelocity=speed, force=torque
            )

    def shapes(self) -> Dict[str, str]:
        names = {
            self.p.GEOM_SPHERE: "sphere",
            self.p.GEOM_BOX: "box",
            self.p.GEOM_CYLINDER: "cylinder",
            self.p.GEOM_MESH: "mesh",
            self.p.GEOM_CAPSULE: "capsule",
        }
        found = {}
        for link, index in self.link_index.items():
            for shape in self.p.getCollisionShapeData(self.robot, index):
                found[link] = names.get(shape[2], str(shape[2]))
        return found


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--urdf", required=True)
    parser.add_argument("--time-step", type=float, required=True)
    parser.add_argument("--steps", type=int, required=True, help="steps per timed repeat")
    parser.add_argument("--repeats", type=int, required=True)
    parser.add_argument("--circle-seconds", type=float, required=True)
    parser.add_argument("--linear", type=float, required=True)
    parser.add_argument("--angular", type=float, required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()

    from importlib.metadata import version

    import pybullet

    with open(args.urdf) as urdf_file:
        urdf_text = urdf_file.read()
    drive, friction, massless = read_robot(urdf_text)
    joints = (drive["left_wheel_joint_name"], drive["right_wheel_joint_name"])
    radius = float(drive["wheel_diameter"]) / 2
    half_track = float(drive["wheel_separation"]) / 2
    torque = float(drive["torque"])
    speeds = (
        (args.linear - args.angular * half_track) / radius,
        (args.linear + args.angular * half_track) / radius,
    )
    with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as patched:
        patched.write(with_negligible_inertials(urdf_text, massless))
    pybullet.connect(pybullet.DIRECT)
    try:
        world = TurtleBotWorld(pybullet, patched.name, args.time_step, friction)
        world.drive(joints, speeds, torque)
        for _ in range(SETTLE_STEPS):
            pybullet.stepSimulation()
        best = float("inf")
        for _ in range(args.repeats):
            start = time.perf_counter()
            for _ in range(args.steps):
                pybullet.stepSimulation()
            best = min(best, time.perf_counter() - start)
        contacts = len(pybullet.getContactPoints(world.robot))
        shapes = world.shapes()

        world = TurtleBotWorld(pybullet, patched.name, args.time_step, friction)
        world.drive(joints, speeds, torque)
        sample_every = max(1, round(SAMPLE_PERIOD_S / args.time_step))
        track = []
        for step in range(1, round(args.circle_seconds / args.time_step) + 1):
            pybullet.stepSimulation()
            if step % sample_every == 0 and step * args.time_step >= SAMPLES_FROM_S:
                track.append(pybullet.getBasePositionAndOrientation(world.robot)[0][:2])
    finally:
        pybullet.disconnect()
        os.unlink(patched.name)
    result = {
        "version": version("pybullet"),
        "steps_per_s": args.steps / best,
        "contacts_per_step": contacts,
        "collision_shapes": shapes,
        "track_xy": track,
        "notes": [
            "links without <inertial> (%s) given 1e-4 kg: PyBullet would give each 1 kg" % ", ".join(massless),
            "cylinders loaded as implicit cylinders (URDF_USE_IMPLICIT_CYLINDER); PyBullet's default is a convex mesh",
            "friction from the URDF's <gazebo> mu1 tags set with changeDynamics (PyBullet ignores <gazebo>)",
            "fixed links kept as links (URDF_MERGE_FIXED_LINKS drops the merged links' inertial origins)",
        ],
    }
    with open(args.out, "w") as out:
        json.dump(result, out)


if __name__ == "__main__":
    main()
