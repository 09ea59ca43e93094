"""ros_control in the simulator, ROS-free: transmissions and joint limits from the URDF, the simulated robot
hardware (gazebo_ros_control's DefaultRobotHWSim), the controller manager and the common controllers of
ros_controllers. The ros layer connects them to topics, services and actions."""
