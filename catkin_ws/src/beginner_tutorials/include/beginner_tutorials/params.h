#ifndef BEGINNER_TUTORIALS_PARAMS_H
#define BEGINNER_TUTORIALS_PARAMS_H

#include <ros/ros.h>

#include <string>

namespace beginner_tutorials
{
/// True when `value` holds what a T parameter needs: roscpp's own getParam() converts silently (2.5 -> 2 for an
/// int, any int for a double), and its param() falls back to the default on a type mismatch.
template <typename T>
bool hasType(const XmlRpc::XmlRpcValue& value);

template <>
inline bool hasType<int>(const XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeInt;
}

template <>
inline bool hasType<double>(const XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeDouble || value.getType() == XmlRpc::XmlRpcValue::TypeInt;
}

template <>
inline bool hasType<bool>(const XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeBoolean;
}

template <>
inline bool hasType<std::string>(const XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeString;
}

/// Reads parameter `name` of `nh` into *value, or `fallback` when it is not set. A parameter of the wrong type
/// is logged as fatal, naming it, and returns false.
template <typename T>
bool readParam(const ros::NodeHandle& nh, const std::string& name, const T& fallback, T* value)
{
  XmlRpc::XmlRpcValue raw;
  if (!nh.getParam(name, raw))
  {
    *value = fallback;
    return true;
  }
  if (hasType<T>(raw) && nh.getParam(name, *value))
    return true;
  ROS_FATAL("Parameter [%s] has the wrong type: [%s]", nh.resolveName(name).c_str(), raw.toXml().c_str());
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
  return readParam(nh, name, T(), value);
}

/// Reads a loop rate in Hz (default `fallback`), fatal unless it is a finite number > 0.
bool readRate(const ros::NodeHandle& nh, const std::string& name, double fallback, double* rate_hz);

}  // namespace beginner_tutorials

#endif  // BEGINNER_TUTORIALS_PARAMS_H
