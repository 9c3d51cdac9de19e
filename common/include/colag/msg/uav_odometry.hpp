#pragma once
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

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
COLAG_MESSAGE_FIELDS(UavOdometry, stamp, uav_id, position_m, orientation_wxyz, velocity_mps,
                     yaw_rate_radps);

// High-rate and superseded quickly: best effort, with a short history so that a UGV can match
// relative-pose stamps; the UAV is expected at least every 200 ms.
template <>
inline constexpr TopicSpec<UavOdometry> kTopicSpec<UavOdometry> = {
    "colag_uav_odometry", &UavOdometry::uav_id, Reliability::kBestEffort, 16,
    std::chrono::milliseconds(200)};

}  // namespace colag::msg
