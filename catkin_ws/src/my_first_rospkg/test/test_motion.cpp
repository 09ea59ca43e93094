// Unit tests of the ROS-free motion core (twin of test/unit/test_motion.py).
#include <gtest/gtest.h>

#include <cmath>

#include "my_first_rospkg/motion.h"

using my_first_rospkg::Bouncer;
using my_first_rospkg::CircleTrajectory;
using my_first_rospkg::Pose2D;
using my_first_rospkg::SpiralTrajectory;
using my_first_rospkg::SquareController;
using my_first_rospkg::SquareParams;
using my_first_rospkg::Velocity;

namespace
{
Pose2D pose(double x, double y, double yaw)
{
  Pose2D p;
  p.x = x;
  p.y = y;
  p.yaw = yaw;
  return p;
}

/// Integrates the unicycle for dt.
Pose2D step(const Pose2D& p, const Velocity& v, double dt)
{
  return pose(p.x + v.linear * std::cos(p.yaw) * dt, p.y + v.linear * std::sin(p.yaw) * dt,
              my_first_rospkg::normalizeAngle(p.yaw + v.angular * dt));
}
}  // namespace

TEST(NormalizeAngle, WrapsIntoHalfOpenInterval)
{
  EXPECT_NEAR(my_first_rospkg::normalizeAngle(3.0 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(my_first_rospkg::normalizeAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(my_first_rospkg::normalizeAngle(0.5), 0.5, 1e-12);
  EXPECT_NEAR(my_first_rospkg::normalizeAngle(-2.0 * M_PI - 0.5), -0.5, 1e-12);
}

TEST(YawFromQuaternion, QuarterTurn)
{
  EXPECT_NEAR(my_first_rospkg::yawFromQuaternion(0.0, 0.0, std::sin(M_PI / 4), std::cos(M_PI / 4)), M_PI / 2, 1e-12);
}

TEST(Circle, ConstantTwistForOneLapThenStop)
{
  const CircleTrajectory circle(2.0, 0.5, 1.0);
  EXPECT_NEAR(circle.duration(), 2.0 * M_PI * 2.0 / 0.5, 1e-12);
  const Velocity v = circle.velocityAt(1.0);
  EXPECT_DOUBLE_EQ(v.linear, 0.5);
  EXPECT_DOUBLE_EQ(v.angular, 0.25);
  EXPECT_DOUBLE_EQ(circle.velocityAt(circle.duration()).linear, 0.0);
  EXPECT_DOUBLE_EQ(circle.velocityAt(-1.0).angular, 0.0);
}

TEST(Spiral, RadiusGrowsWithHeading)
{
  const SpiralTrajectory spiral(0.2, 0.04, 0.5, 1.0);
  EXPECT_NEAR(spiral.duration(), 0.8 / 0.02, 1e-12);
  EXPECT_DOUBLE_EQ(spiral.radiusAt(10.0), 0.2 + 0.04 * 5.0);
  const Velocity v = spiral.velocityAt(10.0);
  EXPECT_DOUBLE_EQ(v.angular, 0.5);
  EXPECT_NEAR(v.linear / v.angular, spiral.radiusAt(10.0), 1e-12);
  EXPECT_DOUBLE_EQ(spiral.velocityAt(spiral.duration()).linear, 0.0);
}

TEST(Bouncer, ReversesOnlyWhenLeaving)
{
  Bouncer bouncer(0.5, 2.0, 2.0);
  EXPECT_DOUBLE_EQ(bouncer.update(pose(1.0, 0.0, 0.0)).linear, 0.5);
  EXPECT_DOUBLE_EQ(bouncer.update(pose(2.1, 0.0, 0.0)).linear, -0.5);
  // still outside but now coming back: no second reversal
  EXPECT_DOUBLE_EQ(bouncer.update(pose(2.05, 0.0, 0.0)).linear, -0.5);
  EXPECT_DOUBLE_EQ(bouncer.update(pose(-2.1, 0.0, 0.0)).linear, 0.5);
  // along y, facing +y
  EXPECT_DOUBLE_EQ(bouncer.update(pose(0.0, 2.1, M_PI / 2)).linear, -0.5);
}

TEST(Bouncer, StaysInsideInSimulation)
{
  Bouncer bouncer(0.5, 2.0, 2.0);
  Pose2D p = pose(0.0, 0.0, 0.3);
  for (int i = 0; i < 6000; ++i)
  {
    p = step(p, bouncer.update(p), 0.02);
    ASSERT_LE(std::abs(p.x), 2.0 + 0.5 * 0.02 + 1e-9);
    ASSERT_LE(std::abs(p.y), 2.0 + 0.5 * 0.02 + 1e-9);
  }
}

TEST(Square, ClosesAndVisitsFourCorners)
{
  SquareParams params;
  SquareController square(params);
  Pose2D p = pose(0.5, -0.2, 0.3);
  const Pose2D start = p;
  int corners = 0;
  SquareController::State previous = square.state();
  double t = 0.0;
  for (; t < 200.0 && !square.done(); t += 0.02)
  {
    const Velocity v = square.update(p, t);
    if (square.state() == SquareController::State::kStopAfterTurn && previous != square.state())
    {
      ++corners;
      EXPECT_NEAR(my_first_rospkg::normalizeAngle(p.yaw - start.yaw - corners * M_PI / 2), 0.0,
                  params.angle_tolerance + 0.01);
    }
    previous = square.state();
    p = step(p, v, 0.02);
  }
  ASSERT_TRUE(square.done());
  EXPECT_EQ(corners, 3);
  EXPECT_EQ(square.sidesDone(), 4);
  EXPECT_LT(std::hypot(p.x - start.x, p.y - start.y), 0.03);
  EXPECT_DOUBLE_EQ(square.update(p, t).linear, 0.0);
}

TEST(Square, StopsBetweenSidesAndCorners)
{
  SquareParams params;
  params.side = 0.1;
  SquareController square(params);
  Pose2D p;
  bool stopped = false;
  for (double t = 0.0; t < 5.0 && !stopped; t += 0.02)
  {
    const Velocity v = square.update(p, t);
    stopped = square.state() == SquareController::State::kStopAfterDrive;
    if (stopped)
    {
      EXPECT_EQ(v.linear, 0.0);
    }
    p = step(p, v, 0.02);
  }
  EXPECT_TRUE(stopped);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
