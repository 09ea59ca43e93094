"""Drop-in rqt: the standalone runner of the workspace's rqt tools and the `rqt` main window."""
