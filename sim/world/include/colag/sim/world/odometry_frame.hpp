#pragma once
// Where a LiDAR-inertial odometry (FAST-LIO2, LIO-SAM) puts the world: its frame is the map it
// builds as it flies, and a place it comes back to is matched against that map, so its error is
// a distortion of space more than a drift with time. Over a site of tens of metres it is a
// similarity: a scale error and a heading error about where it started (what the published
// drifts of 0.1-1 % of the distance travelled amount to over a site), plus what does change with
// time: a slow random walk of the whole frame and rare jumps (a degenerate scan, a
// re-registration). The ideal world's frame is the world.
#include "colag/common/geometry.hpp"
#include "colag/common/random.hpp"
#include "colag/common/time.hpp"

namespace colag::sim {

struct UavOdometryErrors {
  double scale_error = 0.0;        // drawn uniform in +-this
  double yaw_error_rad = 0.0;      // drawn uniform in +-this
  double walk_m_per_sqrt_s = 0.0;  // the frame's slow wandering, each horizontal axis
  double jumps_per_min = 0.0;      // sudden shifts of the frame, on average
  double jump_max_m = 0.0;         // each up to this, in any horizontal direction
  Duration latency{};              // capture to delivery
  bool any() const {
    return scale_error > 0.0 || yaw_error_rad > 0.0 || walk_m_per_sqrt_s > 0.0 ||
           jumps_per_min > 0.0 || latency.count() > 0;
  }
};

class OdometryFrame {
 public:
  OdometryFrame() = default;
  // The frame's errors drawn with `seed`; `origin`: where the odometry started (fixed point).
  OdometryFrame(const UavOdometryErrors& errors, const Vec3& origin, std::uint64_t seed);

  void step(double dt);  // the walk and the jumps

  // A world point, a world direction, and back.
  Vec3 to_odometry(const Vec3& p) const;
  Vec2 to_odometry(const Vec2& p) const { return to_odometry(Vec3(p.x(), p.y(), 0.0)).head<2>(); }
  Pose2 to_odometry(const Pose2& p) const { return {to_odometry(p.p), p.yaw_rad + yaw_}; }
  Vec3 vector_to_odometry(const Vec3& v) const { return (1.0 + scale_) * (turn_ * v); }
  Vec3 vector_to_world(const Vec3& v) const { return turn_.inverse() * v / (1.0 + scale_); }
  double yaw_error_rad() const { return yaw_; }
  const Quat& turn() const { return turn_; }

 private:
  UavOdometryErrors errors_;
  Vec3 origin_ = Vec3::Zero();
  double scale_ = 0.0;
  double yaw_ = 0.0;
  Quat turn_ = Quat::Identity();
  Vec3 shift_ = Vec3::Zero();  // the walk and the jumps so far
  Rng rng_{1};
};

}  // namespace colag::sim
