#pragma once
#include <cstddef>
#include <span>

#include "colag/common/geometry.hpp"
#include "colag/common/time.hpp"
#include "colag/msg/robot_id.hpp"

namespace colag::hal {

// One UGV seen by the UAV's relative-pose device (camera + AprilTag, or the simulator).
struct RelativePoseDetection {
  TimePoint stamp;  // exposure time
  RobotId ugv_id = 0;
  Pose3 ugv_in_uav;                                          // UGV body pose in the UAV body frame
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Identity();  // (x, y, z, yaw) in the UAV frame
};

class RelativePoseSensor {
 public:
  virtual ~RelativePoseSensor() = default;
  // Writes the detections of the newest frame not yet read into `out` (at most out.size()),
  // returns how many were written; 0 when there is no new frame or nothing was seen.
  virtual std::size_t poll(std::span<RelativePoseDetection> out) = 0;
};

}  // namespace colag::hal
