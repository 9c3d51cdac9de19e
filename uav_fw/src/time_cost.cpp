#include "colag/uav/time_cost.hpp"

#include <algorithm>
#include <cmath>

namespace colag::uav {

double cruise_time_s(const Vec2& from, const Vec2& to, const FlightLimits& limits) {
  return (to - from).norm() / limits.v_max_mps;
}

double first_leg_time_s(const Vec2& uav_position, const Vec2& uav_velocity, const Vec2& target,
                        const FlightLimits& limits) {
  const Vec2 delta = target - uav_position;
  const double d = delta.norm();
  if (d < 1e-9) return 0.0;
  const double a = limits.a_max_mps2, vmax = limits.v_max_mps;
  const double v_tan = std::min(uav_velocity.dot(delta / d), vmax);
  const double dis_a = (vmax * vmax - v_tan * v_tan) / (2.0 * a);
  if (dis_a >= d) return (std::sqrt(v_tan * v_tan + 2.0 * a * d) - v_tan) / a;
  return (vmax - v_tan) / a + (d - dis_a) / vmax;
}

}  // namespace colag::uav
