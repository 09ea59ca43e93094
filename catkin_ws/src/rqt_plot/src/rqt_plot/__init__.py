"""rqt_plot for systems without ros-visualization's: numeric message fields plotted against time."""
