// Shows how a relative topic name "chatter" resolves through default, private, namespaced and global handles.
// Run it in a namespace (ROS_NAMESPACE=demo or <group ns="demo">) to see the difference.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <utility>
#include <vector>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "node_handles");
  const std::vector<std::pair<std::string, ros::NodeHandle>> handles = {
    { "default    ros::NodeHandle nh", ros::NodeHandle() },
    { "private    ros::NodeHandle nh(\"~\")", ros::NodeHandle("~") },
    { "namespaced ros::NodeHandle nh(\"sub\")", ros::NodeHandle("sub") },
    { "global     ros::NodeHandle nh(\"/\")", ros::NodeHandle("/") },
  };
  std::vector<ros::Publisher> publishers;
  for (const auto& label_and_handle : handles)
  {
    ros::NodeHandle nh = label_and_handle.second;
    ROS_INFO("%s: \"chatter\" -> %s", label_and_handle.first.c_str(), nh.resolveName("chatter").c_str());
    publishers.push_back(nh.advertise<std_msgs::String>("chatter", 1, true));
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
