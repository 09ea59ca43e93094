#include "turtlesim/square_driver.h"

#include <cmath>
#include <cstdio>

namespace turtlesim
{
double wrapAngle(double theta)
{
  return theta - 2.0 * M_PI * std::floor((theta + M_PI) / (2.0 * M_PI));
}

bool SquareDriver::reached(const SquarePose& pose) const
{
  return std::fabs(pose.x - goal_.x) < kPositionTolerance && std::fabs(pose.y - goal_.y) < kPositionTolerance &&
         std::fabs(wrapAngle(pose.theta - goal_.theta)) < kAngleTolerance;
}

void SquareDriver::setGoal(double x, double y, double theta, std::vector<std::string>* log)
{
  goal_ = { x, y, wrapAngle(theta), 0.0, 0.0 };
  char line[96];
  std::snprintf(line, sizeof(line), "New goal [%f %f, %f]", goal_.x, goal_.y, goal_.theta);
  log->push_back(line);
}

SquareCommand SquareDriver::step(const SquarePose& pose, std::vector<std::string>* log)
{
  const bool stopped = pose.linear_velocity < kStoppedVelocity && std::fabs(pose.angular_velocity) < kStoppedVelocity;
  if (!started_)
  {
    started_ = true;
    state_ = State::kForward;
    setGoal(pose.x + kSide * std::cos(pose.theta), pose.y + kSide * std::sin(pose.theta), pose.theta, log);
  }
  switch (state_)
  {
    case State::kForward:
      if (reached(pose))
      {
        state_ = State::kStopForward;
        return { 0.0, 0.0 };
      }
      return { kLinearSpeed, 0.0 };
    case State::kTurn:
      if (reached(pose))
      {
        state_ = State::kStopTurn;
        return { 0.0, 0.0 };
      }
      return { 0.0, kAngularSpeed };
    case State::kStopForward:
      if (stopped)
      {
        log->push_back("Reached goal");
        state_ = State::kTurn;
        setGoal(pose.x, pose.y, pose.theta + M_PI / 2.0, log);
      }
      return { 0.0, 0.0 };
    case State::kStopTurn:
      if (stopped)
      {
        log->push_back("Reached goal");
        state_ = State::kForward;
        setGoal(pose.x + kSide * std::cos(pose.theta), pose.y + kSide * std::sin(pose.theta), pose.theta, log);
      }
      return { 0.0, 0.0 };
  }
  return { 0.0, 0.0 };
}

}  // namespace turtlesim
