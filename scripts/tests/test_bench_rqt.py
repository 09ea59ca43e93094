"""scripts/bench_rqt.py on a short run: it runs, stops what it started, and every section has figures; the plot
kept up with turtlesim and the console with its flood (the full run's figures are quoted in the READMEs)."""
import math

import pytest
from conftest import run_bench

TIMEOUT_S = 600  # about 60 s on 2 idle cores


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    json_path = str(tmp_path_factory.mktemp("bench") / "bench_rqt.json")
    short = ["--minutes", "0.25", "--data-minutes", "0.5", "--console-seconds", "3"]
    return run_bench("bench_rqt.py", short, json_path, "CPU stolen by the host", TIMEOUT_S)


def test_plot_sections(results):
    injected, real = results["plot_injected"], results["plot_real_time"]
    assert injected["points_per_curve_at_end"] == int(0.5 * 60 * 62.5)
    for section in (injected, real):
        for when in ("frame_first_minute", "frame_last_minute", "frame_fresh_last_minute"):
            assert section[when]["count"] > 0 and math.isfinite(section[when]["median_ms"]), section
        assert section["rss_mib_end"] > 0
    # turtlesim publishes at 62.5 Hz; a busy machine may lose the odd message on the way
    assert real["points_received"] >= 0.9 * real["points_expected"] > 0


def test_console_section_kept_up(results):
    console = results["console"]
    assert console["sent"] == 3000 and console["received"] == console["sent"] == console["kept"]
    assert console["newest_on_top"]
    assert console["event_loop_latency"]["count"] > 0 and console["batch_insert"]["count"] > 0
    assert console["event_loop_latency_idle"]["count"] > 0
    assert 0.0 <= results["machine"]["stolen_cpu_share"] < 1.0
