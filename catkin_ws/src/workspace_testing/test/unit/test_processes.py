"""stop_group stops a process group and whatever below it left the group, as roslaunch's nodes do."""
import os
import subprocess
import time

from workspace_testing.processes import LoggedProcess, descendants, stop_group


def alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().split(")")[-1].split()[0] != "Z"
    except FileNotFoundError:
        return False


def test_a_child_in_a_session_of_its_own_is_stopped_too() -> None:
    # The shell ignores SIGINT (as a node stuck in shutdown would), and its child left the group with setsid.
    process = subprocess.Popen(
        ["bash", "-c", "trap '' INT; setsid sleep 60 & wait"], start_new_session=True, stdout=subprocess.DEVNULL
    )

    def left_the_group() -> list:
        return [pid for pid in descendants(process.pid) if alive(pid) and os.getpgid(pid) != process.pid]

    deadline = time.monotonic() + 10
    while not left_the_group() and time.monotonic() < deadline:  # until setsid has run in the child
        time.sleep(0.05)
    below = left_the_group()
    assert below
    stop_group(process, grace=0.5)
    time.sleep(0.2)
    assert process.poll() is not None
    assert not [pid for pid in below if alive(pid)]


def test_a_logged_process_keeps_its_output_and_stops_with_its_group() -> None:
    logged = LoggedProcess(["bash", "-c", "echo started; echo to stderr >&2; exec sleep 60"], grace=0.5)
    deadline = time.monotonic() + 10
    while "to stderr" not in logged.output() and time.monotonic() < deadline:  # until bash has printed
        time.sleep(0.05)
    assert logged.output() == "started\nto stderr\n"
    assert logged.output(tail=7) == "stderr\n"
    assert logged.process.poll() is None
    logged.stop()
    assert logged.process.poll() is not None
    logged.stop()  # a second stop (rospy.on_shutdown after tearDownClass) does nothing
    logged.close()
