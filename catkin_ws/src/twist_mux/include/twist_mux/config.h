// twist_mux's `topics` and `locks` parameters: a list of {name, topic, timeout, priority} (upstream's form) or a
// dict {name: {topic, timeout, priority}} (the ROS 2 twist_mux's form).
#ifndef TWIST_MUX_CONFIG_H
#define TWIST_MUX_CONFIG_H

#include <stdexcept>
#include <string>
#include <vector>

#include <xmlrpcpp/XmlRpcValue.h>

#include "twist_mux/mux_core.h"

namespace twist_mux
{
// A bad entry; what() names the parameter, the entry and the value.
class ConfigError : public std::runtime_error
{
 public:
  using std::runtime_error::runtime_error;
};

// `param_name` only serves the error messages.
std::vector<InputSpec> parseInputs(const std::string& param_name, XmlRpc::XmlRpcValue& value);

}  // namespace twist_mux

#endif  // TWIST_MUX_CONFIG_H
