"""Graph -> DOT (pydot) -> positions from graphviz `dot` (its "plain" output), ROS-free and Qt-free.

Nodes are ellipses, topics boxes, dead nodes red, as the real rqt_graph draws them (dotcode.py, _add_node and
_add_topic_node). With namespaces grouped, each namespace other than "/" is a cluster.
"""
from __future__ import annotations

import shlex
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Tuple

import pydot

from rqt_graph.graph_model import Graph, is_topic, namespace_of, node_id, topic_id, vertex_name

POINTS_PER_INCH = 72.0
FONT_SIZE = 12.0  # points; the view draws its text at this pixel size, 1 point to 1 scene unit
# Room around a label: an ellipse needs about sqrt(2) times the text's width, a box a margin
ELLIPSE_WIDTH, ELLIPSE_PAD, BOX_PAD = 1.3, 16.0, 14.0

TextWidth = Callable[[str], float]  # a label's width in points, as the view will draw it


def _quoted(text: str) -> str:
    return '"%s"' % text.replace("\\", "\\\\").replace('"', '\\"')


def _min_width(text_width: Optional[TextWidth], label: str, ellipse: bool) -> dict:
    """A node at least as wide as its label drawn by the view (graphviz measures with fonts of its own)."""
    if text_width is None:
        return {}
    points = text_width(label) * ELLIPSE_WIDTH + ELLIPSE_PAD if ellipse else text_width(label) + BOX_PAD
    return {"width": "%.3f" % (points / POINTS_PER_INCH)}


def to_pydot(graph: Graph, group_namespaces: bool = True, text_width: Optional[TextWidth] = None) -> pydot.Dot:
    """``text_width``: how wide the view draws a label; nodes are made at least that wide (without it graphviz's
    own font metrics decide, as for the DOT and SVG files)."""
    dot = pydot.Dot("rosgraph", graph_type="digraph", rankdir="LR", fontsize=FONT_SIZE)
    dot.set_node_defaults(fontsize=FONT_SIZE)
    dot.set_edge_defaults(fontsize=FONT_SIZE)
    clusters: Dict[str, pydot.Cluster] = {}

    def container(name: str):
        namespace = namespace_of(name)
        if not group_namespaces or namespace == "/":
            return dot
        if namespace not in clusters:
            clusters[namespace] = pydot.Cluster(
                "ns%d" % len(clusters), label=_quoted(namespace), style="rounded", color="gray60"
            )
            dot.add_subgraph(clusters[namespace])
        return clusters[namespace]

    for name in sorted(graph.nodes):
        style = {} if graph.nodes[name] else {"color": "red", "tooltip": _quoted(name + " (DEAD)")}
        style.update(_min_width(text_width, name, ellipse=True))
        container(name).add_node(pydot.Node(_quoted(node_id(name)), label=_quoted(name), shape="ellipse", **style))
    for name in sorted(graph.topics):
        size = _min_width(text_width, name, ellipse=False)
        container(name).add_node(pydot.Node(_quoted(topic_id(name)), label=_quoted(name), shape="box", **size))
    for edge in graph.edges:
        attributes = {"label": _quoted(edge.label)} if edge.label else {}
        dot.add_edge(pydot.Edge(_quoted(edge.start), _quoted(edge.end), **attributes))
    return dot


def to_dot(graph: Graph, group_namespaces: bool = True) -> str:
    return to_pydot(graph, group_namespaces).to_string()


@dataclass
class PlacedVertex:
    vertex: str  # graph_model vertex id
    x: float  # centre, points, y downwards
    y: float
    width: float
    height: float
    label: str

    @property
    def is_topic(self) -> bool:
        return is_topic(self.vertex)

    @property
    def name(self) -> str:
        return vertex_name(self.vertex)


@dataclass
class PlacedEdge:
    start: str
    end: str
    points: List[Tuple[float, float]]  # cubic B-spline control points, points, y downwards
    label: str = ""
    label_pos: Optional[Tuple[float, float]] = None


@dataclass
class Layout:
    width: float = 0.0
    height: float = 0.0
    vertices: Dict[str, PlacedVertex] = field(default_factory=dict)
    edges: List[PlacedEdge] = field(default_factory=list)


def parse_plain(text: str) -> Layout:
    """Read graphviz's "plain" output (https://graphviz.org/docs/outputs/plain/) into points with y downwards."""
    layout = Layout()
    height_in = 0.0

    def point(x: str, y: str) -> Tuple[float, float]:
        return float(x) * POINTS_PER_INCH, (height_in - float(y)) * POINTS_PER_INCH

    for line in text.splitlines():
        words = shlex.split(line)
        if not words:
            continue
        if words[0] == "graph":
            height_in = float(words[3])
            layout.width, layout.height = float(words[2]) * POINTS_PER_INCH, height_in * POINTS_PER_INCH
        elif words[0] == "node":
            x, y = point(words[2], words[3])
            layout.vertices[words[1]] = PlacedVertex(
                words[1], x, y, float(words[4]) * POINTS_PER_INCH, float(words[5]) * POINTS_PER_INCH, words[6]
            )
        elif words[0] == "edge":
            count = int(words[3])
            coordinates = words[4 : 4 + 2 * count]
            points = [point(coordinates[i], coordinates[i + 1]) for i in range(0, len(coordinates), 2)]
            rest = words[4 + 2 * count :]
            edge = PlacedEdge(words[1], words[2], points)
            if len(rest) >= 5:  # label xl yl style color
                edge.label, edge.label_pos = rest[0], point(rest[1], rest[2])
            layout.edges.append(edge)
    return layout


def run_dot(dot: pydot.Dot, output_format: str) -> bytes:
    """graphviz `dot`'s output in a format ("plain", "svg", "png"); pydot raises if dot is missing or fails."""
    return dot.create(prog="dot", format=output_format)


def lay_out(graph: Graph, group_namespaces: bool = True, text_width: Optional[TextWidth] = None) -> Layout:
    return parse_plain(run_dot(to_pydot(graph, group_namespaces, text_width), "plain").decode("utf-8"))
