"""The computation graph from a snapshot of the master and the nodes' bus info, ROS-free.

Behaviour follows the real rqt_graph (ros-visualization/rqt_graph, src/rqt_graph/dotcode.py,
RosGraphDotcodeGenerator.generate_dotgraph): three modes, comma-separated name filters where ``-`` excludes, a
"Debug" filter on common debugging names, "Dead sinks" (topics nobody subscribes to) and "Leaf topics" (topics with
one connection only) hidden in the node/topic modes.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Dict, List, NamedTuple, Optional, Set, Tuple

NODES_ONLY = "node_node"
NODES_TOPICS_ACTIVE = "node_topic"
NODES_TOPICS_ALL = "node_topic_all"
MODES = (
    (NODES_ONLY, "Nodes only"),
    (NODES_TOPICS_ACTIVE, "Nodes/Topics (active)"),
    (NODES_TOPICS_ALL, "Nodes/Topics (all)"),
)
# A node or topic whose name contains one of these is a debugging aid (dotcode.py QUIET_NAMES, _quiet_filter).
DEBUG_NAMES = (
    "/diag_agg",
    "/runtime_logger",
    "/pr2_dashboard",
    "/rviz",
    "/rosout",
    "/cpu_monitor",
    "/monitor",
    "/hd_monitor",
    "/rxloggerlevel",
    "/clock",
    "/rqt",
    "/statistics",
)
# Edge labels (topics) hidden by "Debug" in the nodes-only mode (dotcode.py quiet_filter_topic_edge).
DEBUG_TOPICS = ("/time", "/clock", "/rosout", "/statistics")
PLAIN_NAME = re.compile(r"^[a-zA-Z0-9_/]+$")


class Connection(NamedTuple):
    """One live connection in a node's getBusInfo: ``direction`` is "o" (the node publishes to ``peer``), "i"
    (it subscribes from ``peer``) or "b"; ``peer`` is the other node's name, "" when unknown."""

    peer: str
    direction: str
    topic: str
    connected: bool = True


@dataclass
class SystemState:
    """The master's getSystemState plus each node's connections (None: the node did not answer in time)."""

    publishers: Dict[str, List[str]] = field(default_factory=dict)  # topic -> node names
    subscribers: Dict[str, List[str]] = field(default_factory=dict)
    nodes: Set[str] = field(default_factory=set)
    connections: Dict[str, Optional[List[Connection]]] = field(default_factory=dict)

    def is_dead(self, node: str) -> bool:
        return node in self.connections and self.connections[node] is None


@dataclass
class GraphOptions:
    mode: str = NODES_ONLY
    node_filter: str = "/"
    topic_filter: str = "/"
    hide_debug: bool = True
    hide_dead_sinks: bool = True
    hide_leaf_topics: bool = True
    hide_unreachable: bool = False  # the real one hides them by default; the tutorials want dead nodes seen


class Edge(NamedTuple):
    start: str  # vertex ids: node_id(name) or topic_id(name)
    end: str
    label: str = ""


def node_id(name: str) -> str:
    return "n_" + name


def topic_id(name: str) -> str:
    return "t_" + name


def vertex_name(vertex: str) -> str:
    return vertex[2:]


def is_topic(vertex: str) -> bool:
    return vertex.startswith("t_")


@dataclass
class Graph:
    nodes: Dict[str, bool] = field(default_factory=dict)  # node name -> alive
    topics: Set[str] = field(default_factory=set)
    edges: List[Edge] = field(default_factory=list)

    def vertices(self) -> List[str]:
        return sorted(node_id(n) for n in self.nodes) + sorted(topic_id(t) for t in self.topics)


def split_filter(text: str) -> Tuple[List[str], List[str]]:
    """(includes, excludes) of a comma list; "-name" excludes; nothing (or "/") includes everything."""
    includes, excludes = [], []
    for item in (part.strip() for part in text.split(",")):
        if item.startswith("-"):
            excludes.append(item[1:])
        else:
            includes.append(item)
    if includes in ([], ["/"], [""]):
        includes = [".*"]
    return includes, [e for e in excludes if e]


