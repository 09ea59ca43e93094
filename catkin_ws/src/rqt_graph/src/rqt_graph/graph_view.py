"""Draws a Layout into a QGraphicsScene: ellipses for nodes (red when dead), boxes for topics, arrows for edges,
namespace boxes; hovering a node or topic highlights it (orange) and its connections (incoming blue, outgoing red)."""
from __future__ import annotations

import math
from typing import Dict, List

from python_qt_binding.QtCore import QPointF, QRectF, Qt
from python_qt_binding.QtGui import QBrush, QColor, QFont, QFontMetricsF, QPainter, QPainterPath, QPen, QPolygonF
from python_qt_binding.QtWidgets import (
    QGraphicsEllipseItem,
    QGraphicsItemGroup,
    QGraphicsPathItem,
    QGraphicsRectItem,
    QGraphicsScene,
    QGraphicsSimpleTextItem,
    QGraphicsView,
)

from rqt_graph.dot_layout import FONT_SIZE, Layout, PlacedEdge, PlacedVertex
from rqt_graph.graph_model import namespace_of

NORMAL = QColor("black")
DEAD = QColor("red")
INCOMING = QColor(0, 0, 220)
OUTGOING = QColor(220, 0, 0)
NAMESPACE = QColor(150, 150, 150)
ARROW = 9.0  # arrowhead length, points
CLUSTER_MARGIN = 10.0
HOVERED = QColor(255, 140, 0)  # not red: red means dead


def label_font() -> QFont:
    font = QFont()
    font.setPixelSize(int(FONT_SIZE))
    return font


def text_width(label: str) -> float:
    """How wide the view draws a label (for dot_layout, so that the text fits its node)."""
    return QFontMetricsF(label_font()).horizontalAdvance(label)


def _text(label: str) -> QGraphicsSimpleTextItem:
    item = QGraphicsSimpleTextItem(label)
    item.setFont(label_font())
    return item


class EdgeItem(QGraphicsItemGroup):
    def __init__(self, edge: PlacedEdge):
        super().__init__()
        self.edge = edge
        path = QPainterPath(QPointF(*edge.points[0]))
        points = edge.points[1:]
        for i in range(0, len(points) - 2, 3):  # cubic B-spline pieces, as dot gives them
            path.cubicTo(QPointF(*points[i]), QPointF(*points[i + 1]), QPointF(*points[i + 2]))
        self._line = QGraphicsPathItem(path)
        (bx, by), (tx, ty) = edge.points[-2], edge.points[-1]
        angle = math.atan2(ty - by, tx - bx)
        tip = QPointF(tx + ARROW * math.cos(angle), ty + ARROW * math.sin(angle))
        wing = [
            QPointF(
                tx + 0.5 * ARROW * math.cos(angle + s * math.pi / 2),
                ty + 0.5 * ARROW * math.sin(angle + s * math.pi / 2),
            )
            for s in (1, -1)
        ]
        self._head = QGraphicsPathItem()
        head = QPainterPath()
        head.addPolygon(QPolygonF([tip, wing[0], wing[1], tip]))
        self._head.setPath(head)
        self.addToGroup(self._line)
        self.addToGroup(self._head)
        self._label = None
        if edge.label and edge.label_pos:
            self._label = _text(edge.label)
            rect = self._label.boundingRect()
            self._label.setPos(edge.label_pos[0] - rect.width() / 2, edge.label_pos[1] - rect.height() / 2)
            self.addToGroup(self._label)
        self.set_colour(NORMAL)

    def set_colour(self, colour: QColor) -> None:
        pen = QPen(colour, 2.0 if colour != NORMAL else 1.0)
        self._line.setPen(pen)
        self._head.setPen(pen)
        self._head.setBrush(QBrush(colour))
        if self._label is not None:
            self._label.setBrush(QBrush(colour))


