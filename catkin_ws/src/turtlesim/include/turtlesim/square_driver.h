// The draw_square tutorial's state machine without ROS (twin of src/turtlesim/square.py): drive 2 m forward,
// stop, turn a quarter turn left, stop, and again, so the turtle draws a square.
#ifndef TURTLESIM_SQUARE_DRIVER_H
#define TURTLESIM_SQUARE_DRIVER_H

#include <string>
#include <vector>

namespace turtlesim
{
struct SquarePose
{
  double x;
  double y;
  double theta;
  double linear_velocity;
  double angular_velocity;
};

struct SquareCommand
{
  double linear;
  double angular;
};

class SquareDriver
{
 public:
  enum class State
  {
    kForward,
    kStopForward,
    kTurn,
    kStopTurn
  };

  static constexpr double kSide = 2.0;                // m
  static constexpr double kLinearSpeed = 1.0;         // m/s
  static constexpr double kAngularSpeed = 0.4;        // rad/s
  static constexpr double kPositionTolerance = 0.1;   // m
  static constexpr double kAngleTolerance = 0.01;     // rad
  static constexpr double kStoppedVelocity = 0.0001;  // m/s and rad/s

  // The command for one tick given the latest pose; lines worth logging ("New goal [...]", "Reached goal") are
  // appended to *log.
  SquareCommand step(const SquarePose& pose, std::vector<std::string>* log);

  State state() const
  {
    return state_;
  }
  const SquarePose& goal() const
  {
    return goal_;
  }

 private:
  bool reached(const SquarePose& pose) const;
  void setGoal(double x, double y, double theta, std::vector<std::string>* log);

  State state_ = State::kForward;
  bool started_ = false;
  SquarePose goal_ = { 0.0, 0.0, 0.0, 0.0, 0.0 };
};

// theta wrapped to [-pi, pi), as turtlesim reports it.
double wrapAngle(double theta);

}  // namespace turtlesim

#endif  // TURTLESIM_SQUARE_DRIVER_H
