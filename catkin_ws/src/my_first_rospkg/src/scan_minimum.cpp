#include "my_first_rospkg/scan_minimum.h"

#include <cmath>

namespace my_first_rospkg
{
ScanMinimum findScanMinimum(const std::vector<float>& ranges, double angle_min, double angle_increment,
                            double range_min, double range_max)
{
  ScanMinimum minimum;
  for (std::size_t i = 0; i < ranges.size(); ++i)
  {
    const double range = ranges[i];
    const bool too_close = std::isinf(range) && range < 0.0;
    const bool valid = std::isfinite(range) && range >= range_min && range <= range_max;
    if (!too_close && !valid)
      continue;
    const double distance = too_close ? range_min : range;
    const bool better = !minimum.found || (too_close && !minimum.too_close) ||
                        (too_close == minimum.too_close && distance < minimum.distance);
    if (!better)
      continue;
    minimum.found = true;
    minimum.too_close = too_close;
    minimum.distance = distance;
    minimum.angle = angle_min + static_cast<double>(i) * angle_increment;
    minimum.index = i;
  }
  return minimum;
}

}  // namespace my_first_rospkg
