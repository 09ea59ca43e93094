"""scripts/bench_sim.py --quick --no-peer: it runs, stops what it started and writes every section with positive, finite
figures. Its targets are not checked here: they judge the simulator, not the benchmark."""
import math
import os
import re
import subprocess

import pytest
from conftest import run_bench

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TIMEOUT_S = 600  # --quick takes about 90 s on 2 cores; a busy machine may take longer
SECTIONS = ("physics_only", "full_node", "real_time", "launch", "cameras", "ros_control", "scaling", "viewer")
# 0 = unthrottled; linearity needs three robot counts, --quick has two ([] stands for any list index)
MAY_BE_ZERO_OR_NONE = {
    "full_node.real_time_factor",
    "full_node.runs[].real_time_factor",
    "full_node.linearity_at_1ms.wall",
    "full_node.linearity_at_1ms.node_cpu",
    "cameras.in_process.target_met",  # a verdict, False when missed
    "cameras.node.real_time_factor",
    "cameras.node.runs[].real_time_factor",
    "cameras.node.runs[].width",  # None: the run without a camera
    "cameras.node.runs[].height",
    "cameras.node.runs[].rate_hz",
    "viewer.real_time_factor",
    "viewer.runs.no viewer[].real_time_factor",
    "viewer.runs.viewer[].real_time_factor",
}


def bad_figures(value, path):
    """Paths of the numbers under ``value`` that are not positive and finite."""
    if isinstance(value, dict):
        return [bad for key, item in value.items() for bad in bad_figures(item, path + "." + key)]
    if isinstance(value, list):
        return [bad for index, item in enumerate(value) for bad in bad_figures(item, "%s[%d]" % (path, index))]
    if re.sub(r"\[\d+\]", "[]", path) in MAY_BE_ZERO_OR_NONE:
        return []
    if value is None or (isinstance(value, (int, float)) and not (math.isfinite(value) and value > 0)):
        return ["%s = %r" % (path, value)]
    return []


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    json_path = str(tmp_path_factory.mktemp("bench") / "bench_sim.json")
    return run_bench("bench_sim.py", ["--quick", "--no-peer"], json_path, "targets", TIMEOUT_S)


def test_every_section_has_positive_finite_figures(results):
    assert results["mode"] == "quick"
    for section in SECTIONS:
        assert section in results and "error" not in results[section], results.get(section)
        assert not bad_figures(results[section], section)


def test_full_node_covers_robot_counts_and_time_steps_with_every_sensor(results):
    runs = results["full_node"]["runs"]
    assert sorted((run["robots"], run["time_step"]) for run in runs) == [(1, 0.001), (1, 0.01), (2, 0.001), (2, 0.01)]
    for run in runs:
        assert set(run["rates_per_robot_hz"]) == {"odom", "joint_states", "imu", "scan", "tf"}


def test_machine_peer_and_targets_are_recorded(results):
    machine = results["machine"]
    assert machine["nproc"] >= 1 and machine["cpu_model"] and machine["python"]
    assert results["peer"]["status"] == "skipped"
    assert len(results["targets"]) == 18


def test_the_node_and_physics_only_are_measured_in_turns(results):
    """1 robot at 1 ms: each turn's node RTF over the physics-only RTF measured just before it (probe.in_turns)."""
    one_1ms = next(run for run in results["full_node"]["runs"] if (run["robots"], run["time_step"]) == (1, 0.001))
    turns = one_1ms["in_turns"]
    assert len(turns["ratios"]) == len(turns["physics_rtf"]) == len(turns["node_rtf"]) == 5
    for ratio, node, physics in zip(turns["ratios"], turns["node_rtf"], turns["physics_rtf"]):
        assert ratio == pytest.approx(node / physics)
    assert min(turns["ratios"]) <= turns["median_ratio"] <= max(turns["ratios"])
    target = next(row for row in results["targets"] if row["target"] == "1 TurtleBot, 1 ms: the same in turns (median)")
    assert target["value"] == turns["median_ratio"]


def test_camera_runs_render_at_their_rate_only_when_watched(results):
    runs = results["cameras"]["node"]["runs"]
    assert [run["camera"] for run in runs] == [
        "none",
        "320x240 at 15 Hz, unwatched",
        "320x240 at 15 Hz, watched",
        "640x480 at 30 Hz, watched",
    ]
    for run in runs:
        rates = run["rates_per_robot_hz"]
        if "unwatched" in run["camera"] or run["rate_hz"] is None:
            assert not {"image", "depth", "points"} & set(rates), run
        else:
            for kind in ("image", "depth", "points"):  # per sim second, as the plugin's update_rate says
                assert rates[kind] == pytest.approx(run["rate_hz"], rel=0.2), (kind, run)
    sizes = [(row["width"], row["height"]) for row in results["cameras"]["in_process"]["cameras"]]
    assert sizes == [(320, 240), (640, 480)]
    assert all(target["pass"] in (True, False, None) for target in results["targets"])


@pytest.mark.parametrize("script", ["bench_sim.py", "soak.py"])
def test_runs_as_the_readme_shows_without_the_workspace_sourced(tmp_path, script):
    """The scripts source the workspace themselves (scripts/lib/ros_run/workspace_env.py), as demo.sh does: run from another
    folder with a bare environment, their imports of turtle_sim_ode and rospy succeed and --help answers."""
    if not os.path.isfile(os.path.join(REPO, "catkin_ws", "devel", "setup.bash")):
        pytest.skip("the workspace is not built")
    bare = {"HOME": os.environ.get("HOME", "/root"), "PATH": "/usr/local/bin:/usr/bin:/bin"}
    result = subprocess.run(
        [os.path.join(REPO, "scripts", script), "--help"],
        cwd=str(tmp_path),
        env=bare,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert "usage: %s" % script in result.stdout
