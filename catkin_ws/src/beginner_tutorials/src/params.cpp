#include "beginner_tutorials/params.h"

#include <cmath>

namespace beginner_tutorials
{
bool readRate(const ros::NodeHandle& nh, const std::string& name, double fallback, double* rate_hz)
{
  if (!readParam(nh, name, fallback, rate_hz))
    return false;
  if (std::isfinite(*rate_hz) && *rate_hz > 0.0)
    return true;
  ROS_FATAL("Parameter [%s] must be a rate in Hz > 0, got [%g]", nh.resolveName(name).c_str(), *rate_hz);
  return false;
}

}  // namespace beginner_tutorials
