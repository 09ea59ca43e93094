"""DOT out, positions back: graphviz `dot` lays out what graph_model built."""
import pytest
from fake_state import turtlesim_session

from rqt_graph.dot_layout import lay_out, parse_plain, to_dot
from rqt_graph.graph_model import NODES_TOPICS_ACTIVE, GraphOptions, build_graph

# graphviz's plain format (https://graphviz.org/docs/outputs/plain/): inches, y upwards
PLAIN = """graph 1 4 2
node "n_/a" 1 1.5 1.2 0.5 /a ellipse solid black lightgrey
node "n_/b" 3 1.5 1 0.5 "/b x" ellipse solid red lightgrey
edge "n_/a" "n_/b" 4 1.6 1.5 2 1.5 2.2 1.5 2.5 1.5 /t 2 1.7 solid black
stop
"""


def test_parse_plain_turns_inches_into_points_with_y_down():
    layout = parse_plain(PLAIN)
    assert (layout.width, layout.height) == (288.0, 144.0)
    a, b = layout.vertices["n_/a"], layout.vertices["n_/b"]
    assert (a.x, a.y, a.height, a.label) == (72.0, 36.0, 36.0, "/a") and a.width == pytest.approx(86.4)
    assert b.label == "/b x" and b.name == "/b" and not b.is_topic
    (edge,) = layout.edges
    assert (edge.start, edge.end, edge.label) == ("n_/a", "n_/b", "/t")
    assert edge.points[0] == (1.6 * 72, 36.0) and len(edge.points) == 4
    assert edge.label_pos == (144.0, 72 * (2 - 1.7))


def test_dot_places_every_vertex_and_edge():
    graph = build_graph(turtlesim_session(), GraphOptions(mode=NODES_TOPICS_ACTIVE))
    layout = lay_out(graph)
    assert set(layout.vertices) == set(graph.vertices())
    assert [(e.start, e.end) for e in layout.edges] == [(e.start, e.end) for e in graph.edges]
    # left to right, as rqt_graph draws: publisher, topic, subscriber
    xs = [layout.vertices[v].x for v in ("n_/teleop_turtle", "t_/turtle1/cmd_vel", "n_/turtlesim")]
    assert xs == sorted(xs)


def test_dot_text_marks_dead_nodes_and_groups_namespaces():
    graph = build_graph(turtlesim_session(), GraphOptions(mode=NODES_TOPICS_ACTIVE))
    text = to_dot(graph, group_namespaces=True)
    assert '"n_/ghost" [color=red' in text
    assert "subgraph cluster_ns0" in text and 'label="/turtle1"' in text
    assert "cluster" not in to_dot(graph, group_namespaces=False)


def test_nodes_are_at_least_as_wide_as_the_view_draws_their_labels():
    graph = build_graph(turtlesim_session(), GraphOptions(mode=NODES_TOPICS_ACTIVE))
    wide = lambda label: 30.0 * len(label)  # noqa: E731 (a font far wider than graphviz's)
    layout = lay_out(graph, text_width=wide)
    for placed in layout.vertices.values():
        assert placed.width >= wide(placed.label), placed
