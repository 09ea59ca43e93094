"""rqt_console for systems without ros-visualization's: the ROS log (/rosout_agg) in a filterable table."""
