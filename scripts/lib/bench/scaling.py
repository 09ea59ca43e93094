#!/usr/bin/env python3
"""Section 9 of the benchmark (scripts/bench_sim.py), issue #33: where the work grows with the model. The node's
per-step loop (SimulatorNode._advance: a physics step, then every plugin interface that fell due) runs in this
process with the node's own plugin adapters (ros.plugins.model_interfaces) and nobody subscribed, so no master is
needed; each case is measured in turns with its baseline, and reported as a ratio to it:

- 300 IMUs (libgazebo_ros_imu_sensor.so, update_rate 0: every step) on a TurtleBot's base_link, against the bare
  TurtleBot: the share of its real-time factor kept, and whether it keeps real time (RTF >= 1) in real-time mode;
- a 1000-link chain of continuous joints (falling freely, high above the ground: its joints alone), against real
  time, and against its ODE world stepped by the solver alone (``OdeAlone``: the floor of any simulator on ODE with
  Gazebo's solver settings, quickStep at 50 iterations).

``scaling_cost`` returns a dict for bench_sim's JSON; run alone (``python3 -m bench.scaling``
in scripts/lib; ``--quick`` for a shorter run) it prints the table.
"""
from __future__ import annotations

import argparse
import math
import multiprocessing
import os
import sys
import traceback
from typing import Any, Callable, Dict, List, Optional, Sequence

from bench.camera import best_seconds
from bench.plan import MODEL, PACKAGE, URDF_PATH, BenchError

IMUS = 300
CHAIN_LINKS = 1000
INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def imu_block(count: int, link: str) -> str:
    """``count`` IMU sensors on ``link`` at update_rate 0, each on a topic of its own."""
    sensors = "".join(
        '<sensor type="imu" name="imu%d"><update_rate>0</update_rate><plugin name="imu%d" '
        'filename="libgazebo_ros_imu_sensor.so"><topicName>imu%d</topicName></plugin></sensor>' % (i, i, i)
        for i in range(count)
    )
    return '<gazebo reference="%s">%s</gazebo></robot>' % (link, sensors)


def chain_urdf(links: int) -> str:
    """A chain of 0.1 m boxes joined end to end by continuous joints."""
    parts = [
        '<link name="l%d">%s<collision><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry>'
        "</collision></link>" % (i, INERTIAL)
        for i in range(links)
    ]
    parts += [
        '<joint name="j%d" type="continuous"><parent link="l%d"/><child link="l%d"/><origin xyz="0 0 0.1"/>'
        '<axis xyz="0 1 0"/></joint>' % (i, i - 1, i)
        for i in range(1, links)
    ]
    return '<robot name="chain">%s</robot>' % "".join(parts)


class NodeLoop:
    """SimulatorNode._advance without a master: step, then publish_due of every interface once one falls due."""

    def __init__(self, sim: Any) -> None:
        import rospy

        from turtle_sim_ode.ros.periodic import sim_stamp
        from turtle_sim_ode.ros.plugins import model_interfaces
        from turtle_sim_ode.ros.settings import SimulatorSettings

        rospy.has_param = lambda key: False  # no parameter server: no tf_prefix
        self._stamp = sim_stamp
        self.sim = sim
        settings = SimulatorSettings()
        self.interfaces = [i for name in sim.models for i in model_interfaces(name, sim, settings, None, "")]
        for interface in self.interfaces:
            interface.restart(sim.sim_time)
        self._next_due = self._earliest()

    def _earliest(self) -> float:
        return min((interface.next_due for interface in self.interfaces), default=math.inf)

    def run(self, steps: int) -> None:
        sim = self.sim
        for _ in range(steps):
            sim.step()
            now = sim.sim_time
            if now >= self._next_due - 1e-9:
                stamp = self._stamp(now)
                for interface in self.interfaces:
                    interface.publish_due(now, stamp)
                self._next_due = self._earliest()


class OdeAlone:
    """A simulation's ODE world stepped by its solver alone: no collision, no turn counting, no plugins."""

    def __init__(self, sim: Any) -> None:
        self.sim = sim

    def run(self, steps: int) -> None:
        physics = self.sim.physics
        solve, time_step = physics.world.quickStep, physics.time_step
        for _ in range(steps):
            solve(time_step)


