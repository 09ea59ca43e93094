#include "twist_mux/mux_core.h"

#include <algorithm>

namespace twist_mux
{
namespace
{
Input makeInput(const InputSpec& spec)
{
  Input input;
  input.spec = spec;
  input.spec.priority = std::min(std::max(spec.priority, kMinPriority), kMaxPriority);
  return input;
}
}  // namespace

bool Input::hasExpired(double now) const
{
  return spec.timeout > 0.0 && now - stamp > spec.timeout;
}

size_t MuxCore::addVelocity(const InputSpec& spec)
{
  velocities_.push_back(makeInput(spec));
  return velocities_.size() - 1;
}

size_t MuxCore::addLock(const InputSpec& spec)
{
  locks_.push_back(makeInput(spec));
  return locks_.size() - 1;
}

bool MuxCore::velocityReceived(size_t index, double now)
{
  velocities_.at(index).stamp = now;
  return selected(now) == static_cast<int>(index);
}

void MuxCore::lockReceived(size_t index, bool locked, double now)
{
  Input& lock = locks_.at(index);
  lock.stamp = now;
  lock.locked = locked;
}

bool MuxCore::isLocked(size_t index, double now) const
{
  const Input& lock = locks_.at(index);
  return lock.hasExpired(now) || lock.locked;
}

int MuxCore::lockPriority(double now) const
{
  int priority = 0;
  for (size_t i = 0; i < locks_.size(); ++i)
  {
    if (isLocked(i, now))
    {
      priority = std::max(priority, locks_[i].spec.priority);
    }
  }
  return priority;
}

bool MuxCore::isMasked(size_t index, int lock_priority, double now) const
{
  const Input& velocity = velocities_.at(index);
  return velocity.hasExpired(now) || velocity.spec.priority < lock_priority;
}

int MuxCore::selected(double now) const
{
  const int lock_priority = lockPriority(now);
  int best_priority = 0;  // as upstream: an input of priority 0 never passes
  int best = -1;
  for (size_t i = 0; i < velocities_.size(); ++i)
  {
    if (!isMasked(i, lock_priority, now) && velocities_[i].spec.priority > best_priority)
    {
      best_priority = velocities_[i].spec.priority;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace twist_mux
