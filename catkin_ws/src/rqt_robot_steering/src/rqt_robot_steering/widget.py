"""The Robot Steering window: a topic field and Stop, a vertical slider for linear.x and a horizontal one for
angular.z with their step buttons, limit spin boxes and current-speed labels, and upstream's keyboard shortcuts.
The twists go out from a Qt timer on the Qt thread; nothing here runs on a ROS thread."""
from __future__ import annotations

import math
from typing import List

import rospy
from geometry_msgs.msg import Twist
from python_qt_binding.QtCore import Qt, QTimer
from python_qt_binding.QtGui import QKeySequence
from python_qt_binding.QtWidgets import (
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


def step_button(text: str, tooltip: str) -> QPushButton:
    button = QPushButton(text)
    button.setToolTip(tooltip)
    button.setMaximumSize(50, 50)
    return button


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

        self.x_linear_slider = self._slider(Qt.Vertical, params["default_vx_min"], params["default_vx_max"])
        self.x_linear_slider.setTickPosition(QSlider.TicksBothSides)
        linear_buttons = QVBoxLayout()
        linear_buttons.setContentsMargins(40, 0, 0, 0)
        self.linear_buttons = {}
        for steps, text, tooltip in ((1, "+", "Increase linear velocity ([Shift +] W)"),
                                     (0, "0", "Reset linear velocity ([Shift +] X)"),
                                     (-1, "-", "Decrease linear velocity ([Shift +] S)")):
            self.linear_buttons[steps] = step_button(text, tooltip)
            linear_buttons.addWidget(self.linear_buttons[steps])
        self.max_x_linear_double_spin_box = limit_box("Maximum linear velocity", 0.0, LIMIT_BOUND,
                                                      params["default_vx_max"])
        self.current_x_linear_label = QLabel("0.0 m/s")
        self.current_x_linear_label.setToolTip("Current linear velocity")
        self.min_x_linear_double_spin_box = limit_box("Minimum linear velocity", -LIMIT_BOUND, 0.0,
                                                      params["default_vx_min"])
        linear_info = QVBoxLayout()
        for widget in (self.max_x_linear_double_spin_box, self.current_x_linear_label,
                       self.min_x_linear_double_spin_box):
            linear_info.addWidget(widget)
        linear = QHBoxLayout()
        linear.addStretch(1)
        linear.addLayout(linear_buttons)
        linear.addWidget(self.x_linear_slider)
        linear.addLayout(linear_info)
        linear.addStretch(1)

        self.z_angular_slider = self._slider(Qt.Horizontal, params["default_vw_min"], params["default_vw_max"])
        self.z_angular_slider.setInvertedAppearance(True)  # positive (turning left) on the left
        self.z_angular_slider.setTickPosition(QSlider.TicksBelow)
        angular_buttons = QHBoxLayout()
        self.angular_buttons = {}
        for steps, text, tooltip in ((1, "<", "Increase angular velocity ([Shift +] A)"),
                                     (0, "0", "Reset angular velocity ([Shift +] Z)"),
                                     (-1, ">", "Decrease angular velocity ([Shift +] D)")):
            self.angular_buttons[steps] = step_button(text, tooltip)
            angular_buttons.addWidget(self.angular_buttons[steps])
        self.max_z_angular_double_spin_box = limit_box("Maximum angular velocity", 0.0, LIMIT_BOUND,
                                                       params["default_vw_max"])
        self.current_z_angular_label = QLabel("0.0 rad/s")
        self.current_z_angular_label.setToolTip("Current angular velocity")
        self.min_z_angular_double_spin_box = limit_box("Minimum angular velocity", -LIMIT_BOUND, 0.0,
                                                       params["default_vw_min"])
        angular_info = QHBoxLayout()
        # upstream's order, left to right: the maximum (turning left) first
        for widget in (self.max_z_angular_double_spin_box, self.current_z_angular_label,
                       self.min_z_angular_double_spin_box):
            angular_info.addWidget(widget)

        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(linear)
        layout.addWidget(self.z_angular_slider)
        layout.addLayout(angular_buttons)
        layout.addLayout(angular_info)

        self._connect()
        self.topic_line_edit.setText(params["default_topic"])
        self._timer = QTimer(self)
        self._timer.timeout.connect(self._send_twist)
        self._timer.start(PUBLISH_PERIOD_MS)

    @staticmethod
    def _slider(orientation, low: float, high: float) -> QSlider:
        slider = QSlider(orientation)
        slider.setRange(slider_units(low), slider_units(high))
        slider.setSingleStep(SINGLE_STEP)
        slider.setPageStep(PAGE_STEP)
        return slider

    def _connect(self) -> None:
        self.topic_line_edit.textChanged.connect(self._on_topic_changed)
        self.stop_push_button.pressed.connect(self._on_stop)
        self.x_linear_slider.valueChanged.connect(self._on_linear_changed)
        self.z_angular_slider.valueChanged.connect(self._on_angular_changed)
        sliders = {"linear": self.x_linear_slider, "angular": self.z_angular_slider}
        for steps, button in self.linear_buttons.items():
            button.pressed.connect(lambda steps=steps: self._step(self.x_linear_slider, steps, strong=True))
        for steps, button in self.angular_buttons.items():
            button.pressed.connect(lambda steps=steps: self._step(self.z_angular_slider, steps, strong=True))
        for box, slider, setter in (
            (self.max_x_linear_double_spin_box, self.x_linear_slider, QSlider.setMaximum),
            (self.min_x_linear_double_spin_box, self.x_linear_slider, QSlider.setMinimum),
            (self.max_z_angular_double_spin_box, self.z_angular_slider, QSlider.setMaximum),
            (self.min_z_angular_double_spin_box, self.z_angular_slider, QSlider.setMinimum),
        ):
            box.valueChanged.connect(lambda value, slider=slider, setter=setter: setter(slider, slider_units(value)))
        self._shortcuts = []
        for key, (which, steps) in SHORTCUTS.items():
            for strong, sequence in ((False, key), (True, "Shift+" + key)):
                self._add_shortcut(sequence, lambda s=sliders[which], n=steps, p=strong: self._step(s, n, p))
        for sequence in ("Space", "Shift+Space"):
            self._add_shortcut(sequence, self._on_stop)

    def _add_shortcut(self, sequence: str, action) -> None:
        shortcut = QShortcut(QKeySequence(sequence), self)
        shortcut.setContext(Qt.ApplicationShortcut)
        shortcut.activated.connect(action)
        self._shortcuts.append(shortcut)

    def _step(self, slider: QSlider, steps: int, strong: bool) -> None:
        slider.setValue(stepped(slider.value(), steps, strong))

    def _on_topic_changed(self, topic: str) -> None:
        self._unregister()
        if topic:
            self._publisher = rospy.Publisher(topic, Twist, queue_size=10)

    def _on_stop(self) -> None:
        if self.x_linear_slider.value() == 0 and self.z_angular_slider.value() == 0:
            self._gate.resend_zero()
            self._send_twist()
        else:
            self.x_linear_slider.setValue(0)
            self.z_angular_slider.setValue(0)

    def _on_linear_changed(self, value: int) -> None:
        self.current_x_linear_label.setText("%0.2f m/s" % (value / SLIDER_FACTOR))
        self._send_twist()

    def _on_angular_changed(self, value: int) -> None:
        self.current_z_angular_label.setText("%0.2f rad/s" % (value / SLIDER_FACTOR))
        self._send_twist()

    def _send_twist(self) -> None:
        if self._publisher is None:
            return
        speeds = self._gate.next_twist(self.x_linear_slider.value(), self.z_angular_slider.value())
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
