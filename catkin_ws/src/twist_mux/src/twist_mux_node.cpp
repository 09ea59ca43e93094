#include <ros/ros.h>

#include "twist_mux/config.h"
#include "twist_mux/twist_mux.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "twist_mux");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  try
  {
    twist_mux::TwistMux mux(nh, private_nh);
    ros::spin();
  }
  catch (const twist_mux::ConfigError& error)
  {
    ROS_FATAL("Bad twist_mux configuration: %s", error.what());
    return 1;
  }
  return 0;
}
