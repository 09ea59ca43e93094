// Looks up ~fixed_frame -> ~robot_frame with tf2 at ~rate and publishes the distance from the first pose found.
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <string>

#include "beginner_tutorials/params.h"
#include "my_first_rospkg/ros_helpers.h"

namespace my_first_rospkg
{
class TfListenerNode
{
 public:
  TfListenerNode(ros::NodeHandle& nh, const std::string& fixed_frame, const std::string& robot_frame, double rate_hz)
      : fixed_frame_(fixed_frame),
        robot_frame_(robot_frame),
        listener_(buffer_),
        distance_pub_(nh.advertise<std_msgs::Float64>("distance_from_start", 10)),
        timer_(nh.createTimer(ros::Duration(1.0 / rate_hz), &TfListenerNode::onTimer, this))
  {
  }

 private:
  void onTimer(const ros::TimerEvent& /*event*/)
  {
    geometry_msgs::TransformStamped transform;
    try
    {
      transform = buffer_.lookupTransform(fixed_frame_, robot_frame_, ros::Time(0));
    }
    catch (const tf2::TransformException& error)
    {
      ROS_WARN_THROTTLE(5.0, "No transform [%s] -> [%s] yet: %s", fixed_frame_.c_str(), robot_frame_.c_str(),
                        error.what());
      return;
    }
    const auto& t = transform.transform.translation;
    if (!have_start_)
    {
      have_start_ = true;
      start_x_ = t.x;
      start_y_ = t.y;
      ROS_INFO("Start point in [%s]: x [%.3f], y [%.3f]", fixed_frame_.c_str(), t.x, t.y);
    }
    std_msgs::Float64 distance;
    distance.data = std::hypot(t.x - start_x_, t.y - start_y_);
    distance_pub_.publish(distance);
    ROS_INFO_THROTTLE(1.0, "Distance from start: [%.3f] m", distance.data);
  }

  std::string fixed_frame_;
  std::string robot_frame_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  ros::Publisher distance_pub_;
  ros::Timer timer_;
  bool have_start_ = false;
  double start_x_ = 0.0;
  double start_y_ = 0.0;
};

}  // namespace my_first_rospkg

int main(int argc, char** argv)
{
  ros::init(argc, argv, "tf_listener");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  std::string fixed_frame;
  std::string robot_frame;
  double rate_hz = 0.0;
  if (!my_first_rospkg::readNonEmpty(private_nh, "fixed_frame", "odom", &fixed_frame) ||
      !my_first_rospkg::readNonEmpty(private_nh, "robot_frame", "base_footprint", &robot_frame) ||
      !beginner_tutorials::readRate(private_nh, "rate", 10.0, &rate_hz))
    return 1;
  my_first_rospkg::TfListenerNode node(nh, fixed_frame, robot_frame, rate_hz);
  ros::spin();
  return 0;
}
