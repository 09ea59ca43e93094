#include "my_first_rospkg/ros_helpers.h"

#include <atomic>
#include <cmath>
#include <csignal>

#include "beginner_tutorials/params.h"

namespace my_first_rospkg
{
namespace
{
std::atomic<bool> g_shutdown_requested(false);

void onSigint(int /*signal*/)
{
  g_shutdown_requested = true;
}
}  // namespace

bool readPositive(const ros::NodeHandle& nh, const std::string& name, double fallback, double* value)
{
  if (!beginner_tutorials::readParam(nh, name, fallback, value))
    return false;
  if (std::isfinite(*value) && *value > 0.0)
    return true;
  ROS_FATAL("Parameter [%s] must be a finite number > 0, got [%g]", nh.resolveName(name).c_str(), *value);
  return false;
}

bool readPositiveInt(const ros::NodeHandle& nh, const std::string& name, int fallback, int* value)
{
  if (!beginner_tutorials::readParam(nh, name, fallback, value))
    return false;
  if (*value >= 1)
    return true;
  ROS_FATAL("Parameter [%s] must be an integer >= 1, got [%d]", nh.resolveName(name).c_str(), *value);
  return false;
}

bool readNonEmpty(const ros::NodeHandle& nh, const std::string& name, const std::string& fallback, std::string* value)
{
  if (!beginner_tutorials::readParam(nh, name, fallback, value))
    return false;
  if (!value->empty())
    return true;
  ROS_FATAL("Parameter [%s] must not be empty, got [%s]", nh.resolveName(name).c_str(), value->c_str());
  return false;
}

geometry_msgs::Twist toTwist(const Velocity& velocity)
{
  geometry_msgs::Twist twist;
  twist.linear.x = velocity.linear;
  twist.angular.z = velocity.angular;
  return twist;
}

Pose2D toPose2D(const nav_msgs::Odometry& odometry)
{
  const auto& p = odometry.pose.pose.position;
  const auto& q = odometry.pose.pose.orientation;
  Pose2D pose;
  pose.x = p.x;
  pose.y = p.y;
  pose.yaw = yawFromQuaternion(q.x, q.y, q.z, q.w);
  return pose;
}

void installShutdownFlag()
{
  std::signal(SIGINT, onSigint);
}

bool shutdownRequested()
{
  return g_shutdown_requested || !ros::ok();
}

void publishStop(const ros::Publisher& publisher)
{
  publisher.publish(geometry_msgs::Twist());
  // roscpp sends from its own thread and offers no flush: an immediate exit could drop the message.
  ros::WallDuration(0.2).sleep();
}

bool waitForRobot(const ros::Publisher& publisher)
{
  ros::WallRate poll(20.0);
  while (!shutdownRequested() &&
         (publisher.getNumSubscribers() == 0 || !ros::Time::isValid() || ros::Time::now().isZero()))
  {
    ros::spinOnce();
    poll.sleep();
  }
  return !shutdownRequested();
}

}  // namespace my_first_rospkg
