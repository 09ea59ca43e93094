// Logs the closest return of each laser scan on ~topic (ETH "Programming for Robotics" exercise 2).
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <string>

#include "my_first_rospkg/ros_helpers.h"
#include "my_first_rospkg/scan_minimum.h"

namespace my_first_rospkg
{
class ScanMonitor
{
 public:
  ScanMonitor(ros::NodeHandle& nh, const std::string& topic, int queue_size)
      : scan_sub_(nh.subscribe(topic, queue_size, &ScanMonitor::onScan, this))
  {
    ROS_INFO("Monitoring scans on [%s]", scan_sub_.getTopic().c_str());
  }

 private:
  void onScan(const sensor_msgs::LaserScan& scan)
  {
    const ScanMinimum minimum =
        findScanMinimum(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min, scan.range_max);
    if (!minimum.found)
      ROS_WARN_THROTTLE(5.0, "No valid beam in a scan of [%zu] ranges", scan.ranges.size());
    else if (minimum.too_close)
      ROS_INFO("Smallest distance: closer than [%g] m at angle [%g] rad", minimum.distance, minimum.angle);
    else
      ROS_INFO("Smallest distance: [%g] m at angle [%g] rad", minimum.distance, minimum.angle);
  }

  ros::Subscriber scan_sub_;
};

}  // namespace my_first_rospkg

int main(int argc, char** argv)
{
  ros::init(argc, argv, "scan_monitor");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  std::string topic;
  int queue_size = 0;
  if (!my_first_rospkg::readNonEmpty(private_nh, "topic", "scan", &topic) ||
      !my_first_rospkg::readPositiveInt(private_nh, "queue_size", 1, &queue_size))
    return 1;
  my_first_rospkg::ScanMonitor monitor(nh, topic, queue_size);
  ros::spin();
  return 0;
}
