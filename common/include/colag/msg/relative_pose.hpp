#pragma once
#include "colag/common/time.hpp"
#include "colag/msg/fields.hpp"
#include "colag/msg/robot_id.hpp"
#include "colag/msg/topic.hpp"

namespace colag::msg {

// One relative pose estimate (RPE): pose of UGV `ugv_id` in the UAV body frame at the time
// the camera image was taken (UAV -> UGV, ~20 Hz while the UGV is in view).
struct RelativePose {
  TimePoint stamp;  // detection (exposure) time
  RobotId uav_id = 0;
  RobotId ugv_id = 0;
  double position_m[3] = {};                          // UGV body origin in the UAV body frame
  double orientation_wxyz[4] = {1.0, 0.0, 0.0, 0.0};  // UGV body -> UAV body
  // Covariance of (x_m, y_m, z_m, yaw_rad) in the UAV body frame, 4x4 row-major: m^2, m*rad, rad^2.
  double covariance[16] = {};
  friend bool operator==(const RelativePose&, const RelativePose&) = default;
};
COLAG_MESSAGE_FIELDS(RelativePose, stamp, uav_id, ugv_id, position_m, orientation_wxyz, covariance);

// Each one corrects the UGV's estimate: reliable. Filed under the UGV it is about.
template <>
inline constexpr TopicSpec<RelativePose> kTopicSpec<RelativePose> = {
    "colag_relative_pose", &RelativePose::ugv_id, Reliability::kReliable, 8,
    Duration::zero(),      Delivery::kPerUgv};

}  // namespace colag::msg
