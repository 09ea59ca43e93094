// The ETH course's first node: a ros::Rate loop that logs, plus one message at each severity.
#include <ros/ros.h>

#include "beginner_tutorials/params.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "hello_world");
  ros::NodeHandle private_nh("~");
  double rate_hz;
  int count_limit;  // 0 = run until shut down
  if (!beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz) ||
      !beginner_tutorials::readParam(private_nh, "count", 0, &count_limit))
    return 1;

  ROS_DEBUG("DEBUG: shown only when the logger level is debug");
  ROS_INFO("INFO: normal operation");
  ROS_WARN("WARN: something unexpected that the node can live with");
  ROS_ERROR("ERROR: something failed, the node goes on");
  ROS_FATAL("FATAL: an example only, this node keeps running");

  ros::Rate loop_rate(rate_hz);
  for (int count = 0; ros::ok() && (count_limit <= 0 || count < count_limit); ++count)
  {
    ROS_INFO_STREAM("Hello World " << count);
    ros::spinOnce();
    loop_rate.sleep();
  }
  return 0;
}
