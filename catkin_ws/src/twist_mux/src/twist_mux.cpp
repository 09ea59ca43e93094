#include "twist_mux/twist_mux.h"

#include <boost/bind/bind.hpp>

#include "twist_mux/config.h"

namespace twist_mux
{
namespace
{
// Upstream's twist_mux.h DIAGNOSTICS_PERIOD.
constexpr double kDiagnosticsPeriod = 1.0;

std::string describe(const Input& input)
{
  // The wording of upstream's diagnostics values (twist_mux_diagnostics.cpp), which monitoring may parse.
  char text[512];
  snprintf(text, sizeof(text), "(listening to %s @ %fs with priority #%d)", input.spec.topic.c_str(),
           input.spec.timeout, input.spec.priority);
  return text;
}
}  // namespace

TwistMux::TwistMux(ros::NodeHandle& nh, ros::NodeHandle& private_nh)
{
  for (const InputSpec& spec : readInputs(private_nh, "topics"))
  {
    const size_t index = core_.addVelocity(spec);
    subscribers_.push_back(nh.subscribe<geometry_msgs::Twist>(
        spec.topic, 1, boost::bind(&TwistMux::velocityCallback, this, index, boost::placeholders::_1)));
  }
  for (const InputSpec& spec : readInputs(private_nh, "locks"))
  {
    const size_t index = core_.addLock(spec);
    subscribers_.push_back(nh.subscribe<std_msgs::Bool>(
        spec.topic, 1, boost::bind(&TwistMux::lockCallback, this, index, boost::placeholders::_1)));
  }
  for (const auto* inputs : { &core_.velocities(), &core_.locks() })
  {
    for (const Input& input : *inputs)
    {
      ROS_INFO("Topic handler '%s' subscribed to topic '%s': timeout = %s, priority = %d", input.spec.name.c_str(),
               input.spec.topic.c_str(),
               input.spec.timeout > 0.0 ? (std::to_string(input.spec.timeout) + "s").c_str() : "None",
               input.spec.priority);
    }
  }
  cmd_pub_ = nh.advertise<geometry_msgs::Twist>("cmd_vel_out", 1);
  updater_.add("Twist mux status", this, &TwistMux::diagnose);
  updater_.setHardwareID("none");
  diagnostics_timer_ =
      nh.createTimer(ros::Duration(kDiagnosticsPeriod), [this](const ros::TimerEvent&) { updater_.update(); });
}

std::vector<InputSpec> TwistMux::readInputs(ros::NodeHandle& private_nh, const std::string& param_name) const
{
  XmlRpc::XmlRpcValue value;
  if (!private_nh.getParam(param_name, value))
  {
    ROS_WARN("No ~%s parameter (namespace %s): none used", param_name.c_str(), private_nh.getNamespace().c_str());
    return {};
  }
  std::vector<InputSpec> specs = parseInputs("~" + param_name, value);
  for (const InputSpec& spec : specs)
  {
    if (spec.priority < kMinPriority || spec.priority > kMaxPriority)
    {
      ROS_WARN("~%s '%s': priority [%d] clamped to [%d, %d]", param_name.c_str(), spec.name.c_str(), spec.priority,
               kMinPriority, kMaxPriority);
    }
  }
  return specs;
}

void TwistMux::velocityCallback(size_t index, const geometry_msgs::Twist::ConstPtr& msg)
{
  if (core_.velocityReceived(index, ros::Time::now().toSec()))
  {
    cmd_pub_.publish(*msg);
  }
}

void TwistMux::lockCallback(size_t index, const std_msgs::Bool::ConstPtr& msg)
{
  core_.lockReceived(index, msg->data, ros::Time::now().toSec());
}

void TwistMux::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  const double now = ros::Time::now().toSec();
  const int lock_priority = core_.lockPriority(now);
  // Upstream measures neither the loop time nor the data age (both stay 0): its summary is always "ok".
  status.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  for (size_t i = 0; i < core_.velocities().size(); ++i)
  {
    const Input& velocity = core_.velocities()[i];
    status.add("velocity " + velocity.spec.name,
               std::string(core_.isMasked(i, lock_priority, now) ? " masked " : " unmasked ") + describe(velocity));
  }
  for (size_t i = 0; i < core_.locks().size(); ++i)
  {
    const Input& lock = core_.locks()[i];
    status.add("lock " + lock.spec.name, std::string(core_.isLocked(i, now) ? " locked " : " free ") + describe(lock));
  }
  status.add("current priority", lock_priority);
  status.add("loop time in [sec]", 0.0);
  status.add("data age in [sec]", 0.0);
}

}  // namespace twist_mux
