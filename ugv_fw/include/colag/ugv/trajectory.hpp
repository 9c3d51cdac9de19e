#pragma once
// Turns a planned polyline into a time-parametrised trajectory a differential drive can follow:
// - each corner is rounded by a circular arc whose distance from the corner is at most
//   `corner_deviation_m` (the planner's clearance budget), so the path stays drivable without
//   stopping and never cuts deeper into the obstacle margin than that;
// - speed v(s) <= v_max, v <= omega_max / |curvature|, |dv/dt| <= a_max, from the current
//   speed at the start to rest at the goal (forward-backward pass);
// - samples every `spacing_m` along the arc length, each with time, pose, v and omega.
#include <cstddef>

#include "colag/common/geometry.hpp"
#include "colag/common/limits.hpp"
#include "colag/common/planner.hpp"
#include "colag/common/static_vector.hpp"

namespace colag::ugv {

struct TrajectoryLimits {
  double v_max_mps = 0.5;
  double a_max_mps2 = 1.0;
  double omega_max_radps = 1.2;      // turn-rate limit of the chassis
  double corner_deviation_m = 0.05;  // max distance between a corner and its rounding arc
  double spacing_m = 0.1;
};

struct TrajectorySample {
  double s_m = 0.0;  // arc length from the start
  double t_s = 0.0;  // time from the start
  Vec2 p = Vec2::Zero();
  double yaw_rad = 0.0;
  double v_mps = 0.0;
  double omega_radps = 0.0;
  double curvature = 0.0;
};

class Trajectory {
 public:
  using Samples = StaticVector<TrajectorySample, limits::kMaxTrajectorySamples>;

  // Builds from `path`; the robot is at path.waypoints[0] moving at v0. Returns false when the
  // path is empty; a path longer than the sample capacity is cut (the tail is replanned later).
  bool build(const Path& path, double v0_mps, const TrajectoryLimits& limits);
  void clear() { samples_.clear(); }

  bool empty() const { return samples_.empty(); }
  std::size_t size() const { return samples_.size(); }
  const TrajectorySample& operator[](std::size_t i) const { return samples_[i]; }
  const TrajectorySample& back() const { return samples_.back(); }
  const Samples& samples() const { return samples_; }
  // Index of the first sample at or after time t (clamped to the last one).
  std::size_t index_at_time(double t_s, std::size_t from = 0) const;

 private:
  Samples samples_;
};

}  // namespace colag::ugv
