// Serves add_two_ints (the "Writing a Simple Service and Client" tutorial), refusing sums that overflow int64.
#include <ros/ros.h>

#include "beginner_tutorials/AddTwoInts.h"
#include "beginner_tutorials/checked_int.h"

bool add(beginner_tutorials::AddTwoInts::Request& req, beginner_tutorials::AddTwoInts::Response& res)
{
  int64_t sum;
  if (!beginner_tutorials::checkedAdd(req.a, req.b, &sum))
  {
    ROS_ERROR("request refused: %lld + %lld overflows int64", static_cast<long long>(req.a),
              static_cast<long long>(req.b));
    return false;
  }
  res.sum = sum;
  ROS_INFO("request: x=%lld, y=%lld", static_cast<long long>(req.a), static_cast<long long>(req.b));
  ROS_INFO("sending back response: [%lld]", static_cast<long long>(res.sum));
  return true;
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_server");
  ros::NodeHandle nh;
  ros::ServiceServer service = nh.advertiseService("add_two_ints", add);
  ROS_INFO("Ready to add two ints.");
  ros::spin();
  return 0;
}
