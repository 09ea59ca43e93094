"""The controller_manager commands (spawner, controller_manager, unspawner) as ros_control's Noetic scripts run
them, over the controller_manager_msgs services."""
