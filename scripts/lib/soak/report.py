"""The soak's verdict and report (scripts/soak.py): the summary and checks of a run's samples and counters, and the
table of samples printed at the end."""
from __future__ import annotations

import argparse
import math
from typing import Any, Dict, List, Optional, Sequence, Tuple

from soak.node import Stats

# A healthy run grows 0.05-0.2 MiB/min after the warm-up (60 s and 3 min runs, 2 spawns/s). 2 MiB/min is ten times
# that and more than one allocator step (1 MiB) in the 48 s window of the 60 s soak, and it still catches a leak of
# 17 KiB per spawn and delete (a whole model kept) or of 35 bytes per physics step at 1000 steps/s.
DEFAULT_MAX_RSS_GROWTH_MIB_PER_MIN = 2.0
DEFAULT_MAX_COUNT_GROWTH = 5


def kinds_text(growth: Dict[str, int]) -> str:
    """' [eventpoll +18, socket -1]', or '' if nothing changed."""
    return " [%s]" % ", ".join("%s %+d" % item for item in sorted(growth.items())) if growth else ""


def slope_per_minute(points: Sequence[Tuple[float, float]]) -> Optional[float]:
    """Least-squares slope of (t s, value) points, per minute."""
    if len(points) < 3:
        return None
    mean_t = sum(t for t, _ in points) / len(points)
    mean_v = sum(v for _, v in points) / len(points)
    stt = sum((t - mean_t) ** 2 for t, _ in points)
    if stt <= 0:
        return None
    return 60.0 * sum((t - mean_t) * (v - mean_v) for t, v in points) / stt


