// Turns the TurtleBot in place: a Twist with angular.z = ~angular_speed on mobile_base/commands/velocity at ~rate.
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

#include "beginner_tutorials/params.h"
#include "my_first_rospkg/ros_helpers.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "my_first_rospkg_node", ros::init_options::NoSigintHandler);
  my_first_rospkg::installShutdownFlag();
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double rate_hz = 0.0;
  double angular_speed = 0.0;
  if (!beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz) ||
      !beginner_tutorials::readParam(private_nh, "angular_speed", 0.5, &angular_speed))
    return 1;

  ros::Publisher velocity_pub = nh.advertise<geometry_msgs::Twist>("mobile_base/commands/velocity", 1);
  my_first_rospkg::Velocity velocity;
  velocity.angular = angular_speed;
  const geometry_msgs::Twist twist = my_first_rospkg::toTwist(velocity);
  ROS_INFO("Turning in place at [%g] rad/s", angular_speed);
  ros::Rate rate(rate_hz);
  while (!my_first_rospkg::shutdownRequested())
  {
    velocity_pub.publish(twist);
    ros::spinOnce();
    rate.sleep();
  }
  my_first_rospkg::publishStop(velocity_pub);
  ros::shutdown();
  return 0;
}
