// Drives an Archimedean spiral from ~initial_radius to ~max_radius, growing by ~growth_rate per radian turned.
#include <ros/ros.h>

#include <memory>

#include "beginner_tutorials/params.h"
#include "my_first_rospkg/ros_helpers.h"
#include "my_first_rospkg/trajectory_driver.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "spiral", ros::init_options::NoSigintHandler);
  my_first_rospkg::installShutdownFlag();
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double initial_radius = 0.0;
  double growth_rate = 0.0;
  double angular_speed = 0.0;
  double max_radius = 0.0;
  double rate_hz = 0.0;
  if (!my_first_rospkg::readPositive(private_nh, "initial_radius", 0.2, &initial_radius) ||
      !my_first_rospkg::readPositive(private_nh, "growth_rate", 0.04, &growth_rate) ||
      !my_first_rospkg::readPositive(private_nh, "angular_speed", 0.5, &angular_speed) ||
      !my_first_rospkg::readPositive(private_nh, "max_radius", 1.0, &max_radius) ||
      !beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz))
    return 1;
  if (max_radius <= initial_radius)
  {
    ROS_FATAL("Parameter [%s] must be > ~initial_radius [%g], got [%g]", private_nh.resolveName("max_radius").c_str(),
              initial_radius, max_radius);
    return 1;
  }

  my_first_rospkg::TrajectoryDriver driver(
      nh,
      std::unique_ptr<my_first_rospkg::TimedTrajectory>(
          new my_first_rospkg::SpiralTrajectory(initial_radius, growth_rate, angular_speed, max_radius)),
      rate_hz, "spiral");
  driver.run();
  ros::shutdown();
  return 0;
}
