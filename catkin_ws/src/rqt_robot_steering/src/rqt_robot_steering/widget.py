"""The Robot Steering window: a topic field and Stop, a vertical slider for linear.x and a horizontal one for
angular.z with their step buttons, limit spin boxes and current-speed labels, and upstream's keyboard shortcuts.
The twists go out from a Qt timer on the Qt thread; nothing here runs on a ROS thread."""
from __future__ import annotations

import math
from typing import List, Tuple

import rospy
from geometry_msgs.msg import Twist
from python_qt_binding.QtCore import Qt, QTimer
from python_qt_binding.QtGui import QKeySequence
from python_qt_binding.QtWidgets import (
    QBoxLayout,
    QDoubleSpinBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QShortcut,
    QSlider,
    QVBoxLayout,
    QWidget,
)

from rqt_robot_steering.steering import (
    ANGULAR_LIMITS,
    DEFAULT_TOPIC,
    LIMIT_BOUND,
    LIMIT_STEP,
    LINEAR_LIMITS,
    PAGE_STEP,
    PUBLISH_PERIOD_MS,
    SHORTCUTS,
    SINGLE_STEP,
    SLIDER_FACTOR,
    TwistGate,
    slider_units,
    stepped,
)


def read_params() -> dict:
    """~default_topic and ~default_v{x,w}_{max,min}; SystemExit with a fatal message naming a bad one."""
    params = {"default_topic": rospy.get_param("~default_topic", DEFAULT_TOPIC)}
    if not isinstance(params["default_topic"], str):
        rospy.logfatal("rqt_robot_steering: ~default_topic [%r] is not a topic name", params["default_topic"])
        raise SystemExit(1)
    for name, default, low, high in (
        ("default_vx_max", LINEAR_LIMITS[1], 0.0, LIMIT_BOUND),
        ("default_vx_min", LINEAR_LIMITS[0], -LIMIT_BOUND, 0.0),
        ("default_vw_max", ANGULAR_LIMITS[1], 0.0, LIMIT_BOUND),
        ("default_vw_min", ANGULAR_LIMITS[0], -LIMIT_BOUND, 0.0),
    ):
        value = rospy.get_param("~" + name, default)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            rospy.logfatal("rqt_robot_steering: ~%s [%r] is not a number", name, value)
            raise SystemExit(1)
        if not low <= value <= high:
            rospy.logwarn("rqt_robot_steering: ~%s [%r] clamped to [%g, %g]", name, value, low, high)
        params[name] = min(max(float(value), low), high)
    return params


def limit_box(tooltip: str, low: float, high: float, value: float) -> QDoubleSpinBox:
    box = QDoubleSpinBox()
    box.setToolTip(tooltip)
    box.setRange(low, high)
    box.setSingleStep(LIMIT_STEP)
    box.setValue(value)
    return box


class AxisControls:
    """One speed's slider, its increase/reset/decrease buttons (page steps), limit boxes and current-speed label."""

    def __init__(
        self, kind: str, unit: str, orientation, button_texts: Tuple[str, str, str], keys: str, low: float, high: float
    ) -> None:
        self.unit = unit
        self.slider = QSlider(orientation)
        self.slider.setRange(slider_units(low), slider_units(high))
        self.slider.setSingleStep(SINGLE_STEP)
        self.slider.setPageStep(PAGE_STEP)
        self.buttons = []
        for steps, verb, text, key in zip((1, 0, -1), ("Increase", "Reset", "Decrease"), button_texts, keys):
            button = QPushButton(text)
            button.setToolTip("%s %s velocity ([Shift +] %s)" % (verb, kind, key))
            button.setMaximumSize(50, 50)
            button.pressed.connect(lambda steps=steps: self.step(steps, strong=True))
            self.buttons.append(button)
        self.max_box = limit_box("Maximum %s velocity" % kind, 0.0, LIMIT_BOUND, high)
        self.max_box.valueChanged.connect(lambda value: self.slider.setMaximum(slider_units(value)))
        self.label = QLabel("0.0 " + unit)
        self.label.setToolTip("Current %s velocity" % kind)
        self.min_box = limit_box("Minimum %s velocity" % kind, -LIMIT_BOUND, 0.0, low)
        self.min_box.valueChanged.connect(lambda value: self.slider.setMinimum(slider_units(value)))

    def step(self, steps: int, strong: bool) -> None:
        self.slider.setValue(stepped(self.slider.value(), steps, strong))

    def show_speed(self, value: int) -> None:
        self.label.setText("%0.2f %s" % (value / SLIDER_FACTOR, self.unit))

    def fill(self, buttons: QBoxLayout, info: QBoxLayout) -> None:
        """Put the buttons into one box, the limits and the label (maximum first) into the other."""
        for button in self.buttons:
            buttons.addWidget(button)
        for widget in (self.max_box, self.label, self.min_box):
            info.addWidget(widget)


