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
from bench.rqt_sections import console_flood, plot_injected, plot_real_time  # noqa: E402
from ros_run.process_stats import cpu_ticks  # noqa: E402
from ros_run.master import master  # noqa: E402
from ros_run.processes import Processes, ToolError  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
DEFAULT_JSON = os.path.join(REPO, "bench_results", "bench_rqt.json")


def frame_row(name: str, result: Dict[str, Any]) -> str:
    first, last, fresh = (result["frame_" + when] for when in ("first_minute", "last_minute", "fresh_last_minute"))
    return "%-24s %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %7.1f %7.1f" % (
        name,
        first["median_ms"],
        first["p95_ms"],
        last["median_ms"],
        last["p95_ms"],
        fresh["median_ms"],
        fresh["p95_ms"],
        result["rss_mib_start"],
        result["rss_mib_end"],
    )


def table(results: Dict[str, Any]) -> str:
    header = "%-24s %7s %7s %7s %7s %7s %7s %7s %7s"
    lines = [
        "rqt_plot: redraw per frame (ms) in the first and the last minute, and of a twin plot cleared every minute",
        "(a fresh plot at the same moment, drawn alternately with it); memory of the process (MiB)",
        header % ("", "first", "", "last", "", "fresh", "at end", "RSS", "RSS"),
        header % ("", "median", "p95", "median", "p95", "median", "p95", "start", "end"),
    ]
    injected = results.get("plot_injected", {})
    if "error" in injected:
        lines.append("injected: ERROR %s" % injected["error"])
    elif injected:
        lines.append(frame_row("injected, %.0f min data" % injected["data_minutes"], injected))
        lines.append(
            "  %d points a curve kept at the end (bound %d), %.0f s of wall time"
            % (injected["points_per_curve_at_end"], injected["buffer_size"], injected["wall_s"])
        )
    real = results.get("plot_real_time", {})
    if "error" in real:
        lines.append("real time: ERROR %s" % real["error"])
    elif real:
        lines.append(frame_row("real time, %.1f min" % real["wall_minutes"], real))
        lines.append(
            "  points received %d of %d expected (3 x 62.5 Hz); frames late by median %.2f ms, max %.1f ms"
            % (
                real["points_received"],
                real["points_expected"],
                real["frame_lateness"]["median_ms"],
                real["frame_lateness"]["max_ms"],
            )
        )
    console = results.get("console", {})
    lines.append("")
    if "error" in console:
        lines.append("rqt_console: ERROR %s" % console["error"])
    elif console:
        latency, insert = console["event_loop_latency"], console["batch_insert"]
        idle = console["event_loop_latency_idle"]
        lines += [
            "rqt_console at %.0f messages/s for %.0f s" % (console["rate_per_s"], console["seconds"]),
            "  sent %d, received %d, kept %d (limit %d), newest on top: %s"
            % (
                console["sent"],
                console["received"],
                console["kept"],
                console["limit"],
                "yes" if console["newest_on_top"] else "NO",
            ),
            "  event-loop latency (10 ms timer): median %.2f ms, p95 %.2f ms, max %.1f ms"
            % (latency["median_ms"], latency["p95_ms"], latency["max_ms"]),
            "  the same probe idle, before the flood: median %.2f ms, p95 %.2f ms, max %.1f ms"
            % (idle["median_ms"], idle["p95_ms"], idle["max_ms"]),
            "  batch insert (every 100 ms): median %.2f ms, p95 %.2f ms, max %.1f ms over %d batches"
            % (insert["median_ms"], insert["p95_ms"], insert["max_ms"], insert["count"]),
            "  RSS %.1f -> %.1f MiB" % (console["rss_mib_start"], console["rss_mib_end"]),
        ]
    lines.append("")
    lines.append("CPU stolen by the host meanwhile: %.1f %%" % (100 * results["machine"]["stolen_cpu_share"]))
    return "\n".join(lines)


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
