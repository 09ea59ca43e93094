#include "twist_mux/config.h"

#include <map>
#include <sstream>

namespace twist_mux
{
namespace
{
std::string describe(XmlRpc::XmlRpcValue& value)
{
  std::ostringstream text;
  value.write(text);
  return text.str();
}

XmlRpc::XmlRpcValue& member(const std::string& where, XmlRpc::XmlRpcValue& entry, const std::string& name)
{
  if (!entry.hasMember(name))
  {
    throw ConfigError(where + " has no '" + name + "'");
  }
  return entry[name];
}

std::string stringMember(const std::string& where, XmlRpc::XmlRpcValue& entry, const std::string& name)
{
  XmlRpc::XmlRpcValue& value = member(where, entry, name);
  if (value.getType() != XmlRpc::XmlRpcValue::TypeString || static_cast<std::string>(value).empty())
  {
    throw ConfigError(where + "." + name + " [" + describe(value) + "] is not a non-empty string");
  }
  return value;
}

InputSpec parseEntry(const std::string& where, const std::string& name, XmlRpc::XmlRpcValue& entry)
{
  if (entry.getType() != XmlRpc::XmlRpcValue::TypeStruct)
  {
    throw ConfigError(where + " [" + describe(entry) + "] is not a dict of topic, timeout and priority");
  }
  InputSpec spec;
  spec.name = name.empty() ? stringMember(where, entry, "name") : name;
  spec.topic = stringMember(where, entry, "topic");
  XmlRpc::XmlRpcValue& timeout = member(where, entry, "timeout");
  if (timeout.getType() == XmlRpc::XmlRpcValue::TypeDouble)
  {
    spec.timeout = static_cast<double>(timeout);
  }
  else if (timeout.getType() == XmlRpc::XmlRpcValue::TypeInt)
  {
    spec.timeout = static_cast<int>(timeout);
  }
  else
  {
    throw ConfigError(where + ".timeout [" + describe(timeout) + "] is not a number");
  }
  if (!(spec.timeout >= 0.0))
  {
    throw ConfigError(where + ".timeout [" + describe(timeout) + "] is negative (0 means: never expires)");
  }
  XmlRpc::XmlRpcValue& priority = member(where, entry, "priority");
  if (priority.getType() != XmlRpc::XmlRpcValue::TypeInt)
  {
    throw ConfigError(where + ".priority [" + describe(priority) + "] is not an integer");
  }
  spec.priority = priority;
  return spec;
}
}  // namespace

std::vector<InputSpec> parseInputs(const std::string& param_name, XmlRpc::XmlRpcValue& value)
{
  std::vector<InputSpec> specs;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeArray)
  {
    for (int i = 0; i < value.size(); ++i)
    {
      specs.push_back(parseEntry(param_name + "[" + std::to_string(i) + "]", "", value[i]));
    }
  }
  else if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct)
  {
    for (auto& named : value)  // XmlRpcValue's struct is a std::map: in name order
    {
      specs.push_back(parseEntry(param_name + "." + named.first, named.first, named.second));
    }
  }
  else
  {
    throw ConfigError(param_name + " [" + describe(value) + "] is neither a list nor a dict");
  }
  return specs;
}

}  // namespace twist_mux
