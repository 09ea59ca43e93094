#ifndef BEGINNER_TUTORIALS_PARAMS_H
#define BEGINNER_TUTORIALS_PARAMS_H

#include <ros/ros.h>

#include <string>

namespace beginner_tutorials
{
/// Reads parameter `name` of `nh` into *value, or `fallback` when it is not set. A parameter that is set with
/// the wrong type (a string where a number belongs, ...) is logged as fatal, naming it, and returns false:
/// roscpp's own param() would silently fall back to the default instead.
template <typename T>
bool readParam(const ros::NodeHandle& nh, const std::string& name, const T& fallback, T* value)
{
  if (!nh.hasParam(name))
  {
    *value = fallback;
    return true;
  }
  if (nh.getParam(name, *value))
    return true;
  ROS_FATAL("Parameter [%s] has the wrong type", nh.resolveName(name).c_str());
  return false;
}

/// Like readParam, but a missing parameter is fatal too.
template <typename T>
bool readRequiredParam(const ros::NodeHandle& nh, const std::string& name, T* value)
{
  if (!nh.hasParam(name))
  {
    ROS_FATAL("Required parameter [%s] is missing", nh.resolveName(name).c_str());
    return false;
  }
  return readParam(nh, name, *value, value);
}

/// Reads a loop rate in Hz (default `fallback`), fatal unless it is a finite number > 0.
bool readRate(const ros::NodeHandle& nh, const std::string& name, double fallback, double* rate_hz);

}  // namespace beginner_tutorials

#endif  // BEGINNER_TUTORIALS_PARAMS_H
