"""The window runner the workspace's rqt drop-ins share (rqt_graph, rqt_plot, rqt_console, rqt_logger_level, rqt).

A package of its own, not part of the rqt_gui drop-in: where the system's rqt_gui is installed and that drop-in
stands aside, a tool whose drop-in is still in use keeps its runner.
"""
