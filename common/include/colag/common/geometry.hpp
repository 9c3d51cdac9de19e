#pragma once
// 2-D and 3-D poses on Eigen fixed-size types (no heap). World frame: x east, y north, z up;
// yaw counter-clockwise from +x. A Pose maps points from its body frame to its parent frame:
// p_parent = R * p_body + t.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace colag {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Wraps an angle to [-pi, pi).
inline double wrap_angle(double a) {
  if (a >= -M_PI && a < M_PI) return a;
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0.0) a += 2.0 * M_PI;
  return a - M_PI;
}

inline Mat2 rotation2(double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  Mat2 r;
  r << c, -s, s, c;
  return r;
}

struct Pose2 {
  Vec2 p = Vec2::Zero();
  double yaw_rad = 0.0;

  Vec2 transform(const Vec2& body_point) const { return p + rotation2(yaw_rad) * body_point; }
  Pose2 compose(const Pose2& child) const {
    return {transform(child.p), wrap_angle(yaw_rad + child.yaw_rad)};
  }
  Pose2 inverse() const {
    const Mat2 rt = rotation2(yaw_rad).transpose();
    return {-(rt * p), wrap_angle(-yaw_rad)};
  }
};

struct Pose3 {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();

  Vec3 transform(const Vec3& body_point) const { return p + q * body_point; }
  Pose3 compose(const Pose3& child) const {
    return {transform(child.p), (q * child.q).normalized()};
  }
  Pose3 inverse() const {
    const Quat qi = q.conjugate();
    return {-(qi * p), qi};
  }
};

// Heading of a rotation: the yaw of its body x axis projected on the ground plane.
// Well defined for any tilt short of pointing straight up or down.
inline double yaw_of(const Quat& q) {
  const Vec3 x = q * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

inline Quat quat_from_yaw(double yaw_rad) {
  return Quat(Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ()));
}

// Projects a 3-D pose to the ground plane (x, y, heading).
inline Pose2 to_pose2(const Pose3& pose) {
  return {pose.p.head<2>(), yaw_of(pose.q)};
}

inline bool all_finite(const Vec2& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}
inline bool all_finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

}  // namespace colag
