// The draw_square state machine without ROS (twin of test/unit/test_square.py).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "turtlesim/square_driver.h"

using turtlesim::SquareCommand;
using turtlesim::SquareDriver;
using turtlesim::SquarePose;

TEST(SquareDriver, DrivesForwardToAGoalTwoMetresAhead)
{
  SquareDriver driver;
  std::vector<std::string> log;
  const SquareCommand command = driver.step({ 1.0, 1.0, M_PI / 2.0, 0.0, 0.0 }, &log);
  EXPECT_DOUBLE_EQ(command.linear, SquareDriver::kLinearSpeed);
  EXPECT_DOUBLE_EQ(command.angular, 0.0);
  EXPECT_NEAR(driver.goal().x, 1.0, 1e-9);
  EXPECT_NEAR(driver.goal().y, 3.0, 1e-9);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].rfind("New goal [", 0), 0u);
}

TEST(SquareDriver, StopsThenTurnsAQuarterTurn)
{
  SquareDriver driver;
  std::vector<std::string> log;
  driver.step({ 0.0, 0.0, 0.0, 0.0, 0.0 }, &log);
  SquareCommand command = driver.step({ 1.95, 0.0, 0.0, 1.0, 0.0 }, &log);
  EXPECT_EQ(driver.state(), SquareDriver::State::kStopForward);
  EXPECT_DOUBLE_EQ(command.linear, 0.0);
  driver.step({ 1.95, 0.0, 0.0, 0.0, 0.0 }, &log);  // stopped: the next goal is a quarter turn
  EXPECT_EQ(driver.state(), SquareDriver::State::kTurn);
  EXPECT_NEAR(driver.goal().theta, M_PI / 2.0, 1e-9);
  command = driver.step({ 1.95, 0.0, 0.5, 0.0, 0.0 }, &log);
  EXPECT_DOUBLE_EQ(command.angular, SquareDriver::kAngularSpeed);
  EXPECT_EQ(log.back().rfind("New goal [", 0), 0u);
}

TEST(SquareDriver, QuarterTurnPastPiWraps)
{
  SquareDriver driver;
  std::vector<std::string> log;
  driver.step({ 0.0, 0.0, 3.0, 0.0, 0.0 }, &log);
  driver.step({ 2.0 * std::cos(3.0), 2.0 * std::sin(3.0), 3.0, 1.0, 0.0 }, &log);
  driver.step({ 2.0 * std::cos(3.0), 2.0 * std::sin(3.0), 3.0, 0.0, 0.0 }, &log);
  EXPECT_NEAR(driver.goal().theta, 3.0 + M_PI / 2.0 - 2.0 * M_PI, 1e-9);
  // A pose just below +pi and a goal just above -pi are close: reached across the wrap.
  EXPECT_NEAR(turtlesim::wrapAngle(M_PI + 0.1), -M_PI + 0.1, 1e-12);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
