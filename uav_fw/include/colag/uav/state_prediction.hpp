#pragma once
// The UAV's state at t from its newest odometry sample. A LiDAR-inertial odometry is delivered
// tens of milliseconds after it was measured: a scan placed, or a setpoint computed, with the pose
// it had then is off by what the UAV flew since (6 cm at 3 m/s for 20 ms: a smeared map and a
// planner that chases its own past). Moved on at its velocity; at most `max_ahead` (a sample that
// old says nothing about the acceleration since: used as it is beyond that).
#include <algorithm>

#include "colag/hal/odometry_source.hpp"

namespace colag::uav {

inline hal::UavState predict_state(const hal::UavState& s, TimePoint t, Duration max_ahead) {
  hal::UavState out = s;
  const double ahead = std::clamp(to_seconds(t - s.stamp), 0.0, to_seconds(max_ahead));
  out.pose.p += s.velocity_mps * ahead;
  out.stamp = s.stamp + seconds(ahead);
  return out;
}

}  // namespace colag::uav
