#!/usr/bin/env python3
"""Benchmark of the rqt drop-ins (issue #21): prints a table and writes JSON.

1. rqt_plot, injected: 10 minutes of three fields at 62.5 Hz pushed into the plot's data window faster than real
   time, one frame per 40 ms of data: redraw time per frame in the first and the last minute, memory;
2. rqt_plot, real time: `rqt_plot /turtle1/pose/x:y:theta` on turtlesim driving a circle for --minutes (default 1;
   --minutes 10 for the full run): the same figures, and the points received against 3 x 62.5 Hz;
3. rqt_console: 1,000 rosgraph_msgs/Log messages a second on /rosout_agg for --console-seconds: event-loop latency
   (how late a 10 ms timer fires), batch insert time, messages received and kept.

The tools' widgets run in this process, which is their ROS node, on a master of its own (free port); Qt draws on
its offscreen platform unless --display is given. Run with /usr/bin/python3 and the workspace sourced.
"""
from __future__ import annotations

import argparse
import datetime
import os
import shutil
import signal
import sys
import tempfile
from typing import Any, Dict, Optional, Sequence

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib"))
from bench.report import close_machine, machine, write_report  # noqa: E402
from bench.rqt_report import table  # noqa: E402
from bench.rqt_sections import console_flood, plot_injected, plot_real_time  # noqa: E402
from ros_run.process_stats import cpu_ticks  # noqa: E402
from ros_run.master import master  # noqa: E402
from ros_run.processes import Processes, ToolError  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DEFAULT_JSON = os.path.join(REPO, "bench_results", "bench_rqt.json")


def measure(results: Dict[str, Any], key: str, title: str, run, wanted: Sequence[str]) -> None:
    """results[key] = run() if key is wanted, or {"error": why} if it could not be measured."""
    if key not in wanted:
        return
    print("%s ..." % title, flush=True)
    try:
        results[key] = run()
    except ToolError as error:
        results[key] = {"error": str(error)}
        print("  ERROR: %s" % error, flush=True)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--minutes", type=float, default=1.0, help="real-time plot run (default 1; 10 in full)")
    parser.add_argument("--data-minutes", type=float, default=10.0, help="injected plot data (default 10)")
    parser.add_argument("--buffer-size", type=int, default=20000, help="rqt_plot's points per curve (default 20000)")
    parser.add_argument("--console-rate", type=float, default=1000.0, help="log messages per second (default 1000)")
    parser.add_argument("--console-seconds", type=float, default=30.0, help="flood length (default 30)")
    parser.add_argument(
        "--sections", default="plot_injected,plot_real_time,console", help="which to run (default: %(default)s)"
    )
    parser.add_argument("--display", action="store_true", help="draw on $DISPLAY instead of Qt's offscreen platform")
    parser.add_argument("--json", default=DEFAULT_JSON, help="where to write the results (default: %(default)s)")
    args = parser.parse_args(argv)
    wanted = args.sections.split(",")
    unknown = set(wanted) - {"plot_injected", "plot_real_time", "console"}
    if unknown:
        parser.error("unknown sections: %s" % ", ".join(sorted(unknown)))
    if not shutil.which("roscore") or not shutil.which("rosrun"):
        print("roscore/rosrun not found: source catkin_ws/devel/setup.bash first", file=sys.stderr)
        return 2
    if not args.display:
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    results: Dict[str, Any] = {
        "benchmark": "rqt_plot and rqt_console drop-ins, issue #21",
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "platform": "xcb" if args.display else "offscreen",
        "machine": machine(),
    }
    ticks_at_start = cpu_ticks()
    with tempfile.TemporaryDirectory(prefix="bench_rqt-") as log_dir, Processes(log_dir) as processes:
        with master(processes, "", "/bench_rqt", 30.0) as ros:
            os.environ.update(ros.ros_env)
            import rospy
            from python_qt_binding.QtWidgets import QApplication

            app = QApplication.instance() or QApplication(["bench_rqt"])
            rospy.init_node("rqt_gui_py_node_%d" % os.getpid(), disable_signals=True)
            measure(
                results,
                "plot_injected",
                "1. rqt_plot, injected data",
                lambda: plot_injected(app, args.data_minutes, args.buffer_size),
                wanted,
            )
            measure(
                results,
                "plot_real_time",
                "2. rqt_plot, real time on turtlesim",
                lambda: plot_real_time(app, args.minutes, processes, ros.ros_env),
                wanted,
            )
            measure(
                results,
                "console",
                "3. rqt_console flood",
                lambda: console_flood(app, args.console_rate, args.console_seconds, processes, ros.ros_env),
                wanted,
            )
            rospy.signal_shutdown("benchmark done")
    close_machine(results, ticks_at_start)
    return write_report(results, table(results), args.json)


if __name__ == "__main__":
    sys.exit(main())