def turtlebot(extra: str = "") -> Any:
    from turtle_sim_ode.world.simulation import Simulation

    with open(URDF_PATH) as urdf_file:
        urdf = urdf_file.read()
    sim = Simulation()
    sim.spawn_urdf(MODEL, urdf.replace("</robot>", extra) if extra else urdf)
    sim.robots[MODEL].drive.set_command(0.5, 0.0, 0.5)
    sim.robots[MODEL].drive.params.cmd_timeout = 0.0
    return sim


def chain() -> Any:
    from turtle_sim_ode.world.simulation import Simulation

    sim = Simulation()
    sim.spawn_urdf("chain", chain_urdf(CHAIN_LINKS), (0.0, 0.0, 1000.0, 0.0, 0.0, 0.0))
    return sim


def rtfs(loops: Sequence[Any], steps: Sequence[int], repeats: int) -> List[float]:
    """Each loop's best real-time factor over ``repeats`` runs of its ``steps``, in turns."""
    works: List[Callable[[], None]] = [lambda loop=loop, n=n: loop.run(n) for loop, n in zip(loops, steps)]
    return [
        n * loop.sim.physics.time_step / seconds for loop, n, seconds in zip(loops, steps, best_seconds(works, repeats))
    ]


def scaling_cost(steps: int = 3000, repeats: int = 3) -> Dict[str, Any]:
    bare, imus, links = NodeLoop(turtlebot()), NodeLoop(turtlebot(imu_block(IMUS, "base_link"))), NodeLoop(chain())
    chain_steps = max(100, steps // 20)
    bare_rtf, imu_rtf, chain_rtf, ode_rtf = rtfs(
        [bare, imus, links, OdeAlone(chain())], [steps, steps, chain_steps, chain_steps], repeats
    )
    return {
        "time_step": bare.sim.physics.time_step,
        "imus": {
            "count": IMUS,
            "interfaces": len(imus.interfaces),
            "rtf_bare_turtlebot": bare_rtf,
            "rtf": imu_rtf,
            "rtf_share": imu_rtf / bare_rtf,
            "real_time_kept": min(1.0, imu_rtf),
        },
        "chain": {
            "links": CHAIN_LINKS,
            "rtf": chain_rtf,
            "real_time_kept": min(1.0, chain_rtf),
            "rtf_ode_alone": ode_rtf,
            "share_of_ode_alone": chain_rtf / ode_rtf,
        },
    }


def scaling_cost_apart(steps: int = 3000, repeats: int = 3) -> Dict[str, Any]:
    """scaling_cost in a forked child: the node's adapters make rospy publishers and NodeLoop patches rospy.has_param,
    which must not reach the ROS nodes bench_sim forks from this process afterwards (bench.probe; the viewer section
    found the master refusing it when they did)."""
    context = multiprocessing.get_context("fork")
    receive, send = context.Pipe(duplex=False)
    child = context.Process(target=_send_cost, args=(send, steps, repeats), daemon=True)
    child.start()
    send.close()
    try:
        kind, value = receive.recv()
    except EOFError:
        kind, value = "error", "the scaling child ended without an answer (exit %s)" % child.exitcode
    child.join()
    if kind == "error":
        raise BenchError(value)
    return value


def _send_cost(send: Any, steps: int, repeats: int) -> None:
    try:
        send.send(("value", scaling_cost(steps, repeats)))
    except Exception:  # noqa: BLE001 - whatever went wrong is the section's error, told to the parent
        send.send(("error", traceback.format_exc()))


def table(result: Dict[str, Any]) -> List[str]:
    imus, links = result["imus"], result["chain"]
    return [
        "%-44s RTF %7.2f" % ("bare TurtleBot, node loop, 1 ms", imus["rtf_bare_turtlebot"]),
        "%-44s RTF %7.2f  share %.2f  real time kept %.2f"
        % (
            "+ %d IMUs at update_rate 0 on base_link" % imus["count"],
            imus["rtf"],
            imus["rtf_share"],
            imus["real_time_kept"],
        ),
        "%-44s RTF %7.3f  real time kept %.2f"
        % ("%d-link chain of continuous joints" % links["links"], links["rtf"], links["real_time_kept"]),
        "%-44s RTF %7.3f  the chain keeps %.2f of it"
        % ("  its ODE world, quickStep alone (50 iters)", links["rtf_ode_alone"], links["share_of_ode_alone"]),
    ]


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="1 s of sim time per run, 2 repeats")
    args = parser.parse_args(argv)
    sys.path.insert(0, os.path.join(PACKAGE, "src"))
    print("\n".join(table(scaling_cost(1000, 2) if args.quick else scaling_cost())))
    return 0


if __name__ == "__main__":
    sys.exit(main())
