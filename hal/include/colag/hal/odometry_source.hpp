#pragma once
#include "colag/common/geometry.hpp"
#include "colag/common/time.hpp"

namespace colag::hal {

// The UAV's own state from its SLAM / flight stack, world frame.
struct UavState {
  TimePoint stamp;
  Pose3 pose;  // body -> world
  Vec3 velocity_mps = Vec3::Zero();
  double yaw_rate_radps = 0.0;
};

class OdometrySource {
 public:
  virtual ~OdometrySource() = default;
  // True when a state newer than the last one read is available.
  virtual bool poll(UavState& out) = 0;
};

}  // namespace colag::hal
