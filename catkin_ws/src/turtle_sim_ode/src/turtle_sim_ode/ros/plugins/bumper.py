"""gazebo_ros_bumper's topic (sensors.plugins.bumper): gazebo_msgs/ContactsState of a link's collisions."""
from __future__ import annotations

from typing import Dict, List, Tuple

import ode
from gazebo_msgs.msg import ContactsState, ContactState
from geometry_msgs.msg import Point, Vector3, Wrench
import rospy

from turtle_sim_ode.models.built import BuiltModel
from turtle_sim_ode.physics.world import PhysicsWorld
from turtle_sim_ode.ros.periodic import ModelContext, Periodic, plugin_topic, publisher
from turtle_sim_ode.ros.plugin_topics import own_tf_prefix, period, resolve_frame
from turtle_sim_ode.ros.wire import heard, release
from turtle_sim_ode.sensors.plugins.bumper import ContactConfig
from turtle_sim_ode.world.simulation import Simulation


class ContactsPublisher(Periodic):
    """libgazebo_ros_bumper.so: gazebo_msgs/ContactsState of a link's collisions during the last step, one
    ContactState per touching pair with Gazebo's scoped collision names. Contact forces are not measured:
    wrenches are zero."""

    # The ground plane model's collision; the model is named ground_plane unless the world names it otherwise.
    GROUND = "%s::link::collision"

    def __init__(self, sim: Simulation, model: BuiltModel, config: ContactConfig, namespace: str) -> None:
        super().__init__(period(config.update_rate))
        self._pub = publisher(plugin_topic(namespace, config.topic), ContactsState, 1)
        self._sim = sim
        self._physics: PhysicsWorld = sim.physics
        self._watch = self._physics.watch_contacts(model.geoms.get(config.link, []))
        # gazebo_ros_bumper.cpp, Load: frameName through tf::resolve with the namespace's tf_prefix
        self._frame = resolve_frame(own_tf_prefix(namespace), config.frame)
        self._names: Dict[ode.GeomObject, str] = {}

    def _name(self, geom: ode.GeomObject) -> str:
        if geom is self._physics.ground:
            owners = (model.name for model in self._sim.models.values() if geom in model.geoms.get("link", ()))
            return self.GROUND % next(owners, "ground_plane")
        if geom not in self._names:  # a model spawned since: name every geom again
            self._names = {
                g: "%s::%s::%s_collision%s" % (model.name, link, link, "_%d" % i if i else "")
                for model in self._sim.models.values()
                for link, geoms in model.geoms.items()
                for i, g in enumerate(geoms)
            }
        return self._names.get(geom, "unknown")

    def publish(self, stamp: rospy.Time, now: float) -> None:
        if not heard(self._pub):
            return
        pairs: Dict[Tuple[ode.GeomObject, ode.GeomObject], ContactState] = {}
        for contact in self._watch.contacts:
            state = pairs.get((contact.geom, contact.other))
            if state is None:
                state = pairs[(contact.geom, contact.other)] = ContactState(
                    collision1_name=self._name(contact.geom), collision2_name=self._name(contact.other)
                )
                state.info = "%s touches %s" % (state.collision1_name, state.collision2_name)
            state.contact_positions.append(Point(*contact.position))
            state.contact_normals.append(Vector3(*contact.normal))
            state.depths.append(contact.depth)
            state.wrenches.append(Wrench())
        message = ContactsState(states=list(pairs.values()))
        message.header.stamp = stamp
        message.header.frame_id = self._frame
        self._pub.publish(message)

    def close(self) -> None:
        self._physics.unwatch_contacts(self._watch)
        release(self._pub)


def interfaces(context: ModelContext, config: ContactConfig) -> List[Periodic]:
    return [ContactsPublisher(context.sim, context.model, config, context.namespace)]