class RobotSteeringWidget(QWidget):
    def __init__(self, _args: List[str]) -> None:
        super().__init__()
        self.setObjectName("RobotSteeringUi")
        params = read_params()
        self._publisher = None
        self._gate = TwistGate()

        self.topic_line_edit = QLineEdit()
        self.topic_line_edit.setToolTip("Topic to send Twist message to")
        self.stop_push_button = QPushButton("Stop")
        self.stop_push_button.setToolTip("Reset velocities to zero ([Shift +] Space)")
        top = QHBoxLayout()
        top.addWidget(self.topic_line_edit)
        top.addWidget(self.stop_push_button)

        self.linear = AxisControls(
            "linear", "m/s", Qt.Vertical, ("+", "0", "-"), "WXS", params["default_vx_min"], params["default_vx_max"]
        )
        self.linear.slider.setTickPosition(QSlider.TicksBothSides)
        linear_buttons, linear_info = QVBoxLayout(), QVBoxLayout()
        linear_buttons.setContentsMargins(40, 0, 0, 0)
        self.linear.fill(linear_buttons, linear_info)
        linear = QHBoxLayout()
        linear.addStretch(1)
        linear.addLayout(linear_buttons)
        linear.addWidget(self.linear.slider)
        linear.addLayout(linear_info)
        linear.addStretch(1)

        self.angular = AxisControls(
            "angular",
            "rad/s",
            Qt.Horizontal,
            ("<", "0", ">"),
            "AZD",
            params["default_vw_min"],
            params["default_vw_max"],
        )
        self.angular.slider.setInvertedAppearance(True)  # positive (turning left) on the left
        self.angular.slider.setTickPosition(QSlider.TicksBelow)
        angular_buttons, angular_info = QHBoxLayout(), QHBoxLayout()
        self.angular.fill(angular_buttons, angular_info)

        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(linear)
        layout.addWidget(self.angular.slider)
        layout.addLayout(angular_buttons)
        layout.addLayout(angular_info)

        self._connect()
        self.topic_line_edit.setText(params["default_topic"])
        self._timer = QTimer(self)
        self._timer.timeout.connect(self._send_twist)
        self._timer.start(PUBLISH_PERIOD_MS)

    def _connect(self) -> None:
        self.topic_line_edit.textChanged.connect(self._on_topic_changed)
        self.stop_push_button.pressed.connect(self._on_stop)
        for axis in (self.linear, self.angular):
            axis.slider.valueChanged.connect(axis.show_speed)
            axis.slider.valueChanged.connect(self._send_twist)
        axes = {"linear": self.linear, "angular": self.angular}
        self._shortcuts = []
        for key, (which, steps) in SHORTCUTS.items():
            for strong, sequence in ((False, key), (True, "Shift+" + key)):
                self._add_shortcut(sequence, lambda axis=axes[which], n=steps, p=strong: axis.step(n, p))
        for sequence in ("Space", "Shift+Space"):
            self._add_shortcut(sequence, self._on_stop)

    def _add_shortcut(self, sequence: str, action) -> None:
        shortcut = QShortcut(QKeySequence(sequence), self)
        shortcut.setContext(Qt.ApplicationShortcut)
        shortcut.activated.connect(action)
        self._shortcuts.append(shortcut)

    def _on_topic_changed(self, topic: str) -> None:
        self._unregister()
        if topic:
            self._publisher = rospy.Publisher(topic, Twist, queue_size=10)

    def _on_stop(self) -> None:
        if self.linear.slider.value() == 0 and self.angular.slider.value() == 0:
            self._gate.resend_zero()
            self._send_twist()
        else:
            self.linear.slider.setValue(0)
            self.angular.slider.setValue(0)

    def _send_twist(self) -> None:
        if self._publisher is None:
            return
        speeds = self._gate.next_twist(self.linear.slider.value(), self.angular.slider.value())
        if speeds is not None:
            twist = Twist()
            twist.linear.x, twist.angular.z = speeds
            self._publisher.publish(twist)

    def _unregister(self) -> None:
        if self._publisher is not None:
            self._publisher.unregister()
            self._publisher = None

    def shutdown(self) -> None:
        """Called by rqt_standalone's runner when the window closes."""
        self._timer.stop()
        self._unregister()
