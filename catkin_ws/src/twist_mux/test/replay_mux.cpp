// Feeds a schedule from stdin through MuxCore, one answer a line on stdout, for test/unit/test_mux_rules.py.
//   velocity <priority> <timeout> | lock <priority> <timeout>   declare an input (indices count from 0 per kind)
//   v <index> <time>          a command: prints "<forwarded 0|1> <selected> <lock priority>"
//   l <index> <0|1> <time>    a lock message: prints "- <selected> <lock priority>"
#include <iostream>
#include <string>

#include "twist_mux/mux_core.h"

int main()
{
  twist_mux::MuxCore core;
  std::string word;
  while (std::cin >> word)
  {
    if (word == "velocity" || word == "lock")
    {
      twist_mux::InputSpec spec;
      std::cin >> spec.priority >> spec.timeout;
      spec.name = spec.topic = word;
      word == "velocity" ? core.addVelocity(spec) : core.addLock(spec);
      continue;
    }
    size_t index;
    double now;
    std::string forwarded = "-";
    if (word == "v")
    {
      std::cin >> index >> now;
      forwarded = core.velocityReceived(index, now) ? "1" : "0";
    }
    else
    {
      int locked;
      std::cin >> index >> locked >> now;
      core.lockReceived(index, locked != 0, now);
    }
    std::cout << forwarded << " " << core.selected(now) << " " << core.lockPriority(now) << std::endl;
  }
  return 0;
}
