// Drives a square of ~side closed-loop on odometry (drive, stop, turn 90 degrees left; four times), then stops.
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "my_first_rospkg/motion.h"
#include "my_first_rospkg/ros_helpers.h"

namespace my_first_rospkg
{
class SquareNode
{
 public:
  SquareNode(ros::NodeHandle& nh, const SquareParams& params)
      : controller_(params),
        velocity_pub_(nh.advertise<geometry_msgs::Twist>("mobile_base/commands/velocity", 1)),
        odom_sub_(nh.subscribe("odom", 1, &SquareNode::onOdometry, this))
  {
  }

  bool done() const
  {
    return controller_.done();
  }

  void stop()
  {
    odom_sub_.shutdown();
    publishStop(velocity_pub_);
  }

 private:
  void onOdometry(const nav_msgs::Odometry& odometry)
  {
    if (controller_.done())
      return;
    const Pose2D pose = toPose2D(odometry);
    const SquareController::State before = controller_.state();
    const Velocity velocity = controller_.update(pose, odometry.header.stamp.toSec());
    if (controller_.state() != before)
      ROS_INFO("Square: %s at x [%.3f], y [%.3f], yaw [%.3f] (sides done [%d])", toString(controller_.state()), pose.x,
               pose.y, pose.yaw, controller_.sidesDone());
    velocity_pub_.publish(toTwist(velocity));
  }

  SquareController controller_;
  ros::Publisher velocity_pub_;
  ros::Subscriber odom_sub_;
};

}  // namespace my_first_rospkg

int main(int argc, char** argv)
{
  ros::init(argc, argv, "square", ros::init_options::NoSigintHandler);
  my_first_rospkg::installShutdownFlag();
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  my_first_rospkg::SquareParams params;
  if (!my_first_rospkg::readPositive(private_nh, "side", params.side, &params.side) ||
      !my_first_rospkg::readPositive(private_nh, "linear_speed", params.linear_speed, &params.linear_speed) ||
      !my_first_rospkg::readPositive(private_nh, "angular_speed", params.angular_speed, &params.angular_speed) ||
      !my_first_rospkg::readPositive(private_nh, "settle_time", params.settle_time, &params.settle_time) ||
      !my_first_rospkg::readPositive(private_nh, "distance_tolerance", params.distance_tolerance,
                                     &params.distance_tolerance) ||
      !my_first_rospkg::readPositive(private_nh, "angle_tolerance", params.angle_tolerance, &params.angle_tolerance) ||
      !my_first_rospkg::readPositive(private_nh, "gain", params.gain, &params.gain) ||
      !my_first_rospkg::readPositive(private_nh, "min_linear_speed", params.min_linear_speed,
                                     &params.min_linear_speed) ||
      !my_first_rospkg::readPositive(private_nh, "min_angular_speed", params.min_angular_speed,
                                     &params.min_angular_speed))
    return 1;

  my_first_rospkg::SquareNode node(nh, params);
  ros::WallRate poll(100.0);
  while (!my_first_rospkg::shutdownRequested() && !node.done())
  {
    ros::spinOnce();
    poll.sleep();
  }
  node.stop();
  ROS_INFO("Square: %s, robot stopped", node.done() ? "done" : "interrupted");
  ros::shutdown();
  return 0;
}
