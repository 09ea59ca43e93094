"""A master snapshot of the tutorials' turtlesim session (tutorial 6), plus a dead node and a debugging viewer."""
from rqt_graph.graph_model import Connection, SystemState


def turtlesim_session() -> SystemState:
    return SystemState(
        publishers={
            "/turtle1/cmd_vel": ["/teleop_turtle"],
            "/turtle1/pose": ["/turtlesim"],
            "/turtle1/color_sensor": ["/turtlesim"],
            "/rosout": ["/turtlesim", "/teleop_turtle", "/rqt_gui_py_node_42", "/ghost"],
            "/rosout_agg": ["/rosout"],
            "/chatter": ["/ghost"],
        },
        subscribers={
            "/turtle1/cmd_vel": ["/turtlesim"],
            "/rosout": ["/rosout"],
            "/turtle1/pose": ["/rqt_gui_py_node_42"],
            "/chatter": ["/listener"],
        },
        nodes={"/turtlesim", "/teleop_turtle", "/rosout", "/rqt_gui_py_node_42", "/ghost", "/listener"},
        connections={
            # getBusInfo rows as the nodes themselves report them (inbound rows name the publisher by URI, which
            # ros_query resolves to a node name; outbound rows name the subscriber)
            "/turtlesim": [
                Connection("/teleop_turtle", "i", "/turtle1/cmd_vel"),
                Connection("/rosout", "o", "/rosout"),
                Connection("/rqt_gui_py_node_42", "o", "/turtle1/pose"),
            ],
            "/teleop_turtle": [
                Connection("/turtlesim", "o", "/turtle1/cmd_vel"),
                Connection("/rosout", "o", "/rosout"),
            ],
            "/rosout": [Connection("/turtlesim", "i", "/rosout"), Connection("/teleop_turtle", "i", "/rosout")],
            "/rqt_gui_py_node_42": [Connection("/turtlesim", "i", "/turtle1/pose")],
            "/ghost": None,  # did not answer getBusInfo in time
            "/listener": [Connection("", "i", "/chatter", connected=False)],
        },
    )
