"""bench_rqt.py's table: rqt_plot's redraw times and memory, rqt_console's latency and throughput."""
from __future__ import annotations

from typing import Any, Dict


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
