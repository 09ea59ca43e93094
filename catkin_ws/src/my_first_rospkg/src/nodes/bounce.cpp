// Drives forwards and backwards inside |x| <= ~limit_x, |y| <= ~limit_y of odom: one command per odometry message.
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "my_first_rospkg/motion.h"
#include "my_first_rospkg/ros_helpers.h"

namespace my_first_rospkg
{
class BounceNode
{
 public:
  BounceNode(ros::NodeHandle& nh, double speed, double limit_x, double limit_y)
      : bouncer_(speed, limit_x, limit_y),
        velocity_pub_(nh.advertise<geometry_msgs::Twist>("mobile_base/commands/velocity", 1)),
        odom_sub_(nh.subscribe("odom", 1, &BounceNode::onOdometry, this))
  {
  }

  void stop()
  {
    odom_sub_.shutdown();
    publishStop(velocity_pub_);
  }

 private:
  void onOdometry(const nav_msgs::Odometry& odometry)
  {
    const Pose2D pose = toPose2D(odometry);
    const int before = bouncer_.direction();
    const Velocity velocity = bouncer_.update(pose);
    if (bouncer_.direction() != before)
      ROS_INFO("Reversing at x [%.3f], y [%.3f]", pose.x, pose.y);
    velocity_pub_.publish(toTwist(velocity));
  }

  Bouncer bouncer_;
  ros::Publisher velocity_pub_;
  ros::Subscriber odom_sub_;
};

}  // namespace my_first_rospkg

int main(int argc, char** argv)
{
  ros::init(argc, argv, "bounce", ros::init_options::NoSigintHandler);
  my_first_rospkg::installShutdownFlag();
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double speed = 0.0;
  double limit_x = 0.0;
  double limit_y = 0.0;
  if (!my_first_rospkg::readPositive(private_nh, "speed", 0.5, &speed) ||
      !my_first_rospkg::readPositive(private_nh, "limit_x", 2.0, &limit_x) ||
      !my_first_rospkg::readPositive(private_nh, "limit_y", 2.0, &limit_y))
    return 1;

  my_first_rospkg::BounceNode node(nh, speed, limit_x, limit_y);
  ros::WallRate poll(100.0);
  while (!my_first_rospkg::shutdownRequested())
  {
    ros::spinOnce();
    poll.sleep();
  }
  node.stop();
  ros::shutdown();
  return 0;
}