def summarize(result: Dict[str, Any], args: argparse.Namespace, stats: Stats) -> None:
    """The summary and the checks of ``result`` (its samples and events) and ``stats`` into ``result``."""
    samples: List[Dict[str, Any]] = result["samples"]
    summary: Dict[str, Any] = {}
    checks: List[Dict[str, Any]] = []

    def check(name: str, passed: bool, detail: str) -> None:
        checks.append({"name": name, "pass": bool(passed), "detail": detail})

    with stats.lock:
        summary.update(
            spawns=sum(stats.spawns.values()),
            spawns_by_kind=dict(stats.spawns),
            spawn_failures=stats.spawn_failures,
            deletes=stats.deletes,
            delete_failures=stats.delete_failures,
            failure_messages=list(stats.failures),
            odom_messages=stats.odom_messages,
            scan_messages=stats.scan_messages,
            commands=stats.commands,
            robot_max_distance_m=round(stats.max_distance_m, 3),
        )
        for kind, values in stats.latencies.items():
            if values:
                ordered = sorted(values)
                summary["%s_latency_s" % kind] = {
                    "mean": round(sum(ordered) / len(ordered), 4),
                    "p99": round(ordered[max(0, math.ceil(0.99 * len(ordered)) - 1)], 4),
                    "max": round(ordered[-1], 4),
                }
    check(
        "spawns_and_deletes_succeed",
        summary["spawns"] > 0
        and summary["spawn_failures"] == 0
        and summary["delete_failures"] == 0
        and not summary["failure_messages"],
        "%d spawns (%d failed), %d deletes (%d failed)"
        % (summary["spawns"], summary["spawn_failures"], summary["deletes"], summary["delete_failures"]),
    )
    check("simulator_alive", result["simulator_alive"], result.get("death") or "alive to the end")
    check("no_hung_call", not result.get("hung_call"), result.get("hung_call") or "every call returned")
    if len(samples) < 2:
        check("enough_samples", False, "%d samples" % len(samples))
        result.update(summary=summary, checks=checks, passed=False)
        return

    first, last = samples[0], samples[-1]
    warm = next((s for s in samples if s["t"] >= result["warmup_s"]), last)
    if warm is last and len(samples) > 2:
        warm = samples[-2]
    stalls = [
        "%.0f-%.0f s" % (a["t"], b["t"])
        for a, b in zip(samples, samples[1:])
        if a["sim_time"] is None or b["sim_time"] is None or b["sim_time"] <= a["sim_time"]
    ]
    sim_span = (last["sim_time"] or 0.0) - (first["sim_time"] or 0.0)
    wall_span = last["t"] - first["t"]
    window_min = (last["t"] - warm["t"]) / 60.0
    after = [(s["t"], s["rss_mib"]) for s in samples if s["t"] >= warm["t"]]
    rss_growth = last["rss_mib"] - warm["rss_mib"]
    rss_rate = rss_growth / window_min if window_min > 0 else None
    rss_slope = slope_per_minute(after)
    summary.update(
        samples=len(samples),
        wall_s=round(wall_span, 2),
        warmup_sample_t=warm["t"],
        rss_start_mib=first["rss_mib"],
        rss_warmup_mib=warm["rss_mib"],
        rss_end_mib=last["rss_mib"],
        rss_max_mib=max(s["rss_mib"] for s in samples),
        rss_growth_mib=round(rss_growth, 3),
        rss_growth_mib_per_min=None if rss_rate is None else round(rss_rate, 3),
        rss_slope_mib_per_min=None if rss_slope is None else round(rss_slope, 3),
        rss_growth_total_mib=round(last["rss_mib"] - first["rss_mib"], 3),
        threads_start=first["threads"],
        threads_warmup=warm["threads"],
        threads_end=last["threads"],
        threads_growth=last["threads"] - warm["threads"],
        threads_max=max(s["threads_max"] for s in samples),
        fds_start=first["fds"],
        fds_warmup=warm["fds"],
        fds_end=last["fds"],
        fds_growth=last["fds"] - warm["fds"],
        fds_max=max(s["fds_max"] for s in samples),
        sim_time_start=first["sim_time"],
        sim_time_end=last["sim_time"],
        sim_time_advanced_s=round(sim_span, 3),
        rtf=round(sim_span / wall_span, 3) if wall_span > 0 else None,
        cpu_s=last["cpu_s"] - first["cpu_s"],
    )
    if result.get("after_cleanup"):
        summary["after_cleanup"] = result["after_cleanup"]
    check(
        "sim_time_advances",
        sim_span > 0 and not stalls,
        "sim time %.1f s -> %.1f s%s"
        % (first["sim_time"] or 0.0, last["sim_time"] or 0.0, "; stalled in " + ", ".join(stalls) if stalls else ""),
    )
    limit = args.max_rss_growth_mib_per_min
    sustained = rss_rate is not None and rss_slope is not None and rss_rate > limit and rss_slope > limit
    check(
        "rss_flat_after_warmup",
        rss_rate is not None and not sustained,
        (
            "%.2f MiB in %.1f min after warm-up: %s MiB/min end to end, trend %s MiB/min (limit %.1f)"
            % (
                rss_growth,
                window_min,
                "n/a" if rss_rate is None else "%.2f" % rss_rate,
                "n/a" if rss_slope is None else "%.2f" % rss_slope,
                limit,
            )
        )
        if rss_rate is not None
        else "not judged: no sample after the warm-up (the soak ended at %.0f s)" % last["t"],
    )
    # Threads and fds: neither at the end nor at any sample after the warm-up more than the tolerance above the
    # warm-up sample (a count that drops back only when the garbage collector runs grows between its runs).
    later = [s for s in samples if s["t"] >= warm["t"]]
    peak_threads = max(s["threads"] for s in later)
    peak_fds = max(later, key=lambda s: s["fds"])
    kinds = sorted(set(warm["fd_kinds"]) | set(last["fd_kinds"]) | set(peak_fds["fd_kinds"]))

    def by_kind(sample: Dict[str, Any]) -> Dict[str, int]:
        return {
            kind: sample["fd_kinds"].get(kind, 0) - warm["fd_kinds"].get(kind, 0)
            for kind in kinds
            if sample["fd_kinds"].get(kind, 0) != warm["fd_kinds"].get(kind, 0)
        }

    summary.update(
        threads_peak_after_warmup=peak_threads,
        fds_peak_after_warmup=peak_fds["fds"],
        fd_kinds_warmup=warm["fd_kinds"],
        fd_kinds_end=last["fd_kinds"],
        fd_growth_by_kind=by_kind(last),
        fd_peak_growth_by_kind=by_kind(peak_fds),
    )
    check(
        "threads_flat_after_warmup",
        max(last["threads"], peak_threads) - warm["threads"] <= args.max_thread_growth,
        "%d after warm-up, %d at the end, at most %d (limit +%d)"
        % (warm["threads"], last["threads"], peak_threads, args.max_thread_growth),
    )
    check(
        "fds_flat_after_warmup",
        max(last["fds"], peak_fds["fds"]) - warm["fds"] <= args.max_fd_growth,
        "%d after warm-up, %d at the end%s, at most %d at %.0f s%s (limit +%d)"
        % (
            warm["fds"],
            last["fds"],
            kinds_text(by_kind(last)),
            peak_fds["fds"],
            peak_fds["t"],
            kinds_text(by_kind(peak_fds)),
            args.max_fd_growth,
        ),
    )
    result.update(summary=summary, checks=checks, passed=all(c["pass"] for c in checks))


