// Calls add_two_ints with X and Y from the command line and prints the sum; exits 1 on any failure.
#include <ros/ros.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "beginner_tutorials/AddTwoInts.h"
#include "beginner_tutorials/checked_int.h"
#include "beginner_tutorials/params.h"

namespace
{
const char kUsage[] =
    "usage: add_two_ints_client X Y [--timeout SECONDS]  (X, Y: int64; timeout default ~timeout, 5 s)";

int usageError(const std::string& problem)
{
  std::fprintf(stderr, "%s\n%s\n", problem.c_str(), kUsage);
  return 1;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_client", ros::init_options::AnonymousName);

  // ros::init has removed remapping arguments; what is left is ours.
  std::vector<std::string> positional;
  std::string timeout_text;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--timeout")
    {
      if (i + 1 == argc)
        return usageError("--timeout needs a number of seconds");
      timeout_text = argv[++i];
    }
    else if (arg.compare(0, 10, "--timeout=") == 0)
      timeout_text = arg.substr(10);
    else if (arg == "-h" || arg == "--help")
      return usageError("Adds two integers with the add_two_ints service.");
    else
      positional.push_back(arg);
  }
  if (positional.size() != 2)
    return usageError("expected 2 integers, got " + std::to_string(positional.size()) + " arguments");
  int64_t a, b;
  for (size_t i = 0; i < 2; ++i)
  {
    if (!beginner_tutorials::parseInt64(positional[i], i == 0 ? &a : &b))
      return usageError("not an int64 integer: '" + positional[i] + "'");
  }

  if (!ros::master::check())
  {
    ROS_ERROR("no ROS master at %s", ros::master::getURI().c_str());
    return 1;
  }
  // The handle lives to the end: the node shuts down when its last handle goes.
  ros::NodeHandle nh;
  double timeout_s;
  if (!beginner_tutorials::readParam(ros::NodeHandle("~"), "timeout", 5.0, &timeout_s))
    return 1;
  if (!timeout_text.empty())
  {
    char* end = nullptr;
    timeout_s = std::strtod(timeout_text.c_str(), &end);
    if (end == timeout_text.c_str() || *end != '\0')
      return usageError("--timeout takes seconds, got '" + timeout_text + "'");
  }
  if (!(timeout_s > 0.0 && timeout_s <= beginner_tutorials::kMaxTimeout))
  {
    ROS_FATAL("timeout must be in (0, %g] s, got [%g]", beginner_tutorials::kMaxTimeout, timeout_s);
    return 1;
  }

  const std::string service_name = nh.resolveName("add_two_ints");
  if (!ros::service::waitForService(service_name, ros::Duration(timeout_s)))
  {
    ROS_ERROR("service %s did not come up within %g s", service_name.c_str(), timeout_s);
    return 1;
  }
  ros::ServiceClient client = nh.serviceClient<beginner_tutorials::AddTwoInts>(service_name);
  beginner_tutorials::AddTwoInts srv;
  srv.request.a = a;
  srv.request.b = b;
  if (!client.call(srv))
  {
    ROS_ERROR("Failed to call service %s for %lld + %lld", service_name.c_str(), static_cast<long long>(a),
              static_cast<long long>(b));
    return 1;
  }
  ROS_INFO("Sum: %lld", static_cast<long long>(srv.response.sum));
  return 0;
}
