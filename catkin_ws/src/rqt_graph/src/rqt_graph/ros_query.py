"""The ROS side: a SystemState from the master's getSystemState and every node's getBusInfo.

Each node gets ``timeout`` seconds to answer (the real graph code allows 1 s, rosgraph/impl/graph.py
Graph._node_refresh_businfo); one that does not is marked dead. Nodes are asked in parallel, so a snapshot takes
about one time-out however many nodes hang.
"""
from __future__ import annotations

import concurrent.futures
import http.client
import xmlrpc.client
from typing import Dict, List, Optional

import rosgraph

from rqt_graph.graph_model import Connection, SystemState

NODE_TIMEOUT = 1.0  # s
PARALLEL_QUERIES = 8


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float):
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host) -> http.client.HTTPConnection:
        connection = super().make_connection(host)
        connection.timeout = self._timeout
        return connection


def bus_info(uri: str, caller_id: str, timeout: float) -> Optional[list]:
    """The node's getBusInfo list, or None if it does not answer in time (or answers with a failure)."""
    try:
        code, _message, info = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout)).getBusInfo(
            caller_id
        )
    except Exception:  # refused, timed out, garbage: all mean the node is not there for us
        return None
    return info if code == 1 else None


def connections_from_bus_info(info: list, uri_to_node: Dict[str, str]) -> List[Connection]:
    """[connectionId, destinationId, direction, transport, topic, connected?, ...] rows into Connections; the
    destination is a publisher's XML-RPC URI on an inbound row, a subscriber's name on an outbound one."""
    connections = []
    for row in info:
        if len(row) < 5:  # malformed row (rosgraph skips these too)
            continue
        destination, direction, topic = str(row[1]), str(row[2]), str(row[4])
        connected = bool(row[5]) if len(row) > 5 else True
        peer = uri_to_node.get(destination, "") if destination.startswith("http") else destination
        connections.append(Connection(peer, direction, topic, connected))
    return connections


def query_system_state(caller_id: str, master_uri: Optional[str] = None, timeout: float = NODE_TIMEOUT) -> SystemState:
    """A snapshot of the graph; raises if the master itself cannot be reached."""
    master = rosgraph.Master(caller_id, master_uri=master_uri)
    publishers, subscribers, services = master.getSystemState()
    state = SystemState(
        publishers={topic: list(nodes) for topic, nodes in publishers},
        subscribers={topic: list(nodes) for topic, nodes in subscribers},
    )
    for _name, nodes in publishers + subscribers + services:
        state.nodes.update(nodes)

    # The master's proxy is one HTTP connection, not to be shared between threads: look the nodes up in turn (the
    # master answers at once); only the nodes, which may hang, are asked in parallel, each on a connection of its own.
    uris = {node: _lookup(master, node) for node in sorted(state.nodes)}
    uri_to_node = {uri: node for node, uri in uris.items() if uri}
    with concurrent.futures.ThreadPoolExecutor(PARALLEL_QUERIES) as pool:
        infos = pool.map(lambda node: uris[node] and bus_info(uris[node], caller_id, timeout), sorted(state.nodes))
        for node, info in zip(sorted(state.nodes), infos):
            state.connections[node] = None if info is None else connections_from_bus_info(info, uri_to_node)
    return state


def _lookup(master: rosgraph.Master, node: str) -> Optional[str]:
    try:
        return master.lookupNode(node)
    except Exception:  # unregistered meanwhile
        return None
