#pragma once
// Trajectory tracking for a differential drive at 50 Hz: pure pursuit on the planned path with
// the trajectory's speed profile. Why pure pursuit: it follows the path geometrically (the
// reference is the robot's own progress along the path, not a clock), so a robot that stopped
// to wait for support simply resumes; it is O(1), has two intuitive gains, and the trajectory
// already respects the turn-rate and acceleration limits, which an MPC would otherwise enforce.
// Large heading errors are first removed by turning on the spot.
#include <cstddef>

#include "colag/common/geometry.hpp"
#include "colag/ugv/trajectory.hpp"

namespace colag::ugv {

struct ControllerConfig {
  double lookahead_m = 0.35;  // lookahead = lookahead_m + lookahead_time_s * v
  double lookahead_time_s = 0.5;
  double turn_in_place_rad = 0.8;    // heading error above which the robot turns on the spot
  double turn_gain = 2.0;            // omega = gain * heading error when turning on the spot
  double wheel_speed_max_mps = 0.7;  // per wheel
  double track_width_m = 0.4;
  double goal_tolerance_m = 0.15;
  std::size_t search_window = 40;  // samples searched ahead for the progress point
};

struct ControlOutput {
  double v_mps = 0.0;
  double omega_radps = 0.0;
  bool at_goal = false;
  double cross_track_m = 0.0;  // distance from the path at the progress point
};

class Controller {
 public:
  Controller(const ControllerConfig& config, const TrajectoryLimits& limits)
      : config_(config), limits_(limits) {}

  // A new trajectory starts from its first sample.
  void reset() { progress_ = 0; }
  ControlOutput step(const Pose2& pose, const Trajectory& trajectory, double dt_s);
  std::size_t progress() const { return progress_; }
  double last_v() const { return last_v_; }
  void hold() { last_v_ = 0.0; }  // the robot was stopped from outside

 private:
  ControllerConfig config_;
  TrajectoryLimits limits_;
  std::size_t progress_ = 0;
  double last_v_ = 0.0;
};

}  // namespace colag::ugv
