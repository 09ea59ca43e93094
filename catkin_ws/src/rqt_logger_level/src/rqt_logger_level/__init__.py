"""Drop-in rqt_logger_level: see and set the logger levels of running nodes."""
