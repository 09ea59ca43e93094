"""ros_query against XML-RPC servers of the test's own standing in for the master and the nodes: getBusInfo rows
become connections (row layout from ros_comm's rospy/impl/masterslave.py ROSHandler.getBusInfo and
rosgraph/impl/graph.py _node_refresh_businfo), and nodes that never answer are dead after one time-out, all of them
together, not one after another."""
import socket
import threading
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from workspace_testing.timing import assert_within, timed

from rqt_graph.graph_model import Connection
from rqt_graph.ros_query import connections_from_bus_info, query_system_state


def serve(functions):
    server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
    for name, function in functions.items():
        server.register_function(function, name)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server, "http://127.0.0.1:%d/" % server.server_address[1]


@pytest.fixture
def ros_graph():
    """A live /turtlesim and /teleop_turtle, and two nodes whose port accepts but never answers."""
    servers, silent = [], []
    uris = {}
    bus = {}
    for node in ("/turtlesim", "/teleop_turtle"):
        server, uris[node] = serve({"getBusInfo": lambda caller, node=node: [1, "bus info", bus[node]]})
        servers.append(server)
    for node in ("/hung_a", "/hung_b"):
        listener = socket.socket()
        listener.bind(("127.0.0.1", 0))
        listener.listen(5)  # connections complete in the backlog; nobody reads or answers
        silent.append(listener)
        uris[node] = "http://127.0.0.1:%d/" % listener.getsockname()[1]
    bus["/turtlesim"] = [[1, uris["/teleop_turtle"], "i", "TCPROS", "/turtle1/cmd_vel", True, "info"]]
    bus["/teleop_turtle"] = [[2, "/turtlesim", "o", "TCPROS", "/turtle1/cmd_vel", True, "info"]]
    publishers = [["/turtle1/cmd_vel", ["/teleop_turtle"]], ["/rosout", ["/hung_a", "/hung_b"]]]
    subscribers = [["/turtle1/cmd_vel", ["/turtlesim"]]]
    master, master_uri = serve(
        {
            "getSystemState": lambda caller: [1, "state", [publishers, subscribers, [["/gone/srv", ["/gone"]]]]],
            "lookupNode": lambda caller, node: [1, "", uris[node]] if node in uris else [-1, "unknown node", ""],
        }
    )
    servers.append(master)
    yield master_uri, publishers
    for server in servers:
        server.shutdown()
        server.server_close()
    for listener in silent:
        listener.close()


def test_snapshot_with_live_hung_and_unknown_nodes(ros_graph):
    master_uri, publishers = ros_graph
    state, took = timed(lambda: query_system_state("/test", master_uri=master_uri, timeout=0.5))
    assert state.nodes == {"/turtlesim", "/teleop_turtle", "/hung_a", "/hung_b", "/gone"}
    assert state.connections["/turtlesim"] == [Connection("/teleop_turtle", "i", "/turtle1/cmd_vel", True)]
    assert state.connections["/teleop_turtle"] == [Connection("/turtlesim", "o", "/turtle1/cmd_vel", True)]
    assert [node for node in sorted(state.nodes) if state.is_dead(node)] == ["/gone", "/hung_a", "/hung_b"]
    assert took >= 0.5  # the hung nodes were waited for
    publishers[1] = ["/rosout", ["/hung_a"]]
    _, took_for_one = timed(lambda: query_system_state("/test", master_uri=master_uri, timeout=0.5))
    assert_within(took, took_for_one, 1.5, "two hung nodes")  # waited for at the same time: one after another is 2 x


def test_bus_info_rows():
    uris = {"http://host:1/": "/talker"}
    rows = [
        [1, "http://host:1/", "i", "TCPROS", "/chatter", True, "x"],
        [2, "/listener", "o", "TCPROS", "/chatter", False, "x"],
        [3, "http://unknown:2/", "i", "TCPROS", "/a"],  # older nodes send no "connected"
        [4, "short"],  # malformed: skipped
    ]
    assert connections_from_bus_info(rows, uris) == [
        Connection("/talker", "i", "/chatter", True),
        Connection("/listener", "o", "/chatter", False),
        Connection("", "i", "/a", True),
    ]
