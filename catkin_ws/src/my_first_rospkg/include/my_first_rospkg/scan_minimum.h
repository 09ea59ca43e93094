// ROS-free search of the closest return of a laser scan (REP 117 ranges). Twin of src/my_first_rospkg/scan.py.
#ifndef MY_FIRST_ROSPKG_SCAN_MINIMUM_H
#define MY_FIRST_ROSPKG_SCAN_MINIMUM_H

#include <cstddef>
#include <vector>

namespace my_first_rospkg
{
/// The closest return of a scan.
struct ScanMinimum
{
  bool found = false;      ///< false when no beam holds a usable range
  bool too_close = false;  ///< the closest object is nearer than range_min (a -inf beam): distance is range_min
  double distance = 0.0;   ///< m
  double angle = 0.0;      ///< rad, in the scan's frame
  std::size_t index = 0;   ///< beam index
};

/// The smallest range of `ranges` within [range_min, range_max], with its angle. Per REP 117, NaN beams
/// (erroneous) and +inf beams (nothing within range_max) are skipped, and a -inf beam (an object closer than
/// range_min) beats every finite one. Finite values outside [range_min, range_max] are skipped as invalid.
ScanMinimum findScanMinimum(const std::vector<float>& ranges, double angle_min, double angle_increment,
                            double range_min, double range_max);

}  // namespace my_first_rospkg

#endif  // MY_FIRST_ROSPKG_SCAN_MINIMUM_H
