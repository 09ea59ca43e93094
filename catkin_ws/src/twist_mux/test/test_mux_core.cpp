// MuxCore against the rules of ros-teleop/twist_mux 3.1.3 (noetic-devel): topic_handle.h (TopicHandle_::hasExpired,
// VelocityTopicHandle::isMasked, LockTopicHandle::isLocked) and twist_mux.cpp (TwistMux::getLockPriority,
// TwistMux::hasPriority).
#include <gtest/gtest.h>

#include "twist_mux/mux_core.h"

using twist_mux::InputSpec;
using twist_mux::MuxCore;

namespace
{
// Upstream's config/twist_mux_topics.yaml and twist_mux_locks.yaml, in their order.
MuxCore upstreamExample()
{
  MuxCore core;
  core.addVelocity({ "navigation", "nav_vel", 0.5, 10 });
  core.addVelocity({ "joystick", "joy_vel", 0.5, 100 });
  core.addVelocity({ "keyboard", "key_vel", 0.5, 90 });
  core.addVelocity({ "tablet", "tab_vel", 0.5, 100 });
  core.addLock({ "pause", "pause_navigation", 0.0, 100 });
  core.addLock({ "loop_closure", "stop_closing_loop", 0.0, 200 });
  core.addLock({ "joystick", "joy_priority", 0.0, 100 });
  return core;
}
constexpr size_t kNavigation = 0, kJoystick = 1, kKeyboard = 2, kTablet = 3;
constexpr size_t kPause = 0, kLoopClosure = 1;
}  // namespace

TEST(MuxCore, TheOnlyFreshInputPasses)
{
  MuxCore core = upstreamExample();
  EXPECT_TRUE(core.velocityReceived(kNavigation, 10.0));
  EXPECT_EQ(core.selected(10.0), static_cast<int>(kNavigation));
}

TEST(MuxCore, AHigherPriorityInputSilencesALowerOneUntilItExpires)
{
  MuxCore core = upstreamExample();
  EXPECT_TRUE(core.velocityReceived(kKeyboard, 10.0));
  EXPECT_FALSE(core.velocityReceived(kNavigation, 10.1));
  // hasExpired: now - stamp > timeout, strictly
  EXPECT_FALSE(core.velocityReceived(kNavigation, 10.5));
  EXPECT_TRUE(core.velocityReceived(kNavigation, 10.6));
}

TEST(MuxCore, AmongEqualPrioritiesTheFirstConfiguredWins)
{
  // hasPriority keeps the first maximum (`priority < velocity_priority`): joystick before tablet.
  MuxCore core = upstreamExample();
  core.velocityReceived(kJoystick, 10.0);
  EXPECT_FALSE(core.velocityReceived(kTablet, 10.1));
  EXPECT_TRUE(core.velocityReceived(kJoystick, 10.2));
}

TEST(MuxCore, ALockMasksTheInputsBelowItsPriorityOnly)
{
  MuxCore core = upstreamExample();
  core.lockReceived(kPause, true, 10.0);
  EXPECT_EQ(core.lockPriority(10.0), 100);
  EXPECT_FALSE(core.velocityReceived(kNavigation, 10.1));
  EXPECT_FALSE(core.velocityReceived(kKeyboard, 10.1));
  // "Same priority as joystick control, so it'll not block it."
  EXPECT_TRUE(core.velocityReceived(kJoystick, 10.2));
  core.lockReceived(kLoopClosure, true, 10.3);
  EXPECT_EQ(core.lockPriority(10.3), 200);
  EXPECT_FALSE(core.velocityReceived(kJoystick, 10.4));
  core.lockReceived(kLoopClosure, false, 10.5);
  core.lockReceived(kPause, false, 10.5);
  EXPECT_EQ(core.lockPriority(10.5), 0);
  EXPECT_TRUE(core.velocityReceived(kNavigation, 11.0));
}

TEST(MuxCore, ATimedLockHoldsUntilItsFirstMessageAndAfterItsPublisherStops)
{
  // upstream test/system_config.yaml's emergency_255: timeout 0.5, priority 255
  MuxCore core;
  core.addVelocity({ "input1", "vel_1", 0.7, 5 });
  core.addLock({ "emergency_255", "lock_1", 0.5, 255 });
  EXPECT_TRUE(core.isLocked(0, 10.0));
  EXPECT_FALSE(core.velocityReceived(0, 10.0));
  core.lockReceived(0, false, 10.1);
  EXPECT_TRUE(core.velocityReceived(0, 10.2));
  EXPECT_TRUE(core.velocityReceived(0, 10.6));
  EXPECT_FALSE(core.velocityReceived(0, 10.7));
  EXPECT_EQ(core.lockPriority(10.7), 255);
}

TEST(MuxCore, AnInputWithoutTimeoutNeverExpires)
{
  MuxCore core;
  core.addVelocity({ "input2", "vel_2", 0.0, 1 });
  core.addVelocity({ "input1", "vel_1", 0.7, 5 });
  core.velocityReceived(1, 1.0);
  EXPECT_FALSE(core.velocityReceived(0, 1.5));
  EXPECT_TRUE(core.velocityReceived(0, 1.0e6));
}

TEST(MuxCore, PriorityZeroNeverPasses)
{
  // hasPriority starts from priority 0 with a strict comparison: a priority-0 input is never the selected one.
  MuxCore core;
  core.addVelocity({ "idle", "idle_vel", 0.0, 0 });
  EXPECT_FALSE(core.velocityReceived(0, 1.0));
  EXPECT_EQ(core.selected(1.0), -1);
}

TEST(MuxCore, PrioritiesAreClampedToAByte)
{
  // TopicHandle_'s constructor: clamp(priority, 0, 255)
  MuxCore core;
  core.addVelocity({ "high", "a", 0.0, 1000 });
  core.addLock({ "low", "b", 0.0, -5 });
  EXPECT_EQ(core.velocities()[0].spec.priority, 255);
  EXPECT_EQ(core.locks()[0].spec.priority, 0);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
