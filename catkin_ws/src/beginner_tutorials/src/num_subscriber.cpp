// Logs each beginner_tutorials/Num heard on num.
#include <ros/ros.h>

#include "beginner_tutorials/Num.h"

void numCallback(const beginner_tutorials::Num::ConstPtr& msg)
{
  ROS_INFO("I heard: [%lld]", static_cast<long long>(msg->num));
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "num_subscriber");
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe("num", 10, numCallback);
  ros::spin();
  return 0;
}