class VertexItem(QGraphicsItemGroup):
    """A node or topic; on hover its edges and neighbours take the highlight colours."""

    def __init__(self, vertex: PlacedVertex, alive: bool):
        super().__init__()
        self.vertex = vertex
        self.alive = alive
        self.highlight = True
        self.incoming: List[EdgeItem] = []
        self.outgoing: List[EdgeItem] = []
        rect = QRectF(vertex.x - vertex.width / 2, vertex.y - vertex.height / 2, vertex.width, vertex.height)
        self._shape = QGraphicsRectItem(rect) if vertex.is_topic else QGraphicsEllipseItem(rect)
        self._shape.setBrush(QBrush(Qt.white))
        self._text = _text(vertex.label)
        text_rect = self._text.boundingRect()
        self._text.setPos(vertex.x - text_rect.width() / 2, vertex.y - text_rect.height() / 2)
        self.addToGroup(self._shape)
        self.addToGroup(self._text)
        self.setAcceptHoverEvents(True)
        self.setToolTip(vertex.name + ("" if alive else " (DEAD: did not answer getBusInfo)"))
        self.set_colour(NORMAL)

    def set_colour(self, colour: QColor) -> None:
        if colour == NORMAL and not self.alive:
            colour = DEAD
        self._shape.setPen(QPen(colour, 2.0 if colour != NORMAL else 1.0))
        self._text.setBrush(QBrush(colour))

    def hoverEnterEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        if self.highlight:
            self.set_highlighted(True)
        super().hoverEnterEvent(event)

    def hoverLeaveEvent(self, event) -> None:  # noqa: N802
        self.set_highlighted(False)
        super().hoverLeaveEvent(event)

    def set_highlighted(self, on: bool) -> None:
        for edges, colour in ((self.incoming, INCOMING), (self.outgoing, OUTGOING)):
            for edge in edges:
                edge.set_colour(colour if on else NORMAL)
        self.set_colour(HOVERED if on else NORMAL)


def draw(
    scene: QGraphicsScene, layout: Layout, alive: Dict[str, bool], group_namespaces: bool
) -> Dict[str, VertexItem]:
    """Fill the (cleared) scene; returns the vertex items by vertex id."""
    scene.clear()
    vertices = {}
    for vertex_id, placed in layout.vertices.items():
        item = VertexItem(placed, alive.get(placed.name, True) or placed.is_topic)
        item.setZValue(2)
        scene.addItem(item)
        vertices[vertex_id] = item
    for edge in layout.edges:
        item = EdgeItem(edge)
        item.setZValue(1)
        scene.addItem(item)
        if edge.start in vertices:
            vertices[edge.start].outgoing.append(item)
        if edge.end in vertices:
            vertices[edge.end].incoming.append(item)
    if group_namespaces:
        _draw_namespaces(scene, layout)
    return vertices


def _draw_namespaces(scene: QGraphicsScene, layout: Layout) -> None:
    boxes: Dict[str, QRectF] = {}
    for placed in layout.vertices.values():
        namespace = namespace_of(placed.name)
        if namespace == "/":
            continue
        rect = QRectF(placed.x - placed.width / 2, placed.y - placed.height / 2, placed.width, placed.height)
        boxes[namespace] = boxes[namespace].united(rect) if namespace in boxes else rect
    for namespace, rect in boxes.items():
        box = rect.adjusted(-CLUSTER_MARGIN, -CLUSTER_MARGIN - 14, CLUSTER_MARGIN, CLUSTER_MARGIN)
        frame = scene.addRect(box, QPen(NAMESPACE, 1.0, Qt.DashLine))
        frame.setZValue(0)
        label = scene.addSimpleText(namespace, label_font())
        label.setBrush(QBrush(NAMESPACE))
        label.setPos(box.left() + 4, box.top() + 2)


class GraphView(QGraphicsView):
    """Zoom with the wheel, pan by dragging."""

    def __init__(self, scene: QGraphicsScene, parent=None):
        super().__init__(scene, parent)
        self.setRenderHint(QPainter.Antialiasing)
        self.setDragMode(QGraphicsView.ScrollHandDrag)
        self.setTransformationAnchor(QGraphicsView.AnchorUnderMouse)

    def wheelEvent(self, event) -> None:  # noqa: N802
        factor = 1.15 if event.angleDelta().y() > 0 else 1 / 1.15
        self.scale(factor, factor)

    def fit(self) -> None:
        """Shrink a graph larger than the view to fit it; a small one keeps its size (no giant letters)."""
        rect = self.scene().itemsBoundingRect().adjusted(-10, -10, 10, 10)
        if rect.isEmpty():
            return
        self.fitInView(rect, Qt.KeepAspectRatio)
        if self.transform().m11() > 1.0:
            self.resetTransform()
        self.centerOn(rect.center())
