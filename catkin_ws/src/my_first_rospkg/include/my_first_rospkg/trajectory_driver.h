// Plays a TimedTrajectory on the velocity topic at a fixed rate of ROS time (sim time under /use_sim_time).
#ifndef MY_FIRST_ROSPKG_TRAJECTORY_DRIVER_H
#define MY_FIRST_ROSPKG_TRAJECTORY_DRIVER_H

#include <ros/ros.h>

#include <memory>
#include <string>

#include "my_first_rospkg/motion.h"

namespace my_first_rospkg
{
class TrajectoryDriver
{
 public:
  /// Publishes on `mobile_base/commands/velocity` of `nh`.
  TrajectoryDriver(ros::NodeHandle& nh, std::unique_ptr<TimedTrajectory> trajectory, double rate_hz,
                   const std::string& name);
  /// Waits for the robot, drives the trajectory to its end (or shutdown) and stops the robot. False on shutdown.
  bool run();

 private:
  ros::Publisher velocity_pub_;
  std::unique_ptr<TimedTrajectory> trajectory_;
  double rate_hz_;
  std::string name_;
};

}  // namespace my_first_rospkg

#endif  // MY_FIRST_ROSPKG_TRAJECTORY_DRIVER_H
