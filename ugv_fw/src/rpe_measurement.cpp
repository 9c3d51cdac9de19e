#include "colag/ugv/rpe_measurement.hpp"

#include <cmath>

namespace colag::ugv {

namespace {

bool unit_quaternion(const double (&q)[4], Quat& out) {
  for (double v : q) {
    if (!std::isfinite(v)) return false;
  }
  out = Quat(q[0], q[1], q[2], q[3]);
  if (std::abs(out.norm() - 1.0) > 1e-3) return false;
  out.normalize();
  return true;
}

template <std::size_t N>
bool finite(const double (&a)[N]) {
  for (double v : a) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

Status UavOdometryHistory::push(const msg::UavOdometry& m) {
  Quat q;
  if (!finite(m.position_m) || !unit_quaternion(m.orientation_wxyz, q)) {
    return {Errc::kInvalidArgument, "UAV odometry: not finite or not a unit quaternion"};
  }
  if (!entries_.empty() && m.stamp <= entries_.back().t) {
    return {Errc::kOutOfRange, "UAV odometry: stamp not increasing"};
  }
  // A velocity that is not finite is taken as none: the pose alone still places detections
  // between samples.
  const bool moving = finite(m.velocity_mps) && std::isfinite(m.yaw_rate_radps);
  entries_.push_overwrite(
      {m.stamp,
       {Vec3(m.position_m[0], m.position_m[1], m.position_m[2]), q},
       moving ? Vec3(m.velocity_mps[0], m.velocity_mps[1], m.velocity_mps[2]) : Vec3::Zero(),
       moving ? m.yaw_rate_radps : 0.0});
  return Status::ok();
}

bool UavOdometryHistory::pose_at(TimePoint t, Duration tolerance, Pose3& out) const {
  if (entries_.empty()) return false;
  std::size_t i = 0;
  while (i < entries_.size() && entries_[i].t < t)
    ++i;
  if (i > 0 && i < entries_.size()) {
    const Entry& a = entries_[i - 1];
    const Entry& b = entries_[i];
    // Interpolate only across a gap no wider than twice the tolerance.
    if (b.t - a.t > 2 * tolerance) return false;
    const double f = to_seconds(t - a.t) / to_seconds(b.t - a.t);
    out.p = a.pose.p + f * (b.pose.p - a.pose.p);
    out.q = a.pose.q.slerp(f, b.pose.q);
    return true;
  }
  const Entry& nearest = i == 0 ? entries_.front() : entries_.back();
  const Duration gap = nearest.t > t ? nearest.t - t : t - nearest.t;
  if (gap > tolerance) return false;
  out = nearest.pose;
  if (i == entries_.size()) {  // after the newest: where its velocity took it
    const double dt = to_seconds(t - nearest.t);
    out.p += dt * nearest.velocity;
    out.q = (Quat(Eigen::AngleAxisd(dt * nearest.yaw_rate, Vec3::UnitZ())) * nearest.pose.q)
                .normalized();
  }
  return true;
}

Result<PoseMeasurement> world_measurement(const msg::RelativePose& rpe, const Pose3& uav) {
  Quat q_rel;
  if (!finite(rpe.position_m) || !finite(rpe.covariance) ||
      !unit_quaternion(rpe.orientation_wxyz, q_rel)) {
    return Status{Errc::kInvalidArgument, "relative pose: not finite or not a unit quaternion"};
  }
  const Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> cov(rpe.covariance);
  if (cov(0, 0) <= 0.0 || cov(1, 1) <= 0.0 || cov(2, 2) <= 0.0 || cov(3, 3) <= 0.0) {
    return Status{Errc::kInvalidArgument, "relative pose: covariance not positive"};
  }
  const Pose3 rel{Vec3(rpe.position_m[0], rpe.position_m[1], rpe.position_m[2]), q_rel};
  const Pose3 world = uav.compose(rel);
  // Rotate the (x, y, z) block into the world frame; yaw is unchanged by a rotation about z
  // (the UAV hovers level enough for that).
  Eigen::Matrix4d J = Eigen::Matrix4d::Identity();
  J.topLeftCorner<3, 3>() = uav.q.toRotationMatrix();
  const Eigen::Matrix4d w = J * cov * J.transpose();
  PoseMeasurement z;
  z.stamp = rpe.stamp;
  z.pose = to_pose2(world);
  const int idx[3] = {0, 1, 3};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      z.covariance(r, c) = w(idx[r], idx[c]);
  }
  z.covariance = 0.5 * (z.covariance + z.covariance.transpose());
  return z;
}

}  // namespace colag::ugv
