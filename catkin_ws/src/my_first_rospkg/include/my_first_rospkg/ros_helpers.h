// roscpp glue shared by the exercise nodes: checked parameters, message conversions and a shutdown flag that
// lets a node send its last zero Twist before it goes. Twin of src/my_first_rospkg/ros_helpers.py.
#ifndef MY_FIRST_ROSPKG_ROS_HELPERS_H
#define MY_FIRST_ROSPKG_ROS_HELPERS_H

#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include <string>

#include "my_first_rospkg/motion.h"

namespace my_first_rospkg
{
/// Reads a double parameter (default `fallback`), fatal unless it is a finite number > 0.
bool readPositive(const ros::NodeHandle& nh, const std::string& name, double fallback, double* value);

/// Reads an int parameter (default `fallback`), fatal unless it is >= 1.
bool readPositiveInt(const ros::NodeHandle& nh, const std::string& name, int fallback, int* value);

/// Reads a string parameter (default `fallback`), fatal when it is empty.
bool readNonEmpty(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback, std::string* value);

geometry_msgs::Twist toTwist(const Velocity& velocity);
Pose2D toPose2D(const nav_msgs::Odometry& odometry);

/// Replaces roscpp's SIGINT handler (call ros::init with ros::init_options::NoSigintHandler): Ctrl-C only sets a
/// flag, so the node can still publish before calling ros::shutdown().
void installShutdownFlag();
/// True once SIGINT arrived or roscpp is shutting down.
bool shutdownRequested();

/// Publishes a zero Twist and gives the publisher's thread a moment to send it before the node exits.
void publishStop(const ros::Publisher& publisher);

/// Waits (wall time) until a subscriber is connected to `publisher` and sim time is valid; false on shutdown.
bool waitForRobot(const ros::Publisher& publisher);

}  // namespace my_first_rospkg

#endif  // MY_FIRST_ROSPKG_ROS_HELPERS_H
