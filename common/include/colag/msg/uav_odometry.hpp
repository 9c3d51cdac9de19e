#pragma once
#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::msg {

// The UAV's SLAM odometry in the world frame (UAV -> UGVs, ~50-100 Hz).
struct UavOdometry {
  TimePoint stamp;  // time of the pose
  RobotId uav_id = 0;
  double position_m[3] = {};                          // world frame
  double orientation_wxyz[4] = {1.0, 0.0, 0.0, 0.0};  // body -> world
  double velocity_mps[3] = {};                        // world frame
  double yaw_rate_radps = 0.0;
  friend bool operator==(const UavOdometry&, const UavOdometry&) = default;
};

}  // namespace colag::msg
