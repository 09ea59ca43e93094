// The ROS side of twist_mux: one subscriber per input and lock, `cmd_vel_out`, and the diagnostics.
#ifndef TWIST_MUX_TWIST_MUX_H
#define TWIST_MUX_TWIST_MUX_H

#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <std_msgs/Bool.h>

#include "twist_mux/mux_core.h"

namespace twist_mux
{
class TwistMux
{
 public:
  // Reads ~topics and ~locks; throws ConfigError on a bad entry.
  TwistMux(ros::NodeHandle& nh, ros::NodeHandle& private_nh);

 private:
  std::vector<InputSpec> readInputs(ros::NodeHandle& private_nh, const std::string& param_name) const;
  void velocityCallback(size_t index, const geometry_msgs::Twist::ConstPtr& msg);
  void lockCallback(size_t index, const std_msgs::Bool::ConstPtr& msg);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  MuxCore core_;
  std::vector<ros::Subscriber> subscribers_;
  ros::Publisher cmd_pub_;
  diagnostic_updater::Updater updater_;
  ros::Timer diagnostics_timer_;
};

}  // namespace twist_mux

#endif  // TWIST_MUX_TWIST_MUX_H
