#include "colag/sim/world/odometry_frame.hpp"

#include <cmath>

namespace colag::sim {

OdometryFrame::OdometryFrame(const UavOdometryErrors& errors, const Vec3& origin,
                             std::uint64_t seed)
    : errors_(errors), origin_(origin), rng_(seed) {
  scale_ = rng_.uniform(-errors.scale_error, errors.scale_error);
  yaw_ = rng_.uniform(-errors.yaw_error_rad, errors.yaw_error_rad);
  turn_ = Quat(Eigen::AngleAxisd(yaw_, Vec3::UnitZ()));
}

void OdometryFrame::step(double dt) {
  if (errors_.walk_m_per_sqrt_s > 0.0) {
    const double s = errors_.walk_m_per_sqrt_s * std::sqrt(dt);
    const double dx = rng_.gaussian(0.0, s);
    const double dy = rng_.gaussian(0.0, s);
    shift_ += Vec3(dx, dy, 0.0);
  }
  if (errors_.jumps_per_min > 0.0 &&
      rng_.bernoulli(std::min(1.0, errors_.jumps_per_min / 60.0 * dt))) {
    const double a = rng_.uniform(-M_PI, M_PI);
    shift_ += rng_.uniform(0.0, errors_.jump_max_m) * Vec3(std::cos(a), std::sin(a), 0.0);
  }
}

Vec3 OdometryFrame::to_odometry(const Vec3& p) const {
  return origin_ + vector_to_odometry(p - origin_) + shift_;
}

}  // namespace colag::sim
