"""The command line. Expected values from rqt_plot (noetic) src/rqt_plot/plot.py, Plot._parse_args and
Plot.add_arguments: ',' separates fields, 'topic/f1:f2' expands to the topic's fields, -P pauses, -e starts empty."""
import pytest

from rqt_plot.topic_args import expand_field_argument, parse_arguments


def parse(*argv):
    return parse_arguments(argv, resolve=None)


def test_tutorial_pose_fields_expand_to_three():
    assert parse("/turtle1/pose/x:y:theta").topics == ["/turtle1/pose/x", "/turtle1/pose/y", "/turtle1/pose/theta"]


def test_commas_and_spaces_both_separate_fields():
    assert parse("/a/b,/c/d", "/e/f").topics == ["/a/b", "/c/d", "/e/f"]
    assert parse("/a/b,,/c/d,").topics == ["/a/b", "/c/d"]


def test_colon_list_inside_a_comma_list():
    assert expand_field_argument("/t/x:y,/u/v") == ["/t/x", "/t/y", "/u/v"]
    assert expand_field_argument("/t/pos/x::z") == ["/t/pos/x", "/t/pos/z"]


def test_colon_list_without_a_topic_is_a_usage_error(capsys):
    with pytest.raises(SystemExit) as exited:
        parse("x:y")
    assert exited.value.code == 2
    assert "x:y must contain a topic and field name" in capsys.readouterr().err


def test_flags():
    args = parse("-P", "-e", "/a/b")
    assert args.start_paused and args.start_empty and args.topics == ["/a/b"]
    args = parse()
    assert not args.start_paused and not args.start_empty and args.topics == [] and args.buffer_size == 20000


def test_buffer_size_below_two_is_refused(capsys):
    with pytest.raises(SystemExit):
        parse("--buffer-size", "1")
    assert "--buffer-size must be at least 2, got 1" in capsys.readouterr().err


def test_relative_names_resolve_in_the_namespace(monkeypatch):
    # plot.py resolves with rosgraph.names.script_resolve_name('rqt_plot', name): ROS_NAMESPACE applies
    monkeypatch.setenv("ROS_NAMESPACE", "/robot")
    assert parse_arguments(["pose/x:y", "/abs/v"]).topics == ["/robot/pose/x", "/robot/pose/y", "/abs/v"]
