// ROS-free motion planning for the TurtleBot exercises: velocity profiles (circle, spiral), the bounce rule and
// the square state machine. Twin of src/my_first_rospkg/motion.py.
#ifndef MY_FIRST_ROSPKG_MOTION_H
#define MY_FIRST_ROSPKG_MOTION_H

namespace my_first_rospkg
{
/// A unicycle command: forward speed [m/s] and yaw rate [rad/s].
struct Velocity
{
  double linear = 0.0;
  double angular = 0.0;
};

/// A planar pose: position [m] and heading [rad].
struct Pose2D
{
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

/// The angle in (-pi, pi].
double normalizeAngle(double angle);

/// Heading of the unit quaternion (x, y, z, w) about z.
double yawFromQuaternion(double x, double y, double z, double w);

/// A velocity profile over time, zero from duration() on.
class TimedTrajectory
{
 public:
  virtual ~TimedTrajectory() = default;
  /// The command `t` seconds after the start.
  virtual Velocity velocityAt(double t) const = 0;
  /// Seconds until the trajectory is complete.
  virtual double duration() const = 0;
};

/// A circle of `radius` [m] driven at `speed` [m/s], `laps` times, turning left.
class CircleTrajectory : public TimedTrajectory
{
 public:
  CircleTrajectory(double radius, double speed, double laps);
  Velocity velocityAt(double t) const override;
  double duration() const override;

 private:
  double radius_;
  double speed_;
  double laps_;
};

/// An Archimedean spiral: the radius of curvature grows by `growth_rate` [m/rad] with the heading turned,
/// r(theta) = initial_radius + growth_rate * theta, at a constant yaw rate `angular_speed` [rad/s], until it
/// reaches `max_radius` [m].
class SpiralTrajectory : public TimedTrajectory
{
 public:
  SpiralTrajectory(double initial_radius, double growth_rate, double angular_speed, double max_radius);
  Velocity velocityAt(double t) const override;
  double duration() const override;
  /// Radius of curvature `t` seconds after the start.
  double radiusAt(double t) const;

 private:
  double initial_radius_;
  double growth_rate_;
  double angular_speed_;
  double max_radius_;
};

/// Drives straight at `speed` and reverses whenever the robot is beyond |x| > limit_x or |y| > limit_y and still
/// moving outwards.
class Bouncer
{
 public:
  Bouncer(double speed, double limit_x, double limit_y);
  /// The command for the robot at `pose`.
  Velocity update(const Pose2D& pose);
  /// +1 forwards, -1 backwards.
  int direction() const
  {
    return direction_;
  }

 private:
  double speed_;
  double limit_x_;
  double limit_y_;
  int direction_ = 1;
};

/// Settings of SquareController.
struct SquareParams
{
  double side = 1.0;                  ///< m
  double linear_speed = 0.3;          ///< m/s, top speed along a side
  double angular_speed = 0.6;         ///< rad/s, top yaw rate at a corner
  double settle_time = 0.5;           ///< s standing still after each side and corner
  double distance_tolerance = 0.005;  ///< m left of a side when it counts as done
  double angle_tolerance = 0.01;      ///< rad left of a corner when it counts as done
  double gain = 2.0;                  ///< 1/s, proportional slow-down before a target and heading correction
  double min_linear_speed = 0.03;     ///< m/s, floor of the slow-down
  double min_angular_speed = 0.05;    ///< rad/s, floor of the slow-down
};

/// Closed-loop square on odometry: drive a side, stop, turn 90 degrees left, stop; four times.
class SquareController
{
 public:
  enum class State
  {
    kStart,
    kDrive,
    kStopAfterDrive,
    kTurn,
    kStopAfterTurn,
    kDone
  };

  explicit SquareController(const SquareParams& params);
  /// The command for the robot at `pose` at time `now` [s].
  Velocity update(const Pose2D& pose, double now);
  State state() const
  {
    return state_;
  }
  bool done() const
  {
    return state_ == State::kDone;
  }
  /// Sides completed so far.
  int sidesDone() const
  {
    return sides_done_;
  }

 private:
  static constexpr int kSides = 4;
  double clampedSpeed(double error, double min_speed, double max_speed) const;

  SquareParams params_;
  State state_ = State::kStart;
  Pose2D side_start_;
  double target_yaw_ = 0.0;
  double stop_since_ = 0.0;
  int sides_done_ = 0;
};

const char* toString(SquareController::State state);

}  // namespace my_first_rospkg

#endif  // MY_FIRST_ROSPKG_MOTION_H
