#include "colag/ugv/controller.hpp"

#include <algorithm>
#include <cmath>

namespace colag::ugv {

ControlOutput Controller::step(const Pose2& pose, const Trajectory& traj, double dt) {
  ControlOutput out;
  if (traj.empty()) {
    last_v_ = 0.0;
    return out;
  }
  // Progress: the closest sample ahead of the previous progress point (never backwards).
  std::size_t best = std::min(progress_, traj.size() - 1);
  double best_d = (traj[best].p - pose.p).squaredNorm();
  const std::size_t end = std::min(traj.size(), best + config_.search_window);
  for (std::size_t i = best + 1; i < end; ++i) {
    const double d = (traj[i].p - pose.p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  progress_ = best;
  out.cross_track_m = std::sqrt(best_d);

  const TrajectorySample& last = traj.back();
  if (progress_ + 1 >= traj.size() || (last.p - pose.p).norm() < config_.goal_tolerance_m) {
    if ((last.p - pose.p).norm() < config_.goal_tolerance_m || traj.size() == 1) {
      out.at_goal = true;
      last_v_ = 0.0;
      return out;
    }
  }

  // Lookahead point along the path.
  const double lookahead = config_.lookahead_m + config_.lookahead_time_s * last_v_;
  std::size_t la = progress_;
  while (la + 1 < traj.size() && traj[la].s_m - traj[progress_].s_m < lookahead)
    ++la;
  const Vec2 to_target = traj[la].p - pose.p;
  const double alpha = wrap_angle(std::atan2(to_target.y(), to_target.x()) - pose.yaw_rad);
  const double dist = std::max(to_target.norm(), 1e-3);

  double v = 0.0, omega = 0.0;
  if (std::abs(alpha) > config_.turn_in_place_rad) {
    omega =
        std::clamp(config_.turn_gain * alpha, -limits_.omega_max_radps, limits_.omega_max_radps);
  } else {
    v = traj[progress_].v_mps;
    if (v < 0.05 && progress_ + 1 < traj.size()) v = std::max(v, traj[progress_ + 1].v_mps);
    const double curvature = 2.0 * std::sin(alpha) / dist;
    if (std::abs(curvature) * v > limits_.omega_max_radps)
      v = limits_.omega_max_radps / std::abs(curvature);
    omega = v * curvature;
  }
  // Acceleration limit on v, then the wheel-speed limit (scales v and omega together).
  v = std::clamp(v, last_v_ - limits_.a_max_mps2 * dt, last_v_ + limits_.a_max_mps2 * dt);
  v = std::clamp(v, 0.0, limits_.v_max_mps);
  const double half_track = 0.5 * config_.track_width_m;
  const double wheel = std::max(std::abs(v - omega * half_track), std::abs(v + omega * half_track));
  if (wheel > config_.wheel_speed_max_mps) {
    const double k = config_.wheel_speed_max_mps / wheel;
    v *= k;
    omega *= k;
  }
  out.v_mps = v;
  out.omega_radps = omega;
  last_v_ = v;
  return out;
}

}  // namespace colag::ugv
