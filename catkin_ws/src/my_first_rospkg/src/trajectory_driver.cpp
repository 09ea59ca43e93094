#include "my_first_rospkg/trajectory_driver.h"

#include <geometry_msgs/Twist.h>

#include <utility>

#include "my_first_rospkg/ros_helpers.h"

namespace my_first_rospkg
{
TrajectoryDriver::TrajectoryDriver(ros::NodeHandle& nh, std::unique_ptr<TimedTrajectory> trajectory, double rate_hz,
                                   const std::string& name)
    : velocity_pub_(nh.advertise<geometry_msgs::Twist>("mobile_base/commands/velocity", 1)),
      trajectory_(std::move(trajectory)),
      rate_hz_(rate_hz),
      name_(name)
{
}

bool TrajectoryDriver::run()
{
  if (!waitForRobot(velocity_pub_))
    return false;
  const ros::Time start = ros::Time::now();
  ROS_INFO("%s: driving for [%.2f] s", name_.c_str(), trajectory_->duration());
  ros::Rate rate(rate_hz_);
  bool completed = false;
  while (!shutdownRequested())
  {
    const double elapsed = (ros::Time::now() - start).toSec();
    if (elapsed >= trajectory_->duration())
    {
      completed = true;
      break;
    }
    velocity_pub_.publish(toTwist(trajectory_->velocityAt(elapsed)));
    ros::spinOnce();
    rate.sleep();
  }
  publishStop(velocity_pub_);
  ROS_INFO("%s: %s, robot stopped", name_.c_str(), completed ? "done" : "interrupted");
  return completed;
}

}  // namespace my_first_rospkg
