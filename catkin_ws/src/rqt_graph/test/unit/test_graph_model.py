"""Graph building from a fake master state. Expected behaviour from ros-visualization/rqt_graph
src/rqt_graph/dotcode.py (RosGraphDotcodeGenerator.generate_dotgraph, _split_filter_string, matches_any,
_quiet_filter, quiet_filter_topic_edge, _filter_leaf_topics) and rosgraph/impl/graph.py (edge_args)."""
import pytest
from fake_state import turtlesim_session

from rqt_graph.graph_model import (
    NODES_ONLY,
    NODES_TOPICS_ACTIVE,
    NODES_TOPICS_ALL,
    Edge,
    GraphOptions,
    build_graph,
    matches_any,
    namespace_of,
    node_id,
    split_filter,
    topic_id,
)


def graph(**options):
    return build_graph(turtlesim_session(), GraphOptions(**options))


def test_nodes_only_default_shows_the_tutorial_graph_with_topic_labels():
    result = graph()
    # Debug hides /rosout and /rqt*; the dead /ghost is drawn as dead, /listener has no live connection
    assert result.nodes == {"/turtlesim": True, "/teleop_turtle": True, "/ghost": False, "/listener": True}
    assert result.topics == set()
    assert result.edges == [Edge(node_id("/teleop_turtle"), node_id("/turtlesim"), "/turtle1/cmd_vel")]


def test_debug_off_shows_rosout_and_the_viewer():
    result = graph(hide_debug=False)
    assert {"/rosout", "/rqt_gui_py_node_42"} <= set(result.nodes)
    assert Edge(node_id("/turtlesim"), node_id("/rosout"), "/rosout") in result.edges
    assert Edge(node_id("/turtlesim"), node_id("/rqt_gui_py_node_42"), "/turtle1/pose") in result.edges


def test_active_topics_come_from_live_connections_only():
    result = graph(mode=NODES_TOPICS_ACTIVE)
    assert result.topics == {"/turtle1/cmd_vel"}
    assert result.edges == [
        Edge(node_id("/teleop_turtle"), topic_id("/turtle1/cmd_vel")),
        Edge(topic_id("/turtle1/cmd_vel"), node_id("/turtlesim")),
    ]


def test_all_topics_come_from_the_master_even_without_connection():
    result = graph(mode=NODES_TOPICS_ALL)
    # /chatter has a publisher (dead) and a subscriber that never connected: still a topic of the graph
    assert result.topics == {"/turtle1/cmd_vel", "/chatter"}
    assert Edge(topic_id("/chatter"), node_id("/listener")) in result.edges


def test_dead_sinks_and_leaf_topics():
    # /turtle1/color_sensor: published, nobody subscribes -> a dead sink (and a leaf)
    assert "/turtle1/color_sensor" not in graph(mode=NODES_TOPICS_ALL).topics
    shown = graph(mode=NODES_TOPICS_ALL, hide_dead_sinks=False, hide_leaf_topics=False)
    assert "/turtle1/color_sensor" in shown.topics
    # a leaf topic has one connection only: hiding leaves also hides dead sinks (rqt_graph's tooltip says so)
    assert "/turtle1/color_sensor" not in graph(mode=NODES_TOPICS_ALL, hide_dead_sinks=False).topics
    # /turtle1/pose with only the hidden viewer subscribed is a dead sink once Debug hides the viewer
    assert "/turtle1/pose" not in graph(mode=NODES_TOPICS_ALL).topics
    assert "/turtle1/pose" in graph(mode=NODES_TOPICS_ALL, hide_debug=False).topics


def test_unreachable_nodes_can_be_hidden():
    assert "/ghost" not in graph(hide_unreachable=True).nodes


@pytest.mark.parametrize(
    "text, shown",
    [
        ("/", {"/turtlesim", "/teleop_turtle", "/ghost", "/listener"}),
        ("", {"/turtlesim", "/teleop_turtle", "/ghost", "/listener"}),
        ("/turtlesim", {"/turtlesim"}),  # a plain name matches itself only
        ("/turtle.*", {"/turtlesim"}),
        ("/turtlesim,/teleop_turtle", {"/turtlesim", "/teleop_turtle"}),
        ("-/ghost", {"/turtlesim", "/teleop_turtle", "/listener"}),
        ("/.*, -/t.*", {"/ghost", "/listener"}),
    ],
)
def test_node_filter(text, shown):
    assert set(graph(node_filter=text).nodes) == shown


def test_topic_filter_on_edge_labels_and_topics():
    assert graph(topic_filter="-/turtle1/cmd_vel").edges == []
    assert graph(mode=NODES_TOPICS_ACTIVE, topic_filter="-/turtle1/.*").topics == set()


def test_edges_of_filtered_nodes_go_with_them():
    assert graph(node_filter="-/teleop_turtle").edges == []


def test_split_filter_and_matches():
    assert split_filter("/a, -/b ,/c") == (["/a", "/c"], ["/b"])
    assert split_filter("-/rqt.*") == ([".*"], ["/rqt.*"])
    assert matches_any("/rqt_gui_py_node_1", ["/rqt.*"])
    assert not matches_any("/turtlesim2", ["/turtlesim"])
    assert not matches_any("/x", ["[unbalanced"])  # a broken regular expression matches nothing


def test_namespace_of():
    assert namespace_of("/turtle1/cmd_vel") == "/turtle1"
    assert namespace_of("/turtlesim") == "/"
    assert namespace_of("/a/b/c") == "/a/b"
