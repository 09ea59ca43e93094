// Resets the simulator, then drives turtle1 round a 2 m square (the turtlesim draw_square tutorial node).
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <turtlesim/Pose.h>

#include <string>
#include <vector>

#include "turtlesim/square_driver.h"

namespace
{
class DrawSquare
{
 public:
  explicit DrawSquare(ros::NodeHandle& nh)
  {
    pose_sub_ = nh.subscribe("turtle1/pose", 1, &DrawSquare::poseCallback, this);
    twist_pub_ = nh.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 1);
    timer_ = nh.createTimer(ros::Duration(0.016), &DrawSquare::timerCallback, this);
  }

 private:
  void poseCallback(const turtlesim::Pose::ConstPtr& pose)
  {
    pose_ = pose;
  }

  void timerCallback(const ros::TimerEvent&)
  {
    if (!pose_)
      return;
    std::vector<std::string> log;
    const turtlesim::SquareCommand command =
        driver_.step({ pose_->x, pose_->y, pose_->theta, pose_->linear_velocity, pose_->angular_velocity }, &log);
    for (const std::string& line : log)
      ROS_INFO("%s", line.c_str());
    geometry_msgs::Twist twist;
    twist.linear.x = command.linear;
    twist.angular.z = command.angular;
    twist_pub_.publish(twist);
  }

  turtlesim::SquareDriver driver_;
  turtlesim::Pose::ConstPtr pose_;
  ros::Subscriber pose_sub_;
  ros::Publisher twist_pub_;
  ros::Timer timer_;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "draw_square");
  ros::NodeHandle nh;
  ros::ServiceClient reset = nh.serviceClient<std_srvs::Empty>("reset");
  std_srvs::Empty empty;
  if (!reset.waitForExistence(ros::Duration(30.0)) || !reset.call(empty))
  {
    ROS_FATAL("Service [%s] did not answer: is turtlesim_node running?", reset.getService().c_str());
    return 1;
  }
  DrawSquare draw_square(nh);
  ros::spin();
  return 0;
}