def matches_any(name: str, patterns: List[str]) -> bool:
    """A plain name matches itself only; anything else is a regular expression matched at the name's start."""
    for pattern in patterns:
        if name == pattern:
            return True
        if not PLAIN_NAME.match(pattern):
            try:
                if re.match(pattern, name):
                    return True
            except re.error:
                continue
    return False


def _passes(name: str, text: str) -> bool:
    includes, excludes = split_filter(text)
    return matches_any(name, includes) and not matches_any(name, excludes)


def _is_debug(name: str) -> bool:
    return any(quiet in name for quiet in DEBUG_NAMES)


def _directed(node: str, connection: Connection, other: str, label: str = "") -> List[Edge]:
    edges = []
    if connection.direction in ("o", "b"):
        edges.append(Edge(node, other, label))
    if connection.direction in ("i", "b"):
        edges.append(Edge(other, node, label))
    return edges


def _raw_edges(state: SystemState, mode: str) -> Tuple[Set[Edge], Set[str]]:
    """Every edge of the mode before filtering, and the topics it shows."""
    edges: Set[Edge] = set()
    topics: Set[str] = set()
    if mode == NODES_TOPICS_ALL:
        for topic, publishers in state.publishers.items():
            edges.update(Edge(node_id(n), topic_id(topic)) for n in publishers)
            topics.add(topic)
        for topic, subscribers in state.subscribers.items():
            edges.update(Edge(topic_id(topic), node_id(n)) for n in subscribers)
            topics.add(topic)
        return edges, topics
    for node, connections in state.connections.items():
        for connection in connections or ():
            if not connection.connected:
                continue
            if mode == NODES_ONLY:
                if connection.peer:
                    edges.update(_directed(node_id(node), connection, node_id(connection.peer), connection.topic))
            else:
                edges.update(_directed(node_id(node), connection, topic_id(connection.topic)))
                topics.add(connection.topic)
    return edges, topics


def _drop_topics(topics: Set[str], edges: List[Edge], options: GraphOptions) -> Set[str]:
    """Topics without edges always go; dead sinks and leaf topics as the options say."""
    kept = set()
    for topic in topics:
        vertex = topic_id(topic)
        outgoing = sum(1 for e in edges if e.start == vertex)
        incoming = sum(1 for e in edges if e.end == vertex)
        if outgoing + incoming == 0:
            continue
        if options.hide_dead_sinks and outgoing == 0:
            continue
        if options.hide_leaf_topics and outgoing + incoming < 2:
            continue
        kept.add(topic)
    return kept


def build_graph(state: SystemState, options: GraphOptions) -> Graph:
    """The graph the options ask for; edges whose ends were filtered out go with them."""
    nodes = {
        name: not state.is_dead(name)
        for name in state.nodes
        if _passes(name, options.node_filter)
        and not (options.hide_debug and _is_debug(name))
        and not (options.hide_unreachable and state.is_dead(name))
    }
    raw_edges, raw_topics = _raw_edges(state, options.mode)
    if options.mode == NODES_ONLY:
        topics: Set[str] = set()
        edges = [
            e
            for e in raw_edges
            if _passes(e.label, options.topic_filter) and not (options.hide_debug and e.label in DEBUG_TOPICS)
        ]
    else:
        topics = {
            t for t in raw_topics if _passes(t, options.topic_filter) and not (options.hide_debug and _is_debug(t))
        }
        edges = list(raw_edges)
    vertices = {node_id(n) for n in nodes} | {topic_id(t) for t in topics}
    edges = [e for e in edges if e.start in vertices and e.end in vertices]
    if options.mode != NODES_ONLY:
        topics = _drop_topics(topics, edges, options)
        vertices = {node_id(n) for n in nodes} | {topic_id(t) for t in topics}
        edges = [e for e in edges if e.start in vertices and e.end in vertices]
    return Graph(nodes=nodes, topics=topics, edges=sorted(edges))


def namespace_of(name: str) -> str:
    """ "/a/b/c" -> "/a/b"; a name at the root -> "/"."""
    head = name.rstrip("/").rpartition("/")[0]
    return head or "/"