def table(result: Dict[str, Any]) -> str:
    lines = [
        "%8s %9s %6s %9s %7s %5s %5s %5s %6s %6s %5s %7s %7s"
        % (
            "t (s)",
            "sim (s)",
            "RTF",
            "RSS MiB",
            "threads",
            "fds",
            "sock",
            "epoll",
            "spawns",
            "dels",
            "fail",
            "odom/s",
            "scan/s",
        )
    ]
    previous = None
    for sample in result["samples"]:
        rtf = odom = scan = "-"
        if previous is not None and sample["t"] > previous["t"]:
            wall = sample["t"] - previous["t"]
            if sample["sim_time"] is not None and previous["sim_time"] is not None:
                rtf = "%.2f" % ((sample["sim_time"] - previous["sim_time"]) / wall)
            odom = "%.0f" % ((sample["odom_messages"] - previous["odom_messages"]) / wall)
            scan = "%.0f" % ((sample["scan_messages"] - previous["scan_messages"]) / wall)
        lines.append(
            "%8.1f %9.1f %6s %9.2f %7d %5d %5d %5d %6d %6d %5d %7s %7s"
            % (
                sample["t"],
                sample["sim_time"] or 0.0,
                rtf,
                sample["rss_mib"],
                sample["threads"],
                sample["fds"],
                sample["fd_kinds"].get("socket", 0),
                sample["fd_kinds"].get("eventpoll", 0),
                sample["spawns"],
                sample["deletes"],
                sample["failures"],
                odom,
                scan,
            )
        )
        previous = sample
    summary = result.get("summary", {})
    if "rss_end_mib" in summary:
        s = summary
        lines += [
            "",
            "warm-up: %.0f s (sample at %.1f s)" % (result["warmup_s"], s["warmup_sample_t"]),
            "RSS: start %.2f MiB, after warm-up %.2f MiB, end %.2f MiB (max %.2f): %+.2f MiB after warm-up = %s MiB/min,"
            " trend %s MiB/min"
            % (
                s["rss_start_mib"],
                s["rss_warmup_mib"],
                s["rss_end_mib"],
                s["rss_max_mib"],
                s["rss_growth_mib"],
                "n/a" if s["rss_growth_mib_per_min"] is None else "%.2f" % s["rss_growth_mib_per_min"],
                "n/a" if s["rss_slope_mib_per_min"] is None else "%.2f" % s["rss_slope_mib_per_min"],
            ),
            "threads: start %d, after warm-up %d, end %d (%+d; peak after warm-up %d; most seen %d)"
            % (
                s["threads_start"],
                s["threads_warmup"],
                s["threads_end"],
                s["threads_growth"],
                s["threads_peak_after_warmup"],
                s["threads_max"],
            ),
            "fds: start %d, after warm-up %d, end %d (%+d%s; peak after warm-up %d%s; most seen %d)"
            % (
                s["fds_start"],
                s["fds_warmup"],
                s["fds_end"],
                s["fds_growth"],
                kinds_text(s["fd_growth_by_kind"]),
                s["fds_peak_after_warmup"],
                kinds_text(s["fd_peak_growth_by_kind"]),
                s["fds_max"],
            ),
            "fds by kind: after warm-up %s, end %s" % (s["fd_kinds_warmup"], s["fd_kinds_end"]),
            "sim time: %.1f s in %.1f s wall: RTF %.2f; simulator CPU %.1f s"
            % (s["sim_time_advanced_s"], s["wall_s"], s["rtf"] or 0.0, s["cpu_s"]),
        ]
    if summary:
        lines.append(
            "spawns: %d %s (%d failed); deletes: %d (%d failed)"
            % (
                summary["spawns"],
                summary["spawns_by_kind"],
                summary["spawn_failures"],
                summary["deletes"],
                summary["delete_failures"],
            )
        )
        for kind in ("spawn", "delete"):
            latency = summary.get("%s_latency_s" % kind)
            if latency:
                lines.append(
                    "%s calls: mean %.1f ms, p99 %.1f ms, max %.1f ms"
                    % (kind, 1000 * latency["mean"], 1000 * latency["p99"], 1000 * latency["max"])
                )
        if "after_cleanup" in summary:
            cleanup = summary["after_cleanup"]
            lines.append(
                "after deleting every soak model: RSS %.2f MiB, %d threads, %d fds %s"
                % (cleanup["rss_mib"], cleanup["threads"], cleanup["fds"], cleanup["fd_kinds"])
            )
        for message in summary["failure_messages"]:
            lines.append("FAILED: " + message)
    lines.append("")
    for item in result.get("checks", []):
        lines.append("%-27s %s  %s" % (item["name"], "PASS" if item["pass"] else "FAIL", item["detail"]))
    return "\n".join(lines)
