// Reads the nested camera parameters that params.launch loads from config/cameras.yaml; a missing or
// mistyped parameter is a fatal start-up error that names it.
#include <ros/ros.h>

#include <string>

#include "beginner_tutorials/params.h"

namespace
{
bool logCamera(const ros::NodeHandle& private_nh, const std::string& side)
{
  std::string name;
  double exposure;
  if (!beginner_tutorials::readRequiredParam(private_nh, "cameras/" + side + "/name", &name) ||
      !beginner_tutorials::readRequiredParam(private_nh, "cameras/" + side + "/exposure", &exposure))
    return false;
  ROS_INFO("%s camera: name [%s], exposure [%g]", side.c_str(), name.c_str(), exposure);
  return true;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "param_demo");
  ros::NodeHandle private_nh("~");
  if (!logCamera(private_nh, "left") || !logCamera(private_nh, "right"))
    return 1;
  ros::spin();
  return 0;
}
