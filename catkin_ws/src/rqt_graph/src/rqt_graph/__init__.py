"""Drop-in rqt_graph: the ROS computation graph (nodes, topics, connections) laid out by graphviz."""
