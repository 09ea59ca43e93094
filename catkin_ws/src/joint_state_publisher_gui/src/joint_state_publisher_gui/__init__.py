"""joint_state_publisher_gui as upstream's module offers it: ``JointStatePublisherGui(title, jsp, num_rows)``."""
from joint_state_publisher_gui.window import JointStatePublisherGui  # noqa: F401
