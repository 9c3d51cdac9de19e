#include "colag/uav/flight_planner.hpp"

#include <algorithm>
#include <cmath>

#include "colag/common/map_window.hpp"

namespace colag::uav {

namespace {
// Discs along each keep-out line of a UAV that does not cooperate, half a radius apart.
constexpr int kDiscsPerUav = 16;
using KeepOut = StaticVector<DiscObstacle, limits::kMaxUavs * kDiscsPerUav>;
void keep_outs(const Neighbours& others, const SeparationConfig& sep, KeepOut& out) {
  const double r = sep.min_m + sep.path_margin_m;
  for (const Neighbour& o : others) {
    if (o.cooperates) continue;
    const Vec2 line = o.p_end - o.p;
    const int n =
        std::clamp(static_cast<int>(std::ceil(line.norm() / (0.5 * r))), 1, kDiscsPerUav - 1);
    for (int i = 0; i <= n; ++i)
      (void)out.push_back({o.p + line * (static_cast<double>(i) / n), r});
  }
}
}  // namespace

void FlightPlanner::plan(const Vec2& from, TimePoint now, const MapStore& flight_layer,
                         const Neighbours& others) {
  planned_at_ = now;
  KeepOut discs;
  keep_outs(others, config_.separation, discs);
  // A target beyond the flight layer's window: around what it knows up to where the straight
  // line leaves it, then straight on (unknown is free at flight altitude: the UAV sees).
  const Vec2 to = clip_into(flight_layer.geometry(), from, target_, 1.0);
  if (planner_.plan(flight_layer, from, to, {discs.begin(), discs.end()}, path_) ==
      PlanResult::kOk) {
    if (to != target_) {
      if (!path_.waypoints.push_back(target_)) path_.waypoints.back() = target_;
      path_.length_m += (target_ - to).norm();
    }
  } else {
    // Nothing known in the way, or boxed in: fly straight and let the next plan correct it.
    ++plan_failures_;
    path_.waypoints.clear();
    (void)path_.waypoints.push_back(from);
    (void)path_.waypoints.push_back(target_);
  }
}

void FlightPlanner::set_target(const Vec2& target, TimePoint now, const Vec2& from,
                               const MapStore& flight_layer, const Neighbours& others) {
  if (has_target_ && (target - target_).norm() <= config_.retarget_m) return;
  target_ = target;
  has_target_ = true;
  plan(from, now, flight_layer, others);
}

hal::FlightSetpoint FlightPlanner::step(const hal::UavState& s, TimePoint now, double dt,
                                        const MapStore& flight_layer, const Neighbours& others) {
  const Vec2 p = s.pose.p.head<2>();
  const Vec2 v = s.velocity_mps.head<2>();
  Vec2 v_des = Vec2::Zero();
  if (has_target_) {
    if (now - planned_at_ >= config_.replan_period) plan(p, now, flight_layer, others);
    // Lookahead point: the first path point beyond the lookahead distance, walking from the
    // path segment nearest to the UAV.
    std::size_t seg = 1;
    double best = 1e18;
    for (std::size_t i = 1; i < path_.waypoints.size(); ++i) {
      const Vec2 a = path_.waypoints[i - 1], b = path_.waypoints[i];
      const double t =
          std::clamp((p - a).dot(b - a) / std::max((b - a).squaredNorm(), 1e-12), 0.0, 1.0);
      const double d = (a + t * (b - a) - p).squaredNorm();
      if (d < best) {
        best = d;
        seg = i;
      }
    }
    Vec2 aim = target_;
    for (std::size_t i = seg; i < path_.waypoints.size(); ++i) {
      aim = path_.waypoints[i];
      if ((aim - p).norm() >= config_.lookahead_m) break;
    }
    double remaining = (aim - p).norm();
    for (std::size_t i = seg; i + 1 < path_.waypoints.size(); ++i) {
      remaining += (path_.waypoints[i + 1] - path_.waypoints[i]).norm();
    }
    remaining = std::max(remaining, (target_ - p).norm());
    const double speed = std::min(config_.limits.v_max_mps,
                                  std::sqrt(2.0 * config_.limits.a_max_mps2 * 0.9 * remaining));
    const Vec2 to_aim = aim - p;
    if (to_aim.norm() > 1e-3) v_des = speed * to_aim.normalized();
  }
  if (!others.empty())
    v_des = separate(p, v_des, others, config_.limits.v_max_mps, config_.separation);
  // Acceleration limit: change the last setpoint by at most a_max * dt.
  const Vec2 from = have_cmd_ && (last_cmd_ - v).norm() <= config_.resync_mps ? last_cmd_ : v;
  Vec2 dv = v_des - from;
  const double max_dv = config_.limits.a_max_mps2 * dt;
  if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
  const Vec2 v_cmd = from + dv;
  last_cmd_ = v_cmd;
  have_cmd_ = true;
  const double vz = std::clamp(config_.altitude_gain * (config_.altitude_m - s.pose.p.z()),
                               -config_.max_climb_mps, config_.max_climb_mps);
  hal::FlightSetpoint sp;
  sp.stamp = now;
  sp.velocity_mps = Vec3(v_cmd.x(), v_cmd.y(), vz);
  sp.position_m = s.pose.p + sp.velocity_mps * dt;
  sp.acceleration_mps2 = Vec3(dv.x() / dt, dv.y() / dt, 0.0);
  sp.yaw_rad = 0.0;  // constant heading: the camera's view of the UGVs does not depend on it
  return sp;
}

}  // namespace colag::uav
