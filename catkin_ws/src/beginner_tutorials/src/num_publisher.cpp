// Publishes the custom message beginner_tutorials/Num on num, counting up at ~rate Hz.
#include <ros/ros.h>

#include "beginner_tutorials/Num.h"
#include "beginner_tutorials/params.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "num_publisher");
  ros::NodeHandle nh;
  double rate_hz;
  if (!beginner_tutorials::readRate(ros::NodeHandle("~"), "rate", 10.0, &rate_hz))
    return 1;

  ros::Publisher num_pub = nh.advertise<beginner_tutorials::Num>("num", 10);
  ros::Rate loop_rate(rate_hz);
  beginner_tutorials::Num msg;
  for (msg.num = 0; ros::ok(); ++msg.num)
  {
    num_pub.publish(msg);
    loop_rate.sleep();
  }
  return 0;
}
