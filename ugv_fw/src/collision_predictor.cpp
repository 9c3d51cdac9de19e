#include "colag/ugv/collision_predictor.hpp"

#include <cmath>

namespace colag::ugv {

CollisionKind CollisionPredictor::check(const Ellipse& e, const MapStore& map,
                                        std::span<const OtherRobot> others) const {
  const auto& g = map.geometry();
  const bool hit =
      any_cell_touching(g, e, [&](CellIndex c) { return map.predict_blocked_at(g.index(c)); });
  if (hit) return CollisionKind::kMap;
  // Outside the grid counts as unknown, hence blocked.
  const double reach = std::sqrt(std::max(e.M(0, 0), e.M(1, 1)));
  if (!g.contains(Vec2(e.center + Vec2(reach, reach))) ||
      !g.contains(Vec2(e.center - Vec2(reach, reach)))) {
    return CollisionKind::kMap;
  }
  if (others.empty()) return CollisionKind::kNone;
  const double a = e.axes().a_m;
  for (const OtherRobot& o : others) {
    if ((o.p - e.center).norm() <= a + o.radius_m) return CollisionKind::kRobot;
  }
  return CollisionKind::kNone;
}

void CollisionPredictor::predict(const Pose2& pose, const Mat3& covariance, const Trajectory& traj,
                                 std::size_t progress, const MapStore& map,
                                 std::span<const OtherRobot> others, Prediction& out) const {
  out.kind = CollisionKind::kNone;
  out.ellipses.clear();
  const double k = config_.use_uncertainty ? config_.k_sigma : 0.0;
  Mat3 P = config_.use_uncertainty ? covariance : Mat3::Zero();
  const auto test = [&](const Vec2& centre, double t, double heading) {
    const Ellipse e = sigma_ellipse(centre, P.topLeftCorner<2, 2>(), k);
    (void)out.ellipses.push_back(e);
    const CollisionKind kind = check(e, map, others);
    if (kind == CollisionKind::kNone) return false;
    out.kind = kind;
    out.point = centre;
    out.time_s = t;
    out.support_point =
        centre - config_.support_back_off_m * Vec2(std::cos(heading), std::sin(heading));
    return true;
  };
  // Now, at the estimated pose.
  if (test(pose.p, 0.0, pose.yaw_rad) || traj.empty()) return;

  const std::size_t start = std::min(progress, traj.size() - 1);
  const double t0 = traj[start].t_s;
  const Vec2 origin = traj[start].p;
  std::size_t i = start;
  for (int step = 1; step < static_cast<int>(limits::kMaxPredictionSteps); ++step) {
    const double t = step * config_.dt_s;
    if (t > config_.max_horizon_s) return;
    i = traj.index_at_time(t0 + t, i);
    const TrajectorySample& s = traj[i];
    if (config_.use_uncertainty) {
      Vec3 x(s.p.x(), s.p.y(), s.yaw_rad);
      propagate(x, P, s.v_mps, s.omega_radps, config_.dt_s, noise_);
    }
    if (test(s.p, t, s.yaw_rad)) return;
    if ((s.p - origin).norm() >= config_.horizon_m || i + 1 >= traj.size()) return;
  }
}

}  // namespace colag::ugv
