// Drives ~laps circles of ~radius at ~speed, then stops the robot.
#include <ros/ros.h>

#include <memory>

#include "beginner_tutorials/params.h"
#include "my_first_rospkg/ros_helpers.h"
#include "my_first_rospkg/trajectory_driver.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "circle", ros::init_options::NoSigintHandler);
  my_first_rospkg::installShutdownFlag();
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double radius = 0.0;
  double speed = 0.0;
  double laps = 0.0;
  double rate_hz = 0.0;
  if (!my_first_rospkg::readPositive(private_nh, "radius", 1.0, &radius) ||
      !my_first_rospkg::readPositive(private_nh, "speed", 0.3, &speed) ||
      !my_first_rospkg::readPositive(private_nh, "laps", 1.0, &laps) ||
      !beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz))
    return 1;

  my_first_rospkg::TrajectoryDriver driver(
      nh, std::unique_ptr<my_first_rospkg::TimedTrajectory>(new my_first_rospkg::CircleTrajectory(radius, speed, laps)),
      rate_hz, "circle");
  driver.run();
  ros::shutdown();
  return 0;
}
