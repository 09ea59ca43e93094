"""Drop-in rqt: the `rqt` main window and the table of the tools its Plugins menu opens."""
