// Makes one turtle copy another: input/pose in, output/cmd_vel out (the turtlesim mimic tutorial node).
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <turtlesim/Pose.h>

namespace
{
class Mimic
{
 public:
  Mimic()
  {
    ros::NodeHandle input_nh("input");
    ros::NodeHandle output_nh("output");
    twist_pub_ = output_nh.advertise<geometry_msgs::Twist>("cmd_vel", 1);
    pose_sub_ = input_nh.subscribe("pose", 1, &Mimic::poseCallback, this);
  }

 private:
  void poseCallback(const turtlesim::Pose::ConstPtr& pose)
  {
    geometry_msgs::Twist twist;
    twist.linear.x = pose->linear_velocity;
    twist.angular.z = pose->angular_velocity;
    twist_pub_.publish(twist);
  }

  ros::Publisher twist_pub_;
  ros::Subscriber pose_sub_;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "turtle_mimic");
  Mimic mimic;
  ros::spin();
  return 0;
}
