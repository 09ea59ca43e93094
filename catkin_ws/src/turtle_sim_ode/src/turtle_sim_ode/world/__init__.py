"""Named models in one world: the simulation, Gazebo's world API without ROS, model plugins and the drive."""
