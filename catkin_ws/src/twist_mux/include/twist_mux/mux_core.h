// The rules of twist_mux (ros-teleop/twist_mux 3.1.3, noetic-devel) without ROS: which velocity input passes,
// given the inputs' priorities and timeouts and the locks' states. Times are seconds of ROS time.
#ifndef TWIST_MUX_MUX_CORE_H
#define TWIST_MUX_MUX_CORE_H

#include <string>
#include <vector>

namespace twist_mux
{
constexpr int kMinPriority = 0;
constexpr int kMaxPriority = 255;

// One entry of the `topics` or `locks` list.
struct InputSpec
{
  std::string name;
  std::string topic;
  double timeout;  // s; 0 = never expires
  int priority;    // clamped to [kMinPriority, kMaxPriority]
};

// An input and what arrived on it last.
struct Input
{
  InputSpec spec;
  double stamp = 0.0;   // the time of the last message; 0 before the first, so a timed input starts expired
  bool locked = false;  // locks only: the last std_msgs/Bool

  bool hasExpired(double now) const;
};

class MuxCore
{
 public:
  // Both return the new input's index.
  size_t addVelocity(const InputSpec& spec);
  size_t addLock(const InputSpec& spec);

  // A command arrived on velocity input `index` at `now`: true when it is to be published.
  bool velocityReceived(size_t index, double now);
  void lockReceived(size_t index, bool locked, double now);

  // A lock holds while its last message said true, or while it is expired (its publisher died).
  bool isLocked(size_t index, double now) const;
  // The highest priority of the locks that hold, 0 when none does.
  int lockPriority(double now) const;
  // An expired velocity input, or one below the lock priority, is masked.
  bool isMasked(size_t index, int lock_priority, double now) const;
  // The velocity input whose commands pass now, or -1: the unmasked one of highest priority above 0, the first
  // in configuration order among equals.
  int selected(double now) const;

  const std::vector<Input>& velocities() const
  {
    return velocities_;
  }
  const std::vector<Input>& locks() const
  {
    return locks_;
  }

 private:
  std::vector<Input> velocities_;
  std::vector<Input> locks_;
};

}  // namespace twist_mux

#endif  // TWIST_MUX_MUX_CORE_H
