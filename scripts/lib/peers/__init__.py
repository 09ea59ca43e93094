"""The benchmarks' peers (PyBullet, offscreen renderers), each run by the Python of a venv of its own."""
