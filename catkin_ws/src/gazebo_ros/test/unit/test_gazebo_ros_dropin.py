"""The gazebo_ros drop-in's helpers: the display check behind gui:=true, and the notes on args with no effect."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "src"))

from gazebo_ros_dropin import display_problem, parse_bool, unsupported_arg_notes  # noqa: E402


@pytest.fixture
def socket_dir(tmp_path: Path) -> Path:
    (tmp_path / "X0").touch()
    return tmp_path


@pytest.mark.parametrize("environ", [{}, {"DISPLAY": ""}, {"DISPLAY": "  "}])
def test_no_display(environ: dict, socket_dir: Path) -> None:
    assert display_problem(environ, str(socket_dir)) == "DISPLAY is not set"


@pytest.mark.parametrize("display", [":0", ":0.0", "unix:0", "unix:0.1"])
def test_local_display_with_its_server(display: str, socket_dir: Path) -> None:
    assert display_problem({"DISPLAY": display}, str(socket_dir)) is None


@pytest.mark.parametrize("display", [":1", ":93.0", "unix:7"])
def test_local_display_without_a_server(display: str, socket_dir: Path) -> None:
    number = display.split(":")[1].split(".")[0]
    problem = display_problem({"DISPLAY": display}, str(socket_dir))
    assert problem == "DISPLAY=%s has no X server (no %s/X%s)" % (display, socket_dir, number)


@pytest.mark.parametrize("display", ["localhost:10.0", "gateway:0", "10.0.0.2:1"])
def test_remote_display_is_taken_as_given(display: str, socket_dir: Path) -> None:
    assert display_problem({"DISPLAY": display}, str(socket_dir)) is None


def test_gazebo_defaults_have_no_notes() -> None:
    assert unsupported_arg_notes(False, "ode", "") == []


def test_each_unsupported_arg_is_named() -> None:
    notes = unsupported_arg_notes(True, "bullet", " --lockstep ")
    assert len(notes) == 3
    assert notes[0].startswith("recording:=true")
    assert notes[1] == "physics:=bullet: the engine is always ODE here"
    assert notes[2].startswith("extra_gazebo_args [--lockstep] ignored: ")


@pytest.mark.parametrize("text,value", [("true", True), ("True", True), ("1", True), ("false", False), ("0", False)])
def test_parse_bool(text: str, value: bool) -> None:
    assert parse_bool(text) is value


def test_parse_bool_refuses_other_words() -> None:
    with pytest.raises(ValueError, match="not a boolean"):
        parse_bool("maybe")
