#pragma once
// From the UAV's messages to an EKF measurement (paper Eq. (6)-(7)): the UGV's world pose is
// the UAV's odometry at the detection time composed with the relative pose; the RPE
// covariance is rotated into the world frame. The UAV odometry (20 Hz) is kept for ~3 s and
// interpolated at the detection stamp, or carried on by its velocity past the newest sample (a
// detection newer than the odometry that has arrived); pairs more than `tolerance` apart are
// refused.
#include "colag/common/limits.hpp"
#include "colag/common/ring_buffer.hpp"
#include "colag/common/status.hpp"
#include "colag/common/ugv_ekf.hpp"
#include "colag/msg/relative_pose.hpp"
#include "colag/msg/uav_odometry.hpp"

namespace colag::ugv {

class UavOdometryHistory {
 public:
  // Stores a sample; refuses non-finite values, non-unit orientations and stamps that do not
  // increase.
  Status push(const msg::UavOdometry& m);
  // The UAV pose at t: interpolated between the samples around t; within `tolerance` after the
  // newest, that sample moved on by its velocity and yaw rate; within it before the oldest, the
  // oldest.
  bool pose_at(TimePoint t, Duration tolerance, Pose3& out) const;
  TimePoint newest() const { return entries_.empty() ? kNever : entries_.back().t; }
  void clear() { entries_.clear(); }  // the UAV's clock went back: its old samples do not fit

 private:
  struct Entry {
    TimePoint t;
    Pose3 pose;
    Vec3 velocity = Vec3::Zero();
    double yaw_rate = 0.0;
  };
  RingBuffer<Entry, limits::kUavOdometryHistory> entries_;
};

// The UGV's pose in the world frame with its covariance; rejects malformed relative poses.
Result<PoseMeasurement> world_measurement(const msg::RelativePose& rpe, const Pose3& uav_pose);

}  // namespace colag::ugv
