#include "colag/ugv/collision_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace colag::ugv {

CollisionKind CollisionPredictor::check(const Ellipse& e, double t, const MapStore& map,
                                        std::span<const OtherRobot> others,
                                        double closest_allowed_m, MapCause& cause) const {
  const auto& g = map.geometry();
  // Outside the grid counts as unknown, hence blocked.
  const double reach = std::sqrt(std::max(e.M(0, 0), e.M(1, 1)));
  cause = MapCause::kUnknownGround;
  if (!g.contains(Vec2(e.center + Vec2(reach, reach))) ||
      !g.contains(Vec2(e.center - Vec2(reach, reach)))) {
    return CollisionKind::kMap;
  }
  bool near_occupied = false;
  const bool near_unknown = any_cell_touching(g, e, [&](CellIndex c) {
    const auto i = static_cast<std::uint32_t>(g.index(c));
    if (!map.predict_blocked_at(i)) return false;
    // A cell the ellipse overlaps now is excused from blocking, not from the distance rule
    // below: excused entirely, an ellipse already within the radius of a pillar could slide
    // along it, each step over the same excused cells, while the truth at another point of the
    // ellipse closed in (a field-world UGV 2.4 sigma off grazed a pillar that way).
    near_occupied = near_occupied || map.near_occupied_at(i);
    if (std::binary_search(excused_.begin(), excused_.end(), i)) return false;
    return map.near_unknown_at(i);
  });
  if (near_unknown) return CollisionKind::kMap;
  const double a = (near_occupied || !others.empty()) ? e.axes().a_m : 0.0;
  // Known obstacles: never closer (in the worst case of the ellipse) than the robot is now.
  if (near_occupied && map.occupied_distance(e.center, kDistanceSearch_m) - a < closest_allowed_m) {
    cause = MapCause::kNearObstacle;
    return CollisionKind::kMap;
  }
  for (std::size_t k = 0; k < others.size(); ++k) {
    const OtherRobot& o = others[k];
    const double gap = (o.p + t * o.v - e.center).norm() - (a + o.radius_m);
    const double floor = k < robot_floor_.size() ? std::min(robot_floor_[k], 0.0) : 0.0;
    if (gap <= 0.0 && gap < floor - 1e-3) return CollisionKind::kRobot;
  }
  return CollisionKind::kNone;
}

void CollisionPredictor::predict_pose(const Pose2& pose, const Mat3& covariance,
                                      const Trajectory& traj, std::size_t progress,
                                      const MapStore& map, std::span<const OtherRobot> others,
                                      Prediction& out) {
  UgvStateVec x = UgvStateVec::Zero();
  x.head<2>() = pose.p;
  x(2) = pose.yaw_rad;
  UgvStateCov P = UgvStateCov::Zero();
  P.topLeftCorner<3, 3>() = covariance;
  predict(x, P, traj, progress, map, others, out);
}

void CollisionPredictor::predict(const UgvStateVec& state, const UgvStateCov& covariance,
                                 const Trajectory& traj, std::size_t progress, const MapStore& map,
                                 std::span<const OtherRobot> others, Prediction& out) {
  out.kind = CollisionKind::kNone;
  out.cause = MapCause::kNone;
  out.ellipses.clear();
  const double k = config_.use_uncertainty ? config_.k_sigma : 0.0;
  UgvStateCov P = config_.use_uncertainty ? covariance : UgvStateCov::Zero();
  const Pose2 pose{state.head<2>(), state(2)};
  const auto& g = map.geometry();

  // Now: the blocked cells the ellipse overlaps already are excused (collected in the
  // ascending order the rasterisation visits them; too many to excuse: a collision now), and
  // the robot's worst-case distance to the nearest occupied cell is the floor from here on.
  excused_.clear();
  const Ellipse now_e = sigma_ellipse(pose.p, P.topLeftCorner<2, 2>(), k);
  const bool overflow = any_cell_touching(g, now_e, [&](CellIndex c) {
    const auto i = static_cast<std::uint32_t>(g.index(c));
    return map.predict_blocked_at(i) && !excused_.push_back(i);
  });
  const double inflation = map.config().predict_inflation_m;
  const double floor_now = map.occupied_distance(pose.p, kDistanceSearch_m) - now_e.axes().a_m;
  // Outside any occupied cell's inflation nothing changes: the floor is the inflation itself.
  // Never below touching: an ellipse that reaches into an obstacle now is an estimate too
  // uncertain to drive on near it (the robot cannot be inside a box; its estimate can be far
  // off). Excusing that overlap let a UGV 0.75 m off its estimate (3 sigma 1.2 m, no relative
  // pose for 30 s) drive on beside boxes, each step "no closer" by its estimate, into one.
  const double closest_allowed = std::min(std::max(floor_now, 0.0), inflation) - 1e-3;
  robot_floor_.clear();
  for (const OtherRobot& o : others) {
    const double a = now_e.axes().a_m;
    (void)robot_floor_.push_back((o.p - pose.p).norm() - (a + o.radius_m));
  }

  // The trajectory's samples are where the robot should be; it is beside its path now (by
  // `offset` across the path's direction) and the controller takes that back in its own time:
  // every position between the sample and the sample moved by the offset is covered (the
  // ellipse at the midpoint, grown by half the offset). Along the path, being behind or ahead
  // of the schedule changes when, not where: the stop threshold's margin covers that.
  Vec2 shift = Vec2::Zero();
  double grow = 0.0;
  const auto test = [&](const Vec2& centre, double t, double heading) {
    const Ellipse e = sigma_ellipse(centre + shift, P.topLeftCorner<2, 2>(), k).grown(grow);
    (void)out.ellipses.push_back(e);
    MapCause cause = MapCause::kUncertainNow;
    const CollisionKind kind =
        overflow ? CollisionKind::kMap : check(e, t, map, others, closest_allowed, cause);
    if (kind == CollisionKind::kNone) return false;
    out.kind = kind;
    out.cause = kind == CollisionKind::kMap ? cause : MapCause::kNone;
    out.point = centre;
    out.time_s = t;
    out.support_point =
        centre - config_.support_back_off_m * Vec2(std::cos(heading), std::sin(heading));
    return true;
  };
  if (test(pose.p, 0.0, pose.yaw_rad) || traj.empty()) return;

  const std::size_t start = std::min(progress, traj.size() - 1);
  const double t0 = traj[start].t_s;
  const Vec2 origin = traj[start].p;
  const Vec2 along(std::cos(traj[start].yaw_rad), std::sin(traj[start].yaw_rad));
  const Vec2 off = pose.p - origin;
  shift = 0.5 * (off - off.dot(along) * along);
  grow = shift.norm();
  std::size_t i = start;
  for (int step = 1; step < static_cast<int>(limits::kMaxPredictionSteps); ++step) {
    const double t = step * config_.dt_s;
    if (t > config_.max_horizon_s * horizon_scale_) return;
    i = traj.index_at_time(t0 + t, i);
    const TrajectorySample& s = traj[i];
    if (config_.use_uncertainty) {
      // Linearised about the plan: the sample's pose, the calibration estimated now.
      UgvStateVec x = state;
      x.head<2>() = s.p;
      x(2) = s.yaw_rad;
      propagate(x, P, s.v_mps, s.omega_radps, config_.dt_s, noise_, walk_);
      add_frame_walk(P, frame_walk_m_per_sqrt_s_, config_.dt_s);
    }
    if (test(s.p, t, s.yaw_rad)) return;
    if ((s.p - origin).norm() >= config_.horizon_m * horizon_scale_ || i + 1 >= traj.size()) return;
  }
}

}  // namespace colag::ugv
