"""The window without a master: topics come from a fake list, messages are handed to the subscriber callback as
rospy would, and the plot must show them. Buttons and menu as rqt_plot's resource/plot.ui and
PlotWidget._update_remove_topic_menu (one entry per curve, "All" when there are several)."""
import pytest
import rospy
from geometry_msgs.msg import Twist, TwistStamped

from rqt_plot.plot_widget import PlotWidget

TOPICS = {"/turtle1/cmd_vel": "geometry_msgs/Twist", "/stamped": "geometry_msgs/TwistStamped"}


@pytest.fixture
def ros_time(monkeypatch):
    now = [100.0]
    monkeypatch.setattr(rospy, "get_time", lambda: now[0])
    return now


@pytest.fixture
def make_widget(qtbot, ros_time):
    made = []

    def make(*argv):
        widget = PlotWidget(list(argv), topic_types=lambda: dict(TOPICS))
        qtbot.addWidget(widget)
        made.append(widget)
        return widget

    yield make
    for widget in made:
        widget.shutdown()


def curve_data(widget, name):
    item = widget.canvas._curves[name]
    return list(item.xData if item.xData is not None else []), list(item.yData if item.yData is not None else [])


def test_command_line_fields_become_curves_and_show_received_values(make_widget, ros_time):
    widget = make_widget("/turtle1/cmd_vel/linear/x:y", "/turtle1/cmd_vel/angular/z")
    names = ["/turtle1/cmd_vel/linear/x", "/turtle1/cmd_vel/linear/y", "/turtle1/cmd_vel/angular/z"]
    assert widget.canvas.curve_names() == names
    assert [action.text() for action in widget.remove_menu.actions()] == sorted(names) + ["All"]
    for step in range(3):
        ros_time[0] = 101.0 + step
        message = Twist()
        message.linear.x, message.angular.z = step, -step
        widget.subscriptions._on_message(message, "/turtle1/cmd_vel")
    widget.update_plot()
    assert curve_data(widget, names[0]) == ([1.0, 2.0, 3.0], [0.0, 1.0, 2.0])  # x: ROS time - start
    assert curve_data(widget, names[2])[1] == [0.0, -1.0, -2.0]


def test_header_stamp_is_the_time_axis(make_widget):
    widget = make_widget("/stamped/twist/linear/x")
    for stamp, value in ((rospy.Time(105, 500000000), 7.0), (rospy.Time(106), 8.0)):
        message = TwistStamped()
        message.header.stamp = stamp
        message.twist.linear.x = value
        widget.subscriptions._on_message(message, "/stamped")
    widget.update_plot()
    assert curve_data(widget, "/stamped/twist/linear/x") == ([5.5, 6.0], [7.0, 8.0])


def test_topic_box_enables_plus_for_plottable_names_and_adds_a_message_field_by_field(make_widget, qtbot):
    widget = make_widget("-e")
    assert widget.topic_edit.text() == "/"
    widget.topic_edit.setText("/turtle1/cmd_vel/linear/q")
    assert not widget.add_button.isEnabled()
    widget.topic_edit.setText("/turtle1/cmd_vel/angular")
    assert widget.add_button.isEnabled()
    completions = widget._completion_model.stringList()
    assert "/turtle1/cmd_vel/angular/z" in completions and "/stamped/header/seq" in completions
    widget.add_button.click()
    assert widget.canvas.curve_names() == ["/turtle1/cmd_vel/angular/" + axis for axis in "xyz"]


def test_minus_menu_removes_one_or_all(make_widget):
    widget = make_widget("/turtle1/cmd_vel/linear/x:y")
    widget.remove_menu.actions()[0].trigger()
    assert widget.canvas.curve_names() == ["/turtle1/cmd_vel/linear/y"]
    assert [action.text() for action in widget.remove_menu.actions()] == ["/turtle1/cmd_vel/linear/y"]
    widget.add_topic("/turtle1/cmd_vel/linear/z")
    widget.remove_menu.actions()[-1].trigger()  # "All"
    assert widget.canvas.curve_names() == [] and not widget.remove_button.isEnabled()


def test_pause_freezes_the_plot_and_resume_shows_what_came_meanwhile(make_widget):
    # rqt_plot's pause stops the redraw timer while ROSData keeps buffering (PlotWidget.on_pause_button_clicked)
    widget = make_widget("-P", "/turtle1/cmd_vel/linear/x")
    assert widget.pause_button.isChecked()
    widget.subscriptions._on_message(Twist(), "/turtle1/cmd_vel")
    widget.subscriptions._on_message(Twist(), "/turtle1/cmd_vel")
    widget.update_plot()
    assert curve_data(widget, "/turtle1/cmd_vel/linear/x") == ([], [])
    widget.pause_button.click()
    widget.subscriptions._on_message(Twist(), "/turtle1/cmd_vel")
    widget.update_plot()
    assert len(curve_data(widget, "/turtle1/cmd_vel/linear/x")[0]) == 3
    widget.clear_button.click()
    assert curve_data(widget, "/turtle1/cmd_vel/linear/x") == ([], [])


def test_autoscroll_follows_the_newest_point_with_a_ten_second_width(make_widget, ros_time):
    widget = make_widget("/turtle1/cmd_vel/linear/x")
    for second in range(1, 4):
        ros_time[0] = 100.0 + second
        widget.subscriptions._on_message(Twist(), "/turtle1/cmd_vel")
    widget.update_plot()
    (low, high), _ = widget.canvas.plotItem.viewRange()
    assert (low, high) == pytest.approx((1.0, 11.0))  # the first point at the left edge until the window is full
    for second in range(4, 30):
        ros_time[0] = 100.0 + second
        widget.subscriptions._on_message(Twist(), "/turtle1/cmd_vel")
    widget.update_plot()
    (low, high), _ = widget.canvas.plotItem.viewRange()
    assert (low, high) == pytest.approx((19.0, 29.0))
    # only the visible stretch, one point beyond either edge, goes to the curve
    assert curve_data(widget, "/turtle1/cmd_vel/linear/x")[0] == [float(s) for s in range(18, 30)]
    widget.autoscroll_checkbox.setChecked(False)  # now all of it, to pan over
    assert curve_data(widget, "/turtle1/cmd_vel/linear/x")[0] == [float(s) for s in range(1, 30)]


def test_fields_of_topics_not_published_yet_are_added_when_they_appear(make_widget, qtbot):
    widget = make_widget("/later/linear/x")
    assert widget.canvas.curve_names() == [] and widget._retry_timer.isActive()
    TOPICS["/later"] = "geometry_msgs/Twist"
    try:
        qtbot.waitUntil(lambda: widget.canvas.curve_names() == ["/later/linear/x"], timeout=3000)
    finally:
        del TOPICS["/later"]
    assert not widget._retry_timer.isActive()
