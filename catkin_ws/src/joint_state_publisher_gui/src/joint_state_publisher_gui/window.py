"""The joint_state_publisher_gui window: one slider per movable joint, Randomize, Center and the rows box.

joint_state_publisher's JointStatePublisher (the system's own package, not copied here) reads the robot
description, keeps each joint's position in its free_joints dicts and publishes joint_states from a thread of its
own; this window writes the positions the sliders set into those dicts, and moves the sliders when the joint
states of its source_list change them.
"""
from __future__ import annotations

import random
from typing import Dict

import rospy
from python_qt_binding.QtCore import Qt, Signal
from python_qt_binding.QtGui import QFont
from python_qt_binding.QtWidgets import (
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QScrollArea,
    QSlider,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from joint_state_publisher_gui.sliders import RANGE, grid_positions, slider_joints, slider_to_value, value_to_slider


class JointSlider:
    """A joint's label, read-only value field and slider, bound to the joint's dict in JointStatePublisher."""

    def __init__(self, name: str, joint: Dict, font: QFont) -> None:
        self.joint = joint
        self.layout = QVBoxLayout()
        row = QHBoxLayout()
        label = QLabel(name)
        label.setFont(font)
        row.addWidget(label)
        self.display = QLineEdit("0.00")
        self.display.setAlignment(Qt.AlignRight)
        self.display.setFont(font)
        self.display.setReadOnly(True)
        row.addWidget(self.display)
        self.layout.addLayout(row)
        self.slider = QSlider(Qt.Horizontal)
        self.slider.setObjectName(name)
        self.slider.setFont(font)
        self.slider.setRange(0, RANGE)
        self.slider.setValue(RANGE // 2)
        self.slider.valueChanged.connect(self.on_slider_moved)
        self.layout.addWidget(self.slider)

    def on_slider_moved(self, value: int) -> None:
        self.joint["position"] = slider_to_value(value, self.joint)
        self.display.setText("%.3f" % self.joint["position"])

    def show_value(self, value: float) -> None:
        self.slider.setValue(value_to_slider(value, self.joint))


class JointStatePublisherGui(QWidget):
    """Upstream's class name and constructor (title, a JointStatePublisher, rows; 0 rows = one column)."""

    sliderUpdateTrigger = Signal()  # noqa: N815 (upstream's name: callers emit it)

    def __init__(self, title: str, jsp, num_rows: int = 0) -> None:
        super().__init__()
        self.setWindowTitle(title)
        self.jsp = jsp
        font = QFont("Helvetica", 9, QFont.Bold)
        self.sliders = {
            name: JointSlider(name, jsp.free_joints[name], font)
            for name in slider_joints(jsp.joint_list, jsp.free_joints)
        }
        self.grid = QGridLayout()
        self.num_rows = num_rows or len(self.sliders)
        self.place_sliders(self.num_rows)
        self.center()
        # the joint states of ~source_list arrive on a ROS thread: the sliders follow them on the Qt thread
        self.sliderUpdateTrigger.connect(self.update_sliders)
        jsp.set_source_update_cb(self.sliderUpdateTrigger.emit)

        scrollable = QWidget()
        scrollable.setLayout(self.grid)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setWidget(scrollable)
        layout = QVBoxLayout(self)
        layout.addWidget(scroll)
        self.randbutton = QPushButton("Randomize", self)
        self.randbutton.clicked.connect(self.randomize)
        layout.addWidget(self.randbutton)
        self.ctrbutton = QPushButton("Center", self)
        self.ctrbutton.clicked.connect(self.center)
        layout.addWidget(self.ctrbutton)
        self.maxrowsupdown = QSpinBox()
        self.maxrowsupdown.setMinimum(1)
        self.maxrowsupdown.setMaximum(max(1, len(self.sliders)))
        self.maxrowsupdown.setValue(self.num_rows)
        self.maxrowsupdown.valueChanged.connect(self.place_sliders)
        layout.addWidget(self.maxrowsupdown)

    def place_sliders(self, rows: int) -> None:
        """Lay the sliders out on ``rows`` rows, column by column."""
        self.num_rows = rows
        for joint_slider in self.sliders.values():
            self.grid.removeItem(joint_slider.layout)
        for joint_slider, (row, column) in zip(self.sliders.values(), grid_positions(len(self.sliders), rows)):
            self.grid.addLayout(joint_slider.layout, row, column)

    def update_sliders(self) -> None:
        for joint_slider in self.sliders.values():
            joint_slider.show_value(joint_slider.joint["position"])

    def center(self) -> None:
        rospy.loginfo("Centering")
        for joint_slider in self.sliders.values():
            joint_slider.show_value(joint_slider.joint["zero"])

    def randomize(self) -> None:
        rospy.loginfo("Randomizing")
        for joint_slider in self.sliders.values():
            joint_slider.show_value(random.uniform(joint_slider.joint["min"], joint_slider.joint["max"]))
