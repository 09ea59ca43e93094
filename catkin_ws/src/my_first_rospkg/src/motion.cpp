#include "my_first_rospkg/motion.h"

#include <algorithm>
#include <cmath>

namespace my_first_rospkg
{
double normalizeAngle(double angle)
{
  angle = std::fmod(angle + M_PI, 2.0 * M_PI);
  if (angle <= 0.0)
    angle += 2.0 * M_PI;
  return angle - M_PI;
}

double yawFromQuaternion(double x, double y, double z, double w)
{
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

CircleTrajectory::CircleTrajectory(double radius, double speed, double laps)
    : radius_(radius), speed_(speed), laps_(laps)
{
}

Velocity CircleTrajectory::velocityAt(double t) const
{
  Velocity velocity;
  if (t >= 0.0 && t < duration())
  {
    velocity.linear = speed_;
    velocity.angular = speed_ / radius_;
  }
  return velocity;
}

double CircleTrajectory::duration() const
{
  return laps_ * 2.0 * M_PI * radius_ / speed_;
}

SpiralTrajectory::SpiralTrajectory(double initial_radius, double growth_rate, double angular_speed, double max_radius)
    : initial_radius_(initial_radius), growth_rate_(growth_rate), angular_speed_(angular_speed), max_radius_(max_radius)
{
}

double SpiralTrajectory::radiusAt(double t) const
{
  return initial_radius_ + growth_rate_ * angular_speed_ * t;
}

Velocity SpiralTrajectory::velocityAt(double t) const
{
  Velocity velocity;
  if (t >= 0.0 && t < duration())
  {
    velocity.linear = angular_speed_ * radiusAt(t);
    velocity.angular = angular_speed_;
  }
  return velocity;
}

double SpiralTrajectory::duration() const
{
  return std::max(0.0, (max_radius_ - initial_radius_) / (growth_rate_ * angular_speed_));
}

Bouncer::Bouncer(double speed, double limit_x, double limit_y) : speed_(speed), limit_x_(limit_x), limit_y_(limit_y) {}

Velocity Bouncer::update(const Pose2D& pose)
{
  const double heading_x = direction_ * std::cos(pose.yaw);
  const double heading_y = direction_ * std::sin(pose.yaw);
  const bool leaving_x = std::abs(pose.x) > limit_x_ && pose.x * heading_x > 0.0;
  const bool leaving_y = std::abs(pose.y) > limit_y_ && pose.y * heading_y > 0.0;
  if (leaving_x || leaving_y)
    direction_ = -direction_;
  Velocity velocity;
  velocity.linear = direction_ * speed_;
  return velocity;
}

SquareController::SquareController(const SquareParams& params) : params_(params) {}

double SquareController::clampedSpeed(double error, double min_speed, double max_speed) const
{
  const double speed = std::min(max_speed, std::max(min_speed, params_.gain * std::abs(error)));
  return error < 0.0 ? -speed : speed;
}

Velocity SquareController::update(const Pose2D& pose, double now)
{
  Velocity velocity;
  switch (state_)
  {
    case State::kStart:
      side_start_ = pose;
      target_yaw_ = pose.yaw;
      state_ = State::kDrive;
      return update(pose, now);
    case State::kDrive:
    {
      const double travelled =
          (pose.x - side_start_.x) * std::cos(target_yaw_) + (pose.y - side_start_.y) * std::sin(target_yaw_);
      const double remaining = params_.side - travelled;
      if (remaining <= params_.distance_tolerance)
      {
        state_ = State::kStopAfterDrive;
        stop_since_ = now;
        break;
      }
      velocity.linear = clampedSpeed(remaining, params_.min_linear_speed, params_.linear_speed);
      const double heading_error = normalizeAngle(target_yaw_ - pose.yaw);
      velocity.angular =
          std::max(-params_.angular_speed, std::min(params_.angular_speed, params_.gain * heading_error));
      break;
    }
    case State::kStopAfterDrive:
      if (now - stop_since_ >= params_.settle_time)
      {
        if (++sides_done_ == kSides)
        {
          state_ = State::kDone;
          break;
        }
        target_yaw_ = normalizeAngle(target_yaw_ + M_PI / 2.0);
        state_ = State::kTurn;
        return update(pose, now);
      }
      break;
    case State::kTurn:
    {
      const double error = normalizeAngle(target_yaw_ - pose.yaw);
      if (std::abs(error) <= params_.angle_tolerance)
      {
        state_ = State::kStopAfterTurn;
        stop_since_ = now;
        break;
      }
      velocity.angular = clampedSpeed(error, params_.min_angular_speed, params_.angular_speed);
      break;
    }
    case State::kStopAfterTurn:
      if (now - stop_since_ >= params_.settle_time)
      {
        side_start_ = pose;
        state_ = State::kDrive;
        return update(pose, now);
      }
      break;
    case State::kDone:
      break;
  }
  return velocity;
}

const char* toString(SquareController::State state)
{
  switch (state)
  {
    case SquareController::State::kStart:
      return "start";
    case SquareController::State::kDrive:
      return "drive";
    case SquareController::State::kStopAfterDrive:
      return "stop after drive";
    case SquareController::State::kTurn:
      return "turn";
    case SquareController::State::kStopAfterTurn:
      return "stop after turn";
    case SquareController::State::kDone:
      return "done";
  }
  return "unknown";
}

}  // namespace my_first_rospkg
