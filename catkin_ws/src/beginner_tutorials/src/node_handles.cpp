// Shows how a topic name resolves through default, private and namespaced node handles, and as a global name.
// Run it in a namespace (ROS_NAMESPACE=demo or <group ns="demo">) to see the difference.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <string>
#include <vector>

namespace
{
struct NameExample
{
  std::string label;
  ros::NodeHandle handle;
  std::string name;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "node_handles");
  // A global name is spelt with a leading "/": ros::NodeHandle("/") is NOT global in roscpp, "/" is cleaned to an
  // empty namespace and names then resolve like the default handle's.
  const std::vector<NameExample> examples = {
    { "default    ros::NodeHandle nh;      nh.advertise(\"chatter\")", ros::NodeHandle(), "chatter" },
    { "private    ros::NodeHandle nh(\"~\");   nh.advertise(\"chatter\")", ros::NodeHandle("~"), "chatter" },
    { "namespaced ros::NodeHandle nh(\"sub\"); nh.advertise(\"chatter\")", ros::NodeHandle("sub"), "chatter" },
    { "global     ros::NodeHandle nh;      nh.advertise(\"/chatter\")", ros::NodeHandle(), "/chatter" },
  };
  std::vector<ros::Publisher> publishers;
  for (const NameExample& example : examples)
  {
    ros::NodeHandle nh = example.handle;
    ROS_INFO("%s -> %s", example.label.c_str(), nh.resolveName(example.name).c_str());
    publishers.push_back(nh.advertise<std_msgs::String>(example.name, 1, true));
  }
  for (ros::Publisher& publisher : publishers)
  {
    std_msgs::String msg;
    msg.data = "published on " + publisher.getTopic();
    publisher.publish(msg);
  }
  ros::spin();
  return 0;
}
