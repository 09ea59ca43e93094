"""The benchmarks of scripts/bench_sim.py and scripts/bench_rqt.py, section by section, and their report."""
