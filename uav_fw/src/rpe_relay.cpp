#include "colag/uav/rpe_relay.hpp"

#include <cmath>

#include "colag/common/limits.hpp"

namespace colag::uav {

Result<msg::RelativePose> to_message(const hal::RelativePoseDetection& d, RobotId uav_id) {
  if (d.ugv_id >= limits::kMaxUgvs)
    return Status{Errc::kInvalidArgument, "RPE: UGV id out of range"};
  if (!all_finite(d.ugv_in_uav.p) || !d.ugv_in_uav.q.coeffs().allFinite() ||
      !d.covariance.allFinite() || std::abs(d.ugv_in_uav.q.norm() - 1.0) > 1e-3) {
    return Status{Errc::kInvalidArgument, "RPE: pose not finite or not a unit quaternion"};
  }
  for (int i = 0; i < 4; ++i) {
    if (d.covariance(i, i) <= 0.0)
      return Status{Errc::kInvalidArgument, "RPE: covariance not positive"};
  }
  msg::RelativePose m;
  m.stamp = d.stamp;
  m.uav_id = uav_id;
  m.ugv_id = d.ugv_id;
  for (int i = 0; i < 3; ++i)
    m.position_m[i] = d.ugv_in_uav.p[i];
  const Quat q = d.ugv_in_uav.q.normalized();
  m.orientation_wxyz[0] = q.w();
  m.orientation_wxyz[1] = q.x();
  m.orientation_wxyz[2] = q.y();
  m.orientation_wxyz[3] = q.z();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c)
      m.covariance[4 * r + c] = d.covariance(r, c);
  }
  return m;
}

}  // namespace colag::uav
