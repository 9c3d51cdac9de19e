#pragma once
// What the simulated world measures of the firmware against its ground truth, the same way in
// the lock-step simulator (colag_sim) and the SITL world (colag_world).
#include <cmath>
#include <cstdint>

#include "colag/common/geometry.hpp"
#include "colag/ugv/waiting.hpp"

namespace colag::mission {

// NEES of a pose estimate (x, y, yaw) with its covariance against the truth; not finite when
// the covariance cannot be inverted.
inline double pose_nees(const Pose2& estimate, const Mat3& covariance, const Pose2& truth) {
  const Vec3 e(estimate.p.x() - truth.p.x(), estimate.p.y() - truth.p.y(),
               wrap_angle(estimate.yaw_rad - truth.yaw_rad));
  return e.dot(covariance.ldlt().solve(e));
}

// A running mean of the finite samples.
inline void add_to_mean(double sample, double& mean, std::uint64_t& samples) {
  if (!std::isfinite(sample)) return;
  ++samples;
  mean += (sample - mean) / static_cast<double>(samples);
}

// Waiting as a user sees it: standing still (slower than 0.05 m/s by the true motion) before
// the firmware says it arrived; each start of standing counts a stop.
struct StillCount {
  double stopped_s = 0.0;
  int stops = 0;
  bool still = false;
  void update(bool arrived, double speed_mps, double dt_s) {
    const bool now_still = !arrived && std::abs(speed_mps) < ugv::kStillSpeed_mps;
    if (now_still) stopped_s += dt_s;
    if (now_still && !still) ++stops;
    still = now_still;
  }
};

}  // namespace colag::mission
