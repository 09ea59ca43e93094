// Publishes "<message> N" on chatter at ~rate Hz (the "Writing a Simple Publisher" tutorial).
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <string>

#include "beginner_tutorials/params.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");

  double rate_hz;
  std::string prefix;
  if (!beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz) ||
      !beginner_tutorials::readParam<std::string>(private_nh, "message", "hello world", &prefix))
    return 1;

  ros::Publisher chatter_pub = nh.advertise<std_msgs::String>("chatter", 1000);
  ros::Rate loop_rate(rate_hz);
  for (long count = 0; ros::ok(); ++count)
  {
    std_msgs::String msg;
    msg.data = prefix + " " + std::to_string(count);
    ROS_INFO("%s", msg.data.c_str());
    chatter_pub.publish(msg);
    ros::spinOnce();
    loop_rate.sleep();
  }
  return 0;
}
